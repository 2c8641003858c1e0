"""voxr: voxelize triangle meshes on an OpenCL device (GPU, or PoCL on the CPU) into NumPy arrays.

    import voxr
    grid = voxr.voxelize(vertices, faces, res=256, channels="occ,count,normal")
    grid.occupancy          # (nx, ny, nz) bool, indexed [x, y, z]
    grid.count, grid.normal # one row per set voxel, in grid.occupied_indices() order
    grid.save("out.vdb")

The same C++ library as the `voxr` CLI (libvoxr, include/voxr/voxr.h): same settings, same voxels.
Tutorial: docs/python.md.
"""

from __future__ import annotations

from typing import Any, List

from . import _core
from ._context import Context, voxelize, voxelize_file
from ._grid import VoxelGrid

Error = _core.Error
Error.__module__ = "voxr"
Error.__doc__ = "voxr's error (a RuntimeError): bad input or a request the device cannot do; str() is voxr's one line."

__version__: str = _core.version()

__all__ = [
    "Context",
    "Error",
    "VoxelGrid",
    "devices",
    "render",
    "voxelize",
    "voxelize_file",
    "voxelize_files",
    "__version__",
]


def devices() -> List[dict]:
    """Every OpenCL device of every platform, as dicts: id ('P:D', what ``device=`` takes), name,
    platform, type ('GPU', 'CPU', ...), driver_version, compute_units, global_memory, max_allocation (bytes).
    Raises voxr.Error when there is no OpenCL platform."""
    return list(_core.devices())


# voxr.render (python/voxr/render.py) imports only NumPy at module level (its extension on first call), so it is
# imported here: a lazy wrapper named `render` would be replaced by the submodule as soon as anything imports
# voxr.render (the import system sets the package attribute), and `voxr.render(...)` would then call a module.
try:
    from .render import render
except ModuleNotFoundError as _e:
    if _e.name != f"{__name__}.render":
        raise

    def render(*args: Any, **kwargs: Any) -> Any:  # type: ignore[misc]
        """Renders a scene (voxr.render); not part of this build."""
        raise Error("voxr.render: the render module is not part of this build")


def __getattr__(name: str) -> Any:
    # Lazily: voxelize_files (voxr.batch) and voxr.dask import tqdm/dask only when used.
    if name == "voxelize_files":
        try:
            from .batch import voxelize_files
        except ModuleNotFoundError as e:
            if e.name == f"{__name__}.batch":
                raise AttributeError("voxr.voxelize_files: voxr.batch is not part of this build") from None
            raise
        return voxelize_files
    if name == "dask":
        import importlib

        try:
            return importlib.import_module(".dask", __name__)
        except ModuleNotFoundError as e:
            if e.name == f"{__name__}.dask":
                raise AttributeError("voxr.dask is not part of this build") from None
            raise
    raise AttributeError(f"module 'voxr' has no attribute '{name}'")
