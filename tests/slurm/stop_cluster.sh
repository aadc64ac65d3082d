#!/usr/bin/env bash
# Stops the daemons tests/slurm/start_cluster.sh DIR started, by their pid files in DIR.
dir=${1:?usage: stop_cluster.sh DIR}
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
for name in slurmd slurmctld munged; do
  pidfile="$dir/$name.pid"
  [ -s "$pidfile" ] || continue
  pid=$(cat "$pidfile")
  $sudo kill "$pid" 2>/dev/null || continue
  for _ in $(seq 50); do $sudo kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
  $sudo kill -9 "$pid" 2>/dev/null || true
done
exit 0
