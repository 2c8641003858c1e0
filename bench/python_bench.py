#!/usr/bin/env python3
"""Issue 22's Python target: voxr.voxelize of the bunny x16 at 512 from NumPy arrays in a warm process
against the CLI's ms.wall on the same mesh, side by side with trimesh's `mesh.voxelized(pitch)` and Open3D's
`VoxelGrid.create_from_triangle_mesh` at the same voxel size (each when installed; skipped with a note when
not). Target: voxr.voxelize <= 1.2x the CLI's ms.wall.

usage: python bench/python_bench.py [MESH.off] [--res 512] [--repeat 7] [--cli PATH] [--peers-timeout S]
                                   [--peers-memory GiB] [--no-peers]
  MESH: default /work/data/bunny_x16.off, else $VOXR_BENCH_MESH (`voxr bench voxelize` builds "bunnyx16";
  bench/color_mesh.py data/meshes/bunny.obj 2 OUT.ply makes the same mesh as a PLY).
Runs the CLI and the Python call interleaved (one warm-up each, then REPEAT pairs) so both see the same
load; prints a Markdown table and the machine's CPU model and load.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

import voxr
from voxr._cli import cli_path


def read_mesh(path: Path):
    """(float64 vertices, uint32 faces) of a triangle OFF (the numbers the CLI parses), or via trimesh."""
    if path.suffix.lower() == ".off":
        with open(path, "rb") as fh:
            assert fh.readline().strip() == b"OFF"
            nv, nf, _ = (int(t) for t in fh.readline().split())
            v = np.loadtxt(fh, dtype=np.float64, max_rows=nv)
            f = np.loadtxt(fh, dtype=np.int64, max_rows=nf)
        assert (f[:, 0] == 3).all(), "triangles only"
        return np.ascontiguousarray(v), np.ascontiguousarray(f[:, 1:], dtype=np.uint32)
    import trimesh

    m = trimesh.load(path, process=False, force="mesh")
    return np.asarray(m.vertices, dtype=np.float64), np.asarray(m.faces, dtype=np.uint32)


def cli_wall(cli: str, mesh: Path, res: int, report: Path):
    """The CLI's ms.wall (upload to readback) and ms.load (reading the file into voxr's triangle soup)."""
    subprocess.run([cli, "voxelize", str(mesh), "--res", str(res), "-q", "--report", str(report)], check=True)
    ms = json.loads(report.read_text())["ms"]
    return float(ms["wall"]), float(ms.get("load", float("nan")))


def load() -> str:
    return " ".join(Path("/proc/loadavg").read_text().split()[:3])


def cpu_model() -> str:
    for line in Path("/proc/cpuinfo").read_text().splitlines():
        if line.startswith("model name"):
            return line.split(":", 1)[1].strip()
    return "unknown"


def run_peer(peer: str, data: Path, pitch: float, memory_gb: float = 0.0) -> dict:
    """One peer's voxelization of the mesh in `data` at `pitch` (run in a child process)."""
    with np.load(data) as z:
        v, f = z["v"], z["f"]
    if memory_gb > 0:  # trimesh's subdivision grows fast: a MemoryError here, not an OOM on a shared machine
        import resource

        limit = int(memory_gb * (1 << 30))
        resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
    if peer == "trimesh":
        try:
            import trimesh
        except ImportError:
            return {"skip": "not installed (pip install trimesh)"}
        m = trimesh.Trimesh(vertices=v, faces=f, process=False)
        t = time.perf_counter()
        try:
            vg = m.voxelized(pitch=pitch)  # subdivides until every edge is shorter than the pitch
        except MemoryError:
            return {"skip": f"MemoryError under the {memory_gb:g} GiB address-space limit (--peers-memory)"}
        ms = (time.perf_counter() - t) * 1e3
        return {"name": f"trimesh {trimesh.__version__} `mesh.voxelized(pitch)`", "ms": ms,
                "voxels": int(vg.filled_count), "note": f"surface, shape {tuple(int(s) for s in vg.shape)}"}
    try:
        import open3d as o3d
    except ImportError:
        return {"skip": "not installed (pip install open3d)"}
    except Exception as e:  # e.g. a missing system library
        return {"skip": f"import failed: {e}"}
    om = o3d.geometry.TriangleMesh(o3d.utility.Vector3dVector(v), o3d.utility.Vector3iVector(f.astype(np.int32)))
    t = time.perf_counter()
    og = o3d.geometry.VoxelGrid.create_from_triangle_mesh(om, voxel_size=pitch)
    ms = (time.perf_counter() - t) * 1e3
    return {"name": f"Open3D {o3d.__version__} `VoxelGrid.create_from_triangle_mesh`", "ms": ms,
            "voxels": len(og.get_voxels()), "note": "surface"}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("mesh", nargs="?", default=os.environ.get("VOXR_BENCH_MESH", "/work/data/bunny_x16.off"))
    ap.add_argument("--res", type=int, default=512)
    ap.add_argument("--repeat", type=int, default=7)
    ap.add_argument("--cli", default=None)
    ap.add_argument("--peers-timeout", type=float, default=600.0,
                    help="stop a peer's run after this many seconds")
    ap.add_argument("--peers-memory", type=float, default=12.0,
                    help="address-space limit of a peer's process, GiB (0: none)")
    ap.add_argument("--no-peers", action="store_true")
    ap.add_argument("--peer", help=argparse.SUPPRESS)
    ap.add_argument("--data", help=argparse.SUPPRESS)
    ap.add_argument("--pitch", type=float, help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.peer:
        print(json.dumps(run_peer(args.peer, Path(args.data), args.pitch, args.peers_memory)))
        return 0
    mesh = Path(args.mesh)
    cli = args.cli or cli_path()

    t0 = time.perf_counter()
    v, f = read_mesh(mesh)
    print(f"mesh {mesh}: {len(v)} vertices, {len(f)} triangles (read in {time.perf_counter() - t0:.1f} s)")
    print(f"cpu: {cpu_model()}, {os.cpu_count()} cores; load before: {load()}")
    context = voxr.Context()
    print(f"device: {context.device['name']} ({context.device['platform']})")

    report = Path(tempfile.mkdtemp()) / "r.json"
    # warm-up: programs cached, pages touched, both sides once
    grid = context.voxelize(v, f, res=args.res)
    cli_wall(cli, mesh, args.res, report)
    dims, voxel_size, voxels = grid.dims, grid.voxel_size, grid.voxels_set
    del grid
    py_ms, py_inner, cli_ms, cli_load = [], [], [], []
    for _ in range(args.repeat):
        wall, load_ms = cli_wall(cli, mesh, args.res, report)
        cli_ms.append(wall)
        cli_load.append(load_ms)
        t = time.perf_counter()
        grid = context.voxelize(v, f, res=args.res)
        py_ms.append((time.perf_counter() - t) * 1e3)
        py_inner.append(float(grid.report.get("ms", {}).get("wall", float("nan"))))
        del grid
    med = statistics.median
    ratio = med(py_ms) / med(cli_ms)
    rows = [
        ("voxr CLI `voxelize --res %d -q --report` (ms.wall, fresh process)" % args.res, cli_ms),
        ("  the same runs' ms.load (file -> triangle soup, not in ms.wall)", cli_load),
        ("voxr.voxelize(v, f, res=%d) from NumPy, warm Context (Python wall)" % args.res, py_ms),
        ("  of which voxr's own ms.wall (grid.report)", py_inner),
    ]
    print(f"\ngrid {dims[0]}x{dims[1]}x{dims[2]}, voxel size {voxel_size:.6g}, {voxels} voxels set; "
          f"{args.repeat} interleaved pairs after one warm-up; load after: {load()}\n")
    print("| what | median ms | min–max ms |")
    print("|---|---|---|")
    for name, xs in rows:
        print(f"| {name} | {med(xs):.1f} | {min(xs):.1f}–{max(xs):.1f} |")
    print(f"\n**voxr.voxelize / CLI ms.wall = {ratio:.2f}** (target <= 1.2)\n")

    if args.no_peers:
        return 0
    extent = float((v.max(axis=0) - v.min(axis=0)).max())
    data = report.parent / "mesh.npz"
    np.savez(data, v=v, f=f)
    print(f"Peers at the same voxel size ({voxel_size:.6g}), one run each in a fresh process after voxr "
          f"(killed after {args.peers_timeout:.0f} s):\n")
    print("| peer | ms | voxels | note |")
    print("|---|---|---|---|")
    for peer in ("trimesh", "open3d"):
        cmd = [sys.executable, __file__, "--peer", peer, "--data", str(data), "--pitch", repr(voxel_size),
               "--peers-memory", str(args.peers_memory)]
        try:
            done = subprocess.run(cmd, capture_output=True, text=True, timeout=args.peers_timeout)
            lines = done.stdout.strip().splitlines()
            r = json.loads(lines[-1]) if done.returncode == 0 and lines else {"skip": done.stderr.strip()[-200:]}
        except subprocess.TimeoutExpired:
            r = {"skip": f"did not finish in {args.peers_timeout:.0f} s"}
        if "skip" in r:
            print(f"| {peer} | – | – | {r['skip']} |")
        else:
            print(f"| {r['name']} | {r['ms']:.0f} | {r['voxels']} | {r['note']} |")
    print(f"\n(mesh extent {extent:.6g}; load at the end: {load()})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
