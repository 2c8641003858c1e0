"""Keyword arguments of voxelize() -> voxr::VoxelizeSettings, with Python-side checks of types and shapes.

The values themselves (method names, resolution range, ...) are checked by voxr, whose one-line message
arrives as voxr.Error; here only what cannot reach C++ meaningfully (wrong types, negative numbers, wrong
lengths) is refused, as TypeError or ValueError with one line naming the argument.
"""

from __future__ import annotations

import math
import numbers
from typing import Iterable, Optional, Sequence, Union

from . import _core

ChannelsArg = Union[str, Iterable[str]]
MemoryBudget = Union[int, str, None]

_UINT32_MAX = 0xFFFFFFFF


def _whole(name: str, value: object, low: int = 1, high: int = _UINT32_MAX) -> int:
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise TypeError(f"{name}: expected a whole number, got {type(value).__name__} {value!r}")
    v = int(value)
    if v < low or v > high:
        raise ValueError(f"{name}: {v} is out of range {low}..{high}")
    return v


def _text(name: str, value: object) -> str:
    if not isinstance(value, str):
        raise TypeError(f"{name}: expected a string, got {type(value).__name__} {value!r}")
    return value


def channels_text(channels: ChannelsArg) -> str:
    """'occ,count' from 'occ,count' or ('occ', 'count')."""
    if isinstance(channels, str):
        return channels
    try:
        names = list(channels)
    except TypeError:
        raise TypeError(
            f"channels: expected a string such as 'occ,count' or a sequence of names, got {channels!r}"
        ) from None
    for n in names:
        _text("channels", n)
    return ",".join(names)


def memory_budget_text(budget: MemoryBudget) -> str:
    """The text `voxr voxelize --memory-budget` reads: bytes from an int, or a size such as '512M' or '2G'
    (K, M, G, T: powers of 1024) passed to voxr as is (voxr checks it); None gives '' (voxr's default: from
    the device)."""
    if budget is None:
        return ""
    if isinstance(budget, str):
        return budget
    return str(_whole("memory_budget", budget, 1, 10**18))


def device_text(device: Union[str, int, None]) -> str:
    """'' (voxr's default: $VOXR_DEVICE or the first GPU) for None; 'P:D', 'P' or a name substring."""
    if device is None:
        return ""
    if isinstance(device, numbers.Integral) and not isinstance(device, bool):
        return str(int(device))
    return _text("device", device)


def settings(
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
) -> _core.Settings:
    """A checked voxr::VoxelizeSettings."""
    s = _core.Settings()
    s.resolution = 0 if res is None else _whole("res", res)
    if dims is not None:
        if isinstance(dims, (str, bytes)) or len(dims) != 3:
            raise ValueError(f"dims: expected 3 whole numbers (nx, ny, nz), got {dims!r}")
        s.dims = tuple(_whole("dims", d) for d in dims)
    if bounds is not None:
        if isinstance(bounds, (str, bytes)) or len(bounds) != 6:
            raise ValueError(f"bounds: expected 6 numbers (x0, y0, z0, x1, y1, z1), got {bounds!r}")
        b = []
        for v in bounds:
            if not isinstance(v, numbers.Real) or isinstance(v, bool):
                raise TypeError(f"bounds: expected numbers, got {type(v).__name__} {v!r}")
            if not math.isfinite(float(v)):
                raise ValueError(f"bounds: {v!r} is not finite")
            b.append(float(v))
        s.bounds = tuple(b)
    s.method = _text("method", method)
    s.mode = "" if mode is None else _text("mode", mode)
    s.slicing = "" if slicing is None else _text("slicing", slicing)
    s.channels = channels_text(channels)
    s.solid = "" if solid is None else _text("solid", solid)
    s.layout = _text("layout", layout)
    s.memory_budget = memory_budget_text(memory_budget)
    s.device = device_text(device)
    return s
