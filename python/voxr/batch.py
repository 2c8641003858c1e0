"""Many meshes in one process: voxelize each file, save it as out_dir/<stem>.<format>, return a manifest.

The Dask version (voxr.dask.voxelize_files) shares the planning, the per-mesh step and the manifest here, so
both write the same files and the same manifest entries. See docs/python.md and docs/cluster.md.
"""

from __future__ import annotations

import json
import os
import time
from pathlib import Path
from typing import Any, Callable, Dict, Iterable, List, Optional, Sequence, Tuple, Union

from ._progress import Progress

PathLike = Union[str, "os.PathLike[str]"]

# Volume formats voxr writes (docs/cli.md "Output"), by extension.
FORMATS = ("nrrd", "vti", "binvox", "vox", "vdb", "npz")

MANIFEST_NAME = "manifest.json"


def _error_type():
    import voxr  # at call time: voxr/__init__.py may import this module

    return voxr.Error


def plan_outputs(
    paths: Iterable[PathLike],
    out_dir: PathLike,
    format: str = "nrrd",
    names: Optional[Sequence[str]] = None,
) -> List[Tuple[str, str]]:
    """(input, output) pairs: output = out_dir/<name>.<format>, name = names[i] or the input's stem.

    Raises voxr.Error before any work on an unknown format, a names list of another length, or two inputs
    whose output names collide (compared case-insensitively, as some filesystems do), naming both inputs:
    a dataset whose files share a stem (ShapeNet's model_normalized.obj) passes names=.
    """
    error = _error_type()
    fmt = str(format).lower().lstrip(".")
    if fmt not in FORMATS:
        raise error(f"voxelize_files: unknown format '{format}': expected one of {', '.join(FORMATS)}")
    inputs = [os.fspath(p) for p in paths]
    if names is not None:
        names = [str(n) for n in names]
        if len(names) != len(inputs):
            raise error(f"voxelize_files: {len(names)} names for {len(inputs)} paths")
    out = Path(out_dir)
    plan: List[Tuple[str, str]] = []
    seen: Dict[str, str] = {}
    for i, path in enumerate(inputs):
        stem = names[i] if names is not None else Path(path).stem
        if not stem or "/" in stem or os.sep in stem or stem in (".", ".."):
            raise error(f"voxelize_files: '{path}': output name '{stem}' is not a file name")
        key = stem.casefold()
        if key in seen:
            raise error(
                f"voxelize_files: '{path}' and '{seen[key]}' would both write {stem}.{fmt} "
                "(pass names= with one output name per path)"
            )
        seen[key] = path
        plan.append((path, os.fspath(out / f"{stem}.{fmt}")))
    return plan


def empty_entry(path: str) -> Dict[str, Any]:
    """A manifest entry for `path` before (or without) its run: no outputs, no error yet."""
    return {
        "input": path,
        "outputs": [],
        "dims": None,
        "voxels_set": None,
        "ms": {"voxelize": None, "save": None},
        "warnings": [],
        "error": None,
    }


def voxelize_one(
    voxelize_file: Callable[..., Any], path: str, output: str, options: Dict[str, Any]
) -> Dict[str, Any]:
    """One manifest entry: voxelize_file(path, **options), save to output; voxr.Error and OSError become
    the entry's "error" (the mesh's one-line message) instead of raising, so one bad mesh does not stop a
    batch. Other exceptions (a wrong keyword, a bug) propagate."""
    error = _error_type()
    entry = empty_entry(path)
    t0 = time.perf_counter()
    try:
        grid = voxelize_file(path, **options)
        t1 = time.perf_counter()
        entry["ms"]["voxelize"] = (t1 - t0) * 1e3
        entry["dims"] = [int(d) for d in grid.dims]
        entry["voxels_set"] = int(grid.voxels_set)
        entry["warnings"] = [str(w) for w in grid.warnings]
        entry["outputs"] = [os.fspath(f) for f in grid.save(output)]
        entry["ms"]["save"] = (time.perf_counter() - t1) * 1e3
        report_ms = grid.report.get("ms") if isinstance(grid.report, dict) else None
        if isinstance(report_ms, dict):
            # voxr's own split (load, upload, kernels, readback, wall: docs/cli.md "Report").
            entry["ms"]["report"] = {k: v for k, v in report_ms.items() if isinstance(v, (int, float))}
    except (error, OSError) as e:
        entry["error"] = str(e)
    return entry


def write_manifest(out_dir: PathLike, manifest: List[Dict[str, Any]]) -> str:
    """Writes out_dir/manifest.json (a JSON list, one entry per input in input order) atomically."""
    path = Path(out_dir) / MANIFEST_NAME
    tmp = path.with_name(f".{MANIFEST_NAME}.{os.getpid()}.tmp")
    with open(tmp, "w", encoding="utf-8") as f:
        json.dump(manifest, f, indent=1)
        f.write("\n")
    os.replace(tmp, path)
    return os.fspath(path)


def voxelize_files(
    paths: Iterable[PathLike],
    out_dir: PathLike,
    *,
    format: str = "nrrd",
    progress: bool = True,
    device: Optional[str] = None,
    names: Optional[Sequence[str]] = None,
    **options: Any,
) -> List[Dict[str, Any]]:
    """Voxelizes each mesh file and saves it as out_dir/<stem>.<format>, in this process, on one device.

    paths: mesh files (any format voxr reads). out_dir: created if missing. format: nrrd, vti, binvox, vox,
    vdb or npz. progress: a bar on stderr (tqdm when installed, else a line per 10 %). device: as in
    voxr.voxelize (default $VOXR_DEVICE, else the first GPU, else the first CPU). names: output names, one per
    path, instead of the stems. options: voxr.voxelize_file's keywords (res, dims, mode, channels, solid, ...),
    the same for every mesh.

    Every mesh goes through voxr.voxelize_file, i.e. the process's one Context for the device. Returns the
    manifest, also written to out_dir/manifest.json: one dict per input, in input order —
      input (str), outputs (files written, list[str]), dims ([x, y, z]), voxels_set (int),
      ms ({"voxelize": load + voxelize, "save": writing, "report": voxr's own split}), warnings (list[str]),
      error (None, or voxr's one-line message: the mesh is skipped and the batch goes on).
    Raises voxr.Error before any work when two inputs would write the same file (see plan_outputs) or the
    format is unknown.
    """
    import voxr

    plan = plan_outputs(paths, out_dir, format, names)
    os.makedirs(out_dir, exist_ok=True)
    if device is not None:
        options = dict(options, device=device)
    manifest: List[Dict[str, Any]] = []
    with Progress(len(plan), desc="voxr", enabled=progress) as bar:
        for path, output in plan:
            entry = voxelize_one(voxr.voxelize_file, path, output, options)
            manifest.append(entry)
            bar.update(1, errors=entry["error"] is not None)
    write_manifest(out_dir, manifest)
    return manifest
