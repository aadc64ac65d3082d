#!/usr/bin/env bash
# Where lavapipe spends an SDF kernel's time, at the machine-code level (issue 14): samples a
# running `sdfbench render` with perf, reads the sampled JIT code out of the process and
# disassembles it (objdump), then reports the share of lavapipe's texel-fetch helper functions
# against the shader body, and what the body's samples land after (stack traffic, memory, ALU).
#
#   harness/scripts/profile_sdf_kernel.sh [--binary build/sdfbench] [--warmup-s 15] [--seconds 10] \
#       [-- RENDER_FLAGS...]   (default: --scene thesis:bunny:1000 --backend sdf-octree --size 640x360)
#
# --warmup-s must cover the structure build and the shader compilation (the samples should be of
# frames only). Needs perf (Debian: linux-perf), objdump (binutils) and the right to read the
# process' memory (root, or ptrace_scope 0); runs on lavapipe only (the JIT code is on the CPU).
set -euo pipefail
cd "$(dirname "$0")/../.."
binary=build/sdfbench warmup=15 seconds=10
render=(--scene thesis:bunny:1000 --backend sdf-octree --size 640x360)
while [[ $# -gt 0 ]]; do
  case "$1" in
    --binary) binary=$2; shift 2 ;;
    --warmup-s) warmup=$2; shift 2 ;;
    --seconds) seconds=$2; shift 2 ;;
    --) shift; render=("$@"); break ;;
    -h|--help) sed -n 2,12p "$0"; exit 0 ;;
    *) echo "profile_sdf_kernel.sh: error: unknown argument '$1' (see --help)" >&2; exit 1 ;;
  esac
done
for value in "$warmup" "$seconds"; do
  [[ $value =~ ^[0-9]+$ && $value -gt 0 ]] || { echo "profile_sdf_kernel.sh: error: --warmup-s and --seconds take whole seconds > 0, not '$value'" >&2; exit 1; }
done
for tool in perf objdump; do
  command -v "$tool" >/dev/null || { echo "profile_sdf_kernel.sh: error: '$tool' not found (Debian: linux-perf, binutils)" >&2; exit 1; }
done
[[ -x $binary ]] || { echo "profile_sdf_kernel.sh: error: --binary '$binary' is not an executable" >&2; exit 1; }
work=$(mktemp -d)
pid=
cleanup() { [[ -n $pid ]] && kill "$pid" 2>/dev/null; rm -rf "$work"; }
trap cleanup EXIT
# Frames enough to outlast the sampling; the process is stopped once its code has been read.
"$binary" render "${render[@]}" --frames 100000 --warmup 0 >"$work/render.log" 2>&1 &
pid=$!
echo "profile: render (pid $pid) warming up ${warmup} s, then ${seconds} s of samples" >&2
sleep "$warmup"
kill -0 "$pid" 2>/dev/null || { echo "profile_sdf_kernel.sh: error: the render ended early:" >&2; tail -3 "$work/render.log" >&2; exit 1; }
perf record -q -F 4000 -p "$pid" -o "$work/perf.data" -- sleep "$seconds" >/dev/null 2>&1
perf script -i "$work/perf.data" -F ip,dso 2>/dev/null >"$work/samples.txt"
echo "device and render: $("$binary" info 2>/dev/null | grep -m1 -i llvmpipe || true)"
echo "render flags: ${render[*]}"
/usr/bin/python3 harness/scripts/profile_sdf_kernel.py "$pid" "$work/samples.txt"
