#!/usr/bin/env bash
# .ci/slurm/down.sh -- stop the private SLURM cluster started by .ci/slurm/up.sh.
#
# Usage:  bash .ci/slurm/down.sh
#
# Stops ONLY the daemons whose PIDs up.sh recorded in $ROCKSTUDY_SLURM_DIR/pids
# (default /tmp/rockstudy-slurm/pids): SIGTERM, wait up to 30 s, then SIGKILL.
# A recorded PID whose /proc/<pid>/cmdline no longer names the daemon (PID reuse)
# is skipped. Never kills by process name. Safe to run twice / without up.sh.
# Before stopping, jobs still queued on OUR cluster are cancelled.
set -uo pipefail

RUN_DIR="${ROCKSTUDY_SLURM_DIR:-/tmp/rockstudy-slurm}"
PIDS="$RUN_DIR/pids"
say() { printf '[slurm-down] %s\n' "$*"; }

if [ ! -s "$PIDS" ]; then
    say "no pid file $PIDS -- nothing to stop"
    exit 0
fi

is_ours() {   # $1 name, $2 pid
    [ -d "/proc/$2" ] && tr '\0' ' ' < "/proc/$2/cmdline" 2>/dev/null | grep -q "$1"
}

ctld_pid="$(awk '$1=="slurmctld" {p=$2} END {print p}' "$PIDS")"
if [ -n "$ctld_pid" ] && is_ours slurmctld "$ctld_pid" \
   && grep -q 'written by rockstudy' /etc/slurm/slurm.conf 2>/dev/null; then
    jobs="$(timeout 10 squeue -h -o '%i' 2>/dev/null | tr '\n' ' ')"
    if [ -n "${jobs// /}" ]; then
        say "cancelling leftover jobs on the CI cluster: $jobs"
        # shellcheck disable=SC2086
        timeout 10 scancel $jobs || true
        sleep 2
    fi
fi

rc=0
for name in slurmd slurmctld munged; do       # reverse start order
    pid="$(awk -v n="$name" '$1==n {p=$2} END {print p}' "$PIDS")"
    [ -n "$pid" ] || continue
    if ! is_ours "$name" "$pid"; then
        say "$name (pid $pid) not running"
        continue
    fi
    kill -TERM "$pid" 2>/dev/null || true
    for _ in $(seq 1 150); do [ -d "/proc/$pid" ] || break; sleep 0.2; done
    if [ -d "/proc/$pid" ]; then
        say "$name (pid $pid) ignored SIGTERM for 30 s -> SIGKILL"
        kill -KILL "$pid" 2>/dev/null || true
        sleep 0.5
    fi
    if [ -d "/proc/$pid" ]; then
        say "ERROR: $name (pid $pid) still alive"; rc=1
    else
        say "stopped $name (pid $pid)"
    fi
done

[ "$rc" -eq 0 ] && rm -f "$PIDS"
exit "$rc"
