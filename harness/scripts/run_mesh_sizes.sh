#!/usr/bin/env bash
# The mesh-size axis (results/README.md, "Cost against mesh size"): the bunny resized to 1k..1M
# triangles, 1 and 10 objects, primary and shadow, every backend, 640x360; CSVs and markdown
# into results/lavapipe/ (or $1), then the cost-vs-triangles plots. Resumable: run it again to
# finish an interrupted run. About an hour on 2 cores.
set -euo pipefail
cd "$(dirname "$0")/../.."
out=${1:-results/lavapipe}
common=(--table 6.3 --meshes bunny --triangles 1000,4000,16000,64000,256000,1000000 --objects 1,10
  --size 640x360 --frames 3 --warmup 1 --budget-s 60)
for mode in primary shadow; do
  build/sdfbench table "${common[@]}" --mode "$mode" --resume \
    --csv "$out/mesh_sizes_$mode.csv" --markdown "$out/mesh_sizes_$mode.md"
done
mkdir -p "$out/plots"
/usr/bin/python3 harness/scripts/plot_results.py "$out/mesh_sizes_primary.csv" "$out/mesh_sizes_shadow.csv" --out-dir "$out/plots"
