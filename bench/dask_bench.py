#!/usr/bin/env python3
"""Throughput of voxr.voxelize_files (one process) against voxr.dask.voxelize_files (a LocalCluster).

Dataset (generated in a temporary folder, seed fixed): N meshes (200) as binary little-endian .ply — half
copies of the meshes in data/meshes (bunny.obj 69 666 triangles, armadillo 52 000, ChineseDragon 19 994,
bunny00 75 408, mech-holes-shark 10 192, refined_elephant 88 928; those present), the other half UV spheres
(3 480–22 200 triangles) and tori (10 404–48 400), every one randomly rotated, scaled (0.2–5×) and moved.
Each is voxelized at --res (128: 10–40 ms a mesh warm on PoCL, 2 cores) with the default options and saved
as .nrrd (occupancy only).

Runs: a warm-up of both (the single process's Context and each worker's), then --runs (3) timed runs of
each, interleaved (single, dask, dask, single, ...), each into a fresh output folder. Throughput = meshes /
wall seconds of the call; reported as median (min–max). Also the per-mesh split from the manifests: load
(the voxelize_file call minus voxr's ms.wall: reading, checks, grid fit), device (ms.wall: mesh in memory to
grid on the host), save, and the per-mesh total.

    POCL_CACHE_DIR=$PWD/build/pocl-cache python bench/dask_bench.py --res 128 --md bench/results/issue22-dask-2core.md
"""

from __future__ import annotations

import argparse
import os
import platform
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "python" / "tests"))  # meshgen.py: shapes and rotations

import meshgen  # noqa: E402

DATA_MESHES = ["bunny.obj", "armadillo.off", "ChineseDragon-10kv.off", "bunny00.off", "mech-holes-shark.off",
               "refined_elephant.off"]


def read_off(path: Path):
    tokens = path.read_text().split()
    assert tokens[0] == "OFF", path
    nv, nf = int(tokens[1]), int(tokens[2])
    v = np.array(tokens[4 : 4 + 3 * nv], dtype=np.float64).reshape(nv, 3)
    faces, i = [], 4 + 3 * nv
    for _ in range(nf):
        k = int(tokens[i])
        idx = [int(t) for t in tokens[i + 1 : i + 1 + k]]
        faces += [[idx[0], idx[j], idx[j + 1]] for j in range(1, k - 1)]
        i += 1 + k
    return v, np.array(faces, dtype=np.int64)


def read_obj(path: Path):
    verts, faces = [], []
    for line in path.read_text().splitlines():
        if line.startswith("v "):
            verts.append([float(t) for t in line.split()[1:4]])
        elif line.startswith("f "):
            idx = [int(t.split("/")[0]) for t in line.split()[1:]]
            idx = [i - 1 if i > 0 else len(verts) + i for i in idx]
            faces += [[idx[0], idx[j], idx[j + 1]] for j in range(1, len(idx) - 1)]
    return np.array(verts, dtype=np.float64), np.array(faces, dtype=np.int64)


def write_ply_binary(path: Path, v: np.ndarray, f: np.ndarray) -> None:
    header = (
        "ply\nformat binary_little_endian 1.0\n"
        f"element vertex {len(v)}\nproperty float x\nproperty float y\nproperty float z\n"
        f"element face {len(f)}\nproperty list uchar int vertex_indices\nend_header\n"
    )
    faces = np.empty(len(f), dtype=[("n", "u1"), ("i", "<i4", (3,))])
    faces["n"] = 3
    faces["i"] = f
    with open(path, "wb") as out:
        out.write(header.encode())
        out.write(np.ascontiguousarray(v, dtype="<f4").tobytes())
        out.write(faces.tobytes())


