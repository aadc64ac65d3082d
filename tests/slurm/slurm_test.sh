#!/usr/bin/env bash
# The cluster workflow (docs/cluster-and-gpu.md, "Running on a cluster") against a real, running Slurm: starts a
# single-node Slurm on this machine (tests/slurm/start_cluster.sh: slurm-wlm 22.05 and munge
# from Debian 12), submits harness/scripts/slurm_table.sh as the README documents, and checks:
#   1. a 3-task array, merged, gives the unsharded run's rows: same keys, order, deterministic columns;
#   2. the script's own errors: outside an array, an array task outside 1..N, no --shards, its flags;
#   3. a task requeued midway (scontrol requeue) resumes its CSV: no row lost or duplicated, log appended;
#   4. a task that reaches its time limit requeues itself (Slurm would end it as TIMEOUT) and completes;
#   5. one task re-run alone (--array=2, --array=3): the shard count comes from --shards, not the array;
#   6. a re-run with other flags into the same folder is refused by --resume, and merge refuses a
#      shard of another run mixed into the folder, naming the file and the difference.
# The daemons it started are stopped by their pid files at the end. Needs root or sudo (packages,
# daemons) and a built build/sdfbench. Takes ~3 minutes on 2 cores.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
cd "$root"
[ -x build/sdfbench ] || { echo "slurm_test: no build/sdfbench (harness/scripts/build.sh first)" >&2; exit 1; }

work=$(mktemp -d /tmp/sdfbench-slurm-test.XXXXXX)
finish() {
  local status=$?
  tests/slurm/stop_cluster.sh "$work/cluster"
  mkdir -p "$work/logs"  # this test's task logs out of the repository (a user's own logs stay)
  while read -r job; do mv -f slurm-sdfbench-"${job}"_*.log "$work/logs/" 2>/dev/null || true; done < <(cat "$work/jobs" 2>/dev/null)
  if [ "$status" -eq 0 ]; then rm -rf "$work"; else echo "slurm_test: files kept in $work" >&2; fi
}
trap finish EXIT

fail() { echo "slurm_test: FAIL: $*" >&2; exit 1; }
ok() { echo "slurm_test: ok: $*"; }
log_of() { echo "slurm-sdfbench-$1.log"; }  # $1: JOB_TASK; the script logs in the submission folder
state_of() { scontrol -o show job "$1" 2>/dev/null | grep -o 'JobState=[A-Z_]*' | sed -n 1p | cut -d= -f2; }
submit() {  # sbatch ARGS...; prints the job id
  local id
  id=$(sbatch --parsable "$@") || fail "sbatch $*"
  echo "$id" >>"$work/jobs"
  echo "$id"
}
wait_done() {  # JOB_TASK [seconds]: waits until the task has ended; prints its final state
  local state
  for _ in $(seq $((${2:-240} * 5))); do
    state=$(state_of "$1")
    case "$state" in COMPLETED | FAILED | CANCELLED | TIMEOUT | NODE_FAIL | OUT_OF_MEMORY | BOOT_FAIL | DEADLINE)
      echo "$state"; return ;;
    esac
    sleep 0.2
  done
  fail "task $1 still '$state' after ${2:-240} s"
}
wait_for() {  # SECONDS DESCRIPTION COMMAND...: polls COMMAND (run anew each time) until it succeeds
  local seconds=$1 what=$2
  shift 2
  for _ in $(seq $((seconds * 5))); do "$@" && return; sleep 0.2; done
  fail "$what: not after $seconds s"
}
rows_in() { [ -f "$1" ] && echo $(($(wc -l <"$1") - 1)) || echo 0; }  # no field of these rows has a line break
has_rows() { [ "$(rows_in "$1")" -ge "$2" ]; }
in_state() { [ "$(state_of "$1")" = "$2" ]; }
start_now() {  # JOB_TASK [FIELD=VALUE...]: a requeued task, started without Slurm's ~2-minute delay
  # slurmd refuses a relaunch in the same second as the requeue ("job credential revoked").
  sleep 2
  scontrol update JobId="$1" StartTime=now "${@:2}"
}
expect_completed() {
  local state
  state=$(wait_done "$1")
  [ "$state" = COMPLETED ] || fail "task $1 ended $state: $(tail -5 "$(log_of "$1")" 2>/dev/null)"
}

SLURM_CONF=$(tests/slurm/start_cluster.sh "$work/cluster")
export SLURM_CONF

