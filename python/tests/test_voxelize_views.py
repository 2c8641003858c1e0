"""Memory and threads: channel arrays are views of voxr's memory that keep it alive, occupancy is made once,
inputs of the right dtype are not copied, and the GIL is released while voxr works."""

from __future__ import annotations

import gc
import threading
import time
import weakref

import numpy as np
import pytest

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


def longest_stall(ticks: np.ndarray, start: float, end: float) -> float:
    """The longest time within [start, end] during which the ticking thread made no tick."""
    a = np.concatenate([[start], ticks[(ticks > start) & (ticks < end)], [end]])
    return float(np.diff(a).max())


def gil_attempt(v: np.ndarray, f: np.ndarray) -> list:
    """One voxelize + occupancy in a thread while this thread ticks; the windows where it stalled."""
    times = {}

    def work() -> None:
        times["start"] = time.perf_counter()
        grid = voxr.voxelize(v, f, res=448, channels="occ,count,normal")
        times["voxelized"] = time.perf_counter()
        grid.occupancy  # the bit expansion releases the GIL too
        times["expanded"] = time.perf_counter()

    ticks = []
    thread = threading.Thread(target=work)
    thread.start()
    while thread.is_alive():
        ticks.append(time.perf_counter())
        sum(range(200))  # Python work
    thread.join()
    ticks = np.array(ticks)
    stalls = []
    for what, start, end in [("voxelize", times["start"], times["voxelized"]),
                             ("occupancy", times["voxelized"], times["expanded"])]:
        seconds = end - start
        assert seconds > 0.02, f"{what}: the call must be long enough to tell ({seconds:.3f} s)"
        stall = longest_stall(ticks, start, end)
        if stall >= 0.5 * seconds:
            stalls.append(f"{what}: the Python thread stalled {stall:.3f} s of {seconds:.3f} s")
    return stalls


def test_gil_is_released_during_voxelize() -> None:
    """A Python thread keeps running while voxelize and the occupancy expansion work: the longest pause it
    sees is far below each call's duration (with the GIL held it would be the whole call). Up to 3 tries,
    so one scheduling hiccup on a loaded machine does not fail it; a held GIL fails every try."""
    v, f = read_off(mesh_path("armadillo.off"))
    f = f.astype(np.uint32)
    voxr.voxelize(v, f, res=32)  # the Context and programs, outside the timed calls
    failures = []
    for _ in range(3):
        stalls = gil_attempt(v, f)
        if not stalls:
            return
        failures.append("; ".join(stalls))
    pytest.fail("GIL held? " + " | ".join(failures))
