#!/usr/bin/python3
"""Charts for `voxr bench table1` (CSV in, PNG out): time vs resolution per model, time vs triangles, and time
vs accuracy with one point per method x resolution and the Pareto front marked.

usage: bench/table1_charts.py TABLE1.csv OUT_PREFIX      (writes OUT_PREFIX-resolution.png, -triangles.png,
                                                          -accuracy.png)
"""
import csv
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def load(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for key in ("triangles", "res", "voxels", "exact_voxels", "false_positives", "false_negatives",
                    "crossings", "tunnels"):
            r[key] = int(r[key])
        for key in ("kernels_ms", "total_ms"):
            r[key] = float(r[key])
    return rows


def error_rate(r):
    """Wrong voxels (missed + extra) per voxel of the exact set."""
    return (r["false_negatives"] + r["false_positives"]) / max(1, r["exact_voxels"])


def pareto(points):
    """Points (time, error, label) that no other point beats in both time and error."""
    front = []
    for p in sorted(points):
        if not front or p[1] < front[-1][1]:
            front.append(p)
    return front


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    rows = load(sys.argv[1])
    prefix = sys.argv[2]
    device = rows[0]["device"].split(" (")[0] if rows else "?"
    methods = list(dict.fromkeys(r["method"] for r in rows))
    models = list(dict.fromkeys(r["model"] for r in rows))

    # Time vs resolution, one panel per model.
    cols = min(3, len(models))
    nrows = (len(models) + cols - 1) // cols
    fig, axes = plt.subplots(nrows, cols, figsize=(5 * cols, 3.6 * nrows), squeeze=False)
    for ax, model in zip(axes.flat, models):
        for m in methods:
            pts = sorted((r["res"], r["kernels_ms"]) for r in rows if r["model"] == model and r["method"] == m)
            if pts:
                ax.plot(*zip(*pts), marker="o", label=m)
        tris = next(r["triangles"] for r in rows if r["model"] == model)
        ax.set(title=f"{model} ({tris:,} triangles)", xlabel="resolution (longest axis)", ylabel="kernel ms",
               xscale="log", yscale="log")
        ax.set_xticks(sorted({r["res"] for r in rows}), [str(x) for x in sorted({r["res"] for r in rows})])
        ax.grid(True, which="both", alpha=0.3)
    for ax in list(axes.flat)[len(models):]:
        ax.axis("off")
    axes.flat[0].legend(fontsize=8)
    fig.suptitle(f"Voxelization time vs resolution — {device}")
    fig.tight_layout()
    fig.savefig(f"{prefix}-resolution.png", dpi=110)

    # Time vs triangles at each resolution's largest common value.
    res = max(r["res"] for r in rows)
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    for m in methods:
        pts = sorted((r["triangles"], r["kernels_ms"]) for r in rows if r["res"] == res and r["method"] == m)
        if pts:
            ax.plot(*zip(*pts), marker="o", label=m)
    ax.set(title=f"Time vs triangles at {res} — {device}", xlabel="triangles", ylabel="kernel ms", xscale="log",
           yscale="log")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(f"{prefix}-triangles.png", dpi=110)

    # Time vs accuracy for the largest model: one point per method x resolution, Pareto front marked.
    big = max(models, key=lambda m: next(r["triangles"] for r in rows if r["model"] == m))
    fig, ax = plt.subplots(figsize=(7, 5))
    points = []
    for i, m in enumerate(methods):
        pts = [(r["kernels_ms"], error_rate(r), f"{m} {r['res']}") for r in rows
               if r["model"] == big and r["method"] == m]
        if not pts:
            continue
        ax.scatter([p[0] for p in pts], [max(p[1], 1e-6) for p in pts], label=m, s=40)
        for p in pts:
            ax.annotate(p[2].split()[-1], (p[0], max(p[1], 1e-6)), fontsize=7, xytext=(3, 3),
                        textcoords="offset points")
        points += pts
    front = pareto(points)
    ax.plot([p[0] for p in front], [max(p[1], 1e-6) for p in front], "k--", lw=1, label="Pareto front")
    ax.set(title=f"Speed vs accuracy, {big} — {device}", xlabel="kernel ms (log)",
           ylabel="wrong voxels / exact voxels (log; 1e-6 = exact)", xscale="log", yscale="log")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(f"{prefix}-accuracy.png", dpi=110)
    print(f"wrote {prefix}-resolution.png, {prefix}-triangles.png, {prefix}-accuracy.png")


if __name__ == "__main__":
    main()
