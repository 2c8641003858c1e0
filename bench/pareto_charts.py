#!/usr/bin/python3
"""Speed against accuracy for every effect: voxr bench pareto's CSV in, one PNG per effect and a Markdown page out.

usage: bench/pareto_charts.py CSV PAGE IMAGE_DIR [--command TEXT] [--device TEXT] [--date TEXT] [--load TEXT]

The CSV (voxr bench pareto) has one row per (effect, scene, method, resolution) with the columns
    effect,scene,method,resolution,time_ms,time_ms_min,time_ms_max,time_measure,error,error_measure,bytes,
    load_1min,reference,front
front is 1 on the Pareto front of the row's (effect, scene) (computed by voxr: host/bench/pareto_front.h);
reference is 1 for the effect's exact reference (error 0; CSVs from before 2026-12-02 have no such column and
no reference rows); resolution is empty for a method without one (image-space).

Writes IMAGE_DIR/EFFECT.png (one panel per scene: error on x, time on y, both log when they span a wide range;
one colour and marker per method, points labelled with their resolution, each reference as a dashed line at
its time (error 0: every run above the line is dominated by it), the front as a step line: the lowest time
reachable at each error) and PAGE: generated-by header, the pictures (linked relative to PAGE), and per effect
and scene a "pick for a target error" table (for quantiles of the methods' errors, the fastest run meeting
them, the reference included), the front's runs, and every run with whether the reference dominates it. Needs python3 and matplotlib (Debian: python3-matplotlib).
"""
import argparse
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402

MARKERS = "osD^vP*Xh<>p"
COLUMNS = ["effect", "scene", "method", "resolution", "time_ms", "time_ms_min", "time_ms_max", "time_measure",
           "error", "error_measure", "bytes", "load_1min", "front"]
EFFECT_TITLES = {"voxelization": "Voxelization", "shadows": "Shadows", "refraction": "Refraction"}
MEASURES = {
    "kernels": "warm kernel time (ms, profiling events, median of the timed runs)",
    "frame": "warm frame wall time (ms, the whole frame read back, median of the timed frames)",
    "chamfer_rel": "two-sided mean surface distance between the voxels and the triangles, relative to the "
                   "scene's size (metrics/voxel_surface_error.h)",
    "transmittance_rmse": "transmittance RMSE at the visible receivers against Embree's exact transmittance",
    "image_rmse": "image RMSE against the matched Embree reference, rendered with exact shadows",
}
QUANTILES = (0.1, 0.25, 0.5, 0.75)


def number(text):
    """The float a CSV cell holds ("inf", "nan" included), or None for an empty cell or a non-number."""
    try:
        return float(text)
    except (TypeError, ValueError):
        return None


def load(path):
    """Rows of the CSV as dicts, with _time, _error (floats) and _front (bool); exits with a message naming the
    file, the line and the column on a missing column or a bad value."""
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        missing = [c for c in COLUMNS if c not in (reader.fieldnames or [])]
        if missing:
            sys.exit(f"{path}: missing column(s) {', '.join(missing)}")
        rows = []
        for line, r in enumerate(reader, start=2):
            time, error = number(r["time_ms"]), number(r["error"])
            if time is None or not time > 0:
                sys.exit(f"{path}:{line}: column time_ms must be a positive number (got {r['time_ms']!r})")
            if error is None:
                sys.exit(f"{path}:{line}: column error must be a number (got {r['error']!r})")
            if r["front"] not in ("0", "1"):
                sys.exit(f"{path}:{line}: column front must be 0 or 1 (got {r['front']!r})")
            reference = r.get("reference") or "0"
            if reference not in ("0", "1"):
                sys.exit(f"{path}:{line}: column reference must be 0 or 1 (got {reference!r})")
            r["_time"], r["_error"], r["_front"] = time, error, r["front"] == "1"
            r["_reference"] = reference == "1"
            rows.append(r)
    if not rows:
        sys.exit(f"{path}: no rows")
    return rows


def by(rows, key):
    """Rows grouped by key(row), groups in order of first appearance."""
    groups = {}
    for r in rows:
        groups.setdefault(key(r), []).append(r)
    return groups


def quantile(values, q):
    """Linear-interpolated quantile of a non-empty list."""
    v = sorted(values)
    pos = q * (len(v) - 1)
    lo = math.floor(pos)
    hi = min(lo + 1, len(v) - 1)
    return v[lo] + (v[hi] - v[lo]) * (pos - lo)


def round_up(value):
    """value rounded up to two significant digits (a target a run at exactly the quantile still meets)."""
    if value <= 0 or not math.isfinite(value):
        return value
    scale = 10 ** (math.floor(math.log10(value)) - 1)
    return float(f"{math.ceil(value / scale - 1e-9) * scale:.2g}")


def targets(rows):
    """Target errors: the QUANTILES of the methods' finite errors (not the references' zeros), rounded up to two
    significant digits, distinct."""
    errors = [r["_error"] for r in rows if math.isfinite(r["_error"]) and not r["_reference"]]
    if not errors:
        return []
    return sorted(set(round_up(quantile(errors, q)) for q in QUANTILES))


