#!/bin/sh
# sdfbench bundle launcher (harness/scripts/make_bundle.sh): runs bin/sdfbench with the bundle's
# libraries and scene data. The system's C++ runtime, zlib and Vulkan loader are preferred (its
# loader finds its own drivers); lib/fallback is added only when the binary does not start
# without it (a machine without libvulkan.so.1, or with an older libstdc++).
here=$(cd "$(dirname "$0")" && pwd)
libs=$here/lib
if ! LD_LIBRARY_PATH="$libs${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" "$here/bin/sdfbench" --version >/dev/null 2>&1; then
  libs=$libs:$here/lib/fallback
fi
LD_LIBRARY_PATH="$libs${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
SDFBENCH_DATA_DIR=${SDFBENCH_DATA_DIR:-$here/scenes}
export LD_LIBRARY_PATH SDFBENCH_DATA_DIR
exec "$here/bin/sdfbench" "$@"
