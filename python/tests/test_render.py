"""voxr.render against the CLI: the same pixels as `voxr render -o out.exr`, bit for bit, and its errors.

The CLI is found as $VOXR_CLI, voxr/bin/voxr inside the installed package, build/voxr in the repository or
`voxr` on PATH; the tests that need it are skipped (with the reason) when none is there.
"""

from __future__ import annotations

import os
import shutil
import struct
import subprocess
import zlib
from pathlib import Path

import numpy as np
import pytest

import voxr

REPO = Path(__file__).resolve().parents[2]
SIZE = (40, 30)


def _cli() -> Path | None:
    candidates = [os.environ.get("VOXR_CLI"), Path(voxr.__file__).parent / "bin" / "voxr", REPO / "build" / "voxr"]
    which = shutil.which("voxr")
    candidates.append(which)
    for c in candidates:
        if c and Path(c).is_file() and os.access(c, os.X_OK):
            return Path(c)
    return None


def _read_exr(path: Path) -> np.ndarray:
    """A scanline float EXR as voxr writes it (no, ZIPS or ZIP compression) -> (H, W, 4) float32 RGBA."""
    data = path.read_bytes()
    assert data[:4] == b"\x76\x2f\x31\x01", "not an OpenEXR file"
    pos, header = 8, {}
    while data[pos] != 0:
        end = data.index(b"\0", pos)
        name = data[pos:end].decode()
        tend = data.index(b"\0", end + 1)
        (size,) = struct.unpack_from("<i", data, tend + 1)
        header[name] = data[tend + 5 : tend + 5 + size]
        pos = tend + 5 + size
    pos += 1
    x0, y0, x1, y1 = struct.unpack("<4i", header["dataWindow"])
    width, height = x1 - x0 + 1, y1 - y0 + 1
    compression = header["compression"][0]
    lines_per_block = {0: 1, 2: 1, 3: 16}[compression]
    channels, c = [], header["channels"]
    while c[0] != 0:
        end = c.index(b"\0")
        (ptype,) = struct.unpack_from("<i", c, end + 1)
        assert ptype == 2, "float channels expected"
        channels.append(c[:end].decode())
        c = c[end + 17 :]
    blocks = (height + lines_per_block - 1) // lines_per_block
    offsets = struct.unpack_from(f"<{blocks}Q", data, pos)
    planes = {name: np.zeros((height, width), np.float32) for name in channels}
    for offset in offsets:
        y, size = struct.unpack_from("<ii", data, offset)
        raw = data[offset + 8 : offset + 8 + size]
        lines = min(lines_per_block, y1 + 1 - y)
        expected = lines * width * 4 * len(channels)
        if compression != 0 and size < expected:
            t = np.frombuffer(zlib.decompress(raw), np.uint8).astype(np.int64)
            t = ((np.cumsum(t - 128) + 128) % 256).astype(np.uint8)  # undo the predictor (t[0] is kept)
            half = (len(t) + 1) // 2
            out = np.empty_like(t)
            out[0::2], out[1::2] = t[:half], t[half:]
            raw = out.tobytes()
        values = np.frombuffer(raw, "<f4").reshape(lines, len(channels), width)
        for i, name in enumerate(channels):
            planes[name][y - y0 : y - y0 + lines] = values[:, i]
    return np.stack([planes[n] for n in "RGBA"], axis=-1)


def test_default_scene_equals_the_cli_exr(tmp_path):
    cli = _cli()
    if cli is None:
        pytest.skip("no voxr CLI found ($VOXR_CLI, voxr/bin/voxr, build/voxr, PATH)")
    out = tmp_path / "cli.exr"
    env = dict(os.environ)
    env.setdefault("POCL_CACHE_DIR", str(REPO / "build" / "pocl-cache"))
    subprocess.run(
        [str(cli), "render", "--size", f"{SIZE[0]}x{SIZE[1]}", "-q", "-o", str(out)], check=True, env=env
    )
    image, report = voxr.render(size=SIZE)
    assert image.dtype == np.float32 and image.shape == (SIZE[1], SIZE[0], 4)
    assert image.flags["C_CONTIGUOUS"] and image.base is not None  # a view of the C++ buffer
    expected = _read_exr(out)
    assert np.array_equal(image.view(np.uint32), expected.view(np.uint32))
    assert report["size"] == list(SIZE)
    assert report["input"] == "default scene"
    assert report["shadows"] == "voxel"


def test_methods_and_more_reach_the_renderer():
    image, report = voxr.render(size=(16, 12), shadows="opaque", refraction="none", shadow_res=64)
    assert image.shape == (12, 16, 4)
    assert report["shadows"] == "opaque" and report["refraction"] == "none"
    assert np.isfinite(image).all()


def test_bad_scene_path_raises_voxr_error(tmp_path):
    missing = tmp_path / "missing.json"
    with pytest.raises(voxr.Error) as e:
        voxr.render(missing, size=(8, 8))
    assert str(e.value) == f"{missing}: no such file"
    assert isinstance(e.value, RuntimeError)


def test_bad_method_raises_voxr_error():
    with pytest.raises(voxr.Error, match="sideways"):
        voxr.render(shadows="sideways", size=(8, 8))
    with pytest.raises(voxr.Error, match="--layers applies to --refraction distance-maps only"):
        voxr.render(size=(8, 8), layers=8)


def test_unknown_keyword_is_a_type_error():
    with pytest.raises(TypeError, match="colour"):
        voxr.render(size=(8, 8), colour="red")
