"""Small closed meshes written as ASCII .ply / .off, for the batch, Dask and `python -m voxr` tests and for
bench/dask_bench.py. NumPy only (no trimesh)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Tuple

import numpy as np

Mesh = Tuple[np.ndarray, np.ndarray]  # (V, 3) float64 vertices, (F, 3) int64 faces


def cube() -> Mesh:
    v = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=np.float64)
    f = np.array(
        [[0, 2, 1], [1, 2, 3], [4, 5, 6], [5, 7, 6], [0, 1, 4], [1, 5, 4],
         [2, 6, 3], [3, 6, 7], [0, 4, 2], [2, 4, 6], [1, 3, 5], [3, 7, 5]],
        dtype=np.int64,
    )
    return v, f


def tetrahedron() -> Mesh:
    v = np.array([[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]], dtype=np.float64)
    f = np.array([[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]], dtype=np.int64)
    return v, f


def octahedron() -> Mesh:
    v = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], dtype=np.float64)
    f = np.array(
        [[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]],
        dtype=np.int64,
    )
    return v, f


def uv_sphere(rings: int = 12, segments: int = 24) -> Mesh:
    verts = [[0.0, 0.0, 1.0]]
    for i in range(1, rings):
        t = math.pi * i / rings
        for j in range(segments):
            p = 2 * math.pi * j / segments
            verts.append([math.sin(t) * math.cos(p), math.sin(t) * math.sin(p), math.cos(t)])
    verts.append([0.0, 0.0, -1.0])
    faces = []
    last = len(verts) - 1
    for j in range(segments):
        faces.append([0, 1 + j, 1 + (j + 1) % segments])
    for i in range(rings - 2):
        a, b = 1 + i * segments, 1 + (i + 1) * segments
        for j in range(segments):
            k = (j + 1) % segments
            faces.append([a + j, b + j, b + k])
            faces.append([a + j, b + k, a + k])
    a = 1 + (rings - 2) * segments
    for j in range(segments):
        faces.append([a + j, last, a + (j + 1) % segments])
    return np.array(verts, dtype=np.float64), np.array(faces, dtype=np.int64)


def torus(major: float = 1.0, minor: float = 0.35, n: int = 32, m: int = 16) -> Mesh:
    verts = []
    for i in range(n):
        u = 2 * math.pi * i / n
        for j in range(m):
            w = 2 * math.pi * j / m
            r = major + minor * math.cos(w)
            verts.append([r * math.cos(u), r * math.sin(u), minor * math.sin(w)])
    faces = []
    for i in range(n):
        for j in range(m):
            a, b = i * m + j, ((i + 1) % n) * m + j
            c, d = ((i + 1) % n) * m + (j + 1) % m, i * m + (j + 1) % m
            faces.append([a, b, c])
            faces.append([a, c, d])
    return np.array(verts, dtype=np.float64), np.array(faces, dtype=np.int64)


SHAPES = {"cube": cube, "tetrahedron": tetrahedron, "octahedron": octahedron, "sphere": uv_sphere, "torus": torus}


def random_rotation(rng: np.random.Generator) -> np.ndarray:
    """A uniformly random 3x3 rotation (QR of a Gaussian matrix, signs fixed)."""
    q, r = np.linalg.qr(rng.standard_normal((3, 3)))
    q = q * np.sign(np.diag(r))
    if np.linalg.det(q) < 0:
        q[:, 0] = -q[:, 0]
    return q


def write_ply(path: Path, v: np.ndarray, f: np.ndarray) -> Path:
    """ASCII PLY, vertices as %.9g (float64 enough to round-trip float32)."""
    lines = [
        "ply", "format ascii 1.0", f"element vertex {len(v)}", "property double x", "property double y",
        "property double z", f"element face {len(f)}", "property list uchar int vertex_indices", "end_header",
    ]
    lines += [f"{a:.9g} {b:.9g} {c:.9g}" for a, b, c in v]
    lines += [f"3 {a} {b} {c}" for a, b, c in f]
    Path(path).write_text("\n".join(lines) + "\n")
    return Path(path)


def write_off(path: Path, v: np.ndarray, f: np.ndarray) -> Path:
    lines = ["OFF", f"{len(v)} {len(f)} 0"]
    lines += [f"{a:.9g} {b:.9g} {c:.9g}" for a, b, c in v]
    lines += [f"3 {a} {b} {c}" for a, b, c in f]
    Path(path).write_text("\n".join(lines) + "\n")
    return Path(path)


def write_broken_off(path: Path) -> Path:
    """An OFF file cut short: the header promises 4 vertices and 4 faces, the file holds 2 vertices."""
    Path(path).write_text("OFF\n4 4 0\n0 0 0\n1 0 0\n")
    return Path(path)


def small_dataset(folder: Path) -> list:
    """Six files in folder: five closed shapes (.ply and .off, rotated and scaled) and one broken .off."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    rng = np.random.default_rng(22)
    paths = []
    for i, (name, make) in enumerate(SHAPES.items()):
        v, f = make()
        v = v @ random_rotation(rng).T * rng.uniform(0.5, 3.0) + rng.uniform(-5, 5, size=3)
        writer = write_ply if i % 2 == 0 else write_off
        paths.append(writer(folder / f"{name}.{'ply' if i % 2 == 0 else 'off'}", v, f))
    paths.insert(3, write_broken_off(folder / "broken.off"))
    return [str(p) for p in paths]
