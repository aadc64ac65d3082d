#!/usr/bin/env bash
# Builds a relocatable sdfbench bundle for a Linux x86-64 machine that cannot install anything
# (a GPU machine with only its driver; README, "Running on a GPU machine"): the Release binary,
# the shared libraries it needs beyond glibc, the scene data, gpu_run.sh and a launcher that
# sets the library path, as one .tar.gz.
#
#   harness/scripts/make_bundle.sh [--build-dir build] [--out dist] [--max-mib 60]
#
# Layout of sdfbench-<version>-<commit>-linux-x86_64/:
#   sdfbench                   the launcher (run this)
#   bin/sdfbench               the binary
#   lib/                       its libraries from this machine's Debian packages
#   lib/fallback/              the C++ runtime, zlib and the Vulkan loader: every Linux has its
#                              own, which the launcher prefers (its Vulkan loader knows its
#                              drivers); these are used only when the binary does not start
#                              without them
#   scenes/                    meshes, scene files, the thesis' tables
#   harness/scripts/gpu_run.sh the prepared GPU run
#   README.txt, licenses/      how to run it; the copyright files of every library carried
# Prints the archive, its size and the newest glibc symbol version it needs; exit 1 when it is
# larger than --max-mib (compressed) or when a library cannot be found.
set -euo pipefail
cd "$(dirname "$0")/../.."
build_dir=build out=dist max_mib=60
die() { echo "make_bundle.sh: error: $*" >&2; exit 1; }
while [[ $# -gt 0 ]]; do
  case "$1" in
    --build-dir|--out|--max-mib)
      [[ $# -ge 2 ]] || die "$1 needs a value"
      case "$1" in --build-dir) build_dir=$2 ;; --out) out=$2 ;; --max-mib) max_mib=$2 ;; esac
      shift 2 ;;
    -h|--help) sed -n 2,22p "$0"; exit 0 ;;
    *) die "unknown argument '$1' (see --help)" ;;
  esac
done
[[ $max_mib =~ ^[0-9]+$ ]] || die "--max-mib takes a whole number, not '$max_mib'"

cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build_dir" --target sdfbench -j"$(nproc)"
binary=$build_dir/sdfbench
version=$("$binary" --version | awk '{print $2}')
commit=$(git rev-parse --short=7 HEAD 2>/dev/null || echo unknown)
name=sdfbench-$version-$commit-linux-x86_64
mkdir -p "$out"
stage=$(mktemp -d "$out/.$name.XXXXXX")
trap 'rm -rf "$stage"' EXIT
root=$stage/$name
mkdir -p "$root/bin" "$root/lib/fallback" "$root/licenses" "$root/harness/scripts"

# glibc itself stays the machine's: it cannot be carried (the dynamic loader and libc must match).
is_glibc() { [[ $1 =~ ^(linux-vdso|ld-linux-x86-64|libc|libm|libdl|libpthread|librt|libresolv)\.so ]]; }
is_fallback() { [[ $1 =~ ^(libstdc\+\+|libgcc_s|libz|libvulkan)\.so ]]; }
strip --strip-unneeded -o "$root/bin/sdfbench" "$binary"
packages=()
while read -r soname path; do
  is_glibc "$soname" && continue
  [[ -f $path ]] || die "'$soname' is not found on this machine (ldd: '$path')"
  if is_fallback "$soname"; then dest=$root/lib/fallback; else dest=$root/lib; fi
  cp -L "$path" "$dest/$soname"
  # (by file name: with merged /usr, dpkg may know the file under /lib, ldd under /usr/lib)
  package=$(dpkg -S "*/$(basename "$(readlink -f "$path")")" 2>/dev/null | head -1 | cut -d: -f1) || true
  [[ -n $package ]] && packages+=("$package")
done < <(ldd "$binary" | awk '$2 == "=>" {print $1, $3}')
for package in $(printf '%s\n' "${packages[@]}" | sort -u); do
  cp "/usr/share/doc/$package/copyright" "$root/licenses/$package.copyright" 2>/dev/null || true
done

mkdir -p "$root/scenes/meshes"
cp scenes/*.json scenes/*.csv "$root/scenes/"
cp scenes/meshes/*.obj scenes/meshes/PROVENANCE.md "$root/scenes/meshes/"
cp harness/scripts/gpu_run.sh "$root/harness/scripts/"
cp harness/bundle/launcher.sh "$root/sdfbench"
chmod +x "$root/sdfbench"
glibc=$( { objdump -T "$root/bin/sdfbench"; for l in "$root"/lib/*.so* "$root"/lib/fallback/*.so*; do objdump -T "$l"; done; } |
  grep -o 'GLIBC_[0-9.]*' | sort -uV | tail -1)
sed -e "s/@NAME@/$name/g" -e "s/@GLIBC@/${glibc#GLIBC_}/g" harness/bundle/README.txt > "$root/README.txt"

# The launcher must start the binary from the bundle alone (no build tree, no data dir).
SDFBENCH_DATA_DIR= "$root/sdfbench" --version >/dev/null || die "the bundle's launcher does not start the binary"

archive=$out/$name.tar.gz
tar -C "$stage" -czf "$archive.tmp" "$name"
mv "$archive.tmp" "$archive"
bytes=$(stat -c %s "$archive")
unpacked=$(du -sb "$root" | cut -f1)
echo "make_bundle.sh: $archive: $(awk -v b="$bytes" 'BEGIN{printf "%.1f", b/1048576}') MiB compressed," \
  "$(awk -v b="$unpacked" 'BEGIN{printf "%.1f", b/1048576}') MiB unpacked, $(find "$root/lib" -name '*.so*' | wc -l) libraries; needs glibc >= ${glibc#GLIBC_}"
(( bytes <= max_mib * 1048576 )) || die "$archive is larger than --max-mib $max_mib MiB"
