#!/usr/bin/env bash
# harness/scripts/gpu_run.sh end to end on lavapipe at a tiny size (issue 17): the device folder,
# every compare agreeing, the tables' rows, and one-line errors for bad flags and devices.
# Usage: tests/gpu_run_test.sh SDFBENCH_BINARY [run|whitted|storage|fetch|reruns] (five ctest tests)
set -euo pipefail
binary=$(realpath "$1")
part=${2:-run}  # run: primary and shadow compares and a table; whitted: its compares; storage, fetch: one sweep each; reruns: --tables-only, the report, resume, retries, errors
root=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
script=$root/harness/scripts/gpu_run.sh

if [[ $part == run ]]; then
# The compares of one mesh in primary and shadow mode (the other meshes run the same loop; the
# whitted part compares the whitted scenes) and a table of one object count and two backends (the
# reruns part runs every backend): --steps leaves out the sweeps (the storage and fetch parts).
"$script" --binary "$binary" --device lavapipe --size 32x18 --compare-size 32x18 --compare-objects 3 --compare-meshes sphere \
  --compare-whitted none --budget-s 1 --frames 1 --steps compares,tables --out "$work/out" -- --table 6.3 --meshes sphere --objects 1 --backends embree,sdf-octree \
  --check-size 32x18 >"$work/log" 2>&1 || { status=$?; tail -20 "$work/log"; fail "gpu_run.sh on lavapipe exited $status"; }
dir=$(echo "$work"/out/llvmpipe-*)
[[ -d $dir ]] || fail "no folder named after the device under $work/out: $(ls "$work/out")"
for f in info.txt agreement.txt tables.csv tables.md tables_command.txt report.html; do [[ -s $dir/$f ]] || fail "$f missing or empty"; done
grep -q "Vulkan devices" "$dir/info.txt" || fail "info.txt lacks sdfbench info's device list"
[[ $(grep -c '^exit 0$' "$dir/agreement.txt") -eq 2 ]] || fail "expected 2 agreeing compares: $(grep '^exit' "$dir/agreement.txt" | sort | uniq -c)"
! grep -q 'mode whitted' "$dir/agreement.txt" || fail "--compare-whitted none compared in whitted mode"
grep -q 'compare --scene thesis:sphere:3 --mode shadow' "$dir/agreement.txt" || fail "no shadow compare of thesis:sphere:3"
! grep -q 'thesis:bunny' "$dir/agreement.txt" || fail "--compare-meshes sphere compared the bunny"
grep -q "vk-rt" "$dir/agreement.txt" || fail "vk-rt (supported on lavapipe) left out of the compares"
[[ ! -e $dir/storage_vs_texel.csv && ! -e $dir/brick_fetch.csv && ! -e $dir/bvh_layouts.csv ]] || fail "--steps compares,tables ran the sweeps"
done_line=$(grep "gpu_run: done:" "$work/log")
[[ $done_line == *agreement.txt*tables.csv*report.html* && $done_line != *storage_vs_texel* ]] || fail "the done line: $done_line"
rows=$(($(wc -l <"$dir/tables.csv") - 1))
[[ $rows -eq 2 ]] || fail "tables.csv has $rows rows, expected 2 (sphere x 1 object x 2 backends)"
grep -q -- "--device lavapipe" "$dir/tables_command.txt" || fail "tables_command.txt does not record the command"
  echo "gpu_run.sh test (run): all passed"
  exit 0
fi

if [[ $part == whitted ]]; then
# The compares of the default whitted scenes alone (--compare-meshes none), every backend agreeing.
"$script" --binary "$binary" --device lavapipe --compare-size 32x18 --compare-meshes none --steps compares --out "$work/out" \
  >"$work/log" 2>&1 || { status=$?; tail -20 "$work/log"; fail "gpu_run.sh --steps compares (whitted) exited $status"; }
dir=$(echo "$work"/out/llvmpipe-*)
[[ -s $dir/info.txt && ! -e $dir/tables.csv ]] || fail "--steps compares: $(ls "$dir")"
[[ $(grep -c '^exit 0$' "$dir/agreement.txt") -eq 2 && $(grep -c '^exit' "$dir/agreement.txt") -eq 2 ]] ||
  fail "expected 2 agreeing compares: $(grep '^exit' "$dir/agreement.txt" | sort | uniq -c)"
for scene in fig6_1 fig6_3; do
  grep -q "compare --scene scenes/$scene.json --mode whitted" "$dir/agreement.txt" || fail "no whitted compare of $scene"
done
! grep -q 'thesis:' "$dir/agreement.txt" || fail "--compare-meshes none compared thesis meshes"
grep -q "vk-rt" "$dir/agreement.txt" || fail "vk-rt (supported on lavapipe) left out of the compares"
  echo "gpu_run.sh test (whitted): all passed"
  exit 0
fi

