#!/usr/bin/env bash
# The README's first command: install dependencies, build, and run the main job on the
# default device (lavapipe): list devices, the quick thesis tables (every backend, images
# checked against Embree), their plots, and one image per backend. Outputs go to out/.
set -euo pipefail
cd "$(dirname "$0")/../.."
harness/scripts/install_deps.sh
harness/scripts/build.sh
mkdir -p out/plots
sdfbench=build/sdfbench
$sdfbench info
$sdfbench table --quick --csv out/quick.csv --markdown out/quick.md
harness/scripts/plot_results.py out/quick.csv --out-dir out/plots
for backend in embree tri-aabb bvh vk-rt sdf-hash sdf-octree sdf-bricks sdf-global; do
  $sdfbench render --scene thesis:bunny:100 --backend "$backend" --mode shadow --size 320x180 --frames 1 \
    --out "out/bunny100_$backend.png"
done
echo "quickstart: tables in out/quick.md (CSV out/quick.csv), plots in out/plots/, images in out/"
