#!/usr/bin/env bash
# The README's first command: install dependencies, build, and run the main job on the
# default device (lavapipe): list devices, the quick thesis tables (every backend, images
# checked against Embree, each row's check images kept), their plots, the HTML report of both, and
# one image per backend. Outputs go to out/.
set -euo pipefail
cd "$(dirname "$0")/../.."
harness/scripts/install_deps.sh
harness/scripts/build.sh
mkdir -p out/plots
sdfbench=build/sdfbench
$sdfbench info
$sdfbench table --quick --csv out/quick.csv --markdown out/quick.md --keep-images out/images
harness/scripts/plot_results.py out/quick.csv --out-dir out/plots
$sdfbench report out/quick.csv --plots out/plots --out out/report.html
for backend in $($sdfbench backends --names table | tr ',' ' '); do  # the registry's list (`sdfbench backends`)
  $sdfbench render --scene thesis:bunny:100 --backend "$backend" --mode shadow --size 320x180 --frames 1 \
    --out "out/bunny100_$backend.png"
done
echo "quickstart: tables in out/quick.md (CSV out/quick.csv), plots in out/plots/, the report in out/report.html" \
  "(open it in a browser), images in out/"
