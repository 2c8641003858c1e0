"""voxr.VoxelGrid: a voxelization result as NumPy arrays."""

from __future__ import annotations

import json
import os
from typing import Any, Dict, List, Optional, Tuple, Union

import numpy as np
from numpy.typing import NDArray

from . import _core


class VoxelGrid:
    """The voxels of one voxelize() run (voxr::VoxelVolume).

    Voxel (i, j, k) is the box [i, i+1] x [j, j+1] x [k, k+1] in grid units; ``transform`` maps grid units to
    the world (the centre of voxel (i, j, k) is ``transform @ (i + 0.5, j + 0.5, k + 0.5, 1)``).

    Where copies happen:

    * ``occupancy`` and ``inside`` are dense bool arrays expanded from the device's bits (one byte per voxel,
      the one copy that cannot be avoided: NumPy has no bit arrays). Each is made once, on first access,
      and cached; it is read-only, shaped (nx, ny, nz) and indexed [x, y, z] (Fortran strides over voxr's
      x-fastest buffer). ``np.array(grid.occupancy)`` gives a writable copy.
    * ``count``, ``normal``, ``material`` and ``color`` are read-only views of voxr's own arrays (no copy),
      one row per set voxel in the order of ``occupied_indices()``; a view keeps the result alive after
      the VoxelGrid is gone.
    * ``occupied_indices()`` writes a new (N, 3) uint32 array on each call.
    """

    __slots__ = ("_volume", "_report", "__weakref__")

    def __init__(self, volume: _core.Volume) -> None:
        self._volume = volume
        self._report: Optional[Dict[str, Any]] = None

    # -- the grid ---------------------------------------------------------------------------------------
    @property
    def dims(self) -> Tuple[int, int, int]:
        """(nx, ny, nz), voxels along each grid axis."""
        return tuple(self._volume.dims)  # type: ignore[return-value]

    @property
    def shape(self) -> Tuple[int, int, int]:
        """Same as ``dims``: the shape of ``occupancy``."""
        return self.dims

    @property
    def voxel_size(self) -> float:
        """Edge length of a (cubic) voxel, in world units."""
        return float(self._volume.voxel_size)

    @property
    def transform(self) -> NDArray[np.float64]:
        """4x4 float64 matrix mapping grid units (i, j, k, 1) to world coordinates (a new array each call)."""
        return np.array(self._volume.index_to_world, dtype=np.float64).reshape(4, 4, order="F")

    @property
    def channels(self) -> Tuple[str, ...]:
        """The channels the run produced, e.g. ('occ', 'count') (+ 'inside' with a solid)."""
        text = self._volume.channels
        return tuple(c for c in text.split(",") if c)

    @property
    def sparse(self) -> bool:
        """True when voxr built the grid in 8^3 bricks (layout 'sparse', or 'auto' on a large grid)."""
        return bool(self._volume.sparse)

    @property
    def voxels_set(self) -> int:
        """Number of surface voxels (the rows of the channel arrays)."""
        return int(self._volume.voxels_set)

    @property
    def inside_voxels(self) -> int:
        """Number of interior voxels of the solid (0 without ``solid``)."""
        return int(self._volume.inside_voxels)

    # -- dense masks ------------------------------------------------------------------------------------
    @property
    def occupancy(self) -> NDArray[np.bool_]:
        """Surface voxels as a read-only (nx, ny, nz) bool array indexed [x, y, z].

        A copy (bits -> one byte per voxel, made once and cached), computed with the GIL released."""
        return self._volume.occupancy()

    @property
    def inside(self) -> Optional[NDArray[np.bool_]]:
        """Interior voxels of the solid (``solid=...``) as occupancy is, or None without a solid.

        A copy (bits -> bytes, made once and cached)."""
        if "inside" not in self.channels:
            return None
        return self._volume.inside()

    def occupied_indices(self) -> NDArray[np.uint32]:
        """The surface voxels' (i, j, k), an (N, 3) uint32 array (a new copy per call), in the order of the
        channel arrays: increasing linear index (i fastest) for a dense grid, brick by brick for a sparse one."""
        return self._volume.occupied_indices()

    # -- channels (zero-copy views) ---------------------------------------------------------------------
    def _channel(self, name: str) -> Optional[NDArray[Any]]:
        if name not in self.channels:
            return None
        return getattr(self._volume, name)()

    @property
    def count(self) -> Optional[NDArray[np.uint32]]:
        """(N,) uint32: triangles that wrote each surface voxel (view; None unless channel 'count')."""
        return self._channel("count")

    @property
    def normal(self) -> Optional[NDArray[np.float32]]:
        """(N, 3) float32: mean unit normal per surface voxel, 0 where normals cancel (view; None unless
        channel 'normal')."""
        return self._channel("normal")

    @property
    def material(self) -> Optional[NDArray[np.uint32]]:
        """(N,) uint32: largest material id among the voxel's triangles (view; None unless 'material')."""
        return self._channel("material")

    @property
    def color(self) -> Optional[NDArray[np.uint8]]:
        """(N, 4) uint8 RGBA: mean surface colour per voxel (view; None unless channel 'color')."""
        return self._channel("color")

    # -- report and output ------------------------------------------------------------------------------
    @property
    def report(self) -> Dict[str, Any]:
        """The run's report: the object `voxr voxelize --report FILE.json` writes (timings in ``ms``,
        counts, layout, device, ...)."""
        if self._report is None:
            text = self._volume.report_json
            self._report = json.loads(text) if text else {}
        return self._report

    @property
    def warnings(self) -> List[str]:
        """What the CLI would print as 'voxr: warning: ...' lines (an open mesh with a solid, ...)."""
        return list(self._volume.warnings)

    def save(self, path: Union[str, "os.PathLike[str]"]) -> List[str]:
        """Writes the grid by extension (.vdb, .npz, .nrrd, .vti, .binvox, .vox) as `voxr voxelize -o`
        does, atomically; returns the files written (.nrrd writes one per channel)."""
        return list(self._volume.save(os.fspath(path)))

    def __repr__(self) -> str:
        nx, ny, nz = self.dims
        return (
            f"voxr.VoxelGrid(dims=({nx}, {ny}, {nz}), voxel_size={self.voxel_size:.6g}, "
            f"channels={self.channels}, voxels_set={self.voxels_set}, "
            f"layout={'sparse' if self.sparse else 'dense'})"
        )
