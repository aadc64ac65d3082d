#!/usr/bin/env bash
# The README's second command: build (if needed) and run the test suite with ctest.
set -euo pipefail
cd "$(dirname "$0")/../.."
harness/scripts/build.sh
ctest --test-dir "${BUILD_DIR:-build}" --output-on-failure -j"$(nproc)"
