#!/usr/bin/python3
"""Plots from sdfbench CSVs (table, sweep, merge), with Debian's python3-matplotlib.

    harness/scripts/plot_results.py results/lavapipe/tables.csv [more.csv ...] --out-dir results/lavapipe/plots

Writes, for whatever the CSVs contain:
  fps_vs_objects_<mode>.png   FPS vs object count (log-log), one panel per mesh, one line per backend
  thesis_vs_measured.png      each thesis table: our FPS and the thesis' FPS vs object count, per mesh,
                              each series naming its device, resolution and mode
  sweep_<metric>.png          sweep heat maps: hash cell x octree depth -> FPS, steps/ray and
                              instance evaluations/ray (sweeps of the hash and octree)
  brick_sweep.png             sdf-bricks sweeps over --voxels: Mrays/s and the depth error in voxels
                              vs voxels, one line per format, trace mode and hit mode
  global_sweep.png            sdf-global sweeps over --global-voxel: Mrays/s, structure MB and build
                              seconds vs the voxel size, one line per format, band and hit mode
  structure_cost_<mode>.png   build seconds and structure MB vs object count, one panel per mesh,
                              one line per backend that builds a structure
  cost_vs_triangles_<mode>_<n>objects.png
                              the mesh-size axis (meshes "<mesh>@<triangles>", table --triangles):
                              ms per frame, build ms, structure bytes and triangle work per ray vs
                              the real triangle count (log-log), one line per backend
  mrays_vs_overlap_<mesh>_<n>objects_<mode>.png
                              the overlap axis (table --table overlap): Mrays/s vs the overlap measured
                              in each scene (log-log), one line per backend, the k each scene asked
                              for on the top axis
Rows flagged as disagreeing with the reference are drawn hollow; budget-cut rows get a dagger.
"""
import argparse
import csv
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
THESIS_CSV = os.path.join(HERE, "..", "..", "scenes", "thesis_tables.csv")
THESIS_DEVICE = "GTX 1070, 1280x720"


def short_device(name):
    """'llvmpipe (LLVM 15.0.6, 256 bits)' -> 'llvmpipe': a legend's worth of the device's name."""
    return name.split(" (")[0] or "?"


THESIS_CONFIG = {"6.1": ("sdf-octree", "whitted"), "6.2": ("sdf-hash", "whitted"), "6.3": ("tri-aabb", "shadow")}


def read_rows(paths):
    rows = []
    for path in paths:
        with open(path, newline="") as f:
            rows.extend(csv.DictReader(f))
    return rows


def read_thesis():
    values = {}
    with open(THESIS_CSV, newline="") as f:
        for row in csv.DictReader(line for line in f if not line.startswith("#")):
            values[(row["table"], row["mesh"], int(row["objects"]))] = float(row["fps"])
    return values


def number(text):
    try:
        return float(text)
    except (TypeError, ValueError):
        return None


def on_object_axis(row):
    """a row of the thesis' tables or their extra backends (not a sweep, not the overlap table)"""
    return row["table"] not in ("sweep", "overlap")


def asked_overlap(scene):
    """'overlap:bunny:1000:4[:seed]' -> '4'"""
    parts = scene.split(":")
    return parts[3] if parts[0] == "overlap" and len(parts) >= 4 else ""


def usable(row):
    # a TRUNCATED row's FPS is invalid: lavapipe's loop limit cut pixels short
    return not row["agreement"].startswith(("ERROR", "TRUNCATED")) and (number(row["fps"]) or 0) > 0


def save(fig, path):
    tmp = os.path.join(os.path.dirname(path), "." + os.path.basename(path) + ".tmp.png")
    fig.savefig(tmp, dpi=120, bbox_inches="tight")
    os.replace(tmp, path)  # atomic: never a half-written plot
    plt.close(fig)
    print("wrote", path)


def plot_series(ax, points, label, marker="o", color=None):
    points = sorted(points)
    xs = [p[0] for p in points]
    ys = [p[1] for p in points]
    line, = ax.plot(xs, ys, marker=marker, label=label, color=color)
    for x, y, row in points:
        if row is not None and row["agreement"].startswith("DISAGREE"):
            ax.plot([x], [y], marker=marker, markersize=11, markerfacecolor="none", color=line.get_color())
        if row is not None and row["budget_cut"] == "1":
            ax.annotate("\u2020", (x, y), textcoords="offset points", xytext=(4, 4))