if [[ $part == storage || $part == fetch ]]; then
# One sweep step alone (--steps storage or fetch; two tests, so that each compiles half the sweeps'
# kernels), in primary mode (--sweep-modes; shadow runs the same loop and compiles twice as long):
# no compares, no tables, no other sweep, the report of the sweep's CSV.
"$script" --binary "$binary" --device lavapipe --size 32x18 --budget-s 1 --frames 1 --steps "$part" \
  --storage-scene thesis:sphere:3 --sweep-modes primary --out "$work/out" >"$work/log" 2>&1 ||
  { status=$?; tail -20 "$work/log"; fail "gpu_run.sh --steps $part exited $status"; }
dir=$(echo "$work"/out/llvmpipe-*)
[[ ! -e $dir/agreement.txt && ! -e $dir/tables.csv && ! -e $dir/info.txt ]] || fail "--steps $part ran more: $(ls "$dir")"
if [[ $part == storage ]]; then
  # Texel vs storage buffers: 2 backends x both, every row agreeing.
  csv=$dir/storage_vs_texel.csv other=brick_fetch.csv
  column=$(head -1 "$csv" | tr ',' '\n' | grep -nx storage_tables | cut -d: -f1)
  [[ -n $column && $(awk -F, -v c="$column" 'NR > 1 && $c == 1' "$csv" | wc -l) -eq 2 ]] ||
    fail "storage_vs_texel.csv does not hold 2 storage-buffer rows (storage_tables=1)"
else
  # The sampled fields' fetch paths: sdf-bricks and sdf-global x texel and sampler, every row agreeing.
  csv=$dir/brick_fetch.csv other=storage_vs_texel.csv
  grep -q "brick_fetch=sampler" "$csv" || fail "brick_fetch.csv has no sampler row"
fi
[[ -s ${csv%.csv}.md ]] || fail "${csv%.csv}.md missing or empty"
[[ ! -e $dir/$other ]] || fail "--steps $part ran the other sweep ($other)"
rows=$(($(wc -l <"$csv") - 1))
[[ $rows -eq 4 ]] || fail "$(basename "$csv") has $rows rows, expected 4"
[[ $(grep -c ',ok,' "$csv") -eq 4 ]] || fail "not every $(basename "$csv") row agrees"
[[ $(grep -c ',primary,' "$csv") -eq 4 ]] || fail "--sweep-modes primary ran other modes"
[[ $(grep -o '<tr id="f0r[0-9]*"' "$dir/report.html" | wc -l) -eq 4 ]] || fail "report.html does not show the sweep's 4 rows"
done_line=$(grep "gpu_run: done:" "$work/log")
[[ $done_line == *"$(basename "$csv")"*report.html* && $done_line != *"$other"* && $done_line != *agreement* && $done_line != *tables.csv* ]] ||
  fail "the done line: $done_line"
if [[ $part == fetch ]]; then
  # A second call in the same folder merges only its own CSVs, not another call's (a shadow one).
  cp "$dir/brick_fetch/sdf-bricks_primary.csv" "$dir/brick_fetch/sdf-bricks_shadow.csv"
  "$script" --binary "$binary" --device lavapipe --size 32x18 --budget-s 1 --frames 1 --steps fetch \
    --storage-scene thesis:sphere:3 --sweep-modes primary --out "$work/out" >"$work/log2" 2>&1 ||
    { status=$?; tail -20 "$work/log2"; fail "the second --steps fetch call exited $status"; }
  rows=$(($(wc -l <"$csv") - 1))
  [[ $rows -eq 4 ]] || fail "a second call merged $rows rows into brick_fetch.csv, expected its own 4"
fi
  echo "gpu_run.sh test ($part): all passed"
  exit 0
fi

# The reruns: a tables-only run to resume, a failing row retried, a relative --out, bad flags.
"$script" --binary "$binary" --device lavapipe --size 32x18 --budget-s 1 --frames 1 --out "$work/out" --tables-only \
  -- --table 6.3 --meshes sphere --objects 1,10 --check-size 32x18 >"$work/log" 2>&1 || { tail -5 "$work/log"; fail "--tables-only run exited non-zero"; }
