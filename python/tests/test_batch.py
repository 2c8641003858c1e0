"""voxr.voxelize_files (python/voxr/batch.py): one process, one Context, a manifest; the progress bar."""

from __future__ import annotations

import io
import json
import os
from pathlib import Path

import pytest

voxr = pytest.importorskip("voxr", reason="the voxr package is not built/installed (pip install .)")

import meshgen  # noqa: E402  (python/tests/meshgen.py)
from voxr import batch  # noqa: E402
from voxr._progress import Progress  # noqa: E402

RES = 24


@pytest.fixture(scope="module")
def meshes(tmp_path_factory):
    return meshgen.small_dataset(tmp_path_factory.mktemp("meshes"))


def test_outputs_and_manifest(meshes, tmp_path):
    out = tmp_path / "out"
    manifest = batch.voxelize_files(meshes, out, res=RES, progress=False)
    assert [e["input"] for e in manifest] == meshes  # input order
    assert json.loads((out / "manifest.json").read_text()) == json.loads(json.dumps(manifest))
    for path, entry in zip(meshes, manifest):
        if Path(path).name == "broken.off":
            # One bad mesh is reported, with voxr's one-line message naming the file, and does not stop the batch.
            assert entry["error"] and "broken.off" in entry["error"] and "\n" not in entry["error"]
            assert entry["outputs"] == [] and entry["dims"] is None
            assert not (out / "broken.nrrd").exists()
            continue
        assert entry["error"] is None, entry["error"]
        expected = out / (Path(path).stem + ".nrrd")
        assert entry["outputs"][0] == str(expected) and expected.is_file()
        # The same as voxelizing the file alone and saving it: dims, count and the file, byte for byte.
        grid = voxr.voxelize_file(path, res=RES)
        assert entry["dims"] == list(grid.dims) and entry["voxels_set"] == grid.voxels_set > 0
        alone = grid.save(str(tmp_path / ("alone-" + expected.name)))
        assert Path(alone[0]).read_bytes() == expected.read_bytes()
        assert entry["ms"]["voxelize"] > 0 and entry["ms"]["save"] >= 0


def test_channels_and_format_options(meshes, tmp_path):
    good = [p for p in meshes if "broken" not in p][:2]
    manifest = batch.voxelize_files(good, tmp_path, format="vti", channels="occ,count", res=RES, progress=False)
    for entry in manifest:
        assert entry["error"] is None and entry["outputs"][0].endswith(".vti")
    manifest = batch.voxelize_files(good, tmp_path, format=".nrrd", channels="occ,count", res=RES, progress=False)
    # .nrrd writes each channel beside the occupancy file: every file is listed.
    assert all(len(e["outputs"]) == 2 for e in manifest), manifest


def test_colliding_stems_fail_before_any_work(tmp_path):
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    a = str(meshgen.write_ply(tmp_path / "a" / "part.ply", *meshgen.cube()))
    b = str(meshgen.write_off(tmp_path / "b" / "Part.off", *meshgen.cube()))
    out = tmp_path / "out"
    with pytest.raises(voxr.Error, match=r"part\.ply.*Part\.off|Part\.off.*part\.ply") as info:
        batch.voxelize_files([a, b], out, res=RES, progress=False)
    assert "names=" in str(info.value)
    assert not out.exists()  # nothing done, not even the folder
    manifest = batch.voxelize_files([a, b], out, res=RES, names=["a", "b"], progress=False)
    assert [Path(e["outputs"][0]).name for e in manifest] == ["a.nrrd", "b.nrrd"]


def test_bad_arguments(meshes, tmp_path):
    with pytest.raises(voxr.Error, match="unknown format 'stl'"):
        batch.voxelize_files(meshes, tmp_path, format="stl")
    with pytest.raises(voxr.Error, match="2 names for"):
        batch.voxelize_files(meshes, tmp_path, names=["a", "b"])
    with pytest.raises(voxr.Error, match="not a file name"):
        batch.voxelize_files(meshes[:1], tmp_path, names=["../x"])
    assert batch.voxelize_files([], tmp_path / "empty", progress=False) == []
    assert json.loads((tmp_path / "empty" / "manifest.json").read_text()) == []


def test_top_level_name():
    # voxr.voxelize_files is this function (python/voxr/__init__.py re-exports it).
    if not hasattr(voxr, "voxelize_files"):
        pytest.skip("voxr/__init__.py does not re-export voxelize_files yet")
    assert voxr.voxelize_files is batch.voxelize_files


def test_progress_fallback_prints_each_tenth():
    stream = io.StringIO()
    with Progress(20, desc="voxr", use_tqdm=False, stream=stream) as bar:
        for i in range(20):
            bar.update(1, errors=(i == 4))
    lines = stream.getvalue().splitlines()
    assert len(lines) == 10, lines
    assert lines[0].startswith("voxr: 2/20 meshes (10%)")
    assert lines[-1].startswith("voxr: 20/20 meshes (100%), 1 error,")


def test_progress_fallback_few_items_and_disabled():
    stream = io.StringIO()
    bar = Progress(3, use_tqdm=False, stream=stream)
    for _ in range(3):
        bar.update()
    bar.close()
    assert [line.split(" meshes")[0] for line in stream.getvalue().splitlines()] == ["voxr: 1/3", "voxr: 2/3", "voxr: 3/3"]
    stream = io.StringIO()
    with Progress(5, enabled=False, stream=stream) as bar:
        bar.update(5)
    assert stream.getvalue() == ""


def test_progress_uses_tqdm_when_installed(meshes, tmp_path, capsys):
    pytest.importorskip("tqdm", reason="tqdm is not installed (the plain fallback is tested above)")
    batch.voxelize_files(meshes[:2], tmp_path, res=RES, progress=True)
    err = capsys.readouterr().err
    assert "2/2" in err and "mesh" in err
