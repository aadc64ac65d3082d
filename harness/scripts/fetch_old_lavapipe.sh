#!/usr/bin/env bash
# Unpacks Debian 12's own lavapipe (Mesa 22.3, which caps every shader invocation at 65535 loop
# iterations) into .deps/lavapipe-mesa22/ with an ICD file of its own, for the tests of the
# loop-cap guard (tests/loop_limit_test.cpp, which point VK_DRIVER_FILES at it). Nothing is
# installed: the system keeps its Mesa 25 lavapipe. Needs `apt-get update` to have run.
set -euo pipefail
cd "$(dirname "$0")/../.."
dir=.deps/lavapipe-mesa22
icd="$dir/lvp_icd.json"
if [ -f "$icd" ]; then
  echo "fetch_old_lavapipe: $icd present"
  exit 0
fi
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
sandbox=()
[ "$(id -u)" -ne 0 ] || sandbox=(-o APT::Sandbox::User=root)  # root: apt's _apt user cannot write to $work
if ! (cd "$work" && apt-get download -qq "${sandbox[@]}" mesa-vulkan-drivers/bookworm); then
  echo "fetch_old_lavapipe: error: could not download mesa-vulkan-drivers from Debian 12 (bookworm);" \
    "the loop-cap tests need it (run apt-get update, check the network)" >&2
  exit 1
fi
dpkg-deb -x "$work"/mesa-vulkan-drivers_*.deb "$work/x"
version="$(dpkg-deb -f "$work"/mesa-vulkan-drivers_*.deb Version)"
rm -rf "$dir"
mkdir -p "$dir"
cp "$work/x/usr/lib/x86_64-linux-gnu/libvulkan_lvp.so" "$dir/"
# Written last, so that a present ICD file means a complete folder.
cat >"$icd.tmp" <<JSON
{
  "file_format_version": "1.0.0",
  "ICD": {"library_path": "./libvulkan_lvp.so", "api_version": "1.3.230"}
}
JSON
mv "$icd.tmp" "$icd"
echo "fetch_old_lavapipe: Mesa $version lavapipe in $dir (for the loop-cap tests)"