def fps_vs_objects(rows, out_dir):
    table_rows = [r for r in rows if on_object_axis(r) and usable(r) and "@" not in r["mesh"]]
    for mode in sorted({r["mode"] for r in table_rows}):
        mode_rows = [r for r in table_rows if r["mode"] == mode]
        meshes = list(dict.fromkeys(r["mesh"] for r in mode_rows))
        fig, axes = plt.subplots(1, len(meshes), figsize=(4.2 * len(meshes), 3.6), squeeze=False)
        for ax, mesh in zip(axes[0], meshes):
            series = defaultdict(list)
            for r in mode_rows:
                if r["mesh"] == mesh:
                    series[r["backend"]].append((int(r["objects"]), float(r["fps"]), r))
            for backend, points in series.items():
                first = points[0][2]
                plot_series(ax, points, f"{backend} ({short_device(first['device'])}, {first['width']}x{first['height']})")
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_title(f"{mesh}, {mode}")
            ax.set_xlabel("objects")
            ax.set_ylabel("FPS")
            ax.grid(True, which="both", alpha=0.3)
            ax.legend(fontsize=8)
        sizes = sorted({f'{r["width"]}x{r["height"]}' for r in mode_rows})
        devices = sorted({r["device"] for r in mode_rows})
        fig.suptitle(f"FPS vs object count, {mode} ({', '.join(sizes)}; devices: {'; '.join(devices)})", fontsize=9)
        save(fig, os.path.join(out_dir, f"fps_vs_objects_{mode}.png"))


def thesis_vs_measured(rows, out_dir):
    thesis = read_thesis()
    rows = [r for r in rows if "@" not in r["mesh"]]  # resized meshes have no thesis values
    tables = [t for t in THESIS_CONFIG if any(r["table"] == t and usable(r) for r in rows)]
    if not tables:
        return
    fig, axes = plt.subplots(1, len(tables), figsize=(4.8 * len(tables), 3.8), squeeze=False)
    for ax, table in zip(axes[0], tables):
        table_rows = [r for r in rows if r["table"] == table and usable(r)]
        backend, mode = THESIS_CONFIG[table]
        for mesh in dict.fromkeys(r["mesh"] for r in table_rows):
            ours = [(int(r["objects"]), float(r["fps"]), r) for r in table_rows if r["mesh"] == mesh]
            first = next(r for r in table_rows if r["mesh"] == mesh)
            plot_series(ax, ours, f"{mesh}: ours, {short_device(first['device'])}, {first['width']}x{first['height']}, {mode}")
            theirs = [(n, thesis[(table, mesh, n)], None) for n, _, _ in ours if (table, mesh, n) in thesis]
            if theirs:
                plot_series(ax, theirs, f"{mesh}: thesis, {THESIS_DEVICE}, {mode}", marker="x")
        ax.set_title(f"table {table}: {backend}, {mode}")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("objects")
        ax.set_ylabel("FPS")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    sizes = sorted({f'{r["width"]}x{r["height"]}' for r in rows if r["table"] in tables})
    other = [size for size in sizes if size != "1280x720"]
    note = (f"; ours at {', '.join(other)}, the thesis at 1280x720: FPS not comparable across resolutions"
            if other else "; both at 1280x720")
    devices = sorted({short_device(r["device"]) for r in rows if r["table"] in tables})
    fig.suptitle(f"the thesis' FPS ({THESIS_DEVICE}) and ours ({', '.join(devices)}){note}", fontsize=9)
    save(fig, os.path.join(out_dir, "thesis_vs_measured.png"))


