#!/bin/bash
# Example Slurm job array: the full thesis tables split into N shards, one per array task,
# then merged. Submit from the repository root after building (harness/scripts/build.sh):
#
#   sbatch --array=1-8 harness/scripts/slurm_table.sh            # 8 shards
#   # when all tasks are done:
#   build/sdfbench merge results/shards/table_*.csv --csv results/all.csv --markdown results/all.md
#
# Each task is independent and resumable: a task that is killed (time limit, preemption) and
# requeued continues its own shard's CSV with --resume instead of starting over.
#SBATCH --job-name=sdfbench-table
#SBATCH --cpus-per-task=16
#SBATCH --time=12:00:00
#SBATCH --output=results/shards/slurm-%A_%a.log
#SBATCH --requeue
set -euo pipefail

shards=${SLURM_ARRAY_TASK_COUNT:?run as a job array: sbatch --array=1-N}
task=${SLURM_ARRAY_TASK_ID:?}
# Task ids of --array=1-N are 1..N: exactly the K of --shard K/N.
mkdir -p results/shards
export LP_NUM_THREADS=${SLURM_CPUS_PER_TASK:-$(nproc)}  # lavapipe's threads = the cores Slurm gave us

exec build/sdfbench table --table all --size 1280x720 --budget-s 600 \
  --shard "${task}/${shards}" --resume \
  --csv "results/shards/table_${task}_of_${shards}.csv" \
  --markdown "results/shards/table_${task}_of_${shards}.md" "$@"
