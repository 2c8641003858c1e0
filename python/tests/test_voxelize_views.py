"""Memory and threads: channel arrays are views of voxr's memory that keep it alive, occupancy is made once,
inputs of the right dtype are not copied, and the GIL is released while voxr works."""

from __future__ import annotations

import gc
import threading
import time
import weakref

import numpy as np

import voxr
from conftest import mesh_path, read_off, torus
from voxr._mesh import mesh_arrays


def address(a: np.ndarray) -> int:
    return a.__array_interface__["data"][0]


def test_channel_views_are_zero_copy() -> None:
    v, f = torus()
    grid = voxr.voxelize(v, f, res=48, channels="occ,count,normal,material")
    for name in ("count", "normal", "material"):
        a, b = getattr(grid, name), getattr(grid, name)
        assert address(a) == address(b), f"{name}: two accesses, two copies"
        assert not a.flags.writeable and a.flags.c_contiguous
    assert grid.count.dtype == np.uint32 and grid.count.shape == (grid.voxels_set,)
    assert grid.normal.dtype == np.float32 and grid.normal.shape == (grid.voxels_set, 3)
    assert grid.material.dtype == np.uint32
    # occupancy: one copy, cached
    assert address(grid.occupancy) == address(grid.occupancy)
    strides = grid.occupancy.strides
    nx, ny, _ = grid.dims
    assert strides == (1, nx, nx * ny), "Fortran strides over the x-fastest buffer"


def test_views_keep_the_result_alive() -> None:
    v, f = torus()
    grid = voxr.voxelize(v, f, res=64, channels="occ,count,normal")
    count, normal, occupancy = grid.count, grid.normal, grid.occupancy
    expected = (count.copy(), normal.copy(), occupancy.copy())
    ref = weakref.ref(grid)
    del grid
    gc.collect()
    assert ref() is None, "the VoxelGrid itself is gone"
    # allocate and voxelize again so freed memory would be reused
    for _ in range(3):
        voxr.voxelize(v * 2.0, f, res=64, channels="occ,count,normal")
        np.ones(1 << 20, dtype=np.uint32)
    assert np.array_equal(count, expected[0])
    assert np.array_equal(normal.view(np.uint32), expected[1].view(np.uint32))
    assert np.array_equal(occupancy, expected[2])
    del count, normal
    gc.collect()
    assert occupancy.sum() == expected[2].sum()


def test_inputs_of_the_right_dtype_are_not_copied() -> None:
    v, f = torus()
    f32 = f.astype(np.uint32)
    m = mesh_arrays(v, f32)
    assert m.positions is v or np.shares_memory(m.positions, v)
    assert m.triangles is f32 or np.shares_memory(m.triangles, f32)
    # other dtypes or layouts are converted once
    assert not np.shares_memory(mesh_arrays(v.astype(np.float32), f32).positions, v)
    assert mesh_arrays(np.asfortranarray(v), f32).positions.flags.c_contiguous


def test_gil_is_released_during_voxelize() -> None:
    """A Python thread keeps running while voxelize works: the longest pause it sees is far below the
    call's duration (with the GIL held it would be the whole call)."""
    path = mesh_path("armadillo.off")
    v, f = read_off(path)
    f = f.astype(np.uint32)
    voxr.voxelize(v, f, res=32)  # the Context and programs, outside the timed call
    result = {}

    def work() -> None:
        t0 = time.perf_counter()
        result["grid"] = voxr.voxelize(v, f, res=384, channels="occ,count,normal")
        result["occ"] = result["grid"].occupancy  # the bit expansion releases the GIL too
        result["seconds"] = time.perf_counter() - t0

    ticks = []
    thread = threading.Thread(target=work)
    thread.start()
    while thread.is_alive():
        ticks.append(time.perf_counter())
        sum(range(200))  # Python work
    thread.join()
    gaps = np.diff(ticks)
    assert result["seconds"] > 0.05, "the call must be long enough to tell"
    assert len(ticks) > 100
    assert gaps.max() < 0.5 * result["seconds"], (
        f"the Python thread stalled {gaps.max():.3f} s of a {result['seconds']:.3f} s voxelize: GIL held?"
    )
