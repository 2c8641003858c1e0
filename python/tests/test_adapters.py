"""Meshes from trimesh and Open3D give the voxels of the same arrays (each test is skipped, with the reason,
when its package is not installed: neither is a dependency of voxr)."""

from __future__ import annotations

import sys

import numpy as np
import pytest

import voxr
from conftest import rotation, torus

OPTIONS = dict(res=48, channels="occ,count,normal")


def reference():
    v, f = torus()
    v = v @ rotation(11).T
    return v, f, voxr.voxelize(v, f, **OPTIONS)


def test_voxr_imports_neither() -> None:
    import subprocess

    code = "import sys, voxr; print('trimesh' in sys.modules, 'open3d' in sys.modules, 'dask' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.split() == ["False", "False", "False"]


def test_trimesh_mesh() -> None:
    trimesh = pytest.importorskip("trimesh", reason="trimesh is not installed (pip install trimesh)")
    v, f, ref = reference()
    mesh = trimesh.Trimesh(vertices=v, faces=f, process=False)
    grid = voxr.voxelize(mesh, **OPTIONS)
    assert np.array_equal(grid.occupancy, ref.occupancy)
    assert np.array_equal(grid.count, ref.count)
    assert np.array_equal(grid.normal.view(np.uint32), ref.normal.view(np.uint32))
    scene = trimesh.Scene([mesh])
    assert np.array_equal(voxr.voxelize(scene, **OPTIONS).occupancy, ref.occupancy)
    with pytest.raises(TypeError, match="faces"):
        voxr.voxelize(mesh, f)


def test_open3d_mesh() -> None:
    o3d = pytest.importorskip("open3d", reason="open3d is not installed (pip install open3d)")
    v, f, ref = reference()
    mesh = o3d.geometry.TriangleMesh(o3d.utility.Vector3dVector(v), o3d.utility.Vector3iVector(f.astype(np.int32)))
    grid = voxr.voxelize(mesh, **OPTIONS)
    assert np.array_equal(grid.occupancy, ref.occupancy)
    assert np.array_equal(grid.count, ref.count)
    with pytest.raises(TypeError, match="faces"):
        voxr.voxelize(mesh, f)


def test_package_surface() -> None:
    """voxr.render stays the function when voxr.render (the module) is imported, and the lazy names
    resolve or say they are not part of this build."""
    import importlib
    import types

    try:
        importlib.import_module("voxr.render")
    except ModuleNotFoundError:
        with pytest.raises(voxr.Error, match="not part of this build"):
            voxr.render()
    assert callable(voxr.render) and not isinstance(voxr.render, types.ModuleType)
    for name in ("voxelize_files", "dask"):
        try:
            getattr(voxr, name)
        except AttributeError as e:
            assert "not part of this build" in str(e)
    with pytest.raises(AttributeError):
        voxr.no_such_name
