"""Shared fixtures of the Python suite: the CLI to compare with, readers of its .nrrd/.npz outputs, writers of
meshes in formats the CLI reads with exactly the numbers Python holds (binary PLY of doubles, OBJ with
repr()-precision text), and a few meshes.

The installed package is tested (scripts/python-check.sh runs pytest outside the source tree). The CLI is
the `voxr` executable installed with it (voxr/bin/voxr) or $VOXR_CLI; the meshes are under $VOXR_TEST_DATA
(default: the repository's data/)."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path
from typing import Dict, List, Optional, Sequence

import numpy as np
import pytest

import voxr
from voxr._cli import cli_path

DATA = Path(os.environ.get("VOXR_TEST_DATA", Path(__file__).resolve().parents[2] / "data"))


def mesh_path(name: str) -> Path:
    """data/meshes/NAME, or a skip when scripts/fetch-meshes.sh has not fetched it."""
    path = DATA / "meshes" / name
    if not path.is_file():
        pytest.skip(f"{path} is missing (scripts/fetch-meshes.sh)")
    return path


@pytest.fixture(scope="session")
def cli() -> str:
    try:
        return cli_path()
    except voxr.Error as e:
        pytest.skip(str(e))


def run_cli(cli: str, args: Sequence[str]) -> subprocess.CompletedProcess:
    """Runs `voxr ARGS`; fails the test with the CLI's stderr on a non-zero exit."""
    done = subprocess.run([cli, *map(str, args)], capture_output=True, text=True)
    if done.returncode != 0:
        pytest.fail(f"voxr {' '.join(map(str, args))} exited {done.returncode}: {done.stderr.strip()}")
    return done


def cli_options(**options) -> List[str]:
    """voxelize() keywords -> `voxr voxelize` flags."""
    flags: List[str] = []
    for key, value in options.items():
        if value is None:
            continue
        if key == "res":
            flags += ["--res", str(value)]
        elif key in ("dims", "bounds"):
            flags += [f"--{key}", ",".join(repr(float(v)) if key == "bounds" else str(v) for v in value)]
        elif key == "channels":
            flags += ["--channels", value if isinstance(value, str) else ",".join(value)]
        elif key == "memory_budget":
            flags += ["--memory-budget", str(value)]
        else:
            flags += [f"--{key}", str(value)]
    return flags


_NRRD_TYPES = {
    "uint8": np.uint8,
    "uchar": np.uint8,
    "unsigned char": np.uint8,
    "uint32": np.uint32,
    "uint": np.uint32,
    "unsigned int": np.uint32,
    "int32": np.int32,
    "int": np.int32,
    "float": np.float32,
    "double": np.float64,
}


def read_nrrd(path: Path) -> np.ndarray:
    """A raw little-endian NRRD as voxr writes it: (nx, ny, nz) or (nx, ny, nz, c) indexed [x, y, z(, c)]."""
    raw = Path(path).read_bytes()
    end = raw.index(b"\n\n")
    fields: Dict[str, str] = {}
    for line in raw[:end].decode().splitlines()[1:]:
        if line.startswith("#") or ": " not in line:
            continue
        key, value = line.split(": ", 1)
        fields[key] = value
    assert fields["encoding"] == "raw" and fields["endian"] == "little", fields
    sizes = [int(s) for s in fields["sizes"].split()]
    data = np.frombuffer(raw[end + 2 :], dtype=_NRRD_TYPES[fields["type"]])
    data = data.reshape(sizes[::-1])  # slowest axis first: (nz, ny, nx) or (nz, ny, nx, c)
    return data.transpose(2, 1, 0) if data.ndim == 3 else data.transpose(2, 1, 0, 3)


def cli_nrrd(cli: str, mesh: Path, tmp: Path, **options) -> Dict[str, np.ndarray]:
    """`voxr voxelize MESH -o x.nrrd` with `options`: {'occ': ..., 'count': ..., 'inside': ...} arrays."""
    out = tmp / "cli.nrrd"
    run_cli(cli, ["voxelize", mesh, "-q", "-o", out, *cli_options(**options)])
    arrays = {"occ": read_nrrd(out)}
    for f in tmp.glob("cli.*.nrrd"):
        arrays[f.name.split(".")[1]] = read_nrrd(f)
    return arrays


def cli_npz(cli: str, mesh: Path, tmp: Path, **options) -> Dict[str, np.ndarray]:
    """`voxr voxelize MESH -o x.npz` with `options`, loaded."""
    out = tmp / "cli.npz"
    run_cli(cli, ["voxelize", mesh, "-q", "-o", out, *cli_options(**options)])
    with np.load(out) as z:
        return {k: z[k] for k in z.files}


