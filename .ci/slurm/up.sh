#!/usr/bin/env bash
# .ci/slurm/up.sh -- bring up a private one-node SLURM cluster on THIS machine.
#
# Usage:  bash .ci/slurm/up.sh            (as root; Debian 12; idempotent)
#
# What it does
#   1. apt-get installs slurm-wlm + munge if missing (SLURM 22.05 on Debian 12)
#   2. writes /etc/slurm/slurm.conf (default path on purpose: the snakemake SLURM
#      executor strips SLURM_* variables inside jobs, so SLURM_CONF alone is not
#      enough) -- refuses to overwrite a slurm.conf it did not write
#   3. starts munged (as user munge), slurmctld, slurmd as daemons and records
#      "<name> <pid>" lines in $ROCKSTUDY_SLURM_DIR/pids (down.sh kills only those)
#   4. waits until `sinfo` reports the node idle, then runs a 1-task srun smoke test
#      (on timeout: clear error + daemon logs)
#   5. pip installs the pinned snakemake-executor-plugin-slurm
#
# Environment knobs
#   ROCKSTUDY_SLURM_DIR        runtime dir (pids, logs, pidfiles)   [/tmp/rockstudy-slurm]
#   ROCKSTUDY_SLURM_TIMEOUT    seconds to wait for the node         [90]
#   ROCKSTUDY_SLURM_PLUGIN     pip requirement for the executor     [snakemake-executor-plugin-slurm==2.8.0]
#   ROCKSTUDY_SLURM_SKIP_PIP=1 do not touch pip
set -euo pipefail

RUN_DIR="${ROCKSTUDY_SLURM_DIR:-/tmp/rockstudy-slurm}"
TIMEOUT="${ROCKSTUDY_SLURM_TIMEOUT:-90}"
PLUGIN_REQ="${ROCKSTUDY_SLURM_PLUGIN:-snakemake-executor-plugin-slurm==2.8.0}"
PIDS="$RUN_DIR/pids"
LOG_DIR="$RUN_DIR/log"
CONF=/etc/slurm/slurm.conf
MARKER="# written by rockstudy .ci/slurm/up.sh"
STATE_DIR=/var/spool/rockstudy-slurm/ctld
SPOOL_DIR=/var/spool/rockstudy-slurm/d
NODE="$(hostname -s)"
T0=$(date +%s)

say() { printf '[slurm-up %3ss] %s\n' "$(( $(date +%s) - T0 ))" "$*"; }
die() { printf '[slurm-up] ERROR: %s\n' "$*" >&2; exit 1; }

dump_logs() {
    for f in "$LOG_DIR"/munge/munged.log "$LOG_DIR"/slurmctld.log "$LOG_DIR"/slurmd.log; do
        [ -f "$f" ] || continue
        echo "----- tail -n 60 $f -----" >&2
        tail -n 60 "$f" >&2 || true
    done
}

[ "$(id -u)" -eq 0 ] || die "must run as root (starts system daemons)"

# ---------------------------------------------------------------- 1. packages
if ! command -v slurmctld >/dev/null || ! command -v slurmd >/dev/null \
   || ! command -v munged >/dev/null || ! command -v sinfo >/dev/null; then
    say "installing slurm-wlm + munge via apt-get"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    apt-get install -y -qq slurm-wlm munge >/dev/null
fi
say "slurm-wlm $(dpkg-query -W -f='${Version}' slurm-wlm 2>/dev/null || echo '?'), munge $(dpkg-query -W -f='${Version}' munge 2>/dev/null || echo '?')"

mkdir -p "$RUN_DIR" "$LOG_DIR" "$STATE_DIR" "$SPOOL_DIR"
touch "$PIDS"

# pid recorded by us and still alive with the expected executable?
recorded_pid() {   # $1 = name
    awk -v n="$1" '$1==n {p=$2} END {if (p) print p}' "$PIDS"
}
alive() {          # $1 = name  -> 0 if our recorded daemon is running
    local pid; pid="$(recorded_pid "$1")"
    [ -n "$pid" ] && [ -d "/proc/$pid" ] \
        && tr '\0' ' ' < "/proc/$pid/cmdline" 2>/dev/null | grep -q "$1"
}
record() {         # $1 = name, $2 = pid
    { grep -v "^$1 " "$PIDS" || true; } > "$PIDS.tmp"
    echo "$1 $2" >> "$PIDS.tmp"
    mv "$PIDS.tmp" "$PIDS"
}
wait_pidfile() {   # $1 = pidfile, $2 = name; prints pid
    for _ in $(seq 1 100); do
        if [ -s "$1" ] && [ -d "/proc/$(cat "$1")" ]; then cat "$1"; return 0; fi
        sleep 0.1
    done
    dump_logs; die "$2 did not write a live pid to $1"
}

