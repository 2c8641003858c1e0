"""voxr.Context and the module-level voxelize functions (one Context per device per process)."""

from __future__ import annotations

import os
import threading
from typing import Any, Dict, Optional, Sequence, Union

from . import _core
from ._grid import VoxelGrid
from ._mesh import mesh_arrays
from ._options import ChannelsArg, MemoryBudget, device_text, settings

PathLike = Union[str, "os.PathLike[str]"]


class Context:
    """An OpenCL device opened with voxr's programs built (or loaded from the program cache), kept for
    many runs so the driver's start is paid once.

    ``device``: None (``$VOXR_DEVICE`` or the default device), ``'P:D'`` as ``voxr.devices()`` lists,
    ``'P'``, or a substring of the device's name. Raises voxr.Error when it selects nothing.
    A Context runs one voxelization at a time; calls from several threads wait for each other.
    """

    __slots__ = ("_context", "__weakref__")

    def __init__(self, device: Union[str, int, None] = None) -> None:
        self._context = _core.Context(device_text(device))

    @property
    def device(self) -> Dict[str, Any]:
        """The device as ``voxr.devices()`` describes it."""
        return self._context.device

    def voxelize(
        self,
        mesh: Any,
        faces: Any = None,
        *,
        res: Optional[int] = None,
        dims: Optional[Sequence[int]] = None,
        bounds: Optional[Sequence[float]] = None,
        method: str = "hybrid",
        mode: Optional[str] = None,
        slicing: Optional[str] = None,
        channels: ChannelsArg = "occ",
        solid: Optional[str] = None,
        layout: str = "auto",
        memory_budget: MemoryBudget = None,
        materials: Any = None,
    ) -> VoxelGrid:
        """Voxelizes a mesh on this Context's device; see ``voxr.voxelize``."""
        s = settings(
            res=res, dims=dims, bounds=bounds, method=method, mode=mode, slicing=slicing, channels=channels, solid=solid,
            layout=layout, memory_budget=memory_budget,
        )
        m = mesh_arrays(mesh, faces, materials)
        return VoxelGrid(self._context.voxelize(m.positions, m.triangles, m.materials, s, m.name))

    def voxelize_file(
        self,
        path: PathLike,
        *,
        res: Optional[int] = None,
        dims: Optional[Sequence[int]] = None,
        bounds: Optional[Sequence[float]] = None,
        method: str = "hybrid",
        mode: Optional[str] = None,
        slicing: Optional[str] = None,
        channels: ChannelsArg = "occ",
        solid: Optional[str] = None,
        layout: str = "auto",
        memory_budget: MemoryBudget = None,
    ) -> VoxelGrid:
        """Reads a mesh or scene file and voxelizes it as ``voxr voxelize FILE`` does; see
        ``voxr.voxelize_file``."""
        s = settings(
            res=res, dims=dims, bounds=bounds, method=method, mode=mode, slicing=slicing, channels=channels, solid=solid,
            layout=layout, memory_budget=memory_budget,
        )
        return VoxelGrid(self._context.voxelize_file(os.fspath(path), s))

    def __repr__(self) -> str:
        d = self.device
        return f"voxr.Context(device={d.get('id')!r}, name={d.get('name')!r})"


_contexts: Dict[str, Context] = {}
_contexts_lock = threading.Lock()


def shared_context(device: Union[str, int, None] = None) -> Context:
    """The process's Context for `device`, opened on first use (thread-safe)."""
    key = device_text(device)
    with _contexts_lock:
        context = _contexts.get(key)
        if context is None:
            context = Context(key)
            _contexts[key] = context
        return context


def voxelize(
    mesh: Any,
    faces: Any = None,
    *,
    res: Optional[int] = None,
    dims: Optional[Sequence[int]] = None,
    bounds: Optional[Sequence[float]] = None,
    method: str = "hybrid",
    mode: Optional[str] = None,
    slicing: Optional[str] = None,
    channels: ChannelsArg = "occ",
    solid: Optional[str] = None,
    layout: str = "auto",
    memory_budget: MemoryBudget = None,
    device: Union[str, int, None] = None,
    materials: Any = None,
) -> VoxelGrid:
    """Voxelizes a triangle mesh as ``voxr voxelize`` does (same settings, same voxels, bit for bit).

    mesh: a (V, 3) vertex array-like with ``faces`` (F, 3) vertex indices, a ``trimesh.Trimesh`` or an
      ``open3d.geometry.TriangleMesh``. float64 vertices and uint32 faces (C-contiguous) are read in place;
      other float/int dtypes are converted (a copy).
    res: voxels along the bounds' longest side (``--res``; None: 256, or a scene file's own grid);
    dims: exact (nx, ny, nz) instead of res;
    bounds: (x0, y0, z0, x1, y1, z1) world box used exactly (default: fitted with a quarter-voxel margin).
    method: 'hybrid', 'slice', 'grid' or 'slicemap'; mode: 'conservative' (None: the default) or 'center';
    slicing: slicemap only, 'uniform' (None: the default) or 'local';
    channels: 'occ,count,normal,material,color' or a sequence of those names;
    solid: None, 'parity', 'xor', 'late' or 'flood' (adds the 'inside' channel);
    layout: 'auto', 'dense' or 'sparse'; memory_budget: device bytes of a sparse run (int, or '512M', '4G');
    device: as ``voxr.Context``; materials: (F,) material id per triangle (the 'material' channel).

    The GIL is released while the device works. Raises voxr.Error (voxr's one-line message) for what voxr
    refuses, TypeError/ValueError for arguments of the wrong type or shape.
    """
    return shared_context(device).voxelize(
        mesh, faces, res=res, dims=dims, bounds=bounds, method=method, mode=mode, slicing=slicing, channels=channels,
        solid=solid, layout=layout, memory_budget=memory_budget, materials=materials,
    )


def voxelize_file(
    path: PathLike,
    *,
    res: Optional[int] = None,
    dims: Optional[Sequence[int]] = None,
    bounds: Optional[Sequence[float]] = None,
    method: str = "hybrid",
    mode: Optional[str] = None,
    slicing: Optional[str] = None,
    channels: ChannelsArg = "occ",
    solid: Optional[str] = None,
    layout: str = "auto",
    memory_budget: MemoryBudget = None,
    device: Union[str, int, None] = None,
) -> VoxelGrid:
    """Reads a mesh (.obj, .off, .ply, .stl, .gltf/.glb, ...) or scene (.json) file and voxelizes it as
    ``voxr voxelize FILE`` does; the keywords are voxelize()'s. Raises voxr.Error naming the file when it
    cannot be read."""
    return shared_context(device).voxelize_file(
        path, res=res, dims=dims, bounds=bounds, method=method, mode=mode, slicing=slicing, channels=channels, solid=solid,
        layout=layout, memory_budget=memory_budget,
    )