dir=$(echo "$work"/out/llvmpipe-*)
rows=$(($(wc -l <"$dir/tables.csv") - 1))
[[ $rows -eq 16 ]] || fail "tables.csv has $rows rows, expected 16 (sphere x 1,10 objects x 8 backends)"
# The report: every table row on the page with its three kept images.
[[ $(ls "$dir"/images/*.png | wc -l) -eq 48 ]] || fail "expected 48 kept images (16 rows x 3) in $dir/images"
[[ $(grep -o '<tr id="f0r[0-9]*"' "$dir/report.html" | wc -l) -eq 16 ]] || fail "report.html does not show the 16 table rows"
[[ $(grep -o '<img src="report_files/' "$dir/report.html" | wc -l) -ge 48 ]] || fail "report.html lacks the rows' images"
cp "$dir/tables.csv" "$work/before.csv"
"$script" --binary "$binary" --device lavapipe --size 32x18 --budget-s 1 --frames 1 --out "$work/out" --tables-only \
  -- --table 6.3 --meshes sphere --objects 1,10 --check-size 32x18 >"$work/log2" 2>&1 || { tail -5 "$work/log2"; fail "--tables-only rerun exited non-zero"; }
grep -q "16 configuration(s) already" "$work/log2" || fail "the rerun did not resume: $(grep -m2 resume "$work/log2")"
! grep -q "gpu_run: compare" "$work/log2" || fail "--tables-only ran the compares"
done_line=$(grep "gpu_run: done:" "$work/log2")
[[ $done_line == *tables.csv* && $done_line != *agreement.txt* ]] || fail "--tables-only's done line names files it did not write: $done_line"
cmp -s "$work/before.csv" "$dir/tables.csv" || fail "the rerun changed the finished tables"

# Failed rows reach the exit status: with the ray-tracing extension hidden, the table's vk-rt
# rows are ERROR rows, so the run exits 4 (and a run again retries them).
status=0
SDFBENCH_VULKAN_HIDE_EXTENSIONS=VK_KHR_ray_tracing_pipeline "$script" --binary "$binary" --device lavapipe --size 32x18 \
  --budget-s 1 --frames 1 --out "$work/failing" --tables-only -- --table 6.3 --meshes sphere --objects 1 \
  --backends embree,vk-rt --check-size 32x18 >"$work/log3" 2>&1 || status=$?
[[ $status -eq 4 ]] || { tail -5 "$work/log3"; fail "a table with ERROR rows: gpu_run.sh exited $status, expected 4"; }
grep -q "some configurations failed" "$work/log3" || fail "gpu_run.sh did not say that configurations failed: $(tail -3 "$work/log3")"
"$script" --binary "$binary" --device lavapipe --size 32x18 --budget-s 1 --frames 1 --out "$work/failing" --tables-only \
  -- --table 6.3 --meshes sphere --objects 1 --backends embree,vk-rt --check-size 32x18 >"$work/log4" 2>&1 ||
  { tail -5 "$work/log4"; fail "the rerun with ray tracing did not finish cleanly"; }
grep -q "retrying 1 configuration" "$work/log4" || fail "the rerun did not retry the failed row: $(grep -m2 resume "$work/log4")"

# --out is relative to the folder the script is started from, not the repository.
(cd "$work" && "$script" --binary "$binary" --device lavapipe --size 32x18 --budget-s 1 --frames 1 --out relout --tables-only \
  -- --table 6.3 --meshes sphere --objects 1 --backends embree --check-size 32x18 >"$work/log5" 2>&1) ||
  { tail -5 "$work/log5"; fail "--out relout failed"; }
ls "$work"/relout/llvmpipe-*/tables.csv >/dev/null 2>&1 || fail "--out relout did not write under the caller's folder"

# Bad input: one line naming the flag or device, exit 1.
expect_error() {  # PATTERN ARGS...
  local pattern=$1 status=0
  shift
  "$script" --binary "$binary" --out "$work/bad" "$@" >"$work/err" 2>&1 || status=$?
  [[ $status -eq 1 ]] || fail "'$*' exited $status, expected 1"
  grep -q "^gpu_run.sh: error: .*$pattern" "$work/err" || fail "'$*' said: $(cat "$work/err")"
}
expect_error "unknown argument '--bogus'" --bogus
expect_error "no Vulkan device 'no-such-gpu'" --device no-such-gpu
expect_error "--minutes takes whole minutes" --minutes 0
expect_error "--binary '/nonexistent'" --binary /nonexistent
expect_error "--size needs a value" --size
expect_error "--size takes WIDTHxHEIGHT" --size 0x10
expect_error "--compare-size takes WIDTHxHEIGHT" --compare-size big
expect_error "--frames takes a whole number" --frames x
expect_error "--compare-objects takes a whole number" --compare-objects 0
expect_error "--compare-meshes takes mesh names" --compare-meshes 'bunny;rm'
expect_error "--compare-meshes takes mesh names" --compare-meshes ''
expect_error "--budget-s takes seconds" --budget-s -1
expect_error "--steps takes compares, storage, fetch, layouts and tables" --steps compares,plots
expect_error "--steps takes compares, storage, fetch, layouts and tables" --steps sweeps
expect_error "--sweep-modes takes primary, shadow and whitted" --sweep-modes primary,diagonal
expect_error "--compare-whitted: no scene file '$work/nosuch.json'" --compare-whitted "$work/nosuch.json"
expect_error "--compare-whitted takes scenes separated by commas" --compare-whitted 'scenes/fig6_1.json,'
expect_error "--compare-meshes takes mesh names" --compare-meshes none,
[[ ! -e $work/bad ]] || fail "a refused run created its output folder"
echo "gpu_run.sh test (reruns): all passed"
