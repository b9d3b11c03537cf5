"""Progress messages for long BEM runs: frequencies done, elapsed time and an estimate of what is left."""

from __future__ import annotations

import sys
import time
from collections.abc import Callable


def print_flush(message: str) -> None:
    """Print ``message`` to standard output at once (useful when the output goes to a log file)."""
    print(message, file=sys.stdout, flush=True)


class Progress:
    """Counts solved problems and reports every ``interval`` seconds (and at the end).

    Parameters
    ----------
    label : str
        Prefix of every message.
    total : int
        Number of problems to solve.
    n_frequencies : int
        Number of frequencies they span (for the message only).
    report : callable
        Receives each message.
    interval : float
        Least time between two messages [s].
    """

    def __init__(
        self, label: str, total: int, n_frequencies: int, report: Callable[[str], None], interval: float = 20.0
    ) -> None:
        self.label = label
        self.total = max(int(total), 1)
        self.n_frequencies = n_frequencies
        self.report = report
        self.interval = interval
        self.done = 0
        self.start = time.perf_counter()
        self.last = self.start

    def message(self, note: str = "") -> str:
        """The current progress line."""
        elapsed = time.perf_counter() - self.start
        fraction = self.done / self.total
        left = elapsed * (1 - fraction) / fraction if self.done else float("nan")
        freq = round(fraction * self.n_frequencies)
        text = (
            f"{self.label}: {self.done}/{self.total} problems (~{freq}/{self.n_frequencies} frequencies), "
            f"{elapsed / 60:.1f} min elapsed"
        )
        if self.done < self.total and self.done:
            text += f", about {left / 60:.1f} min left"
        return f"{text}{note}"

    def step(self, note: str = "") -> None:
        """Record one solved problem; report if ``interval`` has passed or all are done."""
        self.done += 1
        now = time.perf_counter()
        if self.done >= self.total or now - self.last >= self.interval:
            self.last = now
            self.report(self.message(note))
