"""voxr.voxelize / voxelize_file against the CLI: the same mesh and options give the same arrays, bit for bit
(occupancy, inside and every channel, from the CLI's .nrrd and .npz outputs)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import voxr
from conftest import (
    box,
    cli_npz,
    cli_nrrd,
    linear_order,
    mesh_path,
    read_off,
    rotation,
    torus,
    write_obj,
    write_ply,
)


def dense(grid: voxr.VoxelGrid, values: np.ndarray) -> np.ndarray:
    """A channel's rows scattered into a zero (nx, ny, nz[, c]) array, as the CLI's .nrrd holds it."""
    ijk = grid.occupied_indices().astype(np.int64)
    out = np.zeros(grid.dims + values.shape[1:], dtype=values.dtype)
    out[ijk[:, 0], ijk[:, 1], ijk[:, 2]] = values
    return out


def same_bits(a: np.ndarray, b: np.ndarray) -> bool:
    """Exact equality, floats compared as their bit patterns (so -0.0 != 0.0 and NaN == NaN)."""
    if a.shape != b.shape or a.dtype != b.dtype:
        return False
    if a.dtype.kind == "f":
        a, b = a.view(np.uint32 if a.itemsize == 4 else np.uint64), b.view(np.uint32 if b.itemsize == 4 else np.uint64)
    return bool(np.array_equal(a, b))


def check_against_nrrd(grid: voxr.VoxelGrid, cli: dict) -> None:
    occ = cli["occ"]
    assert grid.dims == occ.shape
    assert grid.occupancy.dtype == np.bool_ and grid.occupancy.shape == occ.shape
    assert np.array_equal(grid.occupancy, occ.astype(bool)), "occupancy differs from the CLI's"
    assert grid.voxels_set == int(occ.astype(bool).sum())
    ijk = grid.occupied_indices()
    assert ijk.shape == (grid.voxels_set, 3) and ijk.dtype == np.uint32
    assert occ[ijk[:, 0], ijk[:, 1], ijk[:, 2]].all()
    if "inside" in grid.channels:
        assert np.array_equal(grid.inside, cli["inside"].astype(bool)), "inside differs"
        assert grid.inside_voxels == int(cli["inside"].astype(bool).sum())
    else:
        assert grid.inside is None and "inside" not in cli
    for name in ("count", "normal", "material", "color"):
        values = getattr(grid, name)
        if name not in grid.channels:
            assert values is None and name not in cli
            continue
        assert len(values) == grid.voxels_set
        assert same_bits(dense(grid, values), cli[name]), f"channel {name} differs from the CLI's"


def check_against_npz(grid: voxr.VoxelGrid, z: dict) -> None:
    assert tuple(int(d) for d in z["dims"]) == grid.dims
    assert float(z["voxel_size"]) == grid.voxel_size
    # transform: grid units -> world; the .npz holds the centre of voxel 0 and the grid axes in the world.
    t = grid.transform
    assert t.shape == (4, 4) and t.dtype == np.float64
    assert np.allclose(t @ [0.5, 0.5, 0.5, 1.0], list(z["origin"]) + [1.0], rtol=0, atol=1e-9 * grid.voxel_size * max(grid.dims))
    assert np.allclose(t[:3, :3].T, np.asarray(z["axes"]) * grid.voxel_size, rtol=1e-12, atol=1e-15)
    ours = grid.occupied_indices()
    order, theirs = linear_order(ours, grid.dims), linear_order(z["ijk"], grid.dims)
    assert np.array_equal(ours[order].astype(np.int64), z["ijk"][theirs].astype(np.int64))
    for name in ("count", "normal", "material", "color"):
        if name in grid.channels:
            assert same_bits(np.asarray(getattr(grid, name))[order], z[name][theirs]), f"{name} differs (.npz)"


FILE_CASES = [
    ("bunny.obj", dict(res=64, channels="occ,count,normal,material")),
    ("armadillo.off", dict(res=48, method="slice", mode="center", solid="parity", channels="occ,count")),
    ("bunny.obj", dict(res=80, layout="sparse", channels=("occ", "count", "normal"))),
    ("ChineseDragon-10kv.off", dict(dims=(41, 29, 33), method="grid", channels="occ,normal")),
    ("mech-holes-shark.off", dict(res=40, method="slicemap")),
    ("refined_elephant.off", dict(res=56, solid="flood", channels="occ,material")),
]


@pytest.mark.parametrize("name,options", FILE_CASES, ids=[f"{n}-{i}" for i, (n, _) in enumerate(FILE_CASES)])
def test_voxelize_file_matches_cli(cli, tmp_path: Path, name: str, options: dict) -> None:
    path = mesh_path(name)
    grid = voxr.voxelize_file(path, **options)
    if options.get("layout") == "sparse":
        assert grid.sparse
    check_against_nrrd(grid, cli_nrrd(cli, path, tmp_path, **options))
    check_against_npz(grid, cli_npz(cli, path, tmp_path, **options))


def test_arrays_match_cli_off(cli, tmp_path: Path) -> None:
    """voxelize(vertices, faces) from the numbers the CLI parses out of the same OFF file."""
    path = mesh_path("armadillo.off")
    v, f = read_off(path)
    options = dict(res=72, channels="occ,count,normal")
    grid = voxr.voxelize(v, f, **options)
    check_against_nrrd(grid, cli_nrrd(cli, path, tmp_path, **options))


@pytest.mark.parametrize(
    "options",
    [
        dict(dims=(37, 23, 51), channels="occ,count,normal"),
        dict(res=45, mode="center", method="slice", solid="xor", channels="occ,normal"),
        dict(res=61, layout="sparse", channels="occ,count,normal"),
        dict(bounds=(-1.5, -1.25, -1.0, 1.25, 1.5, 1.0), res=50, method="grid", channels="occ,count"),
    ],
    ids=["odd-dims", "center-solid", "sparse", "bounds"],
)
def test_rotated_mesh_arrays_match_cli(cli, tmp_path: Path, options: dict) -> None:
    """A rotated torus (no face on a voxel plane) from arrays and from a PLY of the same doubles."""
    v, f = torus()
    v = v @ rotation(7).T + [0.125, -3.0, 2.5]
    grid = voxr.voxelize(v, f, **options)
    ply = write_ply(tmp_path / "torus.ply", v, f)
    check_against_nrrd(grid, cli_nrrd(cli, ply, tmp_path, **options))
    # float32 and int32 inputs are converted (a copy), with the same voxels as float64 of the same values
    v32 = v.astype(np.float32)
    again = voxr.voxelize(v32, f.astype(np.int32), **options)
    ref = voxr.voxelize(v32.astype(np.float64), f, **options)
    assert np.array_equal(again.occupancy, ref.occupancy)


def test_materials_from_arrays_match_cli_obj(cli, tmp_path: Path) -> None:
    """The material channel: materials= per triangle, and an OBJ whose usemtl groups number the same ids."""
    v, f = torus(32, 16)
    v = v @ rotation(3).T
    raw = np.random.default_rng(5).integers(0, 5, len(f))
    first = {m: i for i, m in enumerate(dict.fromkeys(raw.tolist()))}  # ids in order of first use
    materials = np.array([first[m] for m in raw.tolist()], dtype=np.int64)
    options = dict(res=64, channels="occ,count,normal,material")
    grid = voxr.voxelize(v, f, materials=materials, **options)
    assert grid.material.max() == materials.max()
    obj = write_obj(tmp_path / "torus.obj", v, f, materials)
    check_against_nrrd(grid, cli_nrrd(cli, obj, tmp_path, **options))


def test_box_dims_and_transform() -> None:
    """An axis-aligned box: the fitted grid's transform maps voxel centres into the bounds."""
    v, f = box()
    grid = voxr.voxelize(v, f, res=32)
    nx, ny, nz = grid.dims
    assert nx == 32 and grid.occupancy.shape == (nx, ny, nz)
    corners = grid.transform @ np.array([[0, 0, 0, 1], [nx, ny, nz, 1]], dtype=float).T
    assert (corners[:3, 0] < v.min(axis=0)).all() and (corners[:3, 1] > v.max(axis=0)).all()
    assert np.isclose(grid.voxel_size * nx, corners[0, 1] - corners[0, 0])
    occ = grid.occupancy
    assert occ.flags.f_contiguous and not occ.flags.writeable
    assert occ[0].sum() > 0 and occ[:, 0].sum() > 0 and occ[:, :, 0].sum() > 0  # [x, y, z]: faces on all six sides
    assert grid.channels == ("occ",) and grid.count is None and grid.inside is None


