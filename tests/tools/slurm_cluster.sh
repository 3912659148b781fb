#!/usr/bin/env bash
# A one-node Slurm cluster on this host for the scale-out test (SPEC §13): munged, slurmctld and
# slurmd as root with a locally made munge key, everything (config, state, spool, logs, socket)
# under DIR, on ports nothing else uses. `start` prints the environment to export (SLURM_CONF);
# `stop` stops exactly the daemons `start` started (their pid files) and is safe to call twice.
# Usage: slurm_cluster.sh start DIR | stop DIR
set -uo pipefail
cmd=${1:-}; dir=$(realpath -m "${2:-}")
[[ ( $cmd == start || $cmd == stop ) && -n ${2:-} ]] || { echo "usage: $0 start|stop DIR" >&2; exit 2; }

stop() {
  for pidfile in "$dir/slurmd.pid" "$dir/slurmctld.pid" "$dir/munged.pid"; do
    [[ -s $pidfile ]] || continue
    pid=$(cat "$pidfile")
    kill "$pid" 2>/dev/null
    for _ in $(seq 1 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -9 "$pid" 2>/dev/null
    rm -f "$pidfile"
  done
}
if [[ $cmd == stop ]]; then stop; exit 0; fi

for tool in munged mungekey slurmctld slurmd sinfo sbatch; do
  command -v $tool >/dev/null || { echo "slurm_cluster: $tool is missing (apt-get install slurm-wlm munge)" >&2; exit 77; }
done
mkdir -p "$dir/state" "$dir/spool" "$dir/munge"
chmod 700 "$dir/munge"
host=$(hostname -s)
free_port() { python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'; }
ctld_port=$(free_port); slurmd_port=$(free_port)
mem=$(awk '/MemTotal/ { print int($2 / 1024 * 0.8) }' /proc/meminfo)

mungekey --create --keyfile "$dir/munge/munge.key" --force >/dev/null 2>&1 || {
  echo "slurm_cluster: mungekey failed" >&2; exit 77; }
chmod 400 "$dir/munge/munge.key"
munged --force --key-file "$dir/munge/munge.key" --socket "$dir/munge/munge.socket" \
  --pid-file "$dir/munged.pid" --log-file "$dir/munged.log" --seed-file "$dir/munge/munge.seed" \
  2>"$dir/munged.err" || { echo "slurm_cluster: munged did not start: $(cat "$dir/munged.err")" >&2; exit 77; }

cat > "$dir/slurm.conf" <<CONF
ClusterName=fovrt-test
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$dir/munge/munge.socket
CredType=cred/munge
MpiDefault=none
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
ReturnToService=2
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
KillWait=5
NodeName=$host CPUs=$(nproc) RealMemory=$mem State=UNKNOWN
PartitionName=fovrt Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$dir/slurm.conf
slurmctld -f "$dir/slurm.conf" 2>"$dir/slurmctld.err" || { echo "slurm_cluster: slurmctld did not start: $(tail -2 "$dir/slurmctld.err")" >&2; stop; exit 77; }
slurmd -f "$dir/slurm.conf" 2>"$dir/slurmd.err" || { echo "slurm_cluster: slurmd did not start: $(tail -2 "$dir/slurmd.err")" >&2; stop; exit 77; }
for _ in $(seq 1 100); do
  [[ $(sinfo -h -o %t 2>/dev/null) == idle* ]] && { echo "export SLURM_CONF=$dir/slurm.conf"; exit 0; }
  sleep 0.2
done
echo "slurm_cluster: the node did not come up: $(sinfo -h 2>&1 | head -2); $(tail -2 "$dir/slurmctld.log" 2>/dev/null)" >&2
stop; exit 77
