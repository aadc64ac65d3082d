#!/usr/bin/env bash
# Debian 13 (trixie, Embree 4, GCC 14, Mesa 25 with LLVM 19) as a new user meets it (issue 26): in
# a fresh `debootstrap --variant=minbase trixie` root holding a copy of this checkout, the README's
# first command (harness/scripts/quickstart.sh: install_deps.sh, build, the main job on lavapipe)
# and its test command (harness/scripts/run_tests.sh) run as written. Checked besides:
#   - `sdfbench info` names Embree 4 and Mesa 25, and every row of the quick table says Embree 4;
#   - nothing was installed from another suite and the root's apt sources are unchanged;
#   - the build ran with SDFBENCH_WARNINGS_AS_ERRORS=ON (GCC 14), every target.
# Needs root (debootstrap, chroot, mounts) and Debian's mirror.
#   tests/debian13/debian13_test.sh [--fresh] [--tests REGEX] [--exclude REGEX]
# --tests limits the test command to the ctest tests matching REGEX, --exclude leaves out those
# matching REGEX (ctest -R / -E; run_tests.sh passes ctest arguments through); .ci/run leaves out
# the slowest algorithm tests to stay within its time (docs/development.md, "Tests"). The root is kept in $DEBIAN13_WORK (default /tmp/sdfbench-debian13) and reused by
# a later run (its packages and build stay; the source copy is refreshed); --fresh remakes it.
set -euo pipefail
cd "$(dirname "$0")/../.."
work=${DEBIAN13_WORK:-/tmp/sdfbench-debian13}
root=$work/root
src=/opt/sdfbench
fresh=false tests="" exclude=""
fail() { echo "debian13_test: FAIL: $*" >&2; exit 1; }
say() { echo "debian13_test: $*"; }
while [[ $# -gt 0 ]]; do
  case "$1" in
    --fresh) fresh=true; shift ;;
    --tests) [[ $# -ge 2 ]] || fail "--tests needs a regular expression"; tests=$2; shift 2 ;;
    --exclude) [[ $# -ge 2 ]] || fail "--exclude needs a regular expression"; exclude=$2; shift 2 ;;
    *) fail "unknown argument '$1' (usage: $0 [--fresh] [--tests REGEX] [--exclude REGEX])" ;;
  esac
done
[[ $(id -u) -eq 0 ]] || fail "needs root (debootstrap, chroot and mounts)"

. harness/scripts/debian_root.sh
trap 'debian_root_unmount "$root"' EXIT
$fresh && debian_root_remove "$root"

started=$SECONDS
say "debootstrap --variant=minbase trixie (a few minutes; reused when $root has it)"
debian_root_make "$root" trixie "$work/debootstrap.log" || fail "debootstrap failed (log: $work/debootstrap.log)"
grep -q '^VERSION_CODENAME=trixie$' "$root/etc/os-release" || fail "$root is not a Debian 13 root"
debian_root_mount "$root"
in_root() { debian_root_run "$root" "$@"; }
say "root ready after $((SECONDS - started)) s"
debian_root_copy_checkout "$root" "$src"
apt_sources() { cat "$root/etc/apt/sources.list" 2>/dev/null; ls -l "$root/etc/apt/sources.list.d/"; }
sources_before=$(apt_sources)

step() {  # step NAME COMMAND...: run in the root at the checkout, log to $work/NAME.log, time it
  local name=$1 t=$SECONDS
  shift
  say "$name: $* (log: $work/$name.log)"
  if ! in_root env SDFBENCH_WARNINGS_AS_ERRORS=ON bash -c "cd $src && $*" >"$work/$name.log" 2>&1; then
    tail -30 "$work/$name.log"
    fail "$name failed: $*"
  fi
  say "$name: done in $((SECONDS - t)) s"
}

# 1. The README's first command, as written.
step quickstart harness/scripts/quickstart.sh
log=$work/quickstart.log
grep -q 'SDFBENCH_WARNINGS_AS_ERRORS:BOOL=ON' "$root$src/build/CMakeCache.txt" || fail "the build did not use SDFBENCH_WARNINGS_AS_ERRORS=ON"
grep -Eq '^Embree: +4\.' "$log" || fail "sdfbench info does not name Embree 4: $(grep -m1 '^Embree' "$log")"
grep -Eq 'Mesa 25\.' "$log" || fail "sdfbench info does not name Mesa 25: $(grep -m2 -i 'llvmpipe' "$log")"
say "info: $(grep -m1 '^Embree' "$log" | tr -s ' '); $(grep -m1 -o 'Mesa 25[^),]*' "$log")"
csv=$root$src/out/quick.csv
python3 - "$csv" <<'PY' || fail "out/quick.csv (above)"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
bad = [r for r in rows if not r["embree"].startswith("4.") or r["agreement"] not in ("ok", "reference")]
print(f"debian13_test: quick table: {len(rows)} rows, Embree {rows[0]['embree'] if rows else '?'}, "
      f"{sum(r['agreement'] == 'ok' for r in rows)} agree with Embree")
for r in bad[:5]: print("  not Embree 4 or not agreeing:", r["backend"], r["scene"], r["mode"], r["embree"], r["agreement"])
sys.exit(1 if bad or len(rows) < 20 else 0)
PY

# 2. Nothing from another suite, no apt source added.
[[ $(apt_sources) == "$sources_before" ]] || fail "the root's apt sources changed: $(apt_sources)"
foreign=$(in_root dpkg-query -W -f '${Package} ${Version}\n' | grep -E '~bpo|deb12' || true)
[[ -z $foreign ]] || fail "packages from another suite: $foreign"
say "apt sources unchanged, no package from another suite; $(in_root dpkg-query -W -f '${Version}' mesa-vulkan-drivers) mesa-vulkan-drivers"
[[ -f $root$src/.deps/lavapipe-mesa22/libLLVM-15.so.1 ]] || fail "Debian 12's LLVM 15 is not beside the old lavapipe in .deps/"

# 3. The README's test command, as written (with --tests / --exclude: a subset, by ctest -R / -E).
subset=()
[[ -z $tests ]] || subset+=(-R "'$tests'")
[[ -z $exclude ]] || subset+=(-E "'$exclude'")
step tests harness/scripts/run_tests.sh "${subset[@]}"
summary=$(grep -E 'tests passed|tests failed' "$work/tests.log" | tail -1)
say "tests: $summary"
grep -q 'OldLavapipe' "$work/tests.log" || [[ -n $tests && ! OldLavapipe =~ $tests ]] || [[ -n $exclude && OldLavapipe =~ $exclude ]] ||
  fail "the loop-cap tests did not run"
say "all passed in $((SECONDS - started)) s"
