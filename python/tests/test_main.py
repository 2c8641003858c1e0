"""`python -m voxr ARGS` runs voxr's CLI (python/voxr/__main__.py): exit code and output are the CLI's."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

voxr = pytest.importorskip("voxr", reason="the voxr package is not built/installed (pip install .)")

import meshgen  # noqa: E402


def _cli():
    from voxr._cli import cli_path

    try:
        return cli_path()
    except voxr.Error as e:
        pytest.skip(str(e))


def _run(args, env=None):
    return subprocess.run([sys.executable, "-m", "voxr", *args], capture_output=True, text=True, env=env, timeout=120)


def test_help():
    exe = _cli()
    r = _run(["--help"])
    direct = subprocess.run([exe, "--help"], capture_output=True, text=True)
    assert r.returncode == 0 == direct.returncode
    assert r.stdout == direct.stdout and "voxelize" in r.stdout


def test_voxelize_small_mesh(tmp_path):
    _cli()
    mesh = meshgen.write_ply(tmp_path / "cube.ply", *meshgen.cube())
    out = tmp_path / "cube.nrrd"
    r = _run(["voxelize", str(mesh), "--res", "16", "-o", str(out), "-q"])
    assert r.returncode == 0, r.stderr
    assert out.is_file()
    # The same grid as the Python call.
    grid = voxr.voxelize_file(str(mesh), res=16)
    assert Path(grid.save(str(tmp_path / "py.nrrd"))[0]).read_bytes() == out.read_bytes()


def test_exit_code_and_stderr_are_the_clis(tmp_path):
    exe = _cli()
    missing = str(tmp_path / "missing.obj")
    r = _run(["voxelize", missing])
    direct = subprocess.run([exe, "voxelize", missing], capture_output=True, text=True)
    assert r.returncode == direct.returncode != 0
    assert r.stderr == direct.stderr and "missing.obj" in r.stderr


def test_no_cli_is_one_clear_line(tmp_path):
    env = dict(os.environ, VOXR_CLI=str(tmp_path / "nowhere" / "voxr"))
    r = _run(["--help"], env=env)
    assert r.returncode == 2
    assert r.stderr.count("\n") == 1 and r.stderr.startswith("voxr: error: ")
    assert "VOXR_CLI" in r.stderr and "nowhere" in r.stderr
