"""voxr.dask.voxelize_files on a LocalCluster of 2 worker processes (1 thread each): the same files and
manifest as the single-process batch, the broken mesh reported, failures of whole tasks reported."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

voxr = pytest.importorskip("voxr", reason="the voxr package is not built/installed (pip install .)")
distributed = pytest.importorskip("distributed", reason="dask.distributed is not installed (pip install 'dask[distributed]')")

import meshgen  # noqa: E402
import voxr.dask  # noqa: E402
from voxr import batch  # noqa: E402

RES = 24


@pytest.fixture(scope="module")
def client():
    # Processes, as on a real cluster: each worker opens its own OpenCL context. No dashboard (port clashes
    # on CI), a fixed small memory limit so the nanny does not size itself from the machine.
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None, memory_limit="2GiB"
    ) as cluster, distributed.Client(cluster) as c:
        yield c


@pytest.fixture(scope="module")
def meshes(tmp_path_factory):
    return meshgen.small_dataset(tmp_path_factory.mktemp("meshes"))


def _strip(entry):
    """An entry without what differs between runs (times, the worker, the output folder)."""
    return {
        "input": entry["input"],
        "outputs": [Path(f).name for f in entry["outputs"]],
        "dims": entry["dims"],
        "voxels_set": entry["voxels_set"],
        "warnings": entry["warnings"],
        "error": entry["error"],
    }


def test_dask_equals_batch(client, meshes, tmp_path):
    one = batch.voxelize_files(meshes, tmp_path / "one", res=RES, channels="occ,count", progress=False)
    many = voxr.dask.voxelize_files(meshes, tmp_path / "dask", client, res=RES, channels="occ,count", progress=False)
    assert [_strip(e) for e in many] == [_strip(e) for e in one]
    assert json.loads((tmp_path / "dask" / "manifest.json").read_text()) == json.loads(json.dumps(many))
    broken = [e for e in many if e["error"] is not None]
    assert [Path(e["input"]).name for e in broken] == ["broken.off"]
    assert "broken.off" in broken[0]["error"]
    files = sorted(p.name for p in (tmp_path / "one").iterdir())
    assert files == sorted(p.name for p in (tmp_path / "dask").iterdir())
    assert len(files) == 2 * (len(meshes) - 1) + 1  # occupancy + count per good mesh, the manifest
    for name in files:
        if name != "manifest.json":
            assert (tmp_path / "dask" / name).read_bytes() == (tmp_path / "one" / name).read_bytes(), name
    workers = {e["worker"] for e in many if e["error"] is None}
    assert all(w and ":" in w for w in workers)


def test_default_client_and_chunks(client, meshes, tmp_path):
    # client=None takes the default client (the fixture's), chunk_size groups meshes per task.
    assert distributed.default_client() is client
    many = voxr.dask.voxelize_files(meshes, tmp_path, res=RES, chunk_size=4, progress=False)
    assert [e["input"] for e in many] == meshes
    assert sum(e["error"] is not None for e in many) == 1


def test_failed_tasks_are_reported_not_raised(client, meshes, tmp_path):
    # An exception that is not voxr.Error (here a keyword voxelize_file does not take) fails the task; each
    # of its meshes gets the exception in "error" and the call returns the whole manifest.
    many = voxr.dask.voxelize_files(meshes[:3], tmp_path, client, res=RES, no_such_option=1, progress=False)
    assert len(many) == 3
    assert all(e["error"] and e["error"].startswith("TypeError") for e in many), many
    # Colliding names fail before anything is submitted, as in the batch.
    with pytest.raises(voxr.Error, match="names="):
        voxr.dask.voxelize_files([meshes[0], meshes[0]], tmp_path, client, progress=False)