# ---------------------------------------------------------------- 2. configs
NCPU="$(nproc)"
TOTAL_MB="$(awk '/MemTotal/ {print int($2/1024)}' /proc/meminfo)"
AVAIL_MB="$(awk '/MemAvailable/ {print int($2/1024)}' /proc/meminfo)"
# 70% of MemTotal (stable between runs -> idempotent config), but stay below what
# is actually free; rounded down to 256 MB
REAL_MB=$(( TOTAL_MB * 70 / 100 ))
[ "$REAL_MB" -le "$AVAIL_MB" ] || REAL_MB=$(( AVAIL_MB * 80 / 100 ))
REAL_MB=$(( REAL_MB / 256 * 256 ))
[ "$REAL_MB" -ge 1000 ] || die "only ${AVAIL_MB} MB available; need >= 1.25 GB"
DEF_MEM=$(( REAL_MB / NCPU ))                 # a job without --mem gets its cores' share

if [ -f "$CONF" ] && ! grep -qF "$MARKER" "$CONF"; then
    die "$CONF exists and was not written by this script; refusing to touch a real cluster config"
fi

NEW_CONF="$(mktemp)"
cat > "$NEW_CONF" <<CONF
$MARKER -- private one-node CI cluster, do not use in production
ClusterName=rockstudy-ci
SlurmctldHost=${NODE}(127.0.0.1)
SlurmUser=root
SlurmdUser=root
SlurmctldPort=6817
SlurmdPort=6818
AuthType=auth/munge
CredType=cred/munge
StateSaveLocation=${STATE_DIR}
SlurmdSpoolDir=${SPOOL_DIR}
SlurmctldPidFile=${RUN_DIR}/slurmctld.pid
SlurmdPidFile=${RUN_DIR}/slurmd.pid
SlurmctldLogFile=${LOG_DIR}/slurmctld.log
SlurmdLogFile=${LOG_DIR}/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
# no systemd / cgroup handling inside CI containers
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
MpiDefault=none
# no slurmdbd: sacct cannot see finished jobs -> snakemake must use
# --slurm-status-command squeue; squeue keeps finished jobs for MinJobAge seconds
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/none
MinJobAge=300
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
DefMemPerCPU=${DEF_MEM}
ReturnToService=2
SlurmdTimeout=60
InactiveLimit=0
KillWait=10
Waittime=0
NodeName=${NODE} NodeAddr=127.0.0.1 CPUs=${NCPU} RealMemory=${REAL_MB} State=UNKNOWN
PartitionName=debug Nodes=${NODE} Default=YES MaxTime=INFINITE State=UP
CONF

CONF_CHANGED=0
if ! cmp -s "$NEW_CONF" "$CONF" 2>/dev/null; then
    mkdir -p /etc/slurm
    install -m 644 "$NEW_CONF" "$CONF"
    CONF_CHANGED=1
    say "wrote $CONF (node $NODE: CPUs=$NCPU RealMemory=${REAL_MB}MB)"
fi
rm -f "$NEW_CONF"

# ---------------------------------------------------------------- 3. daemons
# munge: runtime dir + key, must run as user munge
install -d -o munge -g munge -m 755 /run/munge
install -d -o munge -g munge -m 700 /var/log/munge /var/lib/munge /etc/munge
install -d -o munge -g munge -m 755 "$LOG_DIR/munge"   # munged opens its log as user munge
if [ ! -s /etc/munge/munge.key ]; then
    say "creating munge key"
    if command -v mungekey >/dev/null; then
        mungekey --create --keyfile=/etc/munge/munge.key
    else
        dd if=/dev/urandom of=/etc/munge/munge.key bs=1024 count=1 status=none
    fi
fi
chown munge:munge /etc/munge/munge.key
chmod 400 /etc/munge/munge.key

if alive munged; then
    say "munged already running (pid $(recorded_pid munged))"