def linear_order(ijk: np.ndarray, dims: Sequence[int]) -> np.ndarray:
    """The permutation sorting voxels (N, 3) by linear index (x fastest)."""
    nx, ny, _ = dims
    ijk = ijk.astype(np.int64)
    return np.argsort((ijk[:, 2] * ny + ijk[:, 1]) * nx + ijk[:, 0], kind="stable")


def write_ply(path: Path, vertices: np.ndarray, faces: np.ndarray) -> Path:
    """Binary little-endian PLY with double vertices: the CLI reads exactly the numbers of `vertices`."""
    v = np.ascontiguousarray(vertices, dtype="<f8")
    f = np.asarray(faces, dtype="<u4")
    header = (
        "ply\nformat binary_little_endian 1.0\n"
        f"element vertex {len(v)}\nproperty double x\nproperty double y\nproperty double z\n"
        f"element face {len(f)}\nproperty list uchar uint vertex_indices\nend_header\n"
    )
    rows = np.zeros(len(f), dtype=[("n", "u1"), ("i", "<u4", (3,))])
    rows["n"] = 3
    rows["i"] = f
    Path(path).write_bytes(header.encode() + v.tobytes() + rows.tobytes())
    return Path(path)


def write_obj(path: Path, vertices: np.ndarray, faces: np.ndarray, materials: Optional[np.ndarray] = None) -> Path:
    """OBJ with repr() text (reads back as the same doubles) and `usemtl m<id>` where the material changes:
    the CLI numbers materials in order of first use, so ids first used in increasing order read back as is."""
    lines = [f"v {x!r} {y!r} {z!r}" for x, y, z in np.asarray(vertices, dtype=np.float64).tolist()]
    current = None
    for t, (a, b, c) in enumerate(np.asarray(faces).tolist()):
        if materials is not None and materials[t] != current:
            current = materials[t]
            lines.append(f"usemtl m{current}")
        lines.append(f"f {a + 1} {b + 1} {c + 1}")
    Path(path).write_text("\n".join(lines) + "\n")
    return Path(path)


def read_off(path: Path):
    """A triangle OFF file -> (float64 vertices, int64 faces), parsed as the CLI parses (correctly rounded)."""
    tokens = Path(path).read_text().split()
    assert tokens[0] == "OFF"
    nv, nf = int(tokens[1]), int(tokens[2])
    v = np.array([float(t) for t in tokens[4 : 4 + 3 * nv]], dtype=np.float64).reshape(nv, 3)
    rows = np.array(tokens[4 + 3 * nv : 4 + 3 * nv + 4 * nf], dtype=np.int64).reshape(nf, 4)
    assert (rows[:, 0] == 3).all(), "triangles only"
    return v, rows[:, 1:]


def torus(rings: int = 24, sides: int = 12, r_major: float = 1.0, r_minor: float = 0.35):
    """A closed torus (vertices float64, faces int64) in the xy plane."""
    u = np.linspace(0, 2 * np.pi, rings, endpoint=False)
    w = np.linspace(0, 2 * np.pi, sides, endpoint=False)
    uu, ww = np.meshgrid(u, w, indexing="ij")
    v = np.stack(
        [(r_major + r_minor * np.cos(ww)) * np.cos(uu), (r_major + r_minor * np.cos(ww)) * np.sin(uu), r_minor * np.sin(ww)],
        axis=-1,
    ).reshape(-1, 3)
    f = []
    for i in range(rings):
        for j in range(sides):
            a, b = i * sides + j, ((i + 1) % rings) * sides + j
            c, d = ((i + 1) % rings) * sides + (j + 1) % sides, i * sides + (j + 1) % sides
            f += [(a, b, c), (a, c, d)]
    return v, np.array(f, dtype=np.int64)


def rotation(seed: int) -> np.ndarray:
    """A random rotation matrix (no axis-aligned faces)."""
    q, r = np.linalg.qr(np.random.default_rng(seed).normal(size=(3, 3)))
    q *= np.sign(np.diag(r))
    if np.linalg.det(q) < 0:
        q[:, 0] = -q[:, 0]
    return q


def box(size=(1.0, 0.6, 0.35)):
    """An axis-aligned closed box centred at the origin (12 triangles, outward winding)."""
    sx, sy, sz = (s / 2 for s in size)
    v = np.array([[x, y, z] for z in (-sz, sz) for y in (-sy, sy) for x in (-sx, sx)], dtype=np.float64)
    f = np.array(
        [[0, 2, 3], [0, 3, 1], [4, 5, 7], [4, 7, 6], [0, 1, 5], [0, 5, 4],
         [2, 6, 7], [2, 7, 3], [0, 4, 6], [0, 6, 2], [1, 3, 7], [1, 7, 5]],
        dtype=np.int64,
    )
    return v, f