def cost_vs_triangles(rows, out_dir):
    sized = [r for r in rows if on_object_axis(r) and usable(r) and "@" in r["mesh"]]
    panels = (("ms_median", "ms per frame"), ("build_ms", "structure build (ms)"), ("structure_bytes", "structure bytes"),
              ("triangle_work", "triangle distances + tests per ray"))
    palette = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    colors = {b: palette[i % len(palette)] for i, b in enumerate(dict.fromkeys(r["backend"] for r in sized))}  # one per backend
    for mode in sorted({r["mode"] for r in sized}):
        for objects in sorted({int(r["objects"]) for r in sized if r["mode"] == mode}):
            group = [r for r in sized if r["mode"] == mode and int(r["objects"]) == objects]
            fig, axes = plt.subplots(1, len(panels), figsize=(4.2 * len(panels), 3.6), squeeze=False)
            for ax, (metric, title) in zip(axes[0], panels):
                series = defaultdict(list)
                for r in group:
                    if metric == "triangle_work":
                        parts = [number(r["triangle_evals_per_ray"]), number(r["triangle_tests_per_ray"])]
                        value = sum(p for p in parts if p is not None) if any(p is not None for p in parts) else None
                    else:
                        value = number(r[metric])
                    if value is not None and value > 0:
                        series[r["backend"]].append((int(r["triangles"]), value, r))  # the mesh's count (once, not per instance)
                for backend, points in series.items():
                    plot_series(ax, points, backend, color=colors[backend])
                ax.set_xscale("log")
                ax.set_yscale("log")
                ax.set_title(title, fontsize=9)
                ax.set_xlabel("triangles per mesh")
                ax.grid(True, which="both", alpha=0.3)
                if series:
                    ax.legend(fontsize=7)
            sizes = sorted({f'{r["width"]}x{r["height"]}' for r in group})
            meshes = sorted({r["mesh"].split("@")[0] for r in group})
            fig.suptitle(f"cost vs triangles: {', '.join(meshes)}, {objects} object(s), {mode}, {', '.join(sizes)} "
                         f"(device: {group[0]['device']})", fontsize=10)
            save(fig, os.path.join(out_dir, f"cost_vs_triangles_{mode}_{objects}objects.png"))


def mrays_vs_overlap(rows, out_dir):
    axis_rows = [r for r in rows if r["table"] == "overlap" and usable(r) and number(r["overlap"]) is not None]
    palette = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    colors = {b: palette[i % len(palette)] for i, b in enumerate(dict.fromkeys(r["backend"] for r in axis_rows))}
    plain = matplotlib.ticker.FuncFormatter(lambda v, _: f"{v:g}")
    for mesh, objects, mode in dict.fromkeys((r["mesh"], int(r["objects"]), r["mode"]) for r in axis_rows):
        group = [r for r in axis_rows if (r["mesh"], int(r["objects"]), r["mode"]) == (mesh, objects, mode)]
        fig, ax = plt.subplots(figsize=(7.2, 4.4))
        series = defaultdict(list)
        for r in group:
            series[r["backend"]].append((number(r["overlap"]), number(r["mrays_per_s"]), r))
        for backend, points in series.items():
            plot_series(ax, points, backend, color=colors[backend])
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.yaxis.set_major_locator(matplotlib.ticker.LogLocator(subs=(1, 2, 5)))
        ax.yaxis.set_major_formatter(plain)
        ax.yaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        # the overlap measured in each scene below, the k its spec asked for above
        measured = {}
        for r in group:
            measured.setdefault(asked_overlap(r["scene"]), number(r["overlap"]))
        ticks = sorted(measured.values())
        ax.set_xticks(ticks, [f"{t:.1f}" for t in ticks])
        ax.xaxis.set_minor_locator(matplotlib.ticker.NullLocator())
        top = ax.secondary_xaxis("top")
        top.set_xticks(ticks, [k for k, _ in sorted(measured.items(), key=lambda item: item[1])])
        top.xaxis.set_minor_locator(matplotlib.ticker.NullLocator())
        top.set_xlabel("k asked (overlap:<mesh>:<count>:<k>)", fontsize=8)
        ax.set_xlabel("overlap measured (instance boxes over a point of their union)")
        ax.set_ylabel("Mrays/s")
        ax.grid(True, which="major", alpha=0.3)
        ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1))
        sizes = sorted({f'{r["width"]}x{r["height"]}' for r in group})
        devices = sorted({short_device(r["device"]) for r in group})
        ax.set_title(f"{mesh}, {objects} objects, {mode}, {', '.join(sizes)} (devices: {', '.join(devices)}; "
                     "hollow: disagrees with Embree)", fontsize=9)
        save(fig, os.path.join(out_dir, f"mrays_vs_overlap_{mesh}_{objects}objects_{mode}.png"))


def is_brick_sweep(row):
    return row["table"] == "sweep" and row.get("voxels", "") != ""


def is_global_sweep(row):
    return row["table"] == "sweep" and number(row.get("global_voxel", "")) is not None