def test_report_and_save(tmp_path: Path) -> None:
    v, f = torus()
    grid = voxr.voxelize(v, f, res=40, channels="occ,count")
    report = grid.report
    assert isinstance(report, dict) and report, "the --report object"
    assert grid.report is report  # parsed once
    assert isinstance(grid.warnings, list)
    written = grid.save(tmp_path / "t.nrrd")
    assert sorted(Path(p).name for p in written) == ["t.count.nrrd", "t.nrrd"]
    written = grid.save(tmp_path / "t.npz")
    with np.load(written[0]) as z:
        assert len(z["ijk"]) == grid.voxels_set
    assert "VoxelGrid(dims=" in repr(grid)


def test_context_reuse_and_devices() -> None:
    listed = voxr.devices()
    assert listed and {"id", "name", "platform", "type", "driver_version", "compute_units", "global_memory",
                       "max_allocation"} <= set(listed[0])
    context = voxr.Context()
    assert context.device["id"] in {d["id"] for d in listed}
    v, f = box()
    a = context.voxelize(v, f, res=24)
    b = context.voxelize(v, f, res=24)
    c = voxr.voxelize(v, f, res=24, device=context.device["id"])
    assert np.array_equal(a.occupancy, b.occupancy) and np.array_equal(a.occupancy, c.occupancy)
