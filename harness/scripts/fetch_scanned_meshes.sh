#!/usr/bin/env bash
# Fetches the real scanned meshes that specs name (thesis:armadillo:100, scenes/named_mesh.h) from
# Debian packages into the mesh cache's scans/ folder: never vendored into the repository, never
# downloaded by sdfbench itself. `apt-get download` needs no root and installs nothing.
#
#   glmark2-data   usr/share/glmark2/models/bunny.obj  -> stanford-bunny.obj (69 666 triangles)
#   libcgal-demo   data.tar.gz: data/meshes/{armadillo,ChineseDragon-10kv,refined_elephant,bunny00}.off
#                  -> armadillo (52 000), dragon (19 994), elephant (88 928), bunny00 (75 408)
#
# The packages' copyright files are copied beside the meshes (scans/LICENSES/) and the lines that
# cover the meshes printed: glmark2-data's "Files: *" (GPL-3+); CGAL's data files carry no notice
# of their own, which its copyright file puts under CC0 1.0 ("All other files that do not have an
# explicit copyright notice"). A MANIFEST records each file's package version and SHA-256.
#
# usage: fetch_scanned_meshes.sh [--cache DIR]   (default: $SDFBENCH_MESH_CACHE, else
#        $XDG_CACHE_HOME/sdfbench/meshes, else ~/.cache/sdfbench/meshes, as sdfbench uses)
set -euo pipefail
die() { echo "fetch_scanned_meshes: error: $*" >&2; exit 1; }

cache="${SDFBENCH_MESH_CACHE:-${XDG_CACHE_HOME:+$XDG_CACHE_HOME/sdfbench/meshes}}"
[ -n "$cache" ] || cache="${HOME:?no HOME: give --cache DIR}/.cache/sdfbench/meshes"
while [ $# -gt 0 ]; do
  case "$1" in
    --cache) [ $# -ge 2 ] || die "--cache needs a folder"; cache="$2"; shift 2 ;;
    -h|--help) sed -n '2,17p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) die "unknown argument '$1' (see --help)" ;;
  esac
done
for tool in apt-get dpkg-deb tar sha256sum; do command -v "$tool" >/dev/null || die "'$tool' is not installed"; done

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
echo "fetch_scanned_meshes: downloading glmark2-data, libcgal-demo and libcgal-dev (its copyright file) into $work"
(cd "$work" && apt-get download glmark2-data libcgal-demo libcgal-dev >/dev/null) ||
  die "apt-get download failed (no package lists? run 'apt-get update' first)"
for deb in "$work"/*.deb; do dpkg-deb -x "$deb" "$work/root"; done

out="$work/scans"
mkdir -p "$out/LICENSES"
cp "$work/root/usr/share/glmark2/models/bunny.obj" "$out/stanford-bunny.obj"
tar -xzf "$work/root/usr/share/doc/libcgal-dev/data.tar.gz" -C "$work" \
  data/meshes/armadillo.off data/meshes/ChineseDragon-10kv.off data/meshes/refined_elephant.off data/meshes/bunny00.off
mv "$work"/data/meshes/*.off "$out/"
cp "$work/root/usr/share/doc/glmark2-data/copyright" "$out/LICENSES/glmark2-data.copyright"
cp "$work/root/usr/share/doc/libcgal-dev/copyright" "$out/LICENSES/libcgal.copyright"

{
  echo "# sdfbench's scanned meshes, fetched by harness/scripts/fetch_scanned_meshes.sh on $(date -u +%Y-%m-%d)"
  for f in "$out"/*.obj "$out"/*.off; do
    case "$(basename "$f")" in stanford-bunny.obj) pkg=glmark2-data ;; *) pkg=libcgal-demo ;; esac
    version="$(dpkg-deb -f "$(ls "$work"/"$pkg"_*.deb)" Version)"
    echo "$(sha256sum "$f" | cut -d' ' -f1)  $(basename "$f")  $pkg $version"
  done
} > "$out/MANIFEST"

echo "licences:"
echo "  glmark2-data ($(grep -m1 -A0 '^Files: \*' "$out/LICENSES/glmark2-data.copyright")): $(awk '/^Files: \*$/{f=1} f && /^License:/{print $2; exit}' "$out/LICENSES/glmark2-data.copyright")"
echo "  libcgal-demo's data: $(grep -m1 -o 'licensed under the Creative Commons CC0 1.0 license' "$out/LICENSES/libcgal.copyright" || echo 'see LICENSES/libcgal.copyright')"

# Into place as a whole: a run cut short leaves the previous scans/ as it was.
mkdir -p "$cache"
rm -rf "$cache/scans.new"
mv "$out" "$cache/scans.new"
rm -rf "$cache/scans.old"
[ ! -e "$cache/scans" ] || mv "$cache/scans" "$cache/scans.old"
mv "$cache/scans.new" "$cache/scans"
rm -rf "$cache/scans.old"
echo "fetch_scanned_meshes: done: $(ls "$cache/scans" | grep -c -E '\.(obj|off)$') meshes in $cache/scans (MANIFEST, LICENSES/)"
