"""The progress report of a run on standard error: a bar with the rate and the time left on a terminal; on a
file or pipe (a log), a plain line at each tenth of the run instead of a bar redrawn every chunk."""

from __future__ import annotations

import sys
import time
from typing import TextIO

#: Lines written when the stream is not a terminal: one per this share of the run.
LOG_SHARE = 0.1


def format_seconds(seconds: float) -> str:
    """``seconds`` as "1h02m", "3m05s" or "12s"."""
    s = round(seconds)
    if s >= 3600:
        return f"{s // 3600}h{s % 3600 // 60:02d}m"
    if s >= 60:
        return f"{s // 60}m{s % 60:02d}s"
    return f"{s}s"


class Progress:
    """Report ``done`` of ``total`` steps with :meth:`update` (nothing when not ``enabled``).

    ``stream`` defaults to standard error; a stream that is not a terminal gets plain lines (one per LOG_SHARE of
    the run), a terminal a bar redrawn in place.
    """

    def __init__(self, total: int, enabled: bool, stream: TextIO | None = None) -> None:
        self.total = max(1, total)
        self.enabled = enabled
        self.stream = stream if stream is not None else sys.stderr
        isatty = getattr(self.stream, "isatty", None)
        self.terminal = bool(isatty()) if callable(isatty) else False
        self.start = time.perf_counter()
        self.next_line = 0.0

    def update(self, done: int) -> None:
        if not self.enabled:
            return
        elapsed = time.perf_counter() - self.start
        rate = done / elapsed if elapsed > 0 else 0.0
        left = (self.total - done) / rate if rate > 0 else float("inf")
        share = done / self.total
        eta = format_seconds(left) if left != float("inf") else "?"
        text = f"{done}/{self.total} steps  {rate:,.0f} steps/s  {eta} left"
        if self.terminal:
            width = 30
            filled = int(width * share)
            print(f"\r[{'#' * filled}{'.' * (width - filled)}] {text}   ", end="", file=self.stream, flush=True)
            if done >= self.total:
                print(file=self.stream, flush=True)
        elif share >= self.next_line or done >= self.total:
            print(f"{share:4.0%} {text}", file=self.stream, flush=True)
            self.next_line = (int(share / LOG_SHARE) + 1) * LOG_SHARE