# 12 configurations, every row ~4 s (the budget ends its frames), so a task of 4 rows runs long
# enough to be requeued midway and to reach a 1-minute time limit's warning.
configurations=(--table 6.3 --meshes sphere,bunny --objects 1,10 --backends embree,bvh,sdf-octree --warmup 0)
table=("${configurations[@]}" --size 64x36 --check-size 64x36 --frames 100000 --budget-s 4)
script=harness/scripts/slurm_table.sh

# The unsharded run, on the CPUs a task gets (1: Slurm's default --cpus-per-task).
LP_NUM_THREADS=1 build/sdfbench table "${table[@]}" --csv "$work/reference.csv" >"$work/reference.log" 2>&1 ||
  fail "unsharded run: $(tail -3 "$work/reference.log")"
[ "$(rows_in "$work/reference.csv")" -eq 12 ] || fail "unsharded run: $(rows_in "$work/reference.csv") rows, expected 12"
ok "unsharded run: 12 rows"

# 1. The documented submission: a shard folder that does not exist yet, defaults for everything else.
array=$(submit --array=1-3 "$script" --shards 3 --out "$work/shards" -- "${table[@]}")
# 2. Meanwhile the script's errors, each one line naming the fix.
out=$(bash "$script" --shards 3 2>&1) && fail "outside an array: exit 0"
grep -q "not a job array task" <<<"$out" || fail "outside an array: '$out'"
bad=$(submit --array=0,4 "$script" --shards 3 --out "$work/bad")
noshards=$(submit --array=1 "$script" --out "$work/bad")
owned=$(submit --array=1 "$script" --shards 3 --out "$work/bad" -- --csv x.csv)
for case in "${bad}_0:array task 0 is not a shard of 1..3" "${bad}_4:array task 4 is not a shard of 1..3" \
  "${noshards}_1:--shards N (or SDFBENCH_SHARDS) is required" "${owned}_1:'--csv' is set by this script"; do
  task=${case%%:*} message=${case#*:}
  [ "$(wait_done "$task")" = FAILED ] || fail "task $task should have failed"
  grep -qF "slurm_table.sh: error: $message" "$(log_of "$task")" || fail "task $task: no '$message' in its log: $(cat "$(log_of "$task")")"
done
[ ! -e "$work/bad" ] || fail "a failed task created its --out folder"
ok "script errors: outside an array, tasks 0 and 4 of 3, no --shards, --csv given"

# A task whose run has failed rows (vk-rt with the ray-tracing extension hidden: an ERROR row)
# ends FAILED with sdfbench's exit status 4, not COMPLETED.
failing=$(SDFBENCH_VULKAN_HIDE_EXTENSIONS=VK_KHR_ray_tracing_pipeline submit --array=1 "$script" --shards 1 \
  --out "$work/failing" -- --table 6.3 --meshes sphere --objects 1 --backends embree,vk-rt --size 32x18 --check-size 32x18 \
  --frames 1 --warmup 0)
[ "$(wait_done "${failing}_1")" = FAILED ] || fail "task ${failing}_1 with an ERROR row did not fail: $(tail -3 "$(log_of "${failing}_1")")"
scontrol -o show job "${failing}_1" | grep "ExitCode=4:0" >/dev/null ||
  fail "task ${failing}_1: not sdfbench's exit status 4: $(scontrol -o show job "${failing}_1" | grep -o 'ExitCode=[^ ]*')"
ok "a task with an ERROR row ends FAILED with exit status 4"

for k in 1 2 3; do expect_completed "${array}_$k"; done
build/sdfbench merge "$work"/shards/table_*_of_3.csv --csv "$work/merged.csv" --markdown "$work/merged.md" >/dev/null ||
  fail "merge of the 3 shards"
tests/slurm/same_rows.py "$work/reference.csv" "$work/merged.csv" || fail "merged shards differ from the unsharded run"
ok "3-task array + merge = the unsharded run (12 rows, same order and deterministic columns)"

# 3. Task 2 alone, requeued as soon as its first row is written. A requeued job waits ~2 minutes
#    before Slurm starts it again (BeginTime); the test starts it at once.
requeued=$(submit --array=2 "$script" --shards 3 --out "$work/requeue" -- "${table[@]}")
# 4. Task 3 alone with a 1-minute limit: Slurm's warning (USR1 20 s before the end; slurmctld
#    checks every 30 s, so it comes 10-40 s after the start) makes the script requeue it; then
#    the limit is raised, as a user would for the next attempt. Rows of 15 s keep it running
#    past the warning.
limited=$(submit --array=3 --time=1 --signal=B:USR1@20 "$script" --shards 3 --out "$work/timeout" -- "${configurations[@]}" \
  --size 64x36 --check-size 64x36 --frames 100000 --budget-s 15)
csv2="$work/requeue/table_2_of_3.csv"
wait_for 60 "task ${requeued}_2's first row" has_rows "$csv2" 1
scontrol requeue "${requeued}_2"
rows_at_requeue=$(rows_in "$csv2")
[ "$rows_at_requeue" -lt 4 ] || fail "task ${requeued}_2 had finished before the requeue"
wait_for 30 "task ${requeued}_2 pending again" in_state "${requeued}_2" PENDING
start_now "${requeued}_2"
wait_for 75 "task ${limited}_3's time-limit warning" grep -q "time limit near" "$(log_of "${limited}_3")"
wait_for 30 "task ${limited}_3 pending again" in_state "${limited}_3" PENDING
start_now "${limited}_3" TimeLimit=10

expect_completed "${requeued}_2"
tests/slurm/same_rows.py "$work/reference.csv" "$csv2" --rows 1,4,7,10 || fail "requeued task 2's rows"
log2=$(log_of "${requeued}_2")
[ "$(grep -c "attempt" "$log2")" -eq 2 ] || fail "task ${requeued}_2's log has not both attempts: $(cat "$log2")"
grep -q "resume: $rows_at_requeue configuration(s) already in" "$log2" || fail "task ${requeued}_2 did not resume its $rows_at_requeue rows: $(cat "$log2")"
ok "task requeued midway ($rows_at_requeue of 4 rows written) resumed: 4 rows, none lost or twice, log appended"

expect_completed "${limited}_3"
tests/slurm/same_rows.py "$work/reference.csv" "$work/timeout/table_3_of_3.csv" --rows 2,5,8,11 --ignore budget_s,run_id ||
  fail "time-limited task 3's rows"
log3=$(log_of "${limited}_3")
grep -q "attempt 2" "$log3" || fail "task ${limited}_3 did not run again: $(cat "$log3")"
scontrol -o show job "${limited}_3" | grep "Restarts=1" >/dev/null || fail "task ${limited}_3: $(scontrol -o show job "${limited}_3")"
ok "task at its time limit requeued itself and completed (Restarts=1, 4 rows)"

# 6. Other flags (--size) into the folder of the first run: --resume refuses the task's CSV.
other=("${configurations[@]}" --size 48x27 --check-size 48x27 --frames 1)
clash=$(submit --array=1 "$script" --shards 3 --out "$work/shards" -- "${other[@]}")
# ... and a shard of that other run, planted beside the first run's shards 1 and 2.
foreign=$(submit --array=3 "$script" --shards 3 --out "$work/other" -- "${other[@]}")
[ "$(wait_done "${clash}_1")" = FAILED ] || fail "task ${clash}_1 resumed a CSV of other settings"
grep -q "sdfbench: error: --resume: '$work/shards/table_1_of_3.csv' row 1 (run_index 0) was measured with width '64', this run asks for '48'" \
  "$(log_of "${clash}_1")" || fail "task ${clash}_1: $(cat "$(log_of "${clash}_1")")"
tests/slurm/same_rows.py "$work/reference.csv" "$work/shards/table_1_of_3.csv" --rows 0,3,6,9 || fail "the refused run changed shard 1"
expect_completed "${foreign}_3"
mkdir "$work/mixed"
cp "$work"/shards/table_[12]_of_3.csv "$work/other/table_3_of_3.csv" "$work/mixed/"
out=$(build/sdfbench merge "$work"/mixed/table_*_of_3.csv --csv "$work/mixed.csv" 2>&1) && fail "merge mixed two runs: $out"
grep -q "sdfbench: error: '$work/mixed/table_3_of_3.csv' is not from the run of '$work/mixed/table_1_of_3.csv'.*width '64'.*'48'" <<<"$out" ||
  fail "merge of mixed runs: '$out'"
[ ! -e "$work/mixed.csv" ] || fail "merge of mixed runs wrote its output"
ok "other settings: --resume refuses the task's CSV, merge refuses the planted shard (naming file and width)"
echo "slurm_test: all passed"