def fastest_within(rows, target):
    """The fastest row with an error at or below target (ties: the lower error, then the first), or None."""
    meeting = [r for r in rows if math.isfinite(r["_error"]) and r["_error"] <= target]
    return min(meeting, key=lambda r: (r["_time"], r["_error"])) if meeting else None


def label(r):
    return r["resolution"] or "-"


def reference_of(rows):
    """The fastest reference row among rows, or None."""
    refs = [r for r in rows if r["_reference"]]
    return min(refs, key=lambda r: r["_time"]) if refs else None


def dominated_by(run, reference):
    """Whether the reference (error 0) is at least as fast as run: then run is never worth choosing."""
    return reference is not None and run is not reference and reference["_time"] <= run["_time"]


def chart(effect, rows, path):
    scenes = by(rows, lambda r: r["scene"])
    methods = list(dict.fromkeys(r["method"] for r in rows if not r["_reference"]))
    style = {m: (f"C{i % 10}", MARKERS[i % len(MARKERS)]) for i, m in enumerate(methods)}
    fig, axes = plt.subplots(1, len(scenes), figsize=(6.4 * len(scenes), 5.2), squeeze=False)
    for ax, (scene, scene_rows) in zip(axes[0], scenes.items()):
        shown = [r for r in scene_rows if math.isfinite(r["_error"]) and not r["_reference"]]
        errors = [r["_error"] for r in shown]
        times = [r["_time"] for r in shown]
        log_x = bool(errors) and min(errors) > 0 and max(errors) / min(errors) > 20
        # Error 0 has no place on a log axis: references and zero-error runs sit at its left edge.
        left = min(errors) / 1.5 if log_x else 0.0
        for ref in (r for r in scene_rows if r["_reference"]):
            ax.axhline(ref["_time"], color="k", ls="--", lw=1.2, alpha=0.8,
                       label=f"{ref['method']} (exact, error 0): {ref['_time']:.3g} ms")
            times.append(ref["_time"])
        for m in methods:
            pts = sorted((r for r in shown if r["method"] == m), key=lambda r: r["_error"])
            if not pts:
                continue
            colour, marker = style[m]
            lo = [number(r["time_ms_min"]) for r in pts]
            hi = [number(r["time_ms_max"]) for r in pts]
            xs, ys = [r["_error"] for r in pts], [r["_time"] for r in pts]
            if all(v is not None for v in lo + hi):
                ax.errorbar(xs, ys, yerr=[[max(0.0, y - v) for y, v in zip(ys, lo)],
                                          [max(0.0, v - y) for y, v in zip(ys, hi)]],
                            fmt="none", ecolor=colour, alpha=0.35, lw=1)
            ax.plot(xs, ys, linestyle=":", lw=0.8, color=colour, marker=marker, ms=7, label=m)
            for r in pts:
                ax.annotate(label(r), (r["_error"], r["_time"]), fontsize=7, xytext=(4, 3),
                            textcoords="offset points")
        front = sorted((r for r in scene_rows if r["_front"] and math.isfinite(r["_error"])),
                       key=lambda r: (r["_error"], r["_time"]))
        if front:
            xs = [max(r["_error"], left) for r in front]
            ys = [r["_time"] for r in front]
            # Beyond the least accurate front run, its time holds: extend the last step to the right edge.
            right = max(errors + xs) * (1.5 if log_x else 1.05)
            ax.step(xs + [right], ys + [ys[-1]], where="post", color="k", lw=1.4, alpha=0.75, zorder=1,
                    label="Pareto front")
        measure = scene_rows[0]
        ax.set(title=f"{EFFECT_TITLES.get(effect, effect)}: {scene}",
               xlabel=f"error: {measure['error_measure']}" + (" (log)" if log_x else ""),
               ylabel=f"{measure['time_measure']} ms (log)", yscale="log", xscale="log" if log_x else "linear")
        if not log_x:
            ax.set_xlim(left=0)
        plain = matplotlib.ticker.FuncFormatter(lambda v, _: f"{v:g}")
        for axis in [ax.yaxis] + ([ax.xaxis] if log_x else []):
            axis.set_major_formatter(plain)
            lo, hi = axis.get_view_interval()
            axis.set_minor_formatter(plain if hi < 10 * lo else matplotlib.ticker.NullFormatter())
        ax.grid(True, which="both", alpha=0.3)
        if len(times) > 0:
            ax.legend(fontsize=7, title="method (labels: resolution)", title_fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def fmt(value):
    return f"{value:.4g}" if math.isfinite(value) else str(value)


def page(rows, images, page_path, args):
    rel = os.path.relpath(images, os.path.dirname(os.path.abspath(page_path)) or ".")
    lines = [
        "<!-- Generated by bench/pareto_charts.py from `voxr bench pareto`; do not edit. -->",
        "",
        "# Speed against accuracy",
        "",
        f"Generated by `{args.command or 'voxr bench pareto'}`; regenerate it with the same command.",
        "",
        f"- Device: {args.device or 'unknown'}",
        f"- Date: {args.date or 'unknown'}",
        f"- Machine load (/proc/loadavg 1, 5, 15 min): {args.load or 'unknown'}; per run in the CSV "
        "(load_1min)",
        "",
        "Every method of each effect at each of its resolutions on a few scenes, time against error. In the "
        "charts error is on x, time on y (log); the black step line is the Pareto front: at any target error, "
        "the lowest time a run reaches while being at least that accurate. To pick a method, go right to the "
        "error you can accept and down to the front; the tables below do this for a few targets (quantiles of "
        "the errors seen). Times are medians with [min, max] bars; errors are measured against exact "
        "references, one measure per effect. Each exact reference is a run too (error 0, its frame time as the "
        "effect's benchmark measures it: `voxr bench shadows`, `voxr bench refraction`), drawn as a dashed line: "
        "a run above the line is dominated by the reference on this machine, whatever its error.",
    ]
    for effect, effect_rows in by(rows, lambda r: r["effect"]).items():
        first = effect_rows[0]
        lines += ["", f"## {EFFECT_TITLES.get(effect, effect)}", "",
                  f"Time: {MEASURES.get(first['time_measure'], first['time_measure'])}. Error: "
                  f"{MEASURES.get(first['error_measure'], first['error_measure'])}.", "",
                  f"![{effect}: time against error]({rel}/{effect}.png)"]
        for scene, scene_rows in by(effect_rows, lambda r: r["scene"]).items():
            lines += ["", f"### {effect}: {scene}", "", "Pick for a target error: the fastest run at or below it.",
                      "", "| target error | method | resolution | time ms | error |", "|---:|---|---:|---:|---:|"]
            for t in targets(scene_rows):
                r = fastest_within(scene_rows, t)
                lines.append(f"| {t:g} | {r['method']} | {label(r)} | {fmt(r['_time'])} | {fmt(r['_error'])} |")
            front = sorted((r for r in scene_rows if r["_front"]), key=lambda r: r["_time"])
            lines += ["", f"Pareto front ({len(front)} of {len(scene_rows)} runs), fastest first:", "",
                      "| method | resolution | time ms | [min, max] | error | bytes |", "|---|---:|---:|---|---:|---:|"]
            for r in front:
                lines.append(f"| {r['method']} | {label(r)} | {fmt(r['_time'])} | [{fmt(number(r['time_ms_min']))}, "
                             f"{fmt(number(r['time_ms_max']))}] | {fmt(r['_error'])} | {r['bytes']} |")
            ref = reference_of(scene_rows)
            if ref is not None:
                methods = [r for r in scene_rows if not r["_reference"]]
                beaten = [r for r in methods if dominated_by(r, ref)]
                names = sorted(set(r["method"] for r in beaten))
                whole = sorted(m for m in names if all(dominated_by(r, ref) for r in methods if r["method"] == m))
                lines += ["", f"The reference ({ref['method']}, {fmt(ref['_time'])} ms) dominates {len(beaten)} of "
                          f"{len(methods)} runs" + (f"; every run of: {', '.join(whole)}" if whole else "") + "."]
            lines += ["", "Every run, most accurate first:", "",
                      "| method | resolution | time ms | error | front | dominated by the reference |",
                      "|---|---:|---:|---:|:---:|:---:|"]
            for r in sorted(scene_rows, key=lambda r: (r["_error"] if math.isfinite(r["_error"]) else math.inf,
                                                        r["_time"])):
                lines.append(f"| {r['method']} | {label(r)} | {fmt(r['_time'])} | {fmt(r['_error'])} | "
                             f"{'yes' if r['_front'] else ''} | {'yes' if dominated_by(r, ref) else ''} |")
    with open(page_path, "w") as f:
        f.write("\n".join(lines) + "\n")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("csv")
    parser.add_argument("page", help="the Markdown page to write")
    parser.add_argument("image_dir", help="where the PNGs go (created if missing)")
    parser.add_argument("--command", default="", help="the command that made the CSV")
    parser.add_argument("--device", default="")
    parser.add_argument("--date", default="")
    parser.add_argument("--load", default="")
    args = parser.parse_args(argv)
    rows = load(args.csv)
    os.makedirs(args.image_dir, exist_ok=True)
    page_dir = os.path.dirname(os.path.abspath(args.page))
    os.makedirs(page_dir, exist_ok=True)
    written = []
    for effect, effect_rows in by(rows, lambda r: r["effect"]).items():
        path = os.path.join(args.image_dir, effect + ".png")
        chart(effect, effect_rows, path)
        written.append(path)
    page(rows, args.image_dir, args.page, args)
    written.append(args.page)
    print("wrote " + ", ".join(written))


if __name__ == "__main__":
    main()
