#!/usr/bin/env bash
# Regenerates every committed result of one device folder (issue 40): the thesis tables, the
# sampled fields, the real scans, the atrium, the overlap axis, the mesh-size axis, the structure
# sweeps, the agreement compares and the kernel profile, then the plots and the report, all from
# one build at one commit. The steps and their commands are listed by --list; results/README.md
# says what each file is and quotes the figures.
#
#   harness/scripts/reproduce_results.sh [--quick] [--out DIR] [--device lavapipe] [--binary B]
#       [--only STEP[,STEP...]] [--fresh] [--allow-dirty] [--list]
#
# --out: the results folder (default results; --quick: build/reproduce-quick); the device's
#   folder under it is results/lavapipe for lavapipe, else the device's name as gpu_run.sh names it.
# --quick: one small row of each step (64x36, one object, one value per axis): a check of the
#   script and of every command it runs, a few minutes on 2 cores (CI runs it).
# Resumable: every table and sweep writes its CSV after each row and runs with --resume, and each
#   finished step is recorded in DIR/<device>/.reproduce/; run the same command again to finish an
#   interrupted run. The record holds the commit and CPU: a run is only resumed with the same
#   binary commit on the same CPU model (--fresh starts over, removing the record and the step outputs).
# A dirty tree is refused (its rows could not be reproduced from any commit) unless --allow-dirty,
#   and then every row's commit column says "-dirty".
# Exit status: 0 every row ran and agreed (≈ approximations included), 2 some row or compare
#   disagreed, 4 some configuration failed (ERROR rows; run again to retry them), 1 an error.
set -euo pipefail
caller_dir=$PWD
cd "$(dirname "$0")/../.."
die() { echo "reproduce_results: error: $*" >&2; exit 1; }
from_caller() { if [[ $1 == /* ]]; then echo "$1"; else echo "$caller_dir/$1"; fi; }

quick=0 out="" device=lavapipe binary=build/sdfbench only="" fresh=0 allow_dirty=0 list=0
while [[ $# -gt 0 ]]; do
  case "$1" in
    --quick) quick=1; shift ;;
    --fresh) fresh=1; shift ;;
    --allow-dirty) allow_dirty=1; shift ;;
    --list) list=1; shift ;;
    --out|--device|--binary|--only)
      [[ $# -ge 2 ]] || die "$1 needs a value"
      case "$1" in
        --out) out=$(from_caller "$2") ;; --device) device=$2 ;; --binary) binary=$(from_caller "$2") ;; --only) only=$2 ;;
      esac
      shift 2 ;;
    -h|--help) sed -n 2,24p "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) die "unknown argument '$1' (see --help)" ;;
  esac
done
[[ -n $out ]] || { [[ $quick -eq 1 ]] && out=$PWD/build/reproduce-quick || out=$PWD/results; }

# The sizes of a full run (about two hours on 2 cores with lavapipe) and of --quick.
if [[ $quick -eq 1 ]]; then
  size=64x36 small=64x36 check=32x18 frames=1 warmup=0 budget=5 compare_size=64x36
else
  size=640x360 small=320x180 check=320x180 frames=3 warmup=1 budget=30 compare_size=320x180
fi
# A list as given for a full run; its first value with --quick.
q() { if [[ $quick -eq 1 ]]; then echo "${1%%,*}"; else echo "$1"; fi; }

# ---- The steps: name, estimated minutes of a full run on 2 cores, what it writes ----
steps=(tables primary scans atrium overlap_1000 overlap_1000_shadow overlap_10000 mesh_sizes
       thesis_structure options sdf_bricks_sweeps sdf_global_sweeps exact_levers storage_vs_texel
       bvh_layouts bvh_overlap agreement profile)
declare -A minutes=(
  [tables]=20 [primary]=8 [scans]=36 [atrium]=7 [overlap_1000]=7 [overlap_1000_shadow]=6 [overlap_10000]=9
  [mesh_sizes]=8 [thesis_structure]=3 [options]=3 [sdf_bricks_sweeps]=7 [sdf_global_sweeps]=6 [exact_levers]=4
  [storage_vs_texel]=3 [bvh_layouts]=8 [bvh_overlap]=12 [agreement]=6 [profile]=1)
declare -A what=(
  [tables]="thesis tables 6.1-6.3 (whitted, shadow): the four thesis meshes x 1/10/100/1000, every backend"
  [primary]="the same meshes and counts in primary mode, every backend"
  [scans]="the five scans x 1/10/100/1000, every backend (tri-aabb x1000 in files of its own), primary and shadow"
  [atrium]="the generated interior, every backend but sdf-cpu, primary/shadow/whitted"
  [overlap_1000]="the overlap axis: bunny and teapot x1000, k 1/4/16/50, every backend, primary"
  [overlap_1000_shadow]="the overlap axis in shadow mode"
  [overlap_10000]="the overlap axis at 10000 objects, k 1/16/50, every backend but tri-aabb, primary"
  [mesh_sizes]="the bunny resized to 1k/16k/256k triangles, 1 and 10 objects, every backend, primary"
  [thesis_structure]="sdf-octree: hash cell 1/2/5/10 x octree depth 0/2/4 on bunny:1000"
  [options]="sdf-octree: --over-relax 1/1.2/1.5/1.8 x --cell-bound 0/1 on bunny:1000"
  [sdf_bricks_sweeps]="sdf-bricks: voxels x format x trace mode, exact and field hits, bunny:1000"
  [sdf_global_sweeps]="sdf-global: voxel x band (exact), voxel (field hits), format x fetch, bunny:1000"
  [exact_levers]="sdf-global's exact-hit levers: --exact-near x --exact-window, --exact-lists triangles x --list-split"
  [storage_vs_texel]="texel against storage buffers: sdf-octree, sdf-global, primary and shadow"
  [bvh_layouts]="bvh: width 2/4/8 x float/quantised nodes x instanced/rebraided/flat top, Embree single/packets x instanced/flat, bunny:1000, primary and shadow"
  [bvh_overlap]="the dense overlap (bunny x10000, k 50): bvh's layouts and top levels beside Embree's modes and sdf-global, primary"
  [agreement]="compare of every backend with Embree: thesis meshes x100 in every mode, fig6_1/6_3/6_5 whitted"
  [profile]="where lavapipe's JIT code spends sdf-global's time (perf), bunny:1000 primary")
if [[ $list -eq 1 ]]; then
  total=0
  for s in "${steps[@]}"; do printf '%-20s ~%3s min  %s\n' "$s" "${minutes[$s]}" "${what[$s]}"; total=$((total + ${minutes[$s]})); done
  echo "total ~$total min on 2 cores (lavapipe)"
  exit 0
fi
if [[ -n $only ]]; then
  IFS=, read -ra chosen <<<"$only"
  for s in "${chosen[@]}"; do [[ -n ${minutes[$s]:-} ]] || die "--only: no step '$s' (see --list)"; done
  steps=("${chosen[@]}")
fi

# ---- What runs, checked before any work ----
[[ -x $binary ]] || die "--binary '$binary' is not an executable (build first: harness/scripts/build.sh)"
binary=$(realpath "$binary")
head=$(git rev-parse --short=12 HEAD 2>/dev/null) || die "not in a git checkout: the rows could name no commit"
version=$("$binary" info 2>/dev/null | sed -n '1s/^.*(commit \(.*\))$/\1/p')
[[ -n $version ]] || die "'$binary info' names no commit"
if [[ -n $(git status --porcelain --untracked-files=no) ]]; then
  [[ $allow_dirty -eq 1 ]] || die "the tree has uncommitted changes: no commit reproduces rows measured now (commit, or --allow-dirty to mark every row -dirty)"
  echo "reproduce_results: warning: a dirty tree (--allow-dirty): every row's commit says -dirty" >&2
fi
[[ ${version%-dirty} == "$head" ]] || die "'$binary' was built from commit $version, not HEAD ($head): rebuild first"
[[ $version != *-dirty || $allow_dirty -eq 1 ]] || die "'$binary' was built from a dirty tree ($version): rebuild from the clean tree"
probe=$("$binary" render --scene thesis:sphere:1 --backend sdf-hash --size 16x9 --frames 1 --warmup 0 --device "$device" 2>&1) ||
  die "no Vulkan device '$device': $(grep -m1 'error' <<<"$probe" || tail -1 <<<"$probe")"
name=$(sed -n 's/^backend  *sdf-hash on \(.*\) \[.*$/\1/p' <<<"$probe" | sed -n 1p)
[[ -n $name ]] || die "could not read the device's name from: $(head -3 <<<"$probe")"
if [[ $name == llvmpipe* ]]; then slug=lavapipe; else slug=$(tr 'A-Z' 'a-z' <<<"$name" | sed 's/[^a-z0-9]\+/-/g; s/^-//; s/-$//'); fi
dir="$out/$slug" record="$out/$slug/.reproduce"
cpu=$(grep -m1 '^model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')
mkdir -p "$dir"

# The record: one commit and one CPU per snapshot.
if [[ $fresh -eq 1 && -d $record ]]; then
  while read -r output; do rm -rf "${dir:?}/$output"; done < <(cat "$record"/*.outputs 2>/dev/null || true)
  rm -rf "$record"
fi
if [[ -f $record/run ]]; then
  prev_version=$(sed -n 's/^version //p' "$record/run") prev_cpu=$(sed -n 's/^cpu //p' "$record/run")
  [[ $prev_version == "$version" ]] ||
    die "$dir holds a run of another binary ($prev_version; this is $version): --fresh to start over"
  [[ $prev_cpu == "$cpu" ]] || die "$dir holds a run on another CPU ($prev_cpu; this is $cpu): --fresh to start over"
  echo "reproduce_results: resuming the run in $dir" >&2
else
  # A new run into a folder that holds results of another (a committed snapshot, a checkout's old
  # files) would resume their CSVs: move them away first (results/history/ keeps old snapshots).
  old=$(find "$dir" -maxdepth 1 \( -name '*.csv' -o -name '*.txt' \) -print -quit)
  if [[ -n $old && -f $dir/COMMANDS.md ]]; then  # a snapshot this script wrote (git keeps the committed one)
    echo "reproduce_results: replacing the snapshot in $dir" >&2
    rm -rf "${dir:?}"/*.csv "$dir"/*.md "$dir"/*.txt "$dir"/plots "$dir"/report.html "$dir"/report_files "$dir"/images "$dir"/parts
    old=
  fi
  [[ -z $old ]] || die "$dir holds results of another run ($(basename "$old"), ...): move them away (e.g. git mv to results/history/) or give another --out"
  mkdir -p "$record"
  printf 'version %s\ncpu %s\nstarted %s\nquick %s\n' "$version" "$cpu" "$(date -u +%FT%TZ)" "$quick" >"$record/run"
fi

common=(--frames "$frames" --warmup "$warmup" --budget-s "$budget" --check-size "$check" --device "$device")
status_of_run=0
note_status() {  # a command's exit status: 2 disagreement, 4 failed rows, else an error
  case $1 in
    0) ;; 2) [[ $status_of_run -eq 4 ]] || status_of_run=2 ;; 4) status_of_run=4 ;;
    *) die "step '$step' failed (exit $1); its log: $record/$step.log" ;;
  esac
}
# One command of a step: logged, its exit status noted, its output files recorded.
run() {  # OUTPUT... -- COMMAND...
  local outputs=()
  while [[ $1 != -- ]]; do outputs+=("$1"); shift; done
  shift
  printf '%s\n' "${outputs[@]}" >>"$record/$step.outputs"
  printf '%s\n' "$*" | sed "s|$dir/||g; s|$binary|sdfbench|g" >>"$record/$step.commands"
  local status=0
  "$@" >>"$record/$step.log" 2>&1 || status=$?
  note_status $status
}
images() { echo "$dir/images/$1"; }
# A table or sweep into NAME.csv/.md with its check images, resumable.
measure() {  # NAME sdfbench-COMMAND FLAGS...
  local name=$1 command=$2
  shift 2
  run "$name.csv" "$name.md" "images/$name" -- "$binary" "$command" "$@" "${common[@]}" --resume \
    --csv "$dir/$name.csv" --markdown "$dir/$name.md" --keep-images "$(images "$name")"
}
# Several sweeps (one backend or mode each) merged into NAME.csv/.md.
merge_parts() {  # NAME PART...
  local name=$1
  shift
  run "$name.csv" "$name.md" -- "$binary" merge "$@" --several-runs --csv "$dir/$name.csv" --markdown "$dir/$name.md"
}
part() { echo "$dir/parts/$1.csv"; }
# A sweep into parts/NAME.csv with its images (for merge_parts).
measure_part() {  # NAME FLAGS...
  local name=$1
  shift
  mkdir -p "$dir/parts"
  run "parts/$name.csv" "images/$name" -- "$binary" sweep "$@" "${common[@]}" --resume --csv "$(part "$name")" \
    --keep-images "$(images "$name")"
}

# --quick: 100 objects where a full run has 1000 or 10000 (the builds of big scenes are most of its time).
many=1000 dense=10000 compare_objects=100
[[ $quick -eq 0 ]] || many=100 dense=100 compare_objects=10
thesis_meshes=$(q bunny,teapot,monkey,sphere) counts=$(q 1,10,100,1000) scene1000=thesis:bunny:$many
scans=$(q stanford-bunny,armadillo,dragon,elephant,bunny00)
all_backends=$("$binary" backends --names table)
no_tri=$(tr ',' '\n' <<<"$all_backends" | grep -vx tri-aabb | paste -sd, -)

step_tables() { measure tables table --size "$size" --meshes "$thesis_meshes" --objects "$counts"; }
step_primary() { measure primary table --table 6.1 --mode primary --size "$size" --meshes "$thesis_meshes" --objects "$counts"; }
step_scans() {
  # tri-aabb tests every triangle of each box a ray enters: 1000 scans of 70k triangles take it
  # one to two minutes a frame (the budget fits one cold frame, †), so its 1000-object rows are
  # files of their own (about 9 minutes a mode) that the other backends' table does not wait for.
  local mode
  for mode in primary shadow; do
    measure "scans_$mode" table --table 6.1 --mode "$mode" --size "$size" --meshes "$scans" --objects "$(q 1,10,100)"
    [[ $quick -eq 1 ]] || measure "scans_${mode}_1000" table --table 6.1 --mode "$mode" --size "$size" --meshes "$scans" \
      --objects 1000 --backends "$no_tri"
    [[ $quick -eq 1 ]] || measure "scans_${mode}_1000_tri-aabb" table --table 6.1 --mode "$mode" --size "$size" \
      --meshes "$scans" --objects 1000 --backends tri-aabb
  done
}
step_atrium() {
  local b mode parts=()
  for mode in primary shadow $( [[ $quick -eq 1 ]] || echo whitted ); do
    for b in $(tr ',' ' ' <<<"$all_backends"); do
      measure_part "atrium_${b}_$mode" --scene atrium --backend "$b" --mode "$mode" --size "$size"
      parts+=("$(part "atrium_${b}_$mode")")
    done
  done
  merge_parts atrium "${parts[@]}"
}
step_overlap_1000() { measure overlap_1000 table --table overlap --meshes "$(q bunny,teapot)" --objects "$many" --overlap "$(q 1,4,16,50)" --size "$small"; }
step_overlap_1000_shadow() {
  measure overlap_1000_shadow table --table overlap --mode shadow --meshes "$(q bunny,teapot)" --objects "$many" \
    --overlap "$(q 1,4,16,50)" --size "$small"
}
step_overlap_10000() {
  measure overlap_10000 table --table overlap --meshes "$(q bunny,teapot)" --objects "$dense" --overlap "$(q 1,16,50)" \
    --size "$small" --backends "$no_tri"
}
step_mesh_sizes() {
  measure mesh_sizes table --table 6.1 --mode primary --meshes bunny --triangles "$(q 1000,16000,256000)" --objects "$(q 1,10)" --size "$size"
}
step_thesis_structure() {
  measure thesis_structure sweep --scene "$scene1000" --backend sdf-octree --hash-cell "$(q 10,5,2,1)" --octree-depth "$(q 4,2,0)" --size "$small"
}
step_options() {
  measure options sweep --scene "$scene1000" --backend sdf-octree --over-relax "$(q 1,1.2,1.5,1.8)" --cell-bound "$(q 0,1)" --size "$small"
}
step_sdf_bricks_sweeps() {
  local hit
  for hit in exact field; do
    measure "sdf_bricks_sweep_$hit" sweep --scene "$scene1000" --backend sdf-bricks --hit "$hit" --voxels "$(q 64,32,128)" \
      --sdf-format "$(q f32,f16,u8)" --brick-trace "$(q instance,min)" --size "$small"
  done
}
step_sdf_global_sweeps() {
  measure sdf_global_sweep_exact sweep --scene "$scene1000" --backend sdf-global --global-voxel "$(q 0.4,0.25,0.7,1)" \
    --brick-band "$(q 4,8)" --size "$small"
  measure sdf_global_sweep_field sweep --scene "$scene1000" --backend sdf-global --hit field \
    --global-voxel "$(q 0.4,0.25,0.7,1)" --size "$small"
  measure sdf_global_formats sweep --scene "$scene1000" --backend sdf-global --sdf-format "$(q f32,f16,u8)" \
    --brick-fetch "$(q texel,sampler)" --size "$small"
}
step_exact_levers() {
  measure_part exact_levers_window --scene "$scene1000" --backend sdf-global --exact-near "$(q 0.5,1)" --exact-window "$(q 8,2)" --size "$size"
  measure_part exact_levers_triangles --scene "$scene1000" --backend sdf-global --exact-lists triangles --list-split "$(q 1,2,3)" --size "$size"
  merge_parts exact_levers "$(part exact_levers_window)" "$(part exact_levers_triangles)"
}
step_storage_vs_texel() {
  local b mode parts=()
  for b in sdf-octree sdf-global; do
    for mode in primary $( [[ $quick -eq 1 ]] || echo shadow ); do
      measure_part "storage_${b}_$mode" --scene "$scene1000" --backend "$b" --mode "$mode" --storage-tables 0,1 --size "$size"
      parts+=("$(part "storage_${b}_$mode")")
    done
  done
  merge_parts storage_vs_texel "${parts[@]}"
}
step_bvh_layouts() {
  local mode parts=()
  for mode in primary $( [[ $quick -eq 1 ]] || echo shadow ); do
    measure_part "bvh_layouts_$mode" --scene "$scene1000" --backend bvh --mode "$mode" --bvh-width "$(q 4,2,8)" \
      --bvh-nodes "$(q float,quantised)" --bvh-top "$(q instanced,rebraided,flat)" --size "$size"
    measure_part "embree_modes_$mode" --scene "$scene1000" --backend embree --mode "$mode" --embree-rays "$(q packets,single)" \
      --embree-scene "$(q instanced,flat)" --size "$size"
    parts+=("$(part "bvh_layouts_$mode")" "$(part "embree_modes_$mode")")
  done
  merge_parts bvh_layouts "${parts[@]}"
}
# The flat trees are left out at 10000 objects: 50 M world-space triangles pass --max-structure-mb's
# default and lavapipe's maxTexelBufferElements (bvh refuses them with an error).
step_bvh_overlap() {
  local scene=overlap:bunny:$dense:50
  [[ $quick -eq 1 ]] && scene=overlap:bunny:$dense:16
  measure_part bvh_overlap_bvh --scene "$scene" --backend bvh --bvh-width "$(q 4,2,8)" --bvh-nodes "$(q float,quantised)" \
    --bvh-top "$(q instanced,rebraided)" --size "$small"
  measure_part bvh_overlap_embree --scene "$scene" --backend embree --embree-rays "$(q packets,single)" --size "$small"
  measure_part bvh_overlap_sdf_global --scene "$scene" --backend sdf-global --size "$small"
  merge_parts bvh_overlap "$(part bvh_overlap_bvh)" "$(part bvh_overlap_embree)" "$(part bvh_overlap_sdf_global)"
}
step_agreement() {
  local file="$dir/agreement.txt" mesh mode scene status
  echo "agreement.txt" >>"$record/$step.outputs"
  : >"$file"
  compare() {  # SCENE MODE
    status=0
    {
      echo "## sdfbench compare --scene $1 --mode $2 --backends $all_backends --size $compare_size --device $device"
      "$binary" compare --scene "$1" --mode "$2" --backends "$all_backends" --size "$compare_size" --device "$device" 2>&1 || status=$?
      echo "exit $status"
      echo
    } >>"$file"
    echo "sdfbench compare --scene $1 --mode $2 --backends $all_backends --size $compare_size --device $device" >>"$record/$step.commands"
    note_status $status
  }
  for mesh in $(tr ',' ' ' <<<"$thesis_meshes"); do
    for mode in primary shadow whitted; do compare "thesis:$mesh:$compare_objects" "$mode"; done
  done
  for scene in $(q scenes/fig6_1.json,scenes/fig6_3.json,scenes/fig6_5.json | tr ',' ' '); do compare "$scene" whitted; done
}
step_profile() {
  if ! command -v perf >/dev/null || ! command -v objdump >/dev/null; then
    echo "reproduce_results: the profile needs perf and objdump (Debian: linux-perf, binutils): skipped" >&2
    return
  fi
  [[ $name == llvmpipe* ]] || { echo "reproduce_results: the profile reads lavapipe's JIT code: skipped on $name" >&2; return; }
  local seconds=10 warm=25
  [[ $quick -eq 1 ]] && seconds=2 warm=8
  run sdf_global_profile.txt -- bash -c "harness/scripts/profile_sdf_kernel.sh --binary '$binary' --warmup-s $warm --seconds $seconds \
    -- --scene $scene1000 --backend sdf-global --size $size --device $device >'$dir/sdf_global_profile.txt'"
}

# The scans come from Debian packages into the mesh cache (harness/scripts/fetch_scanned_meshes.sh).
if [[ " ${steps[*]} " == *" scans "* ]] && ! "$binary" render --scene "thesis:$(q stanford-bunny):1" --backend embree --size 8x8 \
     --frames 1 --warmup 0 >/dev/null 2>&1; then
  harness/scripts/fetch_scanned_meshes.sh >&2 || die "the scans could not be fetched (harness/scripts/fetch_scanned_meshes.sh)"
fi

# ---- The run: the plan, then each step with progress ----
todo=() estimate=0
for step in "${steps[@]}"; do
  [[ -f $record/$step.done ]] && continue
  todo+=("$step")
  estimate=$((estimate + ${minutes[$step]}))
done
echo "reproduce_results: $version on '$name' ($cpu) -> $dir" >&2
echo "reproduce_results: ${#todo[@]} of ${#steps[@]} steps to run$([[ $quick -eq 1 ]] && echo ' (--quick: one small row each)' || echo ", ~$estimate min on 2 cores"):" >&2
for step in "${todo[@]}"; do echo "  $step: ${what[$step]}" >&2; done
start=$SECONDS left=$estimate i=0
for step in "${todo[@]}"; do
  i=$((i + 1))
  elapsed=$(( (SECONDS - start) / 60 ))
  echo "reproduce_results: [$i/${#todo[@]}] $step (elapsed ${elapsed} min$([[ $quick -eq 1 ]] || echo ", ~$left min left"))" >&2
  rm -f "$record/$step.outputs" "$record/$step.commands"
  step_start=$SECONDS
  "step_$step"
  echo "$(( SECONDS - step_start )) s" >"$record/$step.done"
  left=$((left - ${minutes[$step]})); ((left >= 0)) || left=0
done

# ---- Plots, the report, the commands beside the files ----
csvs=()  # in the steps' order, so that the report reads as the plan does
for step in "${steps[@]}"; do
  while read -r output; do [[ $output == *.csv && $output != parts/* ]] && csvs+=("$output"); done < <(cat "$record/$step.outputs" 2>/dev/null || true)
done
[[ ${#csvs[@]} -gt 0 ]] || die "no CSV in $dir"
if /usr/bin/python3 -c 'import matplotlib' 2>/dev/null; then
  mkdir -p "$dir/plots"
  (cd "$dir" && /usr/bin/python3 "$OLDPWD/harness/scripts/plot_results.py" "${csvs[@]}" --out-dir plots) >"$record/plots.log" 2>&1 ||
    die "plot_results.py failed; see $record/plots.log"
  plots=(--plots plots)
else
  echo "reproduce_results: python3-matplotlib is missing: no plots" >&2
  plots=()
fi
# (from the folder, so that the page names the files as they sit beside it)
(cd "$dir" && "$binary" report "${csvs[@]}" "${plots[@]}" --out report.html) >"$record/report.log" 2>&1 ||
  die "sdfbench report failed; see $record/report.log"
{
  echo "# $(basename "$0") at $version on '$name' ($cpu), $(date -u +%FT%TZ)"
  echo "# each file and the commands that made it ('sdfbench' is $binary; paths relative to this folder)"
  for step in "${steps[@]}"; do
    echo
    echo "## $step: ${what[$step]} ($(cat "$record/$step.done" 2>/dev/null || echo 'not run'))"
    cat "$record/$step.commands" 2>/dev/null || true
  done
  echo
  echo "## plots and report"
  echo "harness/scripts/plot_results.py *.csv --out-dir plots"
  echo "sdfbench report *.csv --plots plots --out report.html"
} >"$dir/COMMANDS.md"
total=$(( (SECONDS - start) / 60 ))
echo "reproduce_results: done in $total min: $dir (CSV, markdown, images/, plots/, report.html, COMMANDS.md)" >&2
[[ $status_of_run -eq 0 ]] || echo "reproduce_results: some rows disagreed or failed (exit $status_of_run): the report's red list names them" >&2
exit $status_of_run
