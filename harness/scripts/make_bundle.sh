#!/usr/bin/env bash
# Builds a relocatable sdfbench bundle for a Linux x86-64 machine that cannot install anything
# (a GPU machine with only its driver; docs/cluster-and-gpu.md, "Running on a GPU machine"): the Release binary,
# the shared libraries it needs beyond glibc, the scene data, gpu_run.sh and a launcher that
# sets the library path, as one .tar.gz.
#
#   harness/scripts/make_bundle.sh [--build-dir build] [--out dist] [--max-mib 60] [--max-glibc 2.36]
#                                  [--bookworm-root DIR]
#
# The bundle carries everything but glibc, so it starts where the glibc is at least as new as the
# build host's (its floor, printed and written into README.txt). --max-glibc (default 2.36, Debian
# 12's; Ubuntu 24.04 has 2.39) refuses a bundle with a higher floor: on a newer host (Debian 13:
# 2.41) build it with --bookworm-root DIR, which makes a Debian 12 root at DIR (debootstrap
# --variant=minbase, kept for the next call; needs root), installs the dependencies there
# (install_deps.sh) and builds the bundle inside it from a copy of this checkout.
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
# larger than --max-mib (compressed), needs a newer glibc than --max-glibc, or when a library cannot
# be found.
set -euo pipefail
cd "$(dirname "$0")/../.."
build_dir=build out=dist max_mib=60 max_glibc=2.36 bookworm_root=""
die() { echo "make_bundle.sh: error: $*" >&2; exit 1; }
while [[ $# -gt 0 ]]; do
  case "$1" in
    --build-dir|--out|--max-mib|--max-glibc|--bookworm-root)
      [[ $# -ge 2 ]] || die "$1 needs a value"
      case "$1" in
        --build-dir) build_dir=$2 ;; --out) out=$2 ;; --max-mib) max_mib=$2 ;; --max-glibc) max_glibc=$2 ;;
        --bookworm-root) bookworm_root=$2 ;;
      esac
      shift 2 ;;
    -h|--help) sed -n 2,32p "$0"; exit 0 ;;
    *) die "unknown argument '$1' (see --help)" ;;
  esac
done
[[ $max_mib =~ ^[0-9]+$ ]] || die "--max-mib takes a whole number, not '$max_mib'"
[[ $max_glibc =~ ^2\.[0-9]+$ ]] || die "--max-glibc takes a glibc version such as 2.36, not '$max_glibc'"

if [[ -n $bookworm_root ]]; then
  [[ $(id -u) -eq 0 ]] || die "--bookworm-root needs root (debootstrap, chroot and mounts)"
  bookworm_root=$(realpath -m "$bookworm_root")
  . harness/scripts/debian_root.sh
  trap 'debian_root_unmount "$bookworm_root"' EXIT
  echo "make_bundle.sh: building in a Debian 12 root at $bookworm_root (debootstrap, the dependencies and the build" \
    "take minutes the first time; the root is kept)"
  debian_root_make "$bookworm_root" bookworm "$bookworm_root.debootstrap.log" ||
    die "debootstrap bookworm failed (log: $bookworm_root.debootstrap.log)"
  debian_root_mount "$bookworm_root"
  debian_root_copy_checkout "$bookworm_root" /opt/sdfbench-src
  rm -rf "$bookworm_root/opt/sdfbench-dist"
  debian_root_run "$bookworm_root" bash -c "cd /opt/sdfbench-src && harness/scripts/install_deps.sh >/opt/install_deps.log 2>&1" ||
    { tail -20 "$bookworm_root/opt/install_deps.log" >&2; die "install_deps.sh failed in the Debian 12 root"; }
  debian_root_run "$bookworm_root" /opt/sdfbench-src/harness/scripts/make_bundle.sh --out /opt/sdfbench-dist \
    --max-mib "$max_mib" --max-glibc "$max_glibc" | tail -1
  mkdir -p "$out"
  built=$(ls "$bookworm_root"/opt/sdfbench-dist/sdfbench-*.tar.gz)
  cp "$built" "$out/$(basename "$built").tmp"
  mv "$out/$(basename "$built").tmp" "$out/$(basename "$built")"
  echo "make_bundle.sh: $out/$(basename "$built") (built in the Debian 12 root)"
  exit 0
fi

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
  package=$(dpkg -S "*/$(basename "$(readlink -f "$path")")" 2>/dev/null | sed -n 1p | cut -d: -f1) || true
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
if [[ $(printf '%s\n' "${glibc#GLIBC_}" "$max_glibc" | sort -V | tail -1) != "$max_glibc" ]]; then
  die "the bundle would need glibc >= ${glibc#GLIBC_} (the symbols it links on this host), newer than --max-glibc $max_glibc (default: Debian" \
    "12's), so it would not start on older systems and GPU machines: build it with --bookworm-root DIR, or raise --max-glibc"
fi
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
