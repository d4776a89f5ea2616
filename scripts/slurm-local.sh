#!/usr/bin/env bash
# A one-node Slurm on this machine (munged, slurmctld and slurmd, as root), for running a
# sweep or `lifelong reproduce` with --slurm where no cluster is at hand. Its state lives in
# DIR (default: runs/slurm-local); it prints the SLURM_CONF to export.
#   scripts/slurm-local.sh start [DIR]   start the daemons and wait until the node is idle
#   scripts/slurm-local.sh stop [DIR]    stop them
# Exit 2: not installed or not root; 3: a daemon exited at start (this machine cannot run
# one; its log is printed); 1: the node did not come up idle within 60 s.
# The node offers this machine's CPUs and memory (slurmd -C). tests/apps/sweep_slurm_test.sh
# starts its Slurm with this script, in a temporary directory.
set -euo pipefail
cmd=${1:-}
dir=$(realpath -m "${2:-runs/slurm-local}")
conf=$dir/slurm.conf
stop() {
  for f in slurmctld slurmd munged; do
    [ -f "$dir/$f.pid" ] || continue
    p=$(cat "$dir/$f.pid")
    kill "$p" 2>/dev/null || true
    for _ in $(seq 50); do kill -0 "$p" 2>/dev/null || break; sleep 0.1; done
    kill -9 "$p" 2>/dev/null || true
    rm -f "$dir/$f.pid"
  done
}
case "$cmd" in
  stop) stop; echo "stopped the Slurm in $dir"; exit 0 ;;
  start) ;;
  *) echo "usage: $0 start|stop [DIR]" >&2; exit 2 ;;
esac
for b in munged mungekey slurmctld slurmd sinfo; do
  command -v "$b" >/dev/null || { echo "$b is not installed (scripts/install-deps.sh installs slurm-wlm and munge)" >&2; exit 2; }
done
[ "$(id -u)" -eq 0 ] || { echo "slurmd runs as root here (SlurmUser=root): run as root" >&2; exit 2; }
mkdir -p "$dir/state" "$dir/spool"
chmod 0755 "$dir"
if [ ! -f "$dir/munge.key" ]; then
  mungekey -c -k "$dir/munge.key" || { echo "mungekey failed" >&2; exit 3; }
  chmod 0400 "$dir/munge.key"
fi
munged -f --socket="$dir/munge.sock" --key-file="$dir/munge.key" --pid-file="$dir/munged.pid" \
  --log-file="$dir/munged.log" --seed-file="$dir/munge.seed" ||
  { cat "$dir/munged.log" >&2; echo "munged does not start" >&2; exit 3; }
hw=$(slurmd -C | head -n 1)
cpus=$(sed -n 's/.* CPUs=\([0-9]*\).*/\1/p' <<<"$hw")
mem=$(sed -n 's/.* RealMemory=\([0-9]*\).*/\1/p' <<<"$hw")
if [ -z "$cpus" ] || [ -z "$mem" ]; then
  echo "slurmd -C gives no CPUs/RealMemory: $hw" >&2
  stop
  exit 3
fi
read -r ctld_port node_port < <(python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*[x.getsockname()[1] for x in s])')
cat >"$conf" <<CONF
ClusterName=lifelonglocal
SlurmctldHost=localhost
SlurmctldPort=$ctld_port
SlurmdPort=$node_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge.sock
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
ReturnToService=2
NodeName=localhost CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=local Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$conf
setsid slurmctld -D -f "$conf" >"$dir/slurmctld.out.log" 2>&1 < /dev/null &
pids=($!)
setsid slurmd -D -N localhost -f "$conf" >"$dir/slurmd.out.log" 2>&1 < /dev/null &
pids+=($!)
state=""
for _ in $(seq 120); do
  for p in "${pids[@]}"; do
    kill -0 "$p" 2>/dev/null && continue
    for f in "$dir"/*.log; do echo "--- $f" >&2; tail -n 30 "$f" >&2; done
    echo "a Slurm daemon exited at start" >&2
    stop
    exit 3
  done
  state=$(sinfo -h -n localhost -o %T 2>/dev/null || true)
  [ "$state" = idle ] && break
  sleep 0.5
done
if [ "$state" != idle ]; then
  echo "the node is not idle after 60 s (sinfo: '$state'); logs in $dir" >&2
  stop
  exit 1
fi
echo "Slurm up: one node, $cpus CPUs. Now: export SLURM_CONF=$conf"