def global_sweep(rows, out_dir):
    sweep = [r for r in rows if is_global_sweep(r) and usable(r)]
    if not sweep:
        return
    lines = defaultdict(list)
    for r in sweep:
        lines[(r["sdf_format"], int(number(r["brick_band"])), r["hit"])].append(r)
    metrics = (("mrays_per_s", "Mrays/s", 1.0), ("structure_bytes", "structure MB", 1e-6), ("build_ms", "build s", 1e-3))
    fig, axes = plt.subplots(1, 3, figsize=(13, 3.8))
    for k, ((fmt, band, hit), group) in enumerate(sorted(lines.items())):
        color = plt.cm.tab10(k % 10)
        for ax, (metric, _, scale) in zip(axes, metrics):
            points = sorted(((number(r["global_voxel"]), number(r[metric]) * scale, r) for r in group
                             if number(r[metric]) is not None), key=lambda p: p[:2])
            line, = ax.plot([p[0] for p in points], [p[1] for p in points], "-" if hit == "exact" else "--", marker="o",
                            color=color, label=f"{fmt}, band {band}, {hit} hits")
            for x, y, r in points:
                if not r["agreement"].startswith(("ok", "reference")):
                    ax.plot([x], [y], "o", mfc="white", mec=line.get_color())
    voxels = sorted({number(r["global_voxel"]) for r in sweep})
    for ax, (_, title, _) in zip(axes, metrics):
        ax.set_xscale("log", base=2)
        ax.set_xticks(voxels, [f"{v:g}" for v in voxels])
        ax.set_xlabel("global voxel (world units)")
        ax.set_title(title)
        ax.grid(True, which="both", alpha=0.3)
    axes[1].set_yscale("log")
    axes[2].set_yscale("log")
    axes[0].legend(fontsize=7)
    fig.suptitle(f"{sweep[0]['scene']}, {sweep[0]['backend']} {sweep[0]['mode']} ({sweep[0]['width']}x{sweep[0]['height']}; "
                 "hollow: disagrees with Embree)", fontsize=10)
    save(fig, os.path.join(out_dir, "global_sweep.png"))


def structure_cost(rows, out_dir):
    table_rows = [r for r in rows if on_object_axis(r) and usable(r) and "@" not in r["mesh"]
                  and number(r.get("structure_bytes", "")) is not None]
    for mode in sorted({r["mode"] for r in table_rows}):
        mode_rows = [r for r in table_rows if r["mode"] == mode]
        meshes = list(dict.fromkeys(r["mesh"] for r in mode_rows))
        fig, axes = plt.subplots(2, len(meshes), figsize=(4.2 * len(meshes), 6.4), squeeze=False)
        for col, mesh in enumerate(meshes):
            for row, (metric, title, scale) in enumerate((("build_ms", "build s", 1e-3),
                                                          ("structure_bytes", "structure MB", 1e-6))):
                ax = axes[row][col]
                series = defaultdict(list)
                for r in mode_rows:
                    if r["mesh"] == mesh and number(r[metric]) is not None and number(r[metric]) > 0:
                        series[r["backend"]].append((int(r["objects"]), number(r[metric]) * scale, r))
                for backend, points in series.items():
                    plot_series(ax, points, backend)
                ax.set_xscale("log")
                ax.set_yscale("log")
                ax.set_title(f"{mesh}: {title}")
                ax.set_xlabel("objects")
                ax.grid(True, which="both", alpha=0.3)
                ax.legend(fontsize=7)
        fig.subplots_adjust(hspace=0.4)
        fig.suptitle(f"structure build time and memory vs object count ({mode}; device: {mode_rows[0]['device']})",
                     fontsize=10)
        save(fig, os.path.join(out_dir, f"structure_cost_{mode}.png"))


def brick_sweep(rows, out_dir):
    sweep = [r for r in rows if is_brick_sweep(r) and usable(r)]
    if not sweep:
        return
    lines = defaultdict(list)
    for r in sweep:
        lines[(r["sdf_format"], r["brick_trace"], r["hit"])].append(r)
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for k, ((fmt, trace, hit), group) in enumerate(sorted(lines.items())):
        label = f"{fmt}, {trace}, {hit} hits"
        style = "-" if hit == "exact" else "--"
        color = plt.cm.tab20(k % 20)
        for ax, metric in zip(axes, ("mrays_per_s", "depth_p99_voxels")):
            points = sorted(((number(r["voxels"]), number(r[metric]), r) for r in group if number(r[metric]) is not None),
                            key=lambda p: p[:2])
            if not points:
                continue
            line, = ax.plot([p[0] for p in points], [p[1] for p in points], style, marker="o", color=color, label=label)
            for x, y, r in points:  # disagreeing rows hollow, as elsewhere
                if not r["agreement"].startswith(("ok", "reference")):
                    ax.plot([x], [y], "o", mfc="white", mec=line.get_color())
    voxels = sorted({number(r["voxels"]) for r in sweep})
    for ax, title in zip(axes, ("Mrays/s", "depth error p99 (voxels)")):
        ax.set_xscale("log", base=2)
        ax.set_xticks(voxels, [f"{v:g}" for v in voxels])
        ax.set_xlabel("voxels per mesh extent")
        ax.set_title(title)
        ax.grid(True, which="both", alpha=0.3)
    axes[1].set_yscale("log")
    axes[0].legend(fontsize=6)
    fig.suptitle(f"{sweep[0]['scene']}, {sweep[0]['backend']} {sweep[0]['mode']} ({sweep[0]['width']}x{sweep[0]['height']}; "
                 "hollow: disagrees with Embree)", fontsize=10)
    save(fig, os.path.join(out_dir, "brick_sweep.png"))


