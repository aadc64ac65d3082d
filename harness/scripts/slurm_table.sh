#!/bin/bash
# A Slurm job array that runs one sdfbench table (or sweep) in N shards, one shard per array
# task; merge the shard CSVs when every task is done. Submit from the repository root after
# building (harness/scripts/build.sh); docs/cluster-and-gpu.md, "Running on a cluster":
#
#   sbatch --array=1-8 harness/scripts/slurm_table.sh --shards 8                 # the full tables
#   sbatch --array=1-3 --cpus-per-task=2 harness/scripts/slurm_table.sh --shards 3 --out results/small \
#       -- --table 6.1 --size 320x180 --budget-s 60                              # any table flags after --
#   sbatch --array=2,5 harness/scripts/slurm_table.sh --shards 8                 # re-run tasks 2 and 5 of 8
#   build/sdfbench merge results/shards/table_*_of_8.csv --csv results/all.csv --markdown results/all.md
#
# Options (before --; each also from the environment):
#   --shards N     shards in the whole run (SDFBENCH_SHARDS; required): array task K runs shard K/N,
#                  so K must be in 1..N; N never comes from the array, so some tasks can be re-run
#   --out DIR      shard CSVs and markdown (SDFBENCH_OUT, default results/shards; created)
#   --sweep        run `sdfbench sweep` instead of `sdfbench table` (SDFBENCH_COMMAND=sweep)
#   --binary PATH  the sdfbench binary (SDFBENCH, default build/sdfbench in the submission directory)
# Everything after -- goes to sdfbench table/sweep unchanged; --shard, --csv, --markdown and
# --resume are this script's.
#
# Each task resumes its own CSV (--resume), so a requeued task continues where it stopped (and
# runs again the configurations that failed), and a CSV of another run (other flags) is refused,
# not mixed in. The task exits with sdfbench's status: 0 all rows agree, 2 some disagree, 4 some
# configurations failed (ERROR rows), 1 an error; Slurm shows it as the task's exit code. Slurm does not requeue a task
# that reaches its time limit, so Slurm signals this script (USR1) 5 minutes before it: the
# script stops sdfbench (the CSV is complete up to the last finished row) and requeues the
# task. Lavapipe (and Embree, by default) get the CPUs Slurm allocated (--cpus-per-task, default 1).
#SBATCH --job-name=sdfbench-table
#SBATCH --time=12:00:00
#SBATCH --signal=B:USR1@300
#SBATCH --requeue
#SBATCH --open-mode=append
#SBATCH --output=slurm-sdfbench-%A_%a.log
set -euo pipefail

die() { echo "slurm_table.sh: error: $*" >&2; exit 1; }

shards=${SDFBENCH_SHARDS:-}
out=${SDFBENCH_OUT:-results/shards}
command=${SDFBENCH_COMMAND:-table}
binary=${SDFBENCH:-}
while [ $# -gt 0 ]; do
  case "$1" in
    --shards) [ $# -ge 2 ] || die "--shards needs a number"; shards=$2; shift 2 ;;
    --out) [ $# -ge 2 ] || die "--out needs a folder"; out=$2; shift 2 ;;
    --sweep) command=sweep; shift ;;
    --binary) [ $# -ge 2 ] || die "--binary needs a path"; binary=$2; shift 2 ;;
    --) shift; break ;;
    *) die "unknown option '$1' (sdfbench's own flags go after --)" ;;
  esac
done
for arg in "$@"; do
  case "$arg" in
    --shard|--shard=*|--csv|--csv=*|--markdown|--markdown=*|--resume) die "'$arg' is set by this script (one shard per task, CSVs in --out)" ;;
  esac
done
case "$command" in table|sweep) ;; *) die "SDFBENCH_COMMAND '$command': expected table or sweep" ;; esac

task=${SLURM_ARRAY_TASK_ID:-}
[ -n "$task" ] || die "not a job array task: submit it as sbatch --array=1-N $0 --shards N"
[ -n "$shards" ] || die "--shards N (or SDFBENCH_SHARDS) is required: the number of shards of the whole run, e.g. --shards 8 with --array=1-8"
# (at most 6 digits before any arithmetic: a longer number would overflow the shell's integers)
[[ "$shards" =~ ^[1-9][0-9]{0,5}$ ]] && [ "$shards" -le 100000 ] || die "--shards '$shards': expected a positive integer up to 100000"
[[ "$task" =~ ^[0-9]{1,6}$ ]] && [ "$task" -ge 1 ] && [ "$task" -le "$shards" ] ||
  die "array task $task is not a shard of 1..$shards: use --array within 1-$shards (e.g. --array=1-$shards or --array=2,5)"

cd "${SLURM_SUBMIT_DIR:-.}"
binary=${binary:-build/sdfbench}
[ -x "$binary" ] || die "no sdfbench binary at '$binary' (build first: harness/scripts/build.sh, or pass --binary)"
mkdir -p "$out"

# Lavapipe's and Embree's threads: the CPUs allocated to this task, not the node's.
cpus=${SLURM_CPUS_PER_TASK:-${SLURM_CPUS_ON_NODE:-1}}
export LP_NUM_THREADS=$cpus

job="${SLURM_ARRAY_JOB_ID:-${SLURM_JOB_ID:-}}_${task}"
echo "=== $(date -Is) task $job: $command shard $task/$shards on $(hostname), $cpus CPU(s), attempt $((${SLURM_RESTART_COUNT:-0} + 1))"

base="$out/${command}_${task}_of_${shards}"
child=""
on_time_limit() {
  echo "=== $(date -Is) task $job: time limit near: stopping sdfbench and requeueing (rows so far are kept in $base.csv)"
  if [ -n "$child" ]; then
    kill -TERM "$child" 2>/dev/null || true
    wait "$child" 2>/dev/null || true
  fi
  scontrol requeue "$job" || die "scontrol requeue $job failed; re-run this task with sbatch --array=$task"
  exit 0
}
trap on_time_limit USR1
"$binary" "$command" "$@" --shard "$task/$shards" --resume --csv "$base.csv" --markdown "$base.md" &
child=$!

# wait returns early when a trapped signal arrives; the trap then ends the script.
status=0
wait "$child" || status=$?
echo "=== $(date -Is) task $job: sdfbench exited with $status"
exit "$status"
