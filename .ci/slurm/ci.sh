#!/usr/bin/env bash
# CI (CI=true): bring up a one-node SLURM cluster, run the tiny study locally and through
# Snakemake's SLURM executor, and require identical netCDF results. Stops only its own daemons.
set -euo pipefail
cd "$(dirname "$0")/../.."
bash .ci/slurm/up.sh
trap 'bash .ci/slurm/down.sh' EXIT
LOCAL=/tmp/rockstudy-ci-local
rm -rf "$LOCAL"
snakemake -j2 --configfile .test/config.yaml --replace-workflow-config --config results_dir="$LOCAL"
COMPARE_ARGS="--only-nc --ignore-attr compute_time_s" \
  bash .ci/slurm/check.sh . .test/config.yaml "$LOCAL" -- --replace-workflow-config
