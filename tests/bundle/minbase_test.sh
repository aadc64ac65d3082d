#!/usr/bin/env bash
# Proof that the bundle (harness/scripts/make_bundle.sh) is self-contained (issue 17): it runs in
# a minimal Debian 12 root made with `debootstrap --variant=minbase`, where none of the build's
# -dev packages and none of its libraries exist.
#   1. Before any Vulkan package: `sdfbench --version` starts (the launcher falls back to the
#      bundle's Vulkan loader), `info` says that no driver was found, and a Vulkan render is one
#      error line.
#   2. With only libvulkan1 and lavapipe (mesa-vulkan-drivers from bookworm-backports) added:
#      `info` lists lavapipe, a tiny `table --quick` writes its rows with agreement figures, and
#      harness/scripts/run_bundle_on_device.sh (the prepared GPU-machine command: unpack the
#      bundle, run its gpu_run.sh) runs end to end on lavapipe.
# Needs root (debootstrap, chroot, mounts) and Debian's mirror. The root is kept in
# $MINBASE_WORK (default /tmp/sdfbench-minbase) and reused by a later run; `--fresh` remakes it.
#   tests/bundle/minbase_test.sh [--fresh]
set -euo pipefail
cd "$(dirname "$0")/../.."
work=${MINBASE_WORK:-/tmp/sdfbench-minbase}
mirror=${SDFBENCH_DEBIAN_MIRROR:-http://deb.debian.org/debian}
root=$work/root
fail() { echo "minbase_test: FAIL: $*" >&2; exit 1; }
say() { echo "minbase_test: $*"; }
[[ $(id -u) -eq 0 ]] || fail "needs root (debootstrap, chroot and mounts)"

. harness/scripts/debian_root.sh
trap 'debian_root_unmount "$root"' EXIT
[[ ${1:-} == --fresh ]] && debian_root_remove "$root"
say "debootstrap --variant=minbase bookworm (a few minutes; reused when $root has it)"
debian_root_make "$root" bookworm "$work/debootstrap.log" || fail "debootstrap failed (log: $work/debootstrap.log)"
debian_root_mount "$root"
in_root() { debian_root_run "$root" "$@"; }
no_dev_packages() {
  local dev
  dev=$(in_root dpkg-query -W -f '${Package}\n' | grep -E -- '-dev(:|$)' || true)
  [[ -z $dev ]] || fail "the root has -dev packages: $dev"
}

# On a host newer than Debian 12 (Debian 13: glibc 2.41) the bundle is built in a Debian 12 root of
# its own, as it is for GPU machines, so that it starts in this Debian 12 root.
bundle_flags=()
host_glibc=$(getconf GNU_LIBC_VERSION | awk '{print $2}')
if [[ $(printf '%s\n' "$host_glibc" 2.36 | sort -V | tail -1) != 2.36 ]]; then
  bundle_flags=(--bookworm-root "$work/build-root")
fi
say "making the bundle${bundle_flags[*]:+ (host glibc $host_glibc: ${bundle_flags[*]})}"
harness/scripts/make_bundle.sh --out "$work/dist" "${bundle_flags[@]}" | tee "$work/make_bundle.log" | tail -1
archive=$(ls -t "$work"/dist/sdfbench-*.tar.gz | sed -n 1p)
name=$(basename "$archive" .tar.gz)
rm -rf "$root/opt/sdfbench" && mkdir -p "$root/opt/sdfbench"
tar -C "$root/opt/sdfbench" -xzf "$archive"
bundle=/opt/sdfbench/$name

# 1. No Vulkan loader or driver in the root (a new root has none; a reused one is reset).
in_root dpkg-query -W -f '${Status}' libvulkan1 2>/dev/null | grep '^install ok installed' >/dev/null &&
  in_root apt-get purge -y -qq libvulkan1 mesa-vulkan-drivers >/dev/null
no_dev_packages
[[ ! -e $root/usr/lib/x86_64-linux-gnu/libvulkan.so.1 ]] || fail "the root still has libvulkan.so.1"
out=$(in_root "$bundle/sdfbench" --version) || fail "--version without a system Vulkan loader: $out"
say "no Vulkan in the root: '$out' (the bundle's lib/fallback loader)"
out=$(in_root "$bundle/sdfbench" info 2>&1) || fail "info without a Vulkan driver: $out"
grep -q 'unavailable: no Vulkan driver found' <<<"$out" || fail "info does not say that no Vulkan driver was found: $out"
say "info without a driver: $(grep -m1 unavailable <<<"$out" | sed 's/^ *//')"
if out=$(in_root "$bundle/sdfbench" render --scene thesis:sphere:1 --backend sdf-hash --size 16x9 2>&1); then
  fail "a Vulkan render succeeded without a driver: $out"
fi
[[ $(grep -c . <<<"$out") -eq 1 && $out == "sdfbench: error: "* ]] || fail "a Vulkan render without a driver is not one error line: $out"
say "render without a driver: $out"

# 2. Only the Vulkan loader and lavapipe added.
cat >"$root/etc/apt/sources.list.d/backports.list" <<SRC
deb $mirror bookworm-backports main
SRC
say "installing libvulkan1 and lavapipe (mesa-vulkan-drivers from bookworm-backports)"
in_root apt-get update -qq >"$work/apt.log" 2>&1 || { tail "$work/apt.log"; fail "apt-get update in the root"; }
in_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends libvulkan1 >>"$work/apt.log" 2>&1 &&
  in_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends -t bookworm-backports \
    mesa-vulkan-drivers libdrm2 libdrm-amdgpu1 >>"$work/apt.log" 2>&1 || { tail "$work/apt.log"; fail "installing Vulkan in the root"; }
no_dev_packages
in_root env LD_LIBRARY_PATH="$bundle/lib" "$bundle/bin/sdfbench" --version >/dev/null ||
  fail "the binary does not start with lib/ and the root's own loader, so the launcher would not prefer it"
in_root "$bundle/sdfbench" info >"$work/info.txt" 2>&1 || { cat "$work/info.txt"; fail "info with lavapipe"; }
grep -q llvmpipe "$work/info.txt" || { cat "$work/info.txt"; fail "info does not list lavapipe (llvmpipe)"; }
say "info: $(grep -m1 -i 'llvmpipe' "$work/info.txt" | sed 's/^ *//')"

in_root "$bundle/sdfbench" table --quick --meshes sphere --objects 1 --size 32x18 --check-size 32x18 --budget-s 0.2 \
  --frames 1 --csv /tmp/quick.csv >"$work/table.log" 2>&1 || { tail -20 "$work/table.log"; fail "table --quick in the root"; }
csv=$root/tmp/quick.csv
rows=$(($(wc -l <"$csv") - 1))
head -1 "$csv" | grep psnr >/dev/null || fail "the table's CSV has no agreement (psnr) column: $(head -1 "$csv")"
((rows >= 4)) || fail "table --quick wrote $rows rows"
say "table --quick: $rows rows in the root's CSV"

# The prepared device command as a GPU machine runs it: the repository's script beside dist/.
rm -rf "$root/opt/repo" && mkdir -p "$root/opt/repo/harness/scripts" "$root/opt/repo/dist"
cp harness/scripts/run_bundle_on_device.sh "$root/opt/repo/harness/scripts/"
cp "$archive" "$root/opt/repo/dist/"
rm -rf "$root/tmp/gpu_run"
in_root /opt/repo/harness/scripts/run_bundle_on_device.sh --out /tmp/gpu_run -- --device lavapipe --size 32x18 \
  --compare-size 32x18 --budget-s 0.2 --frames 1 --storage-scene thesis:sphere:10 \
  -- --table 6.3 --meshes sphere --objects 1 --check-size 32x18 >"$work/gpu_run.log" 2>&1 ||
  { tail -20 "$work/gpu_run.log"; fail "run_bundle_on_device.sh (the bundle's gpu_run.sh) on lavapipe"; }
[[ -s $root/tmp/gpu_run/machine.txt ]] || fail "run_bundle_on_device.sh wrote no machine.txt"
dir=$(echo "$root"/tmp/gpu_run/llvmpipe-*)
[[ $(grep -c '^exit 0$' "$dir/agreement.txt") -eq 10 ]] || fail "gpu_run.sh: not 10 agreeing compares in $dir/agreement.txt"
[[ $(grep -c ',ok,' "$dir/storage_vs_texel.csv") -eq 8 ]] || fail "gpu_run.sh: not 8 agreeing texel/storage rows"
[[ $(grep -c ',ok,' "$dir/brick_fetch.csv") -eq 8 ]] || fail "gpu_run.sh: not 8 agreeing sdf-bricks/sdf-global fetch-path rows"
say "gpu_run.sh: $(grep -c '^exit 0$' "$dir/agreement.txt") compares agree, 8 texel/storage rows, 8 brick fetch rows, $(($(wc -l <"$dir/tables.csv") - 1)) table rows"
say "all passed ($(tail -1 "$work/make_bundle.log" | sed 's/^make_bundle.sh: //'))"