def sweep_heatmaps(rows, out_dir):
    # One heat map per sweep run over the hash cell and octree depth (other sweeps' rows, e.g. a
    # sweep of another axis at one cell and depth, would land in the same cells).
    candidates = [r for r in rows if r["table"] == "sweep" and usable(r) and not is_brick_sweep(r) and not is_global_sweep(r)
                  and r.get("hash_cell") and r.get("octree_depth")]
    runs = {}
    for r in candidates:
        runs.setdefault(r.get("run_id", ""), []).append(r)
    sweeps = [rs for rs in runs.values()
              if len({r["hash_cell"] for r in rs}) > 1 or len({r["octree_depth"] for r in rs}) > 1]
    for n, sweep in enumerate(sweeps):
        heatmap(sweep, out_dir, "" if n == 0 else f"_{n + 1}")


def heatmap(sweep, out_dir, suffix):
    cells = sorted({float(r["hash_cell"]) for r in sweep})
    depths = sorted({int(float(r["octree_depth"])) for r in sweep})
    for metric, title in (("fps", "FPS"), ("steps_per_ray", "sphere-tracing steps per ray"),
                          ("instance_evals_per_ray", "instance distance evaluations per ray")):
        grid = [[None for _ in cells] for _ in depths]
        for r in sweep:
            value = number(r[metric])
            if value is not None:
                grid[depths.index(int(float(r["octree_depth"])))][cells.index(float(r["hash_cell"]))] = value
        if all(v is None for line in grid for v in line):
            continue
        fig, ax = plt.subplots(figsize=(1.2 * len(cells) + 2.5, 0.8 * len(depths) + 1.8))
        data = [[v if v is not None else float("nan") for v in line] for line in grid]
        image = ax.imshow(data, cmap="viridis", aspect="auto", origin="lower")
        for y, line in enumerate(grid):
            for x, v in enumerate(line):
                ax.text(x, y, "–" if v is None else f"{v:.3g}", ha="center", va="center", color="w", fontsize=8)
        ax.set_xticks(range(len(cells)), [f"{c:g}" for c in cells])
        ax.set_yticks(range(len(depths)), [str(d) for d in depths])
        ax.set_xlabel("hash cell")
        ax.set_ylabel("octree depth")
        ax.set_title(f"{title}: {sweep[0]['scene']}, {sweep[0]['backend']} {sweep[0]['mode']}", fontsize=9)
        fig.colorbar(image, ax=ax)
        save(fig, os.path.join(out_dir, f"sweep_{metric}{suffix}.png"))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("csv", nargs="+", help="CSV files written by sdfbench table, sweep or merge")
    parser.add_argument("--out-dir", required=True, help="directory for the PNGs (must exist)")
    args = parser.parse_args()
    if not os.path.isdir(args.out_dir):
        sys.exit(f"plot_results.py: error: --out-dir '{args.out_dir}' is not a directory")
    try:
        rows = read_rows(args.csv)
    except (OSError, csv.Error) as e:
        sys.exit(f"plot_results.py: error: {e}")
    if rows and "fps" not in rows[0]:
        sys.exit("plot_results.py: error: not an sdfbench measurement CSV (no 'fps' column)")
    fps_vs_objects(rows, args.out_dir)
    thesis_vs_measured(rows, args.out_dir)
    sweep_heatmaps(rows, args.out_dir)
    brick_sweep(rows, args.out_dir)
    global_sweep(rows, args.out_dir)
    structure_cost(rows, args.out_dir)
    cost_vs_triangles(rows, args.out_dir)
    mrays_vs_overlap(rows, args.out_dir)


if __name__ == "__main__":
    main()
