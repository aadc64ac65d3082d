#!/usr/bin/env bash
# Times sdfbench binaries against each other on the SDF backends, side by side in one run: for each
# backend and mode, ROUNDS rounds of `render` from every binary in turn (FRAMES timed frames each,
# after a warm-up), then the median of each binary's per-round medians and its ratio to the first.
# Also checks that binaries marked "same field" give the same steps per ray and the same image.
#
#   harness/scripts/compare_sdf_kernels.sh [--rounds N] [--frames N] [--size WxH] [--scene S] \
#       NAME=BINARY[@EXTRA_FLAGS] ...
#
# e.g. old=/tmp/old/sdfbench@'--hit thesis' start=/tmp/start/sdfbench new=build/sdfbench: the first is the
# baseline of the ratios; EXTRA_FLAGS go to its every render (use , for spaces: @--hit,thesis).
# Output: a markdown table on stdout; progress and each run's lines on stderr. Needs idiff (OpenImageIO).
set -euo pipefail
rounds=3 frames=2 size=1280x720 scene=thesis:bunny:1000 backends="sdf-octree sdf-hash" modes="primary shadow"
binaries=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --rounds) rounds=$2; shift 2 ;;
    --frames) frames=$2; shift 2 ;;
    --size) size=$2; shift 2 ;;
    --scene) scene=$2; shift 2 ;;
    --backends) backends=${2//,/ }; shift 2 ;;
    --modes) modes=${2//,/ }; shift 2 ;;
    -h|--help) sed -n 2,13p "$0"; exit 0 ;;
    *=*) binaries+=("$1"); shift ;;
    *) echo "compare_sdf_kernels: error: unknown argument '$1' (see --help)" >&2; exit 1 ;;
  esac
done
[[ ${#binaries[@]} -ge 2 ]] || { echo "compare_sdf_kernels: error: give at least two NAME=BINARY" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

names=() paths=() flags=()
for b in "${binaries[@]}"; do
  name=${b%%=*} rest=${b#*=}
  path=${rest%%@*} extra=""
  [[ $rest == *@* ]] && extra=${rest#*@}
  [[ -x $path ]] || { echo "compare_sdf_kernels: error: '$path' is not an executable" >&2; exit 1; }
  names+=("$name") paths+=("$path") flags+=("${extra//,/ }")
done

echo "| backend | mode | $(IFS='|'; echo "${names[*]}" | sed 's/|/ ms | /g') ms | $(for n in "${names[@]:1}"; do printf '%s speed-up | ' "$n"; done)steps/ray ($(IFS=/; echo "${names[*]}")) |"
echo "|---|---|$(for n in "${names[@]}"; do printf -- '---:|'; done)$(for n in "${names[@]:1}"; do printf -- '---:|'; done)---|"
for backend in $backends; do
  for mode in $modes; do
    declare -A ms=()
    for ((r = 0; r < rounds; ++r)); do
      for i in "${!names[@]}"; do
        out="$work/${names[$i]}-$backend-$mode.exr" counters=""
        [[ $r -eq 0 ]] && counters="--counters --out $out"
        # shellcheck disable=SC2086
        log=$("${paths[$i]}" render --backend "$backend" --scene "$scene" --size "$size" --mode "$mode" --frames "$frames" \
              --warmup 1 --cache "$work/${names[$i]}-$backend.cache" ${flags[$i]} $counters 2>&1) ||
          { echo "$log" >&2; echo "compare_sdf_kernels: error: ${names[$i]} failed" >&2; exit 1; }
        median=$(sed -n 's/^time *device median \([0-9.]*\) ms.*/\1/p' <<<"$log")
        ms[$i]+="$median "
        [[ $r -eq 0 ]] && steps[$i]=$(sed -n 's/.*steps \([0-9.]*\),.*/\1/p' <<<"$log")
        echo "$backend $mode round $r ${names[$i]}: $median ms" >&2
      done
    done
    row="| $backend | $mode |" base=""
    meds=()
    for i in "${!names[@]}"; do
      m=$(tr ' ' '\n' <<<"${ms[$i]}" | grep . | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}')
      meds+=("$m")
      row+=" $m |"
    done
    for i in "${!names[@]}"; do
      [[ $i -eq 0 ]] && continue
      row+=" $(awk -v a="${meds[0]}" -v b="${meds[$i]}" 'BEGIN {printf "%.2fx", a / b}') |"
    done
    row+=" $(IFS=/; echo "${steps[*]}") |"
    echo "$row"
    # Image agreement of every binary with the last (the new one): identical pixels or not.
    last=$((${#names[@]} - 1))
    for i in "${!names[@]}"; do
      [[ $i -eq $last ]] && continue
      verdict=$(idiff -a -fail 0 -warn 0 "$work/${names[$i]}-$backend-$mode.exr" "$work/${names[$last]}-$backend-$mode.exr" 2>&1 | tail -1 || true)
      echo "$backend $mode: ${names[$i]} vs ${names[$last]} image: $verdict" >&2
      echo "$backend $mode ${names[$i]} vs ${names[$last]}: $verdict" >>"$work/images.txt"
    done
    unset ms
  done
done
echo
echo "Images (idiff -fail 0 against ${names[-1]}):"
sed 's/^/- /' "$work/images.txt"
