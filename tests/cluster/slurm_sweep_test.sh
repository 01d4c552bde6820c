#!/usr/bin/env bash
# A real single-node Slurm cluster for the length of this test: munged, slurmctld and slurmd
# started as root with a generated slurm.conf (state, spool, logs and the munge key in a
# temporary folder, ports picked free), then scripts/slurm/sweep.sbatch submits a tiny sweep as
# a job array plus a dependent collect job; the merged tables must be byte-identical to a local
# one-process sweep. The daemons this test started are stopped by their pids on every exit.
# Exit 77 (skipped, with the reason) when Slurm cannot be started here.
# Usage: slurm_sweep_test.sh FORMSIM_BINARY SOURCE_DIR
set -euo pipefail
formsim=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
src=$(cd "$2" && pwd)

skip() { echo "SKIPPED: $*"; exit 77; }
[ "$(id -u)" -eq 0 ] || skip "needs root to start munged, slurmctld and slurmd"
for b in munged mungekey slurmctld slurmd sbatch squeue sinfo scontrol; do
  command -v "$b" >/dev/null || skip "$b is not installed (scripts/setup.sh installs slurm-wlm and munge)"
done

T=$(mktemp -d /tmp/formsim-slurm.XXXXXX)
chmod 755 "$T"
mkdir -p "$T/munge" "$T/state" "$T/spool" "$T/log"
export SLURM_CONF="$T/slurm.conf"
# A process that has exited (a zombie counts: this container's init may not reap daemons).
alive() { [ -r "/proc/$1/stat" ] && [ "$(cut -d' ' -f3 "/proc/$1/stat")" != Z ]; }
cleanup() {
  local rc=$?
  # Only the daemons this test started, by the pids they wrote; SIGTERM is their clean stop.
  for pidfile in "$T/slurmd.pid" "$T/slurmctld.pid" "$T/munge/munged.pid"; do
    [ -s "$pidfile" ] || continue
    pid=$(cat "$pidfile")
    alive "$pid" || continue
    kill -TERM "$pid" 2>/dev/null || true
    for _ in $(seq 1 50); do alive "$pid" || break; sleep 0.1; done
    if alive "$pid"; then kill -KILL "$pid" 2>/dev/null || true; fi
  done
  if [ $rc -ne 0 ] && [ $rc -ne 77 ]; then
    echo "---- logs ----"; tail -n 20 "$T"/log/*.log "$T"/munge/munged.log "$T"/slurm/*.out 2>/dev/null || true
  fi
  rm -rf "$T"
  exit $rc
}
trap cleanup EXIT INT TERM

# munge: our own key, socket and pid file.
mungekey -c -k "$T/munge/munge.key" >/dev/null 2>&1 || skip "mungekey cannot create a key"
chmod 400 "$T/munge/munge.key"
munged -f --socket="$T/munge/munge.socket" --key-file="$T/munge/munge.key" \
  --pid-file="$T/munge/munged.pid" --log-file="$T/munge/munged.log" --seed-file="$T/munge/seed" \
  || skip "munged does not start: $(tail -n 3 "$T/munge/munged.log" 2>/dev/null)"

# Two free TCP ports (not listening on this host).
listening=""
while read -r _ local _ state _; do
  [ "$state" = 0A ] && listening+="$((16#${local##*:}))"$'\n'
done < <(cat /proc/net/tcp /proc/net/tcp6 2>/dev/null | grep -v local_address)
pick_port() {
  local p
  for _ in $(seq 1 100); do
    p=$((20000 + RANDOM % 20000))
    grep -qx "$p" <<<"$listening" || { echo "$p"; return; }
  done
  skip "no free port found"
}
ctl_port=$(pick_port)
d_port=$(pick_port)
[ "$ctl_port" != "$d_port" ] || d_port=$((ctl_port + 1))
host=$(hostname -s)
cat > "$SLURM_CONF" <<CONF
ClusterName=formsimtest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctl_port
SlurmdPort=$d_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$T/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$T/state
SlurmdSpoolDir=$T/spool
SlurmctldPidFile=$T/slurmctld.pid
SlurmdPidFile=$T/slurmd.pid
SlurmctldLogFile=$T/log/slurmctld.log
SlurmdLogFile=$T/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SwitchType=switch/none
MpiDefault=none
SchedulerType=sched/backfill
SchedulerParameters=sched_min_interval=100000
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MinJobAge=300
KillWait=5
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=formsim Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
slurmctld -i || skip "slurmctld does not start: $(tail -n 5 "$T/log/slurmctld.log" 2>/dev/null)"
slurmd -N "$host" || skip "slurmd does not start: $(tail -n 5 "$T/log/slurmd.log" 2>/dev/null)"
up=0
for _ in $(seq 1 100); do
  if sinfo -h -o '%t' 2>/dev/null | grep -qx idle; then up=1; break; fi
  sleep 0.2
done
[ $up -eq 1 ] || skip "the node did not come up: $(sinfo 2>&1 | tail -n 2); $(tail -n 5 "$T/log/slurmd.log" 2>/dev/null)"
echo "slurm up on $host (ports $ctl_port, $d_port)"

# The sweep: 2 values x 3 seeds of a shortened scenario.
args=(formation_traj2_ukf --set duration=2 --vary robots.R2.follow.k_phi=0.05,0.1 --seeds 1..3
      --metric links.R1-R2.max_abs_error_after_settle.phi)
"$formsim" sweep "${args[@]}" --out "$T/local" --jobs 2 -q

mkdir -p "$T/out"
cd "$T/out"
submitted=$(SWEEP_SHARDS=3 SWEEP_OUT="$T/slurm" FORMSIM="$formsim" bash "$src/scripts/slurm/sweep.sbatch" "${args[@]}")
echo "$submitted"
done_=0
for _ in $(seq 1 600); do
  if [ -z "$(squeue -h 2>/dev/null)" ]; then done_=1; break; fi
  sleep 0.2
done
[ $done_ -eq 1 ] || { echo "FAILED: the jobs did not finish in 120 s"; squeue; exit 1; }
cat "$T/slurm/slurm-collect.out"
for k in 1 2 3; do
  [ -s "$T/slurm/shards/$k/sweep.manifest" ] || { echo "FAILED: shard $k wrote nothing"; cat "$T/slurm/slurm-shard-$k.out"; exit 1; }
done
for f in runs.csv aggregate.csv ranking_links.R1-R2.max_abs_error_after_settle.phi.txt; do
  cmp "$T/local/$f" "$T/slurm/$f" || { echo "FAILED: $f differs between the Slurm and the local sweep"; exit 1; }
done
[ -s "$T/slurm/plot_links.R1-R2.max_abs_error_after_settle.phi.png" ] || { echo "FAILED: no figure"; exit 1; }
echo "PASSED: a job array of 3 shards and a dependent collect give the local sweep's tables byte for byte"
