#!/usr/bin/env bash
# The real scans (issue 38): harness/scripts/fetch_scanned_meshes.sh fetches them from Debian
# packages into a fresh cache (network: the package mirror install_deps.sh uses), each loads as the
# triangle count its name promises and renders in the thesis layout; without the fetch, a spec
# naming a scan is one error line naming the script; a size (@n) of a scan is refused.
# Usage: tests/scanned_meshes_test.sh SDFBENCH_BINARY
set -euo pipefail
binary=$(realpath "$1")
root=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

# Not fetched: one line, exit 1, naming the script.
set +e
out=$(SDFBENCH_MESH_CACHE="$work/empty" "$binary" render --scene thesis:armadillo:1 --backend embree --size 16x9 --frames 1 2>&1)
rc=$?
set -e
[[ $rc -eq 1 ]] || fail "an unfetched scan exited $rc: $out"
[[ $(printf '%s\n' "$out" | wc -l) -eq 1 && $out == "sdfbench: error: "*fetch_scanned_meshes.sh* ]] || fail "expected one error line naming the script: $out"

"$root/harness/scripts/fetch_scanned_meshes.sh" --cache "$work/cache" >"$work/fetch.log" 2>&1 || { cat "$work/fetch.log"; fail "the fetch failed"; }
[[ -s $work/cache/scans/MANIFEST && -s $work/cache/scans/LICENSES/libcgal.copyright ]] || fail "no MANIFEST or licences beside the scans"
export SDFBENCH_MESH_CACHE="$work/cache"
for scan in stanford-bunny:69666 armadillo:52000 dragon:19994 elephant:88928 bunny00:75408; do
  name=${scan%%:*}
  "$binary" render --scene "thesis:$name:10" --backend embree --size 32x18 --frames 1 --out "$work/$name.png" >"$work/$name.log" 2>&1 ||
    { cat "$work/$name.log"; fail "thesis:$name:10 did not render"; }
  [[ -s $work/$name.png ]] || fail "no image for thesis:$name:10"
done
# A scan whose file no longer holds what it should is refused, naming the file.
printf 'OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n' >"$work/cache/scans/armadillo.off"
set +e
out=$("$binary" render --scene thesis:armadillo:1 --backend embree --size 16x9 --frames 1 2>&1)
rc=$?
set -e
[[ $rc -eq 1 && $out == *"armadillo.off' holds 1 triangles, not the scan's 52000"* ]] || fail "a changed scan was not refused: $out"
set +e
out=$("$binary" render --scene thesis:dragon@5000:1 --backend embree --size 16x9 --frames 1 2>&1)
rc=$?
set -e
[[ $rc -eq 1 && $out == *"not from a scan"* ]] || fail "a size of a scan was not refused: $out"
echo "scanned meshes: fetched, loaded and rendered; the errors are one line each"
