"""A progress bar for calls over many meshes: tqdm when it is installed, else one line per 10 % on stderr.

tqdm is optional (never a dependency of voxr). Both bars count meshes; both write to stderr only, so the
manifest and anything a caller prints on stdout stay clean.
"""

from __future__ import annotations

import sys
import time
from typing import Optional, TextIO


class Progress:
    """Counts `total` items; `update(n)` after each finishes; `close()` (or a `with` block) at the end.

    enabled=False makes every call a no-op. use_tqdm=None picks tqdm when importable; False forces the
    plain fallback (one line per 10 %: "voxr: 20/200 meshes (10%), 3 errors, 4.1 s").
    """

    def __init__(
        self,
        total: int,
        desc: str = "voxr",
        enabled: bool = True,
        use_tqdm: Optional[bool] = None,
        stream: Optional[TextIO] = None,
    ) -> None:
        self.total = int(total)
        self.desc = desc
        self.enabled = bool(enabled) and self.total > 0
        self.done = 0
        self.errors = 0
        self._stream = stream if stream is not None else sys.stderr
        self._start = time.perf_counter()
        self._next_tenth = 1
        self._tqdm = None
        if not self.enabled:
            return
        if use_tqdm is None or use_tqdm:
            try:
                from tqdm.auto import tqdm  # optional
            except ImportError:
                if use_tqdm:
                    raise
            else:
                self._tqdm = tqdm(total=self.total, desc=desc, unit="mesh", file=self._stream)

    def update(self, n: int = 1, errors: int = 0) -> None:
        """Marks n more items done, `errors` of them failed."""
        self.done += n
        self.errors += errors
        if not self.enabled:
            return
        if self._tqdm is not None:
            self._tqdm.update(n)
            if self.errors:
                self._tqdm.set_postfix(errors=self.errors, refresh=False)
            return
        # Plain fallback: a line each time another tenth is passed (and at the end).
        tenth = (self.done * 10) // self.total
        if tenth >= self._next_tenth:
            self._next_tenth = tenth + 1
            seconds = time.perf_counter() - self._start
            errs = f", {self.errors} error{'s' if self.errors != 1 else ''}" if self.errors else ""
            print(
                f"{self.desc}: {self.done}/{self.total} meshes ({100 * self.done // self.total}%){errs}, {seconds:.1f} s",
                file=self._stream,
                flush=True,
            )

    def close(self) -> None:
        if self._tqdm is not None:
            self._tqdm.close()
            self._tqdm = None

    def __enter__(self) -> "Progress":
        return self

    def __exit__(self, *exc) -> None:
        self.close()
