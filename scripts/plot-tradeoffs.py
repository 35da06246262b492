#!/usr/bin/python3
"""Draws the speed-against-accuracy charts of docs/TRADEOFFS.md from tessera_sweep's CSV files.

usage: scripts/plot-tradeoffs.py SWEEP_DIR OUT_DIR

Per knob, a Pareto chart (time relative to the default settings, geometric mean over the
workloads at one thread, against the knob's error measure) and the time per workload at one and
two threads; depth precision (z-fighting against distance per depth format, one panel per
near/far ratio). Uses matplotlib (Debian: python3-matplotlib).
"""
import csv
import math
import os
import shutil
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

DEFAULTS = {"subpixel_bits": "8", "samples": "1", "depth_format": "float32",
            "interpolation": "perspective", "hiz": "on", "bin_tile_size": "64",
            "block_size": "8"}


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def relative_times(speed, knob, threads):
    """{value: geometric mean over workloads of ms(value) / ms(default)} for one thread count."""
    rows = [r for r in speed if r["knob"] == knob and r["threads"] == str(threads)]
    base = {r["workload"]: float(r["ms_median"]) for r in rows if r["value"] == DEFAULTS[knob]}
    out = {}
    for value in dict.fromkeys(r["value"] for r in rows):
        logs = [math.log(float(r["ms_median"]) / base[r["workload"]])
                for r in rows if r["value"] == value and r["workload"] in base]
        out[value] = math.exp(sum(logs) / len(logs))
    return out


def error_measures(sweep):
    """{knob: (label, {value: error})}: each knob's own error measure."""
    quality = read(os.path.join(sweep, "quality.csv"))
    snap = read(os.path.join(sweep, "snapping.csv"))
    depth = read(os.path.join(sweep, "depth_precision.csv"))
    interp = read(os.path.join(sweep, "interpolation.csv"))
    edges = {}
    for r in quality:
        edges.setdefault(r["knob"], {})[r["value"]] = float(r["rmse_edges"])
    displacement = {r["subpixel_bits"]: float(r["max_displacement_px"]) for r in snap}
    # Depth: mean fraction of z-fighting pixels over the distances, at the largest near/far
    # ratio the sweep ran up to 1e4 (a common game camera: 0.1 to 1000).
    ratios = sorted({float(r["near_far_ratio"]) for r in depth})
    ratio = max([x for x in ratios if x <= 1e4] or ratios)
    fight = {}
    for fmt in dict.fromkeys(r["format"] for r in depth):
        vals = [float(r["near_hidden"]) for r in depth
                if r["format"] == fmt and float(r["near_far_ratio"]) == ratio]
        fight[fmt] = sum(vals) / len(vals)
    cells = {r["interpolation"]: float(r["wrong_cells"]) for r in interp}
    return {
        "samples": ("edge RMSE (8-bit units) against 256 samples per pixel", edges["samples"]),
        "subpixel_bits": ("largest vertex displacement by snapping (px)", displacement),
        "depth_format": ("z-fighting: nearer plane hidden (fraction, near/far 1:%g)" % ratio,
                         fight),
        "interpolation": ("checkerboard cells wrong (fraction of floor pixels)", cells),
        "hiz": ("edge RMSE (8-bit units): the image does not change", edges["hiz"]),
        "bin_tile_size": ("edge RMSE (8-bit units): the image does not change",
                          edges["bin_tile_size"]),
        "block_size": ("edge RMSE (8-bit units): the image does not change",
                       edges["block_size"]),
    }


def pareto(speed, errors, out):
    for knob, (label, err) in errors.items():
        times = relative_times(speed, knob, 1)
        fig, ax = plt.subplots(figsize=(6.4, 4.4))
        xs = [times[v] for v in err if v in times]
        ys = [err[v] for v in err if v in times]
        ax.plot(xs, ys, "o", color="tab:blue")
        for v in err:
            if v in times:
                ax.annotate(v, (times[v], err[v]), textcoords="offset points", xytext=(6, 4),
                            fontsize=9)
        ax.set_xlabel("time per frame relative to the default (geometric mean over workloads, 1 thread)")
        ax.set_ylabel(label, fontsize=9)
        ax.set_title("%s: speed against error (default %s)" % (knob, DEFAULTS[knob]))
        if knob == "subpixel_bits":
            ax.set_yscale("log")
        ax.grid(True, alpha=0.3)
        fig.tight_layout()
        fig.savefig(os.path.join(out, "pareto_%s.png" % knob), dpi=110)
        plt.close(fig)


