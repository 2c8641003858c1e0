"""Meshes from NumPy arrays, trimesh.Trimesh and open3d.geometry.TriangleMesh -> the arrays voxr reads.

voxr reads (V, 3) float64 positions and (F, 3) uint32 vertex indices, C-contiguous, in place. Arrays already
in that form are passed without a copy; other float or integer dtypes are converted once (a copy). trimesh
and Open3D are never imported here: their meshes are recognised by their type's module.
"""

from __future__ import annotations

from typing import Any, NamedTuple, Optional

import numpy as np
from numpy.typing import NDArray

_UINT32_MAX = 0xFFFFFFFF


class MeshArrays(NamedTuple):
    positions: NDArray[np.float64]  # (V, 3), C-contiguous
    triangles: NDArray[np.uint32]  # (F, 3), C-contiguous
    materials: Optional[NDArray[np.uint32]]  # (F,) or None
    name: str


def _module_of(obj: object) -> str:
    return type(obj).__module__ or ""


def positions_array(vertices: Any, what: str = "vertices") -> NDArray[np.float64]:
    """(V, 3) float64 C-contiguous; no copy when `vertices` already is one."""
    a = np.asarray(vertices)
    if a.dtype.kind not in "fiu" or a.dtype == np.bool_:
        raise TypeError(f"{what}: expected a float array of shape (V, 3), got dtype {a.dtype}")
    if a.ndim != 2 or a.shape[1] != 3:
        raise ValueError(f"{what}: expected shape (V, 3), got {a.shape}")
    return np.ascontiguousarray(a, dtype=np.float64)


def index_array(values: Any, what: str, columns: Optional[int], vertex_count: Optional[int]) -> NDArray[np.uint32]:
    """uint32 C-contiguous of shape (F, columns) (or (F,) for columns None), checked to be >= 0, to fit uint32
    and, with vertex_count, to be < vertex_count; no copy when already uint32 C-contiguous."""
    a = np.asarray(values)
    if a.dtype.kind not in "iu":
        raise TypeError(f"{what}: expected an integer array, got dtype {a.dtype}")
    if columns is None:
        if a.ndim != 1:
            raise ValueError(f"{what}: expected shape (F,), got {a.shape}")
    elif a.ndim != 2 or a.shape[1] != columns:
        raise ValueError(f"{what}: expected shape (F, {columns}), got {a.shape}")
    if a.size:
        hi = int(a.max())
        if a.dtype.kind == "i":
            lo = int(a.min())
            if lo < 0:
                raise ValueError(f"{what}: index {lo} is negative")
        if hi > _UINT32_MAX:
            raise ValueError(f"{what}: index {hi} does not fit in 32 bits")
        if vertex_count is not None and hi >= vertex_count:
            raise ValueError(f"{what}: vertex index {hi} is out of range for {vertex_count} vertices")
    return np.ascontiguousarray(a, dtype=np.uint32)


def mesh_arrays(mesh: Any, faces: Any = None, materials: Any = None) -> MeshArrays:
    """The arrays voxr reads from `mesh` (and `faces`): a (V, 3) vertex array-like with (F, 3) faces, a
    trimesh.Trimesh (or a trimesh.Scene, concatenated), or an open3d.geometry.TriangleMesh."""
    name = "mesh"
    module = _module_of(mesh)
    if module.startswith("trimesh"):
        if faces is not None:
            raise TypeError("faces: not with a trimesh mesh (it has its own)")
        if not hasattr(mesh, "faces") and hasattr(mesh, "geometry"):  # a trimesh.Scene
            mesh = mesh.to_mesh() if hasattr(mesh, "to_mesh") else mesh.dump(concatenate=True)
        if not hasattr(mesh, "faces") or not hasattr(mesh, "vertices"):
            raise TypeError(f"mesh: a {type(mesh).__name__} is not a triangle mesh")
        name = str(getattr(mesh, "metadata", {}).get("file_name", "trimesh"))
        vertices, faces = mesh.vertices, mesh.faces
    elif module.startswith("open3d"):
        if faces is not None:
            raise TypeError("faces: not with an Open3D mesh (it has its own)")
        if not hasattr(mesh, "triangles") or not hasattr(mesh, "vertices"):
            raise TypeError(
                f"mesh: a {type(mesh).__name__} is not an open3d.geometry.TriangleMesh "
                "(tensor meshes: use .to_legacy())"
            )
        name = "open3d"
        vertices, faces = np.asarray(mesh.vertices), np.asarray(mesh.triangles)
    else:
        if faces is None:
            raise TypeError("faces: required with a vertex array (voxelize(vertices, faces))")
        vertices = mesh
    positions = positions_array(vertices)
    triangles = index_array(faces, "faces", 3, positions.shape[0])
    mats = None
    if materials is not None:
        mats = index_array(materials, "materials", None, None)
        if mats.shape[0] != triangles.shape[0]:
            raise ValueError(
                f"materials: expected one id per triangle ({triangles.shape[0]}), got {mats.shape[0]}"
            )
    return MeshArrays(positions, triangles, mats, name)
