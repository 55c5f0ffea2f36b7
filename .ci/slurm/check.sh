#!/usr/bin/env bash
# .ci/slurm/check.sh -- run a workflow through Snakemake's SLURM executor on the
# CI cluster (started by .ci/slurm/up.sh) and compare its results with a local run.
#
# Usage:
#   bash .ci/slurm/check.sh <workflow-dir> <configfile> <local-results-dir> [-- <extra snakemake args>]
#
#   <workflow-dir>       directory snakemake is started in (it finds Snakefile or
#                        workflow/Snakefile there), e.g. "." or ".ci/slurm/toy"
#   <configfile>         the config the local run used (e.g. the tiny CI config)
#   <local-results-dir>  results tree of the LOCAL run of that config (reference)
#   extra args           e.g. targets, --forceall, -n ...
#
# The SLURM run writes to a separate folder: check.sh passes
#   --config <OUTDIR_KEY>=<SLURM_RESULTS_DIR>
# so the workflow must take its output root from that config key.
#
# Environment:
#   OUTDIR_KEY          config key holding the output root        [results_dir]
#   SLURM_RESULTS_DIR   where the SLURM run writes (wiped first)  [/tmp/rockstudy-slurm/results-<name>]
#   SLURM_CHECK_TIMEOUT seconds before the snakemake run is killed [1800]
#   COMPARE_ARGS        extra args for compare_results.py, e.g. "--ignore-attr git_sha --exclude '*.png'"
#   PROFILE             snakemake profile                          [<repo>/profiles/slurm]
#
# CI-only settings added on top of the profile: --slurm-init-seconds-before-status-checks 5,
# --slurm-logdir/--slurm-keep-successful-logs (logs kept under $ROCKSTUDY_SLURM_DIR).
# No account is configured: the plugin's account guess fails harmlessly on the CI
# cluster ("Unable to guess SLURM account. Trying to proceed without.").
# (--slurm-no-account exists in plugin 2.8.0 but is not wired up -- don't rely on it.)
#
# Exit status: 0 = ran through SLURM and results identical; non-zero otherwise.
set -euo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
REPO="$(cd "$HERE/../.." && pwd)"
RUN_DIR="${ROCKSTUDY_SLURM_DIR:-/tmp/rockstudy-slurm}"

usage() { sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//' >&2; exit 2; }
[ $# -ge 3 ] || usage
WF_DIR="$(cd "$1" && pwd)"
CFG="$(cd "$(dirname "$2")" && pwd)/$(basename "$2")"
LOCAL_RES="$(cd "$3" && pwd)"
shift 3
[ "${1:-}" = "--" ] && shift
[ -f "$CFG" ] || { echo "check.sh: no config file $CFG" >&2; exit 2; }

NAME="$(basename "$WF_DIR")"; [ "$WF_DIR" = "$REPO" ] && NAME=main
OUTDIR_KEY="${OUTDIR_KEY:-results_dir}"
OUT="${SLURM_RESULTS_DIR:-$RUN_DIR/results-$NAME}"
TIMEOUT="${SLURM_CHECK_TIMEOUT:-1800}"
PROFILE="${PROFILE:-$REPO/profiles/slurm}"
SLOGS="$RUN_DIR/slurm_logs-$NAME"
LOG="$RUN_DIR/snakemake-$NAME.log"

say() { printf '[slurm-check] %s\n' "$*"; }

node_state="$(sinfo -h -o '%t' 2>/dev/null | head -n1 || true)"
case "$node_state" in
    idle|mix|alloc) ;;
    *) echo "check.sh: SLURM cluster not up (sinfo: '${node_state}'); run .ci/slurm/up.sh first" >&2; exit 1 ;;
esac

rm -rf "$OUT" "$SLOGS"
mkdir -p "$(dirname "$OUT")" "$SLOGS"
say "workflow $WF_DIR, config $CFG"
say "SLURM run -> $OUT (log: $LOG)"

cmd=(snakemake --profile "$PROFILE" --configfile "$CFG"
     --config "$OUTDIR_KEY=$OUT"
     --slurm-init-seconds-before-status-checks 5
     --slurm-logdir "$SLOGS" --slurm-keep-successful-logs
     "$@")
say "cd $WF_DIR && ${cmd[*]}"

t0=$(date +%s)
set +e
( cd "$WF_DIR" && timeout --signal=INT --kill-after=60 "$TIMEOUT" "${cmd[@]}" ) > "$LOG" 2>&1
rc=$?
set -e
dt=$(( $(date +%s) - t0 ))

if [ "$rc" -ne 0 ]; then
    tail -n 80 "$LOG" >&2
    [ "$rc" -eq 124 ] && echo "check.sh: snakemake did not finish within ${TIMEOUT}s" >&2
    echo "----- squeue -----" >&2; squeue -l >&2 || true
    # private CI cluster: do not leave pending/running jobs behind
    left="$(squeue -h -o '%i' 2>/dev/null | tr '\n' ' ' || true)"
    # shellcheck disable=SC2086
    [ -n "${left// /}" ] && { echo "cancelling jobs: $left" >&2; scancel $left || true; }
    for f in $(find "$SLOGS" -name '*.log' 2>/dev/null | sort | tail -n 5); do
        echo "----- $f -----" >&2; tail -n 40 "$f" >&2
    done
    echo "check.sh: SLURM run FAILED (rc=$rc, ${dt}s)" >&2
    exit 1
fi

# prove the jobs really went through SLURM
jobids="$(grep -oE 'submitted with SLURM jobid [0-9]+' "$LOG" | grep -oE '[0-9]+$' | sort -un | tr '\n' ' ' || true)"
n_slurm="$(echo "$jobids" | wc -w)"
if [ "$n_slurm" -eq 0 ]; then
    tail -n 40 "$LOG" >&2
    echo "check.sh: snakemake succeeded but submitted no SLURM job (nothing to do? stale outputs?)" >&2
    exit 1
fi
say "snakemake via SLURM ok in ${dt}s; $n_slurm SLURM job(s): $jobids"

# shellcheck disable=SC2086
eval "python3 \"$HERE/compare_results.py\" \"$LOCAL_RES\" \"$OUT\" ${COMPARE_ARGS:-}"
