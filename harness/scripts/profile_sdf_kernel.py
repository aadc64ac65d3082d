#!/usr/bin/env python3
"""Report of profile_sdf_kernel.sh: lavapipe's JIT code of a running render, by sampled region.

Reads perf samples (`perf script -F ip,dso`), groups the JIT samples (no file behind them) into
contiguous code regions, reads each region out of the live process (/proc/PID/mem) and
disassembles it with objdump. Small regions that return without calling anything are lavapipe's
texel-fetch helpers (one per texel buffer); regions of more than a page are the shader's code,
whose samples are put to the instruction before them (a timer sample lands on the instruction after the one that
stalled) and classed: stack traffic (spills, reloads, a helper's results read back), other
memory operands, calls, branches, or the ALU operation.
"""
import collections
import re
import subprocess
import sys
import tempfile

GAP = 4096  # samples further apart than this belong to different regions
INSTRUCTION = re.compile(r"^\s*([0-9a-f]+):\t(?:[0-9a-f]{2} )+\s*\t(.*)$")


def jit_samples(path):
    """Sample addresses outside every file-backed object (JIT code)."""
    counts = collections.Counter()
    total = 0
    for line in open(path):
        parts = line.split(None, 1)
        if len(parts) != 2:
            continue
        total += 1
        dso = parts[1]
        if "perf-" in dso or "[unknown]" in dso or "//anon" in dso:
            counts[int(parts[0], 16)] += 1
    return counts, total


def regions(counts):
    addresses = sorted(counts)
    groups = [[addresses[0]]]
    for a in addresses[1:]:
        if a - groups[-1][-1] > GAP:
            groups.append([])
        groups[-1].append(a)
    return [(g[0] & ~0xFFF, g[-1] + 64) for g in groups]


def disassemble(pid, start, end):
    with open(f"/proc/{pid}/mem", "rb") as mem:
        mem.seek(start)
        code = mem.read(end - start)
    with tempfile.NamedTemporaryFile(suffix=".bin") as f:
        f.write(code)
        f.flush()
        out = subprocess.run(["objdump", "-D", "-b", "binary", "-m", "i386:x86-64", f"--adjust-vma={start:#x}", f.name],
                             check=True, capture_output=True, text=True).stdout
    listing = []
    for line in out.splitlines():
        m = INSTRUCTION.match(line)
        if m:
            listing.append((int(m.group(1), 16), m.group(2).strip()))
    return listing


SHIFT = re.compile(r"vpslld \$0x([0-9a-f]+),%ymm0,")
INDEXED_LOAD = re.compile(r"\(%r\w+,%r\w+,")
# The SDF kernels' texel formats by size (sdf_scene_distance.glsl).
FORMATS = {4: "R32UI: hash cells, octree nodes, instance lists", 8: "RG32UI: mesh-grid cells",
           16: "RGBA32: instance and mesh records, list entries, vertices, normals"}


def helper_kind(listing):
    """A texel-fetch helper (a short function that returns before any call): its texel size and loads; else None."""
    for i, (address, text) in enumerate(listing):
        if text.startswith("call") or address - listing[0][0] > 1024:
            return None
        if text.startswith("ret"):
            body = [t for _, t in listing[:i]]
            shift = next((SHIFT.search(t) for t in body if SHIFT.search(t)), None)
            size = 1 << int(shift.group(1), 16) if shift else 0
            gathers = sum(1 for t in body if "gather" in t)
            loads = sum(1 for t in body if INDEXED_LOAD.search(t))
            how = f"{gathers} hardware gather" if gathers else f"{loads} loads"
            return f"texel fetch, {size}-byte texels ({FORMATS.get(size, '?')}), {how} per call"
    return None


def classify(previous):
    if not previous:
        return "other"
    op = previous.split()[0]
    if "%rsp" in previous or "%rbp" in previous:
        return "after a stack operand (spill, reload, a helper's result read back)"
    if op.startswith("call"):
        return "after a call (a helper returned)"
    if op.startswith("j"):
        return "after a branch"
    if "(%" in previous:
        return "after another memory operand"
    return "after ALU: " + op


def main():
    pid, samples_path = int(sys.argv[1]), sys.argv[2]
    counts, total = jit_samples(samples_path)
    jit = sum(counts.values())
    if jit == 0:
        sys.exit("profile_sdf_kernel.py: error: no JIT samples (is the device lavapipe, and --warmup-s long enough?)")
    print(f"samples: {total}, in JIT code: {jit} ({100 * jit / total:.1f} %)")
    found = []
    for start, end in regions(counts):
        listing = disassemble(pid, start, end)
        share = sum(counts[a] for a, _ in listing)
        found.append((share, start, end, listing))
    found.sort(reverse=True)
    print("\nJIT code sampled (regions of > 0.5 % of the samples), share of the JIT samples:")
    helpers = 0
    body = []  # the shader's own code: every region that is not a helper and spans more than a page
    for share, start, end, listing in found:
        kind = helper_kind(listing)
        if kind:
            helpers += share
        elif end - start > 4096:
            body.append((share, listing))
            kind = "shader code"
        if share >= 0.005 * jit:
            print(f"{end - start:7d} bytes {100 * share / jit:6.1f} %  {kind or 'other JIT code'}")
    print(f"texel-fetch helpers in all: {100 * helpers / jit:.1f} % of JIT samples")
    classes = collections.Counter()
    listings = [listing for _, listing in body]
    for listing in listings:
        for i, (address, _) in enumerate(listing):
            classes[classify(listing[i - 1][1] if i else "")] += counts.get(address, 0)
    share = sum(s for s, _ in body)
    size = sum(len(listing) for listing in listings)
    calls = sum(1 for listing in listings for _, t in listing if t.startswith("call"))
    stack = sum(1 for listing in listings for _, t in listing if "%rsp" in t or "%rbp" in t)
    print(f"\nshader code: {100 * share / jit:.1f} % of JIT samples; {size} instructions sampled over, {calls} calls,"
          f" {stack} with a stack operand; its samples by the instruction before them:")
    for name, n in classes.most_common(14):
        print(f"  {100 * n / share:5.1f} %  {name}")


if __name__ == "__main__":
    main()
