#!/usr/bin/env bash
# CI (CI=true): bring up a one-node SLURM cluster, run the tiny study locally and through
# Snakemake's SLURM executor, and require identical netCDF results. Stops only its own daemons.
#
# The cleanup trap is set BEFORE up.sh: if up.sh fails half-way (e.g. after starting munged,
# slurmctld and slurmd), down.sh still stops the daemons it recorded. down.sh is safe to run
# when nothing was started.
set -euo pipefail
cd "$(dirname "$0")/../.."
LOCAL="$(mktemp -d /tmp/rockstudy-ci-local.XXXXXX)"   # this run's own: two runs on one machine do not share it
trap 'bash .ci/slurm/down.sh; rm -rf "$LOCAL"' EXIT
bash .ci/slurm/up.sh
snakemake -j2 --configfile .test/config.yaml --replace-workflow-config --config results_dir="$LOCAL"
COMPARE_ARGS="--only-nc --ignore-attr compute_time_s" \
  bash .ci/slurm/check.sh . .test/config.yaml "$LOCAL" -- --replace-workflow-config
