#!/usr/bin/env bash
# Unpacks Debian 12's own lavapipe (Mesa 22.3, which caps every shader invocation at 65535 loop
# iterations) into .deps/lavapipe-mesa22/ with an ICD file of its own, for the tests of the
# loop-cap guard (tests/loop_limit_test.cpp, which point VK_DRIVER_FILES at it). Nothing is
# installed and the system's apt configuration is not touched: the packages come through an apt
# state of this script's own (.deps/apt-bookworm/, Debian 12's main suite from
# ${SDFBENCH_DEBIAN_MIRROR:-http://deb.debian.org/debian}), so this works on Debian 12 and 13.
# The driver is built on LLVM 15: where the system has no libLLVM-15.so.1 (Debian 13 ships LLVM 19),
# Debian 12's libllvm15 is unpacked beside the driver, whose RUNPATH ($ORIGIN, set by patchelf)
# makes it found there.
set -euo pipefail
cd "$(dirname "$0")/../.."
dir=.deps/lavapipe-mesa22
icd="$dir/lvp_icd.json"
if [ -f "$icd" ]; then
  echo "fetch_old_lavapipe: $icd present"
  exit 0
fi
mirror="${SDFBENCH_DEBIAN_MIRROR:-http://deb.debian.org/debian}"
keyring=/usr/share/keyrings/debian-archive-keyring.gpg
state="$PWD/.deps/apt-bookworm"
fail() {
  echo "fetch_old_lavapipe: error: $* (the loop-cap tests need Debian 12's lavapipe; check the network or" \
    "SDFBENCH_DEBIAN_MIRROR)" >&2
  exit 1
}
[ -f "$keyring" ] || fail "no $keyring (package debian-archive-keyring) to verify Debian 12's packages"
mkdir -p "$state/lists/partial" "$state/cache/archives/partial" "$state/sources.list.d"
echo "deb [signed-by=$keyring] $mirror bookworm main" >"$state/sources.list"
apt_private=(-o "Dir::Etc::SourceList=$state/sources.list" -o "Dir::Etc::SourceParts=$state/sources.list.d"
  -o "Dir::State::Lists=$state/lists" -o "Dir::Cache=$state/cache" -o "Debug::NoLocking=1")
[ "$(id -u)" -ne 0 ] || apt_private+=(-o APT::Sandbox::User=root)  # root: apt's _apt user cannot write here
apt-get "${apt_private[@]}" update -qq >"$state/update.log" 2>&1 ||
  fail "apt-get update of Debian 12's main suite failed ($(tail -1 "$state/update.log"))"

packages=(mesa-vulkan-drivers)
need_llvm=false
if ! /sbin/ldconfig -p | grep 'libLLVM-15\.so\.1 ' >/dev/null; then  # not grep -q (pipefail + SIGPIPE)
  need_llvm=true
  packages+=(libllvm15)
  command -v patchelf >/dev/null || fail "patchelf is missing (install_deps.sh installs it on Debian 13)"
fi
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
(cd "$work" && apt-get "${apt_private[@]}" download -qq "${packages[@]/%//bookworm}") >"$work/download.log" 2>&1 ||
  fail "could not download ${packages[*]} from Debian 12 ($(tail -1 "$work/download.log"))"
for deb in "$work"/*.deb; do dpkg-deb -x "$deb" "$work/x"; done
version="$(dpkg-deb -f "$work"/mesa-vulkan-drivers_*.deb Version)"
rm -rf "$dir"
mkdir -p "$dir"
cp "$work/x/usr/lib/x86_64-linux-gnu/libvulkan_lvp.so" "$dir/"
llvm_note=""
if $need_llvm; then
  cp "$work"/x/usr/lib/x86_64-linux-gnu/libLLVM-15.so.1 "$dir/"
  patchelf --set-rpath '$ORIGIN' "$dir/libvulkan_lvp.so"
  llvm_note=", with Debian 12's libLLVM-15.so.1 beside it"
fi
# Written last, so that a present ICD file means a complete folder.
cat >"$icd.tmp" <<JSON
{
  "file_format_version": "1.0.0",
  "ICD": {"library_path": "./libvulkan_lvp.so", "api_version": "1.3.230"}
}
JSON
mv "$icd.tmp" "$icd"
echo "fetch_old_lavapipe: Mesa $version lavapipe in $dir$llvm_note (for the loop-cap tests)"