def speed_bars(speed, out):
    for knob in DEFAULTS:
        rows = [r for r in speed if r["knob"] == knob]
        workloads = list(dict.fromkeys(r["workload"] for r in rows))
        values = list(dict.fromkeys(r["value"] for r in rows))
        threads = sorted({int(r["threads"]) for r in rows})
        fig, axes = plt.subplots(1, len(threads), figsize=(6.0 * len(threads), 4.2), squeeze=False)
        for ax, t in zip(axes[0], threads):
            width = 0.8 / len(values)
            for i, v in enumerate(values):
                ys = []
                for w in workloads:
                    ms = [float(r["ms_median"]) for r in rows
                          if r["workload"] == w and r["value"] == v and r["threads"] == str(t)]
                    ys.append(ms[0] if ms else 0.0)
                ax.bar([j + i * width for j in range(len(workloads))], ys, width, label=v)
            ax.set_xticks([j + 0.4 - width / 2 for j in range(len(workloads))])
            ax.set_xticklabels(workloads, rotation=30)
            ax.set_yscale("log")
            ax.set_ylabel("ms per frame (median)")
            ax.set_title("%s, %d thread%s" % (knob, t, "" if t == 1 else "s"))
            ax.grid(True, axis="y", alpha=0.3)
            ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(out, "speed_%s.png" % knob), dpi=100)
        plt.close(fig)


def depth_chart(sweep, out):
    depth = read(os.path.join(sweep, "depth_precision.csv"))
    ratios = sorted({float(r["near_far_ratio"]) for r in depth})
    formats = list(dict.fromkeys(r["format"] for r in depth))
    cols = min(3, len(ratios))
    rows_n = (len(ratios) + cols - 1) // cols
    fig, axes = plt.subplots(rows_n, cols, figsize=(4.6 * cols, 3.6 * rows_n), squeeze=False)
    for k, ratio in enumerate(ratios):
        ax = axes[k // cols][k % cols]
        for fmt in formats:
            pts = [(float(r["distance"]), float(r["near_hidden"])) for r in depth
                   if r["format"] == fmt and float(r["near_far_ratio"]) == ratio]
            pts.sort()
            # float32 and unorm24 coincide (both keep 24 bits near 1): dashes show both.
            style = "--" if fmt == "unorm24" else "-"
            ax.plot([p[0] for p in pts], [p[1] for p in pts], style, marker=".", label=fmt)
        ax.set_xscale("log")
        ax.set_ylim(-0.03, 1.03)
        ax.set_title("near 1, far %g" % ratio)
        ax.set_xlabel("distance of the planes (near plane = 1)")
        ax.set_ylabel("nearer plane hidden (fraction of pixels)")
        ax.grid(True, alpha=0.3)
    for k in range(len(ratios), rows_n * cols):
        axes[k // cols][k % cols].axis("off")
    axes[0][0].legend(fontsize=8)
    fig.suptitle("Depth precision: two planes 0.01% of their distance apart (z-fighting)")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "depth_precision.png"), dpi=100)
    plt.close(fig)


def texture_chart(sweep, out):
    """Texture filters: time relative to trilinear (geometric mean over the textured grid, medium
    and floor, one thread) against the floor's RMSE. Skipped when the sweep has no texture tables."""
    speed_path = os.path.join(sweep, "texture_speed.csv")
    quality_path = os.path.join(sweep, "texture_quality.csv")
    if not (os.path.exists(speed_path) and os.path.exists(quality_path)):
        return
    speed = [r for r in read(speed_path) if r["threads"] == "1"]
    rmse = {r["filter"]: float(r["rmse"]) for r in read(quality_path)}
    base = {r["workload"]: float(r["ms_median"]) for r in speed if r["filter"] == "trilinear"}
    if not base:
        return
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for name in rmse:
        logs = [math.log(float(r["ms_median"]) / base[r["workload"]])
                for r in speed if r["filter"] == name and r["workload"] in base]
        if not logs:
            continue
        t = math.exp(sum(logs) / len(logs))
        ax.plot([t], [rmse[name]], "o", color="tab:blue")
        ax.annotate(name, (t, rmse[name]), textcoords="offset points", xytext=(6, 4), fontsize=9)
    ax.set_xlabel("time per frame relative to trilinear (geometric mean: textured grid, medium "
                  "and floor, 1 thread)", fontsize=8)
    ax.set_ylabel("floor RMSE (8-bit units) against 256 filtered samples per pixel", fontsize=9)
    ax.set_title("texture filter: speed against error")
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "pareto_texture_filter.png"), dpi=110)
    plt.close(fig)


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    sweep, out = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    speed = read(os.path.join(sweep, "speed.csv"))
    pareto(speed, error_measures(sweep), out)
    speed_bars(speed, out)
    depth_chart(sweep, out)
    texture_chart(sweep, out)
    for name in os.listdir(sweep):
        if name.endswith((".csv", ".json")) or name.startswith(("checkerboard_", "texture_")):
            shutil.copy(os.path.join(sweep, name), os.path.join(out, name))
    print("plot-tradeoffs: wrote charts and data to %s" % out)


if __name__ == "__main__":
    main()
