"""A progress line for sweeps: cases done, failed, left and the estimated time left; redrawn in place on a terminal,
a plain line now and then otherwise (so a log file is not flooded)."""

from __future__ import annotations

import sys
import time
from typing import TextIO

LOG_INTERVAL_S: float = 30.0
"""Least time between two progress lines when the stream is not a terminal [s] (the last case always prints)."""


class Progress:
    """Counts of a sweep's cases, printed as ``[#####.....] 12/40 done, 1 failed, ETA 3m20s``.

    Parameters
    ----------
    total : int
        Cases to run in this call (skipped cases not counted).
    stream : text stream, optional
        Default: standard error. None prints nothing.
    """

    def __init__(self, total: int, stream: TextIO | None = sys.stderr, width: int = 30) -> None:
        self.total = total
        self.done = 0
        self.failed = 0
        self.stream = stream
        self.width = width
        self.start = time.perf_counter()
        self._last = -float("inf")
        self._tty = bool(stream is not None and getattr(stream, "isatty", lambda: False)())

    def update(self, ok: bool) -> None:
        """One more case finished (``ok``) or failed."""
        self.done += ok
        self.failed += not ok
        self._show()

    @property
    def eta_s(self) -> float | None:
        """Estimated time left [s] from the mean time per finished case so far (None before the first)."""
        finished = self.done + self.failed
        if finished == 0:
            return None
        return (time.perf_counter() - self.start) / finished * (self.total - finished)

    def line(self) -> str:
        """The progress text."""
        finished = self.done + self.failed
        filled = int(self.width * finished / self.total) if self.total else self.width
        from ..sim import format_seconds  # the runs' own; lazy: the simulator need not load to count cases

        eta = self.eta_s
        eta_text = "--" if eta is None else format_seconds(eta)
        return (
            f"[{'#' * filled}{'.' * (self.width - filled)}] {finished}/{self.total} cases: {self.done} done, "
            f"{self.failed} failed, ETA {eta_text}"
        )

    def _show(self) -> None:
        if self.stream is None:
            return
        now = time.perf_counter()
        last = self.done + self.failed == self.total
        if self._tty:
            self.stream.write("\r" + self.line() + ("\n" if last else ""))
        elif last or now - self._last >= LOG_INTERVAL_S:
            self.stream.write(self.line() + "\n")
            self._last = now
        self.stream.flush()
