#!/usr/bin/env python3
"""Checks that a merged CSV holds exactly the rows of a reference CSV: the same configurations
(run_index and every column below), in the same order, each once. Timings, frame counts, where
it ran and build times differ from run to run and are not compared.
Usage: same_rows.py REFERENCE.csv MERGED.csv [--rows I,J,...] [--ignore COLUMN,...]
  --rows: only the reference's rows of these run_index; --ignore: columns not compared"""
import csv
import sys

DETERMINISTIC = [
    "run_index", "run_id", "table", "scene", "mesh", "triangles", "objects", "backend", "mode", "max_depth",
    "width", "height", "hash_cell", "octree_depth", "octree_min_objects", "octree_min_size", "lists", "mesh_cell",
    "cells_per_extent", "hit", "max_steps", "hit_epsilon", "hit_footprint", "over_relax", "cell_bound",
    "requested_frames", "warmup", "budget_s", "reference", "requested_device", "whitted_passes", "validate",
    "clock", "rays_per_pixel", "steps_per_ray", "instance_evals_per_ray", "triangle_evals_per_ray",
    "aabb_tests_per_ray", "triangle_tests_per_ray", "out_of_steps_per_ray", "structure_bytes", "check_size",
    "hit_agreement", "id_agreement", "psnr", "agreement", "threads",
]


def rows(path):
    with open(path, newline="") as f:
        table = list(csv.DictReader(f))
    missing = [c for c in DETERMINISTIC if table and c not in table[0]]
    if missing:
        sys.exit(f"same_rows: '{path}' has no column {missing[0]}")
    return [[r[c] for c in DETERMINISTIC] for r in table]


def main():
    args = sys.argv[1:]
    def option(name):
        if name not in args:
            return None
        k = args.index(name)
        if k + 1 >= len(args):
            sys.exit(__doc__)
        value = set(args[k + 1].split(","))
        del args[k:k + 2]
        return value
    only, ignored = option("--rows"), option("--ignore") or set()
    if len(args) != 2:
        sys.exit(__doc__)
    reference, merged = rows(args[0]), rows(args[1])
    if only is not None:
        reference = [r for r in reference if r[0] in only]
    indices = [r[0] for r in merged]
    if len(set(indices)) != len(indices):
        sys.exit(f"same_rows: '{args[1]}' measures a run_index twice: {indices}")
    if [r[0] for r in reference] != indices:
        sys.exit(f"same_rows: '{args[1]}' has run_index {indices}, '{args[0]}' {[r[0] for r in reference]}")
    for ref, got in zip(reference, merged):
        for name, a, b in zip(DETERMINISTIC, ref, got):
            if a != b and name not in ignored:
                sys.exit(f"same_rows: run_index {ref[0]}: {name} is '{b}' in '{args[1]}', '{a}' in '{args[0]}'")
    print(f"same_rows: {len(merged)} rows of '{args[1]}' match '{args[0]}'")


main()
