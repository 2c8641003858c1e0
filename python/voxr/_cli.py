"""Where the `voxr` CLI executable is: $VOXR_CLI, else voxr/bin/voxr installed with the package."""

from __future__ import annotations

import os
from pathlib import Path

from ._core import Error


def cli_path() -> str:
    """Path of the `voxr` executable (voxr-render and the OpenVDB plugin lie beside it).

    Raises voxr.Error when neither $VOXR_CLI nor the package's bin/voxr exists."""
    env = os.environ.get("VOXR_CLI")
    if env:
        if not Path(env).is_file():
            raise Error(f"$VOXR_CLI '{env}': no such file")
        return env
    path = Path(__file__).resolve().parent / "bin" / "voxr"
    if not path.is_file():
        raise Error(f"{path}: the voxr CLI is not installed with this package (set $VOXR_CLI)")
    return str(path)