else
    rm -f /run/munge/munged.pid
    runuser -u munge -- /usr/sbin/munged --log-file="$LOG_DIR/munge/munged.log" \
        --pid-file=/run/munge/munged.pid \
        || { dump_logs; die "munged failed to start"; }
    record munged "$(wait_pidfile /run/munge/munged.pid munged)"
    say "started munged (pid $(recorded_pid munged))"
fi
munge -n | unmunge >/dev/null || { dump_logs; die "munge round-trip failed"; }

if [ "$CONF_CHANGED" = 1 ] && { alive slurmctld || alive slurmd; }; then
    say "slurm.conf changed -> restarting our slurm daemons"
    for n in slurmd slurmctld; do
        if alive "$n"; then
            p="$(recorded_pid "$n")"; kill "$p"
            for _ in $(seq 1 100); do [ -d "/proc/$p" ] || break; sleep 0.2; done
        fi
    done
fi

if alive slurmctld; then
    say "slurmctld already running (pid $(recorded_pid slurmctld))"
else
    rm -f "$RUN_DIR/slurmctld.pid"
    # -c: start with a clean job state (private CI cluster)
    /usr/sbin/slurmctld -c -f "$CONF" || { dump_logs; die "slurmctld failed to start"; }
    record slurmctld "$(wait_pidfile "$RUN_DIR/slurmctld.pid" slurmctld)"
    say "started slurmctld (pid $(recorded_pid slurmctld))"
fi

if alive slurmd; then
    say "slurmd already running (pid $(recorded_pid slurmd))"
else
    rm -f "$RUN_DIR/slurmd.pid"
    /usr/sbin/slurmd -N "$NODE" -f "$CONF" || { dump_logs; die "slurmd failed to start"; }
    record slurmd "$(wait_pidfile "$RUN_DIR/slurmd.pid" slurmd)"
    say "started slurmd (pid $(recorded_pid slurmd))"
fi

# ---------------------------------------------------------------- 4. wait idle
state=""
deadline=$(( $(date +%s) + TIMEOUT ))
while :; do
    state="$(sinfo -h -N -n "$NODE" -o '%t' 2>/dev/null | head -n1 || true)"
    case "$state" in
        idle|mix|alloc) break ;;
        down*|drain*|drng*)
            # e.g. left DOWN by an earlier unclean stop
            scontrol update NodeName="$NODE" State=RESUME >/dev/null 2>&1 || true ;;
    esac
    if [ "$(date +%s)" -ge "$deadline" ]; then
        sinfo -N -l >&2 || true
        scontrol show node "$NODE" >&2 || true
        dump_logs
        die "node $NODE not idle after ${TIMEOUT}s (last state: '${state:-no answer}')"
    fi
    sleep 1
done
say "node $NODE is $state"

if ! out="$(timeout 60 srun -N1 -n1 --time=1 --mem=100 -J rockstudy-smoke hostname 2>&1)"; then
    echo "$out" >&2; dump_logs; die "srun smoke test failed"
fi
say "srun smoke test ok ($out)"

# ---------------------------------------------------------------- 5. plugin
if [ "${ROCKSTUDY_SLURM_SKIP_PIP:-0}" != 1 ]; then
    PY="${PYTHON:-python3}"
    want="${PLUGIN_REQ#*==}"
    # `pip show` exits 1 when the plugin is not installed (always so on a new machine); under
    # `set -euo pipefail` that would end this script silently, so its status is ignored here.
    have="$({ "$PY" -m pip show snakemake-executor-plugin-slurm 2>/dev/null || true; } | awk '/^Version:/ {print $2}')"
    if [ "$have" != "$want" ]; then
        say "pip install $PLUGIN_REQ"
        "$PY" -m pip install -q --disable-pip-version-check "$PLUGIN_REQ"
    fi
    have="$({ "$PY" -m pip show snakemake-executor-plugin-slurm 2>/dev/null || true; } | awk '/^Version:/ {print $2}')"
    [ "$have" = "$want" ] || die "snakemake-executor-plugin-slurm is '${have:-not installed}' after pip install, want $want"
    say "snakemake $(snakemake --version), executor-plugin-slurm $have ($("$PY" -c 'import sys; print(sys.prefix)'))"
fi

say "cluster up; pids in $PIDS: $(tr '\n' ' ' < "$PIDS")"
