"""`python -m voxr ARGS`: runs voxr's CLI with ARGS (docs/cli.md), replacing this process (os.execv), so the
exit code, stdin, stdout and stderr are the CLI's own.

The executable is voxr._cli.cli_path()'s: $VOXR_CLI when set, else the one installed in the package
(voxr/bin/voxr, by `pip install .`). Neither: one line on stderr ("voxr: error: ...") and exit code 2.
"""

from __future__ import annotations

import os
import sys
from typing import List, Optional


def main(argv: Optional[List[str]] = None) -> int:
    """Execs the CLI with argv (default sys.argv[1:]); returns 2 only when there is no CLI to run."""
    from . import Error
    from ._cli import cli_path

    args = sys.argv[1:] if argv is None else list(argv)
    try:
        exe = os.path.abspath(cli_path())
    except Error as e:
        print(f"voxr: error: {e}", file=sys.stderr)
        return 2
    sys.stdout.flush()
    sys.stderr.flush()
    # argv[0] is the executable's path, as a shell would give it.
    os.execv(exe, [exe] + args)
    return 0  # not reached


if __name__ == "__main__":
    sys.exit(main())
