"""Many meshes over a dask.distributed cluster: one task per mesh (or per chunk), one Context per worker.

Needs the optional packages dask and distributed (`pip install "dask[distributed]"`); importing this module
without them raises ImportError naming them. Running on a real cluster: docs/cluster.md.
"""

from __future__ import annotations

import asyncio
import os
import socket
import threading
import uuid
from typing import Any, Dict, Iterable, List, Optional, Sequence

try:
    import distributed
except ImportError as e:  # pragma: no cover - depends on the environment
    raise ImportError(
        "voxr.dask needs dask.distributed: pip install 'dask[distributed]'"
    ) from e

from ._progress import Progress
from .batch import PathLike, empty_entry, plan_outputs, voxelize_one, write_manifest

# Worker-local state: a worker is a process with its own OpenCL context(s). One voxr.Context per device,
# created on the worker's first task; each has a lock, so a worker with several threads never runs two
# voxelizations on one Context at once (its threads then overlap only the saving, outside the lock).
_contexts: Dict[Optional[str], Any] = {}
_locks: Dict[Optional[str], threading.Lock] = {}
_contexts_lock = threading.Lock()


def _worker_context(device: Optional[str]):
    """This process's Context for device (None: $VOXR_DEVICE or voxr's default) and its lock."""
    import voxr

    with _contexts_lock:
        if device not in _contexts:
            _contexts[device] = voxr.Context(device)
            _locks[device] = threading.Lock()
        return _contexts[device], _locks[device]


def _where() -> str:
    return f"{socket.gethostname()}:{os.getpid()}"


def _run_chunk(items: List[List[str]], options: Dict[str, Any]) -> List[Dict[str, Any]]:
    """Runs on a worker: voxelizes [(input, output), ...] with the worker's Context; manifest entries."""
    device = options.get("device")
    rest = {k: v for k, v in options.items() if k != "device"}
    entries = []
    for path, output in items:
        try:
            ctx, lock = _worker_context(device)
        except _voxr_error() as e:  # no such device on this worker: each mesh says so
            entries.append(_failed_entry(path, str(e)))
            continue

        def locked_voxelize(p, **kw):
            with lock:
                return ctx.voxelize_file(p, **kw)

        entry = voxelize_one(locked_voxelize, path, output, rest)
        entry["worker"] = _where()
        entries.append(entry)
    return entries


def _voxr_error():
    import voxr

    return voxr.Error


def _failed_entry(path: str, message: str, worker: bool = True) -> Dict[str, Any]:
    entry = empty_entry(path)
    entry["error"] = message
    entry["worker"] = _where() if worker else None
    return entry


def voxelize_files(
    paths: Iterable[PathLike],
    out_dir: PathLike,
    client: Optional["distributed.Client"] = None,
    *,
    format: str = "nrrd",
    progress: bool = True,
    names: Optional[Sequence[str]] = None,
    chunk_size: Optional[int] = None,
    **options: Any,
) -> List[Dict[str, Any]]:
    """voxr.voxelize_files over a Dask cluster: the same outputs and manifest, plus "worker" (host:pid).

    client: a distributed.Client; None uses the current default client (the last Client made in this
    process), and when there is none starts a LocalCluster of os.cpu_count() worker processes with one
    thread each (and POCL_MAX_PTHREAD_COUNT=1 unless set), closed before returning. out_dir must be
    reachable by every worker at the same path (a shared filesystem on a real cluster), as must the inputs.
    chunk_size: meshes per task; None: about 8 tasks per worker thread, at most 16 meshes a task (a task
    costs the cluster ~5-8 ms of CPU, as much as a small mesh: bench/results/issue22-dask-2core.md); 1: one
    task per mesh. options: voxr.voxelize_file's keywords, with device= naming the device on every worker
    (default: each worker's $VOXR_DEVICE, else its first GPU, else its first CPU).

    Each worker voxelizes with one Context per device, created on its first task and kept for the worker's
    life. Errors per mesh as in voxr.voxelize_files: voxr's message in "error"; a task that fails another way
    (a worker that died twice on it: KilledWorker, an exception) puts "<ExceptionType>: <message>" in the
    error of each of its meshes; the call still returns the whole manifest. Progress: as tasks complete
    (distributed.as_completed).
    """
    plan = plan_outputs(paths, out_dir, format, names)
    os.makedirs(out_dir, exist_ok=True)
    if chunk_size is not None and chunk_size < 1:
        raise ValueError("chunk_size must be >= 1")

    token = uuid.uuid4().hex  # task keys unique to this call
    own_cluster = None
    if client is None:
        try:
            client = distributed.default_client()
        except ValueError:
            # One PoCL thread per worker unless the caller chose (a CPU device: n workers x all cores
            # each oversubscribe the machine; no effect on GPUs).
            env = {} if "POCL_MAX_PTHREAD_COUNT" in os.environ else {"POCL_MAX_PTHREAD_COUNT": "1"}
            own_cluster = distributed.LocalCluster(
                n_workers=os.cpu_count() or 1, threads_per_worker=1, processes=True, env=env
            )
            client = distributed.Client(own_cluster)
    try:
        if chunk_size is None:
            threads = sum(client.nthreads().values()) or 1
            chunk_size = max(1, min(16, len(plan) // (8 * threads)))
        chunks = [plan[i : i + chunk_size] for i in range(0, len(plan), chunk_size)]
        futures = client.map(
            _run_chunk,
            [[list(pair) for pair in c] for c in chunks],
            options=dict(options),
            pure=False,
            key=[f"voxr-{token}-{i}" for i in range(len(chunks))],
        )
        index = {f.key: i for i, f in enumerate(futures)}
        results: List[Optional[List[Dict[str, Any]]]] = [None] * len(chunks)
        with Progress(len(plan), desc="voxr.dask", enabled=progress) as bar:
            for future in distributed.as_completed(futures):
                i = index[future.key]
                try:
                    entries = future.result()
                except (Exception, asyncio.CancelledError) as exc:  # raised on the worker, or lost there
                    message = f"{type(exc).__name__}: {exc}".splitlines()[0]
                    entries = [_failed_entry(p, message, worker=False) for p, _ in chunks[i]]
                results[i] = entries
                bar.update(len(entries), errors=sum(e["error"] is not None for e in entries))
                future.release()
    finally:
        if own_cluster is not None:
            client.close()
            own_cluster.close()
    manifest = [e for entries in results for e in entries]  # type: ignore[union-attr]
    write_manifest(out_dir, manifest)
    return manifest
