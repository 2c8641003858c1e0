"""Every way to call voxr wrongly ends in a Python exception with one clear line: voxr.Error (voxr's own
message) for what voxr refuses, TypeError/ValueError for arguments of the wrong type or shape; never a
crash."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import voxr
from conftest import box


@pytest.fixture(scope="module")
def mesh():
    return box()


def one_line(e: pytest.ExceptionInfo) -> str:
    text = str(e.value)
    assert text and "\n" not in text, f"not one line: {text!r}"
    return text


def test_error_is_a_runtime_error() -> None:
    assert issubclass(voxr.Error, RuntimeError)
    assert voxr.Error.__module__ == "voxr"


def test_missing_file(tmp_path: Path) -> None:
    missing = tmp_path / "no-such-mesh.obj"
    with pytest.raises(voxr.Error) as e:
        voxr.voxelize_file(missing)
    assert str(missing) in one_line(e)


def test_unreadable_and_unsupported_files(tmp_path: Path) -> None:
    bad = tmp_path / "broken.off"
    bad.write_text("OFF\n3 1 0\n0 0 0\n1 0 0\n")  # truncated
    with pytest.raises(voxr.Error) as e:
        voxr.voxelize_file(bad)
    assert "broken.off" in one_line(e)
    other = tmp_path / "mesh.xyz"
    other.write_text("1 2 3\n")
    with pytest.raises(voxr.Error) as e:
        voxr.voxelize_file(other)
    assert "mesh.xyz" in one_line(e)


@pytest.mark.parametrize(
    "options,word",
    [
        (dict(method="octree"), "octree"),
        (dict(mode="outer"), "outer"),
        (dict(channels="occ,colour"), "colour"),
        (dict(channels=["occ", "density"]), "density"),
        (dict(layout="bricks"), "bricks"),
        (dict(solid="fill"), "fill"),
        (dict(res=100000), "100000"),
        (dict(method="slicemap", mode="center"), "slicemap"),
        (dict(layout="sparse", solid="parity"), "dense"),
        (dict(layout="sparse", memory_budget="lots"), "lots"),
        (dict(layout="sparse", memory_budget="12X"), "12X"),
        (dict(method="slicemap", slicing="curved"), "curved"),
    ],
)
def test_bad_settings_are_voxr_errors(mesh, options: dict, word: str) -> None:
    with pytest.raises(voxr.Error) as e:
        voxr.voxelize(*mesh, **options)
    assert word in one_line(e)


@pytest.mark.parametrize(
    "options,exc,word",
    [
        (dict(res=0), ValueError, "res"),
        (dict(res=-5), ValueError, "res"),
        (dict(res="256"), TypeError, "res"),
        (dict(res=2.5), TypeError, "res"),
        (dict(dims=(10, 10)), ValueError, "dims"),
        (dict(dims=(10, -1, 10)), ValueError, "dims"),
        (dict(bounds=(0, 0, 0, 1, 1)), ValueError, "bounds"),
        (dict(bounds=(0, 0, 0, 1, 1, float("nan"))), ValueError, "bounds"),
        (dict(method=3), TypeError, "method"),
        (dict(channels=5), TypeError, "channels"),
        (dict(memory_budget=-1), ValueError, "memory_budget"),
        (dict(memory_budget=2.5), TypeError, "memory_budget"),
        (dict(slicing=1), TypeError, "slicing"),
    ],
)
def test_bad_argument_types(mesh, options: dict, exc: type, word: str) -> None:
    with pytest.raises(exc) as e:
        voxr.voxelize(*mesh, **options)
    assert word in one_line(e)


def test_memory_budget_text() -> None:
    from voxr._options import memory_budget_text

    assert memory_budget_text("512M") == "512M"
    assert memory_budget_text(None) == ""
    assert memory_budget_text(1 << 24) == str(1 << 24)


@pytest.mark.parametrize(
    "vertices,faces,exc,word",
    [
        (np.zeros((8, 2)), np.zeros((1, 3), int), ValueError, "(V, 3)"),
        (np.zeros(24), np.zeros((1, 3), int), ValueError, "(V, 3)"),
        (np.array([["a", "b", "c"]]), np.zeros((1, 3), int), TypeError, "vertices"),
        (np.zeros((8, 3)), np.zeros((4, 4), int), ValueError, "(F, 3)"),
        (np.zeros((8, 3)), np.zeros((4, 3)), TypeError, "integer"),
        (np.zeros((8, 3)), np.array([[0, 1, 8]]), ValueError, "out of range"),
        (np.zeros((8, 3)), np.array([[0, -1, 2]]), ValueError, "negative"),
        (np.zeros((8, 3)), np.array([[0, 1, 1 << 40]]), ValueError, "32 bits"),
        (np.zeros((8, 3)), None, TypeError, "faces"),
        ([[0, 0, 0], [1, 0, 0]], [[0, 1, 5]], ValueError, "out of range"),
    ],
)
def test_bad_mesh_arrays(vertices, faces, exc: type, word: str) -> None:
    with pytest.raises(exc) as e:
        voxr.voxelize(vertices, faces)
    assert word in one_line(e)


def test_bad_materials(mesh) -> None:
    v, f = mesh
    with pytest.raises(ValueError, match="one id per triangle"):
        voxr.voxelize(v, f, materials=np.zeros(len(f) - 1, int), channels="occ,material")
    with pytest.raises(ValueError, match="negative"):
        voxr.voxelize(v, f, materials=np.full(len(f), -2), channels="occ,material")
    with pytest.raises(TypeError, match="integer"):
        voxr.voxelize(v, f, materials=np.zeros(len(f)), channels="occ,material")


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_non_finite_vertices(mesh, bad: float) -> None:
    v, f = mesh
    v = v.copy()
    v[3, 1] = bad
    with pytest.raises((voxr.Error, ValueError)) as e:
        voxr.voxelize(v, f)
    text = one_line(e)
    assert "finite" in text or "NaN" in text or "nan" in text or "inf" in text


def test_no_triangles() -> None:
    with pytest.raises((voxr.Error, ValueError)) as e:
        voxr.voxelize(np.zeros((3, 3)), np.zeros((0, 3), np.uint32))
    one_line(e)


def test_unknown_device(mesh) -> None:
    with pytest.raises(voxr.Error) as e:
        voxr.Context("no-such-device-name")
    assert "no-such-device-name" in one_line(e)
    with pytest.raises(voxr.Error) as e:
        voxr.voxelize(*mesh, device="97:3")
    assert "97:3" in one_line(e)
    with pytest.raises(TypeError):
        voxr.Context(device=1.5)


def test_bad_save_paths(mesh, tmp_path: Path) -> None:
    grid = voxr.voxelize(*mesh, res=16)
    with pytest.raises(voxr.Error) as e:
        grid.save(tmp_path / "out.txt")
    assert "out.txt" in one_line(e)
    with pytest.raises(voxr.Error) as e:
        grid.save(tmp_path / "no" / "such" / "folder" / "out.nrrd")
    assert "out.nrrd" in one_line(e)


def test_foreign_mesh_objects() -> None:
    class NotAMesh:
        pass

    with pytest.raises(TypeError):
        voxr.voxelize(NotAMesh())
    with pytest.raises((TypeError, ValueError)):
        voxr.voxelize(NotAMesh(), [[0, 1, 2]])
