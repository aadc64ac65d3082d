#!/usr/bin/env bash
# Configures and builds sdfbench (Release) into ${BUILD_DIR:-build}. SDFBENCH_WARNINGS_AS_ERRORS=ON
# in the environment builds with -Werror (CI does, on Debian 12's GCC 12 and Debian 13's GCC 14).
set -euo pipefail
cd "$(dirname "$0")/../.."
build_dir="${BUILD_DIR:-build}"
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release ${SDFBENCH_WARNINGS_AS_ERRORS:+"-DSDFBENCH_WARNINGS_AS_ERRORS=$SDFBENCH_WARNINGS_AS_ERRORS"}
cmake --build "$build_dir" -j"$(nproc)"
