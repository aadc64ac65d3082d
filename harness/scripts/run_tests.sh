#!/usr/bin/env bash
# The README's second command: build (if needed) and run the test suite with ctest. Arguments are
# passed to ctest (e.g. -R 'Cli|OldLavapipe' for a subset).
set -euo pipefail
cd "$(dirname "$0")/../.."
harness/scripts/build.sh
ctest --test-dir "${BUILD_DIR:-build}" --output-on-failure -j"$(nproc)" "$@"
