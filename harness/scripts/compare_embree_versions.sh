#!/usr/bin/env bash
# Embree 3 (this Debian 12 host's build) against Embree 4 (the Debian 13 root that
# tests/debian13/debian13_test.sh leaves in $DEBIAN13_WORK, default /tmp/sdfbench-debian13) on the
# same machine: the embree backend's frame time (sdfbench render's wall median), the two builds run
# in turn, A B A B, so that the VM's drift falls on both; prints every pair and, per scene and mode,
# the median time of each and the median, min and max of the per-pair ratio (Embree 4 / Embree 3).
# What differs is the whole stack a user gets: Embree 3.13.5 + GCC 12 + TBB 2021 against Embree
# 4.3.3 + GCC 14 + TBB 2022 (the shading is sdfbench's C++ either way). Needs root (chroot).
#   harness/scripts/compare_embree_versions.sh [--pairs 7] [--size 640x360] [--frames 20]
set -euo pipefail
cd "$(dirname "$0")/../.."
pairs=7 size=640x360 frames=20
while [[ $# -gt 0 ]]; do
  case "$1" in
    --pairs|--size|--frames)
      [[ $# -ge 2 ]] || { echo "compare_embree_versions.sh: error: $1 needs a value" >&2; exit 1; }
      case "$1" in --pairs) pairs=$2 ;; --size) size=$2 ;; --frames) frames=$2 ;; esac
      shift 2 ;;
    *) echo "compare_embree_versions.sh: error: unknown argument '$1'" >&2; exit 1 ;;
  esac
done
root=${DEBIAN13_WORK:-/tmp/sdfbench-debian13}/root
[[ -x $root/opt/sdfbench/build/sdfbench ]] || { echo "compare_embree_versions.sh: error: no Debian 13 build in $root (run tests/debian13/debian13_test.sh)" >&2; exit 1; }
[[ -x build/sdfbench ]] || { echo "compare_embree_versions.sh: error: no build/sdfbench (run harness/scripts/build.sh)" >&2; exit 1; }
. harness/scripts/debian_root.sh
trap 'debian_root_unmount "$root"' EXIT
debian_root_mount "$root"
run_embree3() { build/sdfbench "$@"; }
run_embree4() { debian_root_run "$root" /opt/sdfbench/build/sdfbench "$@"; }
rows=$(mktemp)
trap 'debian_root_unmount "$root"; rm -f "$rows"' EXIT
echo "# scene mode pair build wall_median_ms (embree backend, $size, $frames frames after 2 warm-up)"
for config in "thesis:bunny:1000 primary" "thesis:bunny:1000 shadow" "thesis:bunny:1000 whitted" \
  "thesis:teapot:100 primary" "thesis:monkey:1000 primary" "thesis:bunny@64000:100 primary"; do
  read -r scene mode <<<"$config"
  for ((pair = 1; pair <= pairs; ++pair)); do
    for build in embree3 embree4; do
      ms=$(run_$build render --scene "$scene" --backend embree --mode "$mode" --size "$size" --frames "$frames" --warmup 2 |
        grep -o 'wall median [0-9.]*' | sed -n 1p | awk '{print $3}')
      echo "$scene $mode $pair $build $ms"
    done
  done
done | tee "$rows"
python3 -c "$(cat <<'PY'
import collections, statistics as st, sys
runs = collections.defaultdict(dict)
for line in open(sys.argv[1]):
    if line.startswith("#"): continue
    scene, mode, pair, build, ms = line.split()
    runs[(scene, mode)].setdefault(pair, {})[build] = float(ms)
print("scene mode | median ms Embree 3 | median ms Embree 4 | ratio 4/3 median (min-max)")
for (scene, mode), by_pair in runs.items():
    ratios = [p["embree4"] / p["embree3"] for p in by_pair.values()]
    e3 = st.median(p["embree3"] for p in by_pair.values())
    e4 = st.median(p["embree4"] for p in by_pair.values())
    print(f"{scene} {mode} | {e3:.2f} | {e4:.2f} | {st.median(ratios):.3f} ({min(ratios):.3f}-{max(ratios):.3f})")
PY
)" "$rows"
