"""`python -m voxr ARGS`: runs voxr's CLI with ARGS (docs/cli.md), replacing this process (os.execv), so the
exit code, stdin, stdout and stderr are the CLI's own.

The executable: $VOXR_CLI when set (an explicit choice wins), else the one shipped in the package
(voxr/bin/voxr, installed by `pip install .`). Neither: one line on stderr and exit code 2.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path
from typing import List, Optional


def cli_path() -> Optional[str]:
    """The CLI executable python -m voxr runs, or None. Raises FileNotFoundError naming $VOXR_CLI when it
    is set but is not an executable file."""
    env = os.environ.get("VOXR_CLI")
    if env:
        if os.path.isfile(env) and os.access(env, os.X_OK):
            return os.path.abspath(env)
        raise FileNotFoundError(f"$VOXR_CLI='{env}' is not an executable file")
    bundled = Path(__file__).resolve().parent / "bin" / "voxr"
    if bundled.is_file() and os.access(bundled, os.X_OK):
        return os.fspath(bundled)
    return None


def main(argv: Optional[List[str]] = None) -> int:
    args = sys.argv[1:] if argv is None else list(argv)
    try:
        exe = cli_path()
    except FileNotFoundError as e:
        print(f"voxr: error: {e}", file=sys.stderr)
        return 2
    if exe is None:
        here = Path(__file__).resolve().parent / "bin" / "voxr"
        print(
            f"voxr: error: no voxr CLI: {here} is missing and $VOXR_CLI is not set "
            "(reinstall with `pip install .`, or set VOXR_CLI=/path/to/build/voxr)",
            file=sys.stderr,
        )
        return 2
    sys.stdout.flush()
    sys.stderr.flush()
    # argv[0] is the executable's path: voxr finds voxr-render beside itself (host/cli/main.cpp).
    os.execv(exe, [exe] + args)
    return 0  # not reached


if __name__ == "__main__":
    sys.exit(main())
