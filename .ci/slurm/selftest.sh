#!/usr/bin/env bash
# .ci/slurm/selftest.sh -- end-to-end proof of the CI SLURM machinery on the toy
# workflow in .ci/slurm/toy (no project code involved).
#
# Usage:  bash .ci/slurm/selftest.sh        (root; KEEP_UP=1 leaves the cluster running)
#
#   up.sh -> local run of the toy (--cores 2) -> check.sh (SLURM run + compare) -> down.sh
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
RUN_DIR="${ROCKSTUDY_SLURM_DIR:-/tmp/rockstudy-slurm}"

bash "$HERE/up.sh"
[ "${KEEP_UP:-0}" = 1 ] || trap 'bash "$HERE/down.sh"' EXIT

LOCAL="$RUN_DIR/toy-local"
rm -rf "$LOCAL"
echo "[selftest] local run of the toy -> $LOCAL"
( cd "$HERE/toy" && snakemake --cores 2 --configfile config.yaml \
      --config results_dir="$LOCAL" -q > "$RUN_DIR/snakemake-toy-local.log" 2>&1 ) \
    || { tail -n 40 "$RUN_DIR/snakemake-toy-local.log" >&2; exit 1; }

bash "$HERE/check.sh" "$HERE/toy" "$HERE/toy/config.yaml" "$LOCAL"

# the 8 jobs of group "spectra" must have shared ONE slurm job
where="$(cat "$RUN_DIR"/results-toy.where/* | sort -u)"
[ "$(echo "$where" | wc -l)" -eq 1 ] && [ "$where" != local ] \
    || { echo "[selftest] group 'spectra' ran in: $where (expected one SLURM job)" >&2; exit 1; }
echo "[selftest] OK: group 'spectra' ran as ONE SLURM job ($where)"