def make_dataset(folder: Path, n: int, seed: int = 22):
    """n meshes in folder; returns (paths, rows of (kind, triangles))."""
    folder.mkdir(parents=True, exist_ok=True)
    rng = np.random.default_rng(seed)
    sources = []
    for name in DATA_MESHES:
        p = ROOT / "data" / "meshes" / name
        if p.is_file():
            v, f = read_obj(p) if p.suffix == ".obj" else read_off(p)
            v = v - v.mean(axis=0)
            sources.append((Path(name).stem, v / np.abs(v).max(), f))
    paths, rows = [], []
    for i in range(n):
        if sources and i % 2 == 0:
            kind, v, f = sources[(i // 2) % len(sources)]
        elif i % 4 == 1:
            rings = int(rng.integers(30, 76))
            kind, (v, f) = "sphere", meshgen.uv_sphere(rings, 2 * rings)
        else:
            k = int(rng.integers(50, 111))
            kind, (v, f) = "torus", meshgen.torus(1.0, float(rng.uniform(0.15, 0.5)), 2 * k, k)
        v = v @ meshgen.random_rotation(rng).T * rng.uniform(0.2, 5.0) + rng.uniform(-10, 10, size=3)
        path = folder / f"{i:03d}-{kind}.ply"
        write_ply_binary(path, v, f)
        paths.append(str(path))
        rows.append((kind, len(f)))
    return paths, rows


def split(manifest):
    """Per-mesh medians (ms): load, device (report ms.wall), save, call total."""
    good = [e for e in manifest if e["error"] is None]
    rep = [e["ms"].get("report", {}) for e in good]

    def med(values):
        values = [x for x in values if x is not None]
        return statistics.median(values) if values else float("nan")

    return {
        # The API's report has no ms.load: load (+ checks, grid fit) = the call's time - voxr's ms.wall.
        "load": med([e["ms"]["voxelize"] - r["wall"] if "wall" in r else None for e, r in zip(good, rep)]),
        "device": med([r.get("wall") for r in rep]),
        "save": med([e["ms"]["save"] for e in good]),
        "total": med([e["ms"]["voxelize"] + e["ms"]["save"] for e in good]),
        "errors": len(manifest) - len(good),
    }


def _own_cpu():
    import resource

    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


def cpu_seconds(client):
    """CPU seconds used so far by this process (client and the LocalCluster's scheduler, all threads,
    PoCL's included) and by every worker process: a cost per mesh that does not depend on how busy the
    machine is."""
    return _own_cpu() + sum(client.run(_own_cpu).values())


def sh(cmd):
    try:
        return subprocess.run(cmd, shell=True, capture_output=True, text=True).stdout.strip()
    except OSError:
        return ""


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--n", type=int, default=200)
    ap.add_argument("--res", type=int, default=128)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--format", default="nrrd")
    ap.add_argument("--device", default=None)
    ap.add_argument("--pocl-threads", type=int, default=0,
                    help="POCL_MAX_PTHREAD_COUNT for the workers only (0: PoCL's default, all cores)")
    ap.add_argument("--chunk-size", type=int, default=None, help="meshes per task (default: voxr.dask's choice)")
    ap.add_argument("--md", help="append the results as Markdown to this file")
    ap.add_argument("--keep", action="store_true", help="keep the temporary folder")
    args = ap.parse_args()

    import distributed

    import voxr
    import voxr.dask
    from voxr import batch

    tmp = Path(tempfile.mkdtemp(prefix="voxr-dask-bench-"))
    t0 = time.perf_counter()
    paths, rows = make_dataset(tmp / "meshes", args.n)
    gen_s = time.perf_counter() - t0
    tris = sorted(t for _, t in rows)
    kinds = {}
    for k, t in rows:
        kinds.setdefault(k, []).append(t)
    mix = ", ".join(f"{k} ×{len(v)} ({min(v)}–{max(v)} triangles)" for k, v in kinds.items())
    print(f"dataset: {len(paths)} meshes in {gen_s:.1f} s: {mix}; triangles median {tris[len(tris) // 2]}, "
          f"total {sum(tris)}", flush=True)

    opts = dict(res=args.res)
    if args.device:
        opts["device"] = args.device
    load_before = sh("uptime")

    # Warm-up: this process's Context, then the cluster and each worker's Context.
    batch.voxelize_files(paths[:4], tmp / "warm1", progress=False, **opts)
    env = {"POCL_MAX_PTHREAD_COUNT": str(args.pocl_threads)} if args.pocl_threads else {}
    for key in ("POCL_CACHE_DIR", "VOXR_DEVICE"):
        if key in os.environ:
            env[key] = os.environ[key]
    t0 = time.perf_counter()
    cluster = distributed.LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True,
                                       dashboard_address=None, env=env)
    client = distributed.Client(cluster)
    start_s = time.perf_counter() - t0
    client.run(lambda: voxr.dask._worker_context(opts.get("device")) and None)
    voxr.dask.voxelize_files(paths[: 2 * args.workers], tmp / "warm2", client, progress=False, **opts)

    results = {"one process": [], f"dask, {args.workers} workers": []}
    splits = {k: [] for k in results}
    names = list(results)
    for run in range(args.runs):
        order = names if run % 2 == 0 else names[::-1]
        for name in order:
            out = tmp / f"out-{run}-{name[:4]}"
            c0 = cpu_seconds(client)
            t0 = time.perf_counter()
            if name == "one process":
                m = batch.voxelize_files(paths, out, format=args.format, progress=False, **opts)
            else:
                m = voxr.dask.voxelize_files(paths, out, client, format=args.format, progress=False,
                                             chunk_size=args.chunk_size, **opts)
            s = time.perf_counter() - t0
            cpu = cpu_seconds(client) - c0
            results[name].append(len(paths) / s)
            splits[name].append(dict(split(m), cpu=1e3 * cpu / len(paths), cores=cpu / s))
            print(f"run {run + 1} {name}: {s:.2f} s, {len(paths) / s:.2f} meshes/s, split "
                  + ", ".join(f"{k} {v:.1f}" for k, v in splits[name][-1].items()), flush=True)
            shutil.rmtree(out)
    load_after = sh("uptime")
    client.close()
    cluster.close()

    def cell(values):
        return f"{statistics.median(values):.2f} ({min(values):.2f}–{max(values):.2f})"

    base = statistics.median(results["one process"])
    lines = [
        "| mode | meshes/s median (min–max) | speed-up | load ms | device ms | save ms | per mesh ms "
        "| CPU ms per mesh | cores used |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for name in names:
        sp = {k: statistics.median(s[k] for s in splits[name])
              for k in ("load", "device", "save", "total", "cpu", "cores")}
        lines.append(f"| {name} | {cell(results[name])} | {statistics.median(results[name]) / base:.2f}× | "
                     f"{sp['load']:.1f} | {sp['device']:.1f} | {sp['save']:.1f} | {sp['total']:.1f} | "
                     f"{sp['cpu']:.1f} | {sp['cores']:.2f} |")
    table = "\n".join(lines)
    print(table)
    if args.md:
        cpu = "; ".join(" ".join(line.split()) for line in sh("lscpu | grep -E 'Model name|^CPU\\(s\\)'").splitlines())
        dev = voxr.Context(args.device).device if hasattr(voxr, "Context") else {}
        cmd = " ".join([Path(sys.executable).name] + [os.path.relpath(sys.argv[0], ROOT)] + sys.argv[1:])
        text = [
            f"\n## {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}: {args.n} meshes at res {args.res}, "
            f"{args.workers} workers{f', POCL_MAX_PTHREAD_COUNT={args.pocl_threads} per worker' if args.pocl_threads else ''}"
            f"{f', chunk_size {args.chunk_size}' if args.chunk_size else ', chunk_size auto'}\n",
            f"- command: `{'POCL_CACHE_DIR=build/pocl-cache ' if 'POCL_CACHE_DIR' in os.environ else ''}{cmd}`",
            f"- CPU: {cpu}; Python {platform.python_version()}; device: {dev.get('name', '?')} ({dev.get('platform', '?')})",
            f"- load before: `{load_before}`; after: `{load_after}`",
            f"- dataset: {mix}; {sum(tris)} triangles in all, median {tris[len(tris) // 2]} per mesh; "
            f"format .{args.format}; cluster start {start_s:.1f} s (not timed)",
            f"- {args.runs} runs of each, interleaved; load/device/save/per mesh: medians over meshes (load: "
            "the voxelize_file call minus voxr's ms.wall; device: ms.wall, mesh in memory to grid on the host; save; "
            "per mesh: voxelize_file + save), median over runs; CPU ms per mesh: user+sys of this process and "
            "of the workers over the call / meshes; cores used: CPU seconds / wall seconds, \n",
            table,
            "",
        ]
        with open(args.md, "a", encoding="utf-8") as f:
            f.write("\n".join(text))
    if args.keep:
        print(f"kept {tmp}")
    else:
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
