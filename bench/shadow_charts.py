#!/usr/bin/python3
"""Speed vs accuracy charts for the shadow (and refraction) benchmarks: CSV in, one PNG per scene and a Markdown
table out.

usage: bench/shadow_charts.py CSV OUT_DIR [--error-column COL] [--time-column COL] [--group-columns A,B]
                              [--label-column COL] [--scene-column COL] [--higher-is-better]

The CSV has one row per run. The shadow benchmark writes the columns
    scene,method,mode,resolution,frame_ms,frame_ms_min,frame_ms_max,rmse,max_abs,share_over_0.05,psnr
(times in ms per frame, errors of the transmittance at receiver pixels against the reference).

Writes into OUT_DIR (created if missing):
  SCENE.png    time (log x; bars from TIME_min to TIME_max when those columns exist) against error, one
               colour and marker per group (method + mode), points labelled by resolution, the Pareto front
               (no other run is both faster and more accurate) as a step line.
  STEM.md      every row, sorted by scene, group columns and resolution, Pareto-optimal rows marked, where
               STEM is the CSV's file name without .csv.
The refraction benchmark (voxr bench refraction) runs it once per error column (rmse, angle_mean_deg) into
OUT-charts/COLUMN/ with --group-columns method,step,normals --label-column res; cells may be empty (image-space
and the reference have no step, normals or res). --error-column psnr --higher-is-better keeps the higher scores.
Needs python3 and matplotlib (Debian: python3-matplotlib).
"""
import argparse
import csv
import math
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402

MARKERS = "osD^vP*Xh<>p"


def number(text):
    """The float a CSV cell holds ("inf", "nan" included), or None for an empty cell or a non-number."""
    try:
        return float(text)
    except (TypeError, ValueError):
        return None


def natural_key(text):
    """Sorts "64" before "512" and "r64" before "r512": digit runs compare as numbers."""
    return [(0, int(part), "") if part.isdigit() else (1, 0, part) for part in re.split(r"(\d+)", str(text))]


def load(path, args):
    """Rows of the CSV as dicts (cells as text), plus the time and error of each as floats; exits with a
    message naming the file, the line and the column on a missing column or a bad value."""
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        columns = reader.fieldnames or []
        needed = [args.scene_column, args.time_column, args.error_column, args.label_column] + args.group_columns
        missing = [c for c in needed if c not in columns]
        if missing:
            sys.exit(f"{path}: missing column(s) {', '.join(missing)} (the file has: {', '.join(columns)})")
        rows = []
        for line, r in enumerate(reader, start=2):
            for key in (args.time_column, args.error_column):
                value = number(r[key])
                if value is None:
                    sys.exit(f"{path}:{line}: column {key} must be a number (got {r[key]!r})")
            time = number(r[args.time_column])
            if not time > 0:
                sys.exit(f"{path}:{line}: column {args.time_column} must be positive (got {r[args.time_column]!r})")
            r["_time"], r["_error"] = time, number(r[args.error_column])
            r["_group"] = " ".join(r[c] for c in args.group_columns if r[c])
            rows.append(r)
    if not rows:
        sys.exit(f"{path}: no rows")
    return columns, rows


def pareto(rows, higher_is_better=False):
    """The rows no other row beats: another row is at least as fast and as accurate and better in one of the
    two. Accuracy is a lower error, or a higher value with higher_is_better (PSNR, SSIM). Rows with a NaN
    error are never on the front. Sorted by time."""
    sign = -1.0 if higher_is_better else 1.0
    ok = [r for r in rows if not math.isnan(r["_error"])]
    front = []
    for r in ok:
        t, e = r["_time"], sign * r["_error"]
        beaten = any(o["_time"] <= t and sign * o["_error"] <= e and (o["_time"] < t or sign * o["_error"] < e)
                     for o in ok)
        if not beaten:
            front.append(r)
    return sorted(front, key=lambda r: (r["_time"], sign * r["_error"]))


def file_stem(text):
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", text).strip("._") or "scene"


