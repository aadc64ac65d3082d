#!/usr/bin/env bash
# The README's first command: install dependencies, build, and run the main job on the
# default device (lavapipe): list devices, render the thesis bunny scene with every backend
# and check that their images agree. Outputs go to out/.
set -euo pipefail
cd "$(dirname "$0")/../.."
harness/scripts/install_deps.sh
harness/scripts/build.sh
mkdir -p out
sdfbench=build/sdfbench
$sdfbench info
for backend in embree tri-aabb; do
  $sdfbench render --scene thesis:bunny:100 --backend "$backend" --mode shadow --size 320x180 \
    --out "out/bunny100_$backend.png" --aov "out/bunny100_$backend.exr"
done
$sdfbench compare --scene thesis:bunny:100 --backends embree,tri-aabb --mode shadow --size 320x180 --out-dir out
echo "quickstart: images in out/"
