#!/usr/bin/env bash
# Starts a single-node Slurm cluster on this machine for the Slurm test: installs slurm-wlm and
# munge (no recommends), writes slurm.conf from `slurmd -C` into $1 (proctrack/linuxproc,
# task/none, no cgroups, no accounting; its own ports, state and spool under $1, so no system
# config changes; the daemons talk over 127.0.0.1, so the host name need not resolve), starts
# munged (as the munge user, /run/munge created) unless one answers, then slurmctld and slurmd,
# and waits until the node is idle. Prints the SLURM_CONF to export.
# tests/slurm/stop_cluster.sh $1 stops what this started, by its pid files.
set -euo pipefail
dir=${1:?usage: start_cluster.sh DIR}
mkdir -p "$dir"
dir=$(cd "$dir" && pwd)
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
log() { echo "start_cluster: $*" >&2; }

if ! command -v slurmctld >/dev/null || ! command -v slurmd >/dev/null || ! command -v munged >/dev/null; then
  log "installing slurm-wlm and munge"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends slurm-wlm munge >/dev/null
fi

# munged runs as the munge user; its socket folder /run/munge must exist and be theirs.
if ! munge -n 2>/dev/null | unmunge >/dev/null 2>&1; then
  [ -s /etc/munge/munge.key ] || $sudo runuser -u munge -- mungekey --create
  $sudo mkdir -p /run/munge
  $sudo chown munge:munge /run/munge
  $sudo chmod 0755 /run/munge
  $sudo runuser -u munge -- /usr/sbin/munged
  for _ in $(seq 50); do munge -n 2>/dev/null | unmunge >/dev/null 2>&1 && break; sleep 0.1; done
  munge -n | unmunge >/dev/null || { log "munged does not answer"; exit 1; }
  cp /run/munge/munged.pid "$dir/munged.pid"  # ours to stop (the munge user writes only in /run/munge)
fi

node_line=$(slurmd -C | sed -n 1p)  # NodeName=... CPUs=... RealMemory=...
node=$(sed -n 's/^NodeName=\([^ ]*\).*/\1/p' <<<"$node_line")
mkdir -p "$dir/state" "$dir/spool"
cat >"$dir/slurm.conf" <<CONF
ClusterName=sdfbench-test
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=16817
SlurmdPort=16818
SlurmUser=root
AuthType=auth/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
MpiDefault=none
ReturnToService=2
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
$node_line NodeAddr=127.0.0.1 State=UNKNOWN
PartitionName=test Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$dir/slurm.conf"
$sudo env SLURM_CONF="$SLURM_CONF" slurmctld -c  # -c: a clean start, no state of an earlier test
$sudo env SLURM_CONF="$SLURM_CONF" slurmd
for _ in $(seq 120); do
  state=$(sinfo -h -N -o %T 2>/dev/null | sed -n 1p || true)
  [ "$state" = idle ] && break
  sleep 0.5
done
[ "$state" = idle ] || { log "node '$node' is '${state:-not known}' after 60 s (see $dir/slurmctld.log, $dir/slurmd.log)"; exit 1; }
log "node $node idle ($node_line)"
echo "$SLURM_CONF"