def chart(scene, rows, front, args, path, references=()):
    groups = list(dict.fromkeys(r["_group"] for r in rows))
    shown = [r for r in rows if math.isfinite(r["_error"])]
    errors = [r["_error"] for r in shown]
    log_y = bool(errors) and min(errors) > 0 and max(errors) / min(errors) > 20
    fig, ax = plt.subplots(figsize=(7.5, 5.2))
    has_range = f"{args.time_column}_min" in rows[0] and f"{args.time_column}_max" in rows[0]
    for i, g in enumerate(groups):
        pts = sorted((r for r in shown if r["_group"] == g), key=lambda r: r["_time"])
        if not pts:
            continue
        xs, ys = [r["_time"] for r in pts], [r["_error"] for r in pts]
        colour = f"C{i % 10}"
        if has_range:
            lo = [number(r[f"{args.time_column}_min"]) for r in pts]
            hi = [number(r[f"{args.time_column}_max"]) for r in pts]
            if all(v is not None for v in lo + hi):
                ax.errorbar(xs, ys, xerr=[[max(0.0, x - v) for x, v in zip(xs, lo)],
                                          [max(0.0, v - x) for x, v in zip(xs, hi)]],
                            fmt="none", ecolor=colour, alpha=0.35, lw=1)
        ax.plot(xs, ys, linestyle=":", lw=0.8, color=colour, marker=MARKERS[i % len(MARKERS)], ms=7,
                label=g or "(all)")
        for r in pts:
            ax.annotate(r[args.label_column], (r["_time"], r["_error"]), fontsize=7, xytext=(4, 3),
                        textcoords="offset points")
    for r in references:  # the exact method's cost: a line, not a point at error 0 that beats everything
        ax.axvline(r["_time"], linestyle="--", color="k", alpha=0.5, lw=1,
                   label=f"{r['_group']} (the reference): {r['_time']:.0f}")
    on_front = [r for r in front if math.isfinite(r["_error"])]
    if on_front:
        ax.step([r["_time"] for r in on_front], [r["_error"] for r in on_front], where="post", color="k",
                lw=1.2, alpha=0.7, label="Pareto front")
    left_out = len(rows) - len(shown)
    note = f" ({left_out} run(s) with a non-finite error not shown)" if left_out else ""
    ax.set(title=f"{scene}: {args.time_column} vs {args.error_column}{note}",
           xlabel=f"{args.time_column} (log)", ylabel=args.error_column + (" (log)" if log_y else ""),
           xscale="log", yscale="log" if log_y else "linear")
    if not log_y:
        ax.set_ylim(bottom=0)
    plain = matplotlib.ticker.FuncFormatter(lambda v, _: f"{v:g}")  # 3 rather than 3x10^0
    for axis in [ax.xaxis] + ([ax.yaxis] if log_y else []):
        axis.set_major_formatter(plain)
        axis.set_minor_formatter(plain if axis.get_view_interval()[1] < 10 * axis.get_view_interval()[0] else
                                 matplotlib.ticker.NullFormatter())
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, title=",".join(args.group_columns), title_fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def cell(text):
    """A CSV cell for the Markdown table: numbers to 4 significant digits, pipes escaped."""
    value = number(text)
    if value is not None and not re.fullmatch(r"[+-]?\d+", text.strip()):
        return f"{value:.4g}"
    return str(text).replace("|", "\\|")


def table(columns, rows, fronts, args, path):
    on_front = {id(r) for front in fronts.values() for r in front}
    order = sorted(rows, key=lambda r: (natural_key(r[args.scene_column]),
                                        [natural_key(r[c]) for c in args.group_columns],
                                        natural_key(r[args.label_column])))
    lines = [f"Runs by {args.scene_column}, {', '.join(args.group_columns)} and {args.label_column}; "
             f"**P** marks the Pareto-optimal runs of each {args.scene_column} "
             f"(no other run has both a lower {args.time_column} and a "
             f"{'higher' if args.higher_is_better else 'lower'} {args.error_column}).",
             "",
             "| P | " + " | ".join(columns) + " |",
             "|---|" + "|".join("---" if c in (args.scene_column, args.label_column) or c in args.group_columns
                                else "--:" for c in columns) + "|"]
    for r in order:
        lines.append(("| **P** | " if id(r) in on_front else "|  | ") + " | ".join(cell(r[c]) for c in columns) +
                     " |")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("csv")
    parser.add_argument("out_dir")
    parser.add_argument("--error-column", default="rmse", help="y axis (default: rmse)")
    parser.add_argument("--time-column", default="frame_ms",
                        help="x axis, log scale; TIME_min and TIME_max give bars (default: frame_ms)")
    parser.add_argument("--group-columns", default="method,mode",
                        help="comma-separated columns naming a series (default: method,mode)")
    parser.add_argument("--label-column", default="resolution", help="point labels (default: resolution)")
    parser.add_argument("--scene-column", default="scene", help="one chart per value (default: scene)")
    parser.add_argument("--reference", default="",
                        help="group (as --group-columns joins it) of the exact method's rows: drawn as a vertical "
                             "line at its time, left out of the points and the Pareto front")
    parser.add_argument("--higher-is-better", action="store_true",
                        help="the error column is a score where higher is better (psnr, ssim)")
    args = parser.parse_args(argv)
    args.group_columns = [c for c in args.group_columns.split(",") if c]

    columns, rows = load(args.csv, args)
    os.makedirs(args.out_dir, exist_ok=True)
    scenes = list(dict.fromkeys(r[args.scene_column] for r in rows))
    fronts = {}
    written = []
    used = set()
    for scene in scenes:
        scene_rows = [r for r in rows if r[args.scene_column] == scene]
        references = [r for r in scene_rows if args.reference and r["_group"] == args.reference]
        scene_rows = [r for r in scene_rows if not (args.reference and r["_group"] == args.reference)]
        fronts[scene] = pareto(scene_rows, args.higher_is_better)
        stem = file_stem(scene)
        while stem in used:
            stem += "_"
        used.add(stem)
        path = os.path.join(args.out_dir, stem + ".png")
        chart(scene, scene_rows, fronts[scene], args, path, references)
        written.append(path)
    md = os.path.join(args.out_dir, os.path.splitext(os.path.basename(args.csv))[0] + ".md")
    table(columns, rows, fronts, args, md)
    written.append(md)
    print("wrote " + ", ".join(written))


if __name__ == "__main__":
    main()
