#!/usr/bin/env bash
# Builds (Release, into ${BUILD_DIR:-build}, like build.sh) and runs the CPU SDF microbenchmarks.
# Extra arguments go to Google Benchmark, e.g. --benchmark_filter=Query. The build log goes to
# stderr so that stdout is only the benchmark report.
set -euo pipefail
cd "$(dirname "$0")/../.."
build_dir="${BUILD_DIR:-build}"
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release >&2
cmake --build "$build_dir" -j"$(nproc)" --target sdfbench_microbench >&2
exec "$build_dir/tests/bench/sdfbench_microbench" "$@"
