#!/usr/bin/env bash
# Builds (Release, into ${BUILD_DIR:-build}, like build.sh) and runs the SDF kernel benchmarks of
# tests/bench/sdf_kernel_bench.cpp: `ceiling` (the device's point-triangle distances per second) and
# `breakdown` (the sdf-octree kernel's time per part); arguments go to the tool, e.g.
#   harness/scripts/run_kernel_bench.sh ceiling
#   harness/scripts/run_kernel_bench.sh breakdown --mode shadow --size 640x360 --frames 3
# The build log goes to stderr so that stdout is only the report.
set -euo pipefail
cd "$(dirname "$0")/../.."
build_dir="${BUILD_DIR:-build}"
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release >&2
cmake --build "$build_dir" -j"$(nproc)" --target sdfbench_kernel_bench >&2
exec "$build_dir/tests/bench/sdfbench_kernel_bench" "$@"
