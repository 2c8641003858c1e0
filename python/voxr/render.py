"""voxr.render: one ``voxr render`` run from Python, returning the image as a NumPy array.

The same settings give the same pixels as ``voxr render -o out.exr`` (both run the same C++ function,
voxr::render; docs/library.md). The image is linear RGBA float32, shape (height, width, 4), row 0 at the top;
the array owns the renderer's buffer (no copy) and the GIL is released while rendering.
"""

from __future__ import annotations

import json
import os
import warnings
from typing import Any, Optional, Sequence, Tuple, Union

import numpy as np

__all__ = ["render"]

# The keywords `more` takes: the other flags of `voxr render` (docs/cli.md), same names with '_' for '-'.
_MORE = (
    "shadow_res",
    "res",
    "mode",
    "bias",
    "normal_offset",
    "refraction_grid",
    "coarse_res",
    "step",
    "normals",
    "angle_threshold",
    "layers",
    "layer_res",
    "dm_depth",
    "frames",
    "error_target",
    "compare_reference",
)


def render(
    scene: Union[str, os.PathLike, None] = None,
    *,
    shadows: Optional[str] = None,
    refraction: Optional[str] = None,
    size: Optional[Sequence[int]] = (640, 480),
    device: Optional[str] = None,
    **more: Any,
) -> Tuple[np.ndarray, dict]:
    """Render a scene with transparent shadows and refraction, as ``voxr render`` does.

    Args:
        scene: a scene file (.json, docs/scene-format.md) or a mesh; None renders the built-in default scene.
        shadows: the shadow method (``voxel``, ``uniform``, ``filter``, ``opaque``, ``voxel-exact``,
            ``reference``, ``none``); None: ``voxel`` (``reference`` with a reference refraction).
        refraction: the refraction method (``--refraction``); None: ``voxel-exact``.
        size: (width, height) in pixels; None: the scene camera's.
        device: an OpenCL device, "P:D", "P" or a name substring; None: $VOXR_DEVICE or the default.
        **more: the other flags of ``voxr render`` by name: shadow_res, res, mode, bias, normal_offset,
            refraction_grid, coarse_res, step, normals, angle_threshold, layers, layer_res, dm_depth,
            frames, error_target, compare_reference (the report's ``compare_reference``; no error image
            is written).

    Returns:
        (image, report): a float32 array (height, width, 4) and the dict ``voxr render --report`` writes.
        The scene's warnings are issued as Python warnings (UserWarning).

    Raises:
        voxr.Error: voxr's one-line message for a scene that cannot be read, an unknown method, a setting out
            of range or one that does not apply to the method.
        TypeError: an unknown keyword.
    """
    from . import _render

    settings = _render.RenderSettings()
    if scene is not None:
        settings.scene = os.fspath(scene)
    if shadows is not None:
        settings.shadows = shadows
    if refraction is not None:
        settings.refraction = refraction
    if size is not None:
        width, height = (int(v) for v in size)
        if width <= 0 or height <= 0:
            raise ValueError(f"size {tuple(size)}: width and height must be positive")
        settings.width, settings.height = width, height
    if device is not None:
        settings.device = str(device)
    for name, value in more.items():
        if name not in _MORE:
            raise TypeError(f"render() got an unexpected keyword argument '{name}'")
        setattr(settings, name, value)
    image, report, scene_warnings = _render.render(settings)
    for w in scene_warnings:
        warnings.warn(f"voxr: {w}", UserWarning, stacklevel=2)
    return image, json.loads(report)
