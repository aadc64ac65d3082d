#!/usr/bin/env bash
# One prepared run for a machine with a GPU (issue 17): the device's `info`, the image agreement
# of every Vulkan backend with Embree (the thesis meshes x100 in primary and shadow mode, fig6_1
# and fig6_3 in whitted mode), then the thesis tables, all under one folder named after the
# device. The tables run under a wall-clock limit; their CSV is rewritten after every row, so a
# second call with the same flags (--resume) finishes what the limit cut.
#
#   harness/scripts/gpu_run.sh [--device gpu] [--size 1280x720] [--compare-size 640x360]
#       [--budget-s 2] [--frames 3] [--minutes 8] [--out results] [--binary build/sdfbench]
#       [--storage-scene thesis:bunny:1000] [--sweep-modes primary,shadow] [--compare-objects 100]
#       [--compare-meshes LIST] [--compare-whitted SCENES]
#       [--steps compares,storage,fetch,layouts,tables | --tables-only] [-- TABLE_FLAGS...]
#       (TABLE_FLAGS, e.g. -- --table 6.3 --objects 1,10: passed to `sdfbench table`)
#
# --steps: which parts run (default all five, in this order; the device's info.txt goes with the
# compares); --tables-only is --steps tables. The report is written of the CSVs the folder holds.
# Between the compares and the tables, two sweeps: storage, the SDF tables in texel buffers
# against storage buffers (`sweep --storage-tables 0,1`, sdf-octree and sdf-hash, primary and
# shadow, on --storage-scene at --size), side by side in storage_vs_texel.csv/.md (lavapipe: texel
# buffers; a GPU may differ); and fetch, the sampled fields' two fetch paths (`--brick-fetch
# texel,sampler`: texel buffers with the kernel's trilinear against the sampler's filtered 3D
# image; sdf-bricks and sdf-global), primary and shadow, in brick_fetch.csv/.md. --sweep-modes: the
# sweeps' modes (default primary,shadow; whitted too, or one). layouts: bvh's widths, nodes and top levels
# and Embree's rays and scenes (issue 58) on --storage-scene, in bvh_layouts.csv/.md.
#
# --compare-objects N: the thesis meshes' object count in the compares (thesis:<mesh>:N);
# --compare-meshes: which meshes (default bunny,teapot,monkey,sphere; any name a thesis: spec takes;
# none: no mesh compares). --compare-whitted: the scenes compared in whitted mode, separated by
# commas (default scenes/fig6_1.json,scenes/fig6_3.json; a file or a generator spec; none: no
# whitted compares).
# On lavapipe, as a check of the script: --device lavapipe --size 64x36 --compare-size 64x36.
# --binary defaults to $SDFBENCH, else build/sdfbench, else ./sdfbench (the launcher at the top
# of a bundle from make_bundle.sh, where this script is harness/scripts/gpu_run.sh).
# Exit status: 0 when every compare agreed and every table and sweep row ran and agreed, 2 when a
# compare or a row disagreed, 3 when the tables were cut by --minutes (run it again, with
# --tables-only to skip the info and the compares already done, to finish; failed rows are run
# again), 4 when some table or sweep configurations failed (ERROR rows), 1 on an error.
# --out, --binary and --compare-whitted files, when given, are relative to the caller's folder.
set -euo pipefail
caller_dir=$PWD
cd "$(dirname "$0")/../.."
device=gpu size=1280x720 compare_size=640x360 budget=2 frames=3 minutes=8 out=results
storage_scene=thesis:bunny:1000 sweep_modes=primary,shadow compare_objects=100 compare_meshes=bunny,teapot,monkey,sphere compare_whitted=default
binary=${SDFBENCH:-build/sdfbench}
[[ -n ${SDFBENCH:-} || -x $binary || ! -x sdfbench ]] || binary=./sdfbench
table_flags=() steps=compares,storage,fetch,layouts,tables failed=0
die() { echo "gpu_run.sh: error: $*" >&2; exit 1; }
from_caller() { if [[ $1 == /* ]]; then echo "$1"; else echo "$caller_dir/$1"; fi; }
while [[ $# -gt 0 ]]; do
  case "$1" in
    --device|--size|--compare-size|--budget-s|--frames|--minutes|--out|--binary|--storage-scene|--sweep-modes|--compare-objects|--compare-meshes|--compare-whitted|--steps)
      [[ $# -ge 2 ]] || die "$1 needs a value"
      case "$1" in
        --device) device=$2 ;; --size) size=$2 ;; --compare-size) compare_size=$2 ;; --budget-s) budget=$2 ;;
        --frames) frames=$2 ;; --minutes) minutes=$2 ;; --out) out=$(from_caller "$2") ;; --binary) binary=$(from_caller "$2") ;;
        --storage-scene) storage_scene=$2 ;; --sweep-modes) sweep_modes=$2 ;; --compare-objects) compare_objects=$2 ;; --compare-meshes) compare_meshes=$2 ;;
        --compare-whitted) compare_whitted=$2 ;;
        --steps) steps=$2 ;;
      esac
      shift 2 ;;
    --tables-only) steps=tables; shift ;;
    --) shift; table_flags=("$@"); break ;;
    -h|--help) sed -n 2,37p "$0"; exit 0 ;;
    *) die "unknown argument '$1' (see --help)" ;;
  esac
done
# Every value checked before minutes of work.
[[ $steps =~ ^(compares|storage|fetch|layouts|tables)(,(compares|storage|fetch|layouts|tables))*$ ]] ||
  die "--steps takes compares, storage, fetch, layouts and tables separated by commas, not '$steps'"
runs() { [[ ,$steps, == *,$1,* ]]; }
[[ $minutes =~ ^[0-9]{1,5}$ && $minutes -gt 0 ]] || die "--minutes takes whole minutes > 0, not '$minutes'"
[[ $frames =~ ^[0-9]{1,5}$ && $frames -gt 0 ]] || die "--frames takes a whole number > 0, not '$frames'"
[[ $compare_objects =~ ^[0-9]{1,7}$ && $compare_objects -gt 0 ]] || die "--compare-objects takes a whole number > 0, not '$compare_objects'"
[[ $sweep_modes =~ ^(primary|shadow|whitted)(,(primary|shadow|whitted))*$ ]] ||
  die "--sweep-modes takes primary, shadow and whitted separated by commas, not '$sweep_modes'"
[[ $compare_meshes =~ ^[a-z0-9_]+(,[a-z0-9_]+)*$ ]] ||
  die "--compare-meshes takes mesh names separated by commas (e.g. bunny,teapot) or none, not '$compare_meshes'"
[[ $compare_meshes == none ]] && compare_meshes=
[[ $compare_whitted =~ ^[^,[:space:]]+(,[^,[:space:]]+)*$ ]] ||
  die "--compare-whitted takes scenes separated by commas (files or generator specs) or none, not '$compare_whitted'"
whitted_scenes=(scenes/fig6_1.json scenes/fig6_3.json)  # the repository's
if [[ $compare_whitted != default ]]; then
  whitted_scenes=()
  [[ $compare_whitted == none ]] || IFS=, read -ra whitted_scenes <<<"$compare_whitted"
  for i in "${!whitted_scenes[@]}"; do
    scene=${whitted_scenes[$i]}
    if [[ $scene == *.json ]]; then  # a file, relative to the caller's folder
      scene=$(from_caller "$scene")
      [[ -f $scene ]] || die "--compare-whitted: no scene file '$scene'"
      whitted_scenes[$i]=$scene
    fi
  done
fi
[[ $budget =~ ^([0-9]+\.?[0-9]*|\.[0-9]+)$ ]] && awk -v b="$budget" 'BEGIN{exit !(b > 0 && b <= 1e7)}' ||
  die "--budget-s takes seconds > 0, not '$budget'"
for pair in "--size:$size" "--compare-size:$compare_size"; do
  value=${pair#*:}
  [[ $value =~ ^[1-9][0-9]{0,4}x[1-9][0-9]{0,4}$ ]] || die "${pair%%:*} takes WIDTHxHEIGHT (e.g. 1280x720), not '$value'"
done

[[ -x $binary ]] || die "--binary '$binary' is not an executable (build first, or set SDFBENCH)"

# The device's name, as the renderer reports it, names the folder.
probe=$("$binary" render --scene thesis:sphere:1 --backend sdf-hash --size 16x9 --frames 1 --warmup 0 --device "$device" 2>&1) ||
  die "no Vulkan device '$device': $(grep -m1 'error' <<<"$probe" || tail -1 <<<"$probe")"
name=$(sed -n 's/^backend  *sdf-hash on \(.*\) \[.*$/\1/p' <<<"$probe" | sed -n 1p)
[[ -n $name ]] || die "could not read the device's name from: $(head -3 <<<"$probe")"
slug=$(tr 'A-Z' 'a-z' <<<"$name" | sed 's/[^a-z0-9]\+/-/g; s/^-//; s/-$//')
dir="$out/$slug"
mkdir -p "$dir"
echo "gpu_run: device '$name' -> $dir" >&2

agreement="$dir/agreement.txt" disagreed=0
# Every backend `table` runs by default (the registry's list), Embree (the reference) first and
# vk-rt only where the device runs it.
backends=$("$binary" backends --names table | tr ',' '\n' | grep -vx -e embree -e vk-rt | paste -sd, -)
[[ -n $backends ]] || die "could not read the backends from '$binary backends --names table'"
if "$binary" render --scene thesis:sphere:1 --backend vk-rt --size 16x9 --frames 1 --warmup 0 --device "$device" >/dev/null 2>&1; then
  backends=$backends,vk-rt
else
  echo "gpu_run: vk-rt does not run on '$name': left out of the compares and the tables" >&2
  # (unless the table flags name their own backends)
  [[ " ${table_flags[*]} " == *" --backends"* ]] || table_flags=(--backends "embree,$backends" "${table_flags[@]}")
fi
if runs compares; then
  {
    echo "# $(date -u +%Y-%m-%dT%H:%M:%SZ) harness/scripts/gpu_run.sh on $(uname -n)"
    "$binary" --version
    "$binary" info
  } >"$dir/info.txt" 2>&1

  # Agreement: each compare's table, and one line per compare with its exit status.
  : >"$agreement"
  run_compare() {  # SCENE MODE
    echo "gpu_run: compare $1 $2" >&2
    local status=0
    {
      echo "## sdfbench compare --scene $1 --mode $2 --backends embree,$backends --size $compare_size --device $device"
      "$binary" compare --scene "$1" --mode "$2" --backends "embree,$backends" --size "$compare_size" --device "$device" 2>&1 || status=$?
      echo "exit $status"
      echo
    } >>"$agreement"
    case $status in 0) ;; 2) disagreed=1 ;; *) die "compare of $1 ($2) failed; see $agreement" ;; esac
  }
  for mesh in ${compare_meshes//,/ }; do
    for mode in primary shadow; do run_compare "thesis:$mesh:$compare_objects" "$mode"; done
  done
  for scene in "${whitted_scenes[@]}"; do run_compare "$scene" whitted; done
fi

# One sweep of a sweep step on --storage-scene into $parts/NAME.csv (its log beside it), added to
# `swept`: rows that disagree (exit 2) or failed (exit 4) are noted, any other failure ends the run.
sweep_part() {  # NAME WHAT SWEEP-FLAGS...
  local name=$1 what=$2 status=0
  shift 2
  "$binary" sweep --scene "$storage_scene" --size "$size" --frames "$frames" --budget-s "$budget" --device "$device" "$@" \
    --csv "$parts/$name.csv" >"$parts/$name.log" 2>&1 || status=$?
  case $status in
    0) ;; 2) disagreed=1 ;; 4) failed=1 ;;
    *) die "the $what sweep failed; see $parts/$name.log" ;;
  esac
  swept+=("$parts/$name.csv")
}
# This call's sweeps of a step (`swept`) merged into NAME.csv/.md.
merge_swept() {  # NAME
  "$binary" merge "${swept[@]}" --several-runs --csv "$dir/$1.csv" --markdown "$dir/$1.md" >/dev/null || die "merging ${swept[*]} failed"
}

if runs storage; then
  # Texel against storage buffers for the SDF tables, each pair side by side in one sweep.
  parts="$dir/storage_vs_texel" swept=()  # this call's CSVs (an earlier call may have run other modes)
  mkdir -p "$parts"
  for backend in sdf-octree sdf-hash; do
    for mode in ${sweep_modes//,/ }; do
      echo "gpu_run: texel vs storage buffers, $backend $mode" >&2
      cell=10; [[ $backend == sdf-hash ]] && cell=1  # each backend's thesis configuration (tables 6.1, 6.2)
      sweep_part "${backend}_$mode" "storage-vs-texel ($backend, $mode)" --backend "$backend" --hash-cell "$cell" --mode "$mode" \
        --storage-tables 0,1
    done
  done
  merge_swept storage_vs_texel
fi

if runs fetch; then
  # The sampled fields' fetch paths (sdf-bricks, sdf-global), each pair side by side in one sweep.
  parts="$dir/brick_fetch" swept=()
  mkdir -p "$parts"
  for backend in sdf-bricks sdf-global; do
    for mode in ${sweep_modes//,/ }; do
      echo "gpu_run: $backend texel vs sampler fetch, $mode" >&2
      sweep_part "${backend}_$mode" "brick fetch ($backend, $mode)" --backend "$backend" --mode "$mode" --brick-fetch texel,sampler
    done
  done
  merge_swept brick_fetch
fi

if runs layouts; then
  # bvh's layouts and top levels, and Embree's modes, on the same scene (issue 58): the GPU answers
  # the question lavapipe's rows answer (a GPU has no Embree, but its rows name the CPU's).
  parts="$dir/bvh_layouts" swept=()
  mkdir -p "$parts"
  for mode in ${sweep_modes//,/ }; do
    echo "gpu_run: bvh and embree layouts, $mode" >&2
    sweep_part "bvh_$mode" "bvh layout ($mode)" --backend bvh --mode "$mode" --bvh-width 2,4,8 --bvh-nodes float,quantised \
      --bvh-top instanced,rebraided,flat
    sweep_part "embree_$mode" "embree mode ($mode)" --backend embree --mode "$mode" --embree-rays single,packets \
      --embree-scene instanced,flat
  done
  merge_swept bvh_layouts
fi

if runs tables; then
  # The tables, under the wall-clock limit (a cut run resumes on the next call).
  echo "gpu_run: tables at $size, ${budget} s per configuration, at most $minutes min" >&2
  table=("$binary" table --size "$size" --budget-s "$budget" --frames "$frames" --device "$device" --resume
         --csv "$dir/tables.csv" --markdown "$dir/tables.md" --keep-images "$dir/images" "${table_flags[@]}")
  echo "${table[*]}" >"$dir/tables_command.txt"
  status=0
  timeout --signal=INT "${minutes}m" "${table[@]}" || status=$?
  case $status in
    0) ;;
    2) disagreed=1 ;;
    4) failed=1 ;;
    124|130) echo "gpu_run: the tables were cut at $minutes min; run the same command again (with --tables-only) to finish them" >&2; exit 3 ;;
    *) die "the tables failed (exit $status)" ;;
  esac
fi
# The page of every CSV the folder holds, with each table row's check images beside the reference's.
reports=()
for f in tables storage_vs_texel brick_fetch; do [[ -f $dir/$f.csv ]] && reports+=("$dir/$f.csv"); done
if [[ ${#reports[@]} -gt 0 ]]; then
  "$binary" report "${reports[@]}" --out "$dir/report.html" >/dev/null || die "sdfbench report failed"
fi
[[ $failed -eq 0 ]] || { echo "gpu_run: some configurations failed (ERROR rows in $dir/tables.csv or the sweeps); run it again to retry them" >&2; exit 4; }
[[ $disagreed -eq 0 ]] || { echo "gpu_run: a compare or a table row disagreed; see $agreement and $dir/tables.md" >&2; exit 2; }
written=()  # what this call wrote (the steps it did not run leave their files as they were)
if runs compares; then written+=(info.txt agreement.txt); fi
if runs storage; then written+=(storage_vs_texel.csv storage_vs_texel.md); fi
if runs fetch; then written+=(brick_fetch.csv brick_fetch.md); fi
if runs tables; then written+=(tables.csv tables.md); fi
[[ ${#reports[@]} -eq 0 ]] || written+=(report.html)
echo "gpu_run: done: $dir ($(IFS=,; echo "${written[*]}" | sed 's/,/, /g'))" >&2
