#!/usr/bin/env bash
# The one prepared command for a lent GPU machine, which has its driver and nothing else: unpack
# the newest bundle from dist/ (harness/scripts/make_bundle.sh, made on a Debian machine and
# carried along; e.g. the device tool's carry ["dist"]), print what the machine offers, and run
# the bundle's gpu_run.sh, leaving results/<device>/ under --out (default $OUT/results, else
# results). Flags after -- go to gpu_run.sh (default: --device gpu --minutes 4).
#
#   harness/scripts/run_bundle_on_device.sh [--bundle dist/sdfbench-...tar.gz] [--out DIR] [-- GPU_RUN_FLAGS...]
#
# Checked on lavapipe: --out /tmp/x -- --device lavapipe --size 32x18 --compare-size 32x18 ...
# Exit status: gpu_run.sh's (0 done, 2 a compare disagreed, 3 the tables were cut, 1 an error).
set -euo pipefail
cd "$(dirname "$0")/../.."
bundle="" out=${OUT:+$OUT/results}
out=${out:-results}
gpu_run_flags=(--device gpu --minutes 4)
die() { echo "run_bundle_on_device.sh: error: $*" >&2; exit 1; }
while [[ $# -gt 0 ]]; do
  case "$1" in
    --bundle|--out) [[ $# -ge 2 ]] || die "$1 needs a value"; [[ $1 == --bundle ]] && bundle=$2 || out=$2; shift 2 ;;
    --) shift; gpu_run_flags=("$@"); break ;;
    -h|--help) sed -n 2,12p "$0"; exit 0 ;;
    *) die "unknown argument '$1' (see --help)" ;;
  esac
done
[[ -n $bundle ]] || bundle=$(ls -t dist/sdfbench-*-linux-x86_64.tar.gz 2>/dev/null | sed -n 1p)
[[ -n $bundle && -f $bundle ]] || die "no bundle (give --bundle, or make one with harness/scripts/make_bundle.sh)"
mkdir -p "$out"
out=$(cd "$out" && pwd)
unpacked=$(mktemp -d)
trap 'rm -rf "$unpacked"' EXIT
tar -C "$unpacked" -xzf "$bundle"
root=$(echo "$unpacked"/sdfbench-*)
{
  echo "# $(date -u +%Y-%m-%dT%H:%M:%SZ) $(basename "$bundle") on $(uname -n), $(uname -r)"
  ldd --version 2>&1 | sed -n 1p  # sed reads it all: head would close the pipe early and, under pipefail, fail the script
  nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader 2>/dev/null || echo "(no nvidia-smi)"
  ls /usr/share/vulkan/icd.d /etc/vulkan/icd.d 2>/dev/null || echo "(no ICD folders)"
} | tee "$out/machine.txt" >&2
status=0
"$root/harness/scripts/gpu_run.sh" --out "$out" "${gpu_run_flags[@]}" || status=$?
echo "run_bundle_on_device.sh: gpu_run.sh exited $status; results under $out" >&2
exit "$status"
