"""What the ``wecss`` command does to its own process: ``wecss.cli.main()`` on the process's command line (the
``wecss`` script, ``python -m wecss.cli``); a call from Python (``main([...])``) leaves the caller's process alone.

- :func:`enter`: for every command but ``sweep`` (a long process, which may use dask), dask is kept out
  (``wecss.dask_free``; ``run --allow-dask`` lets it in) and the cyclic garbage collector collects at
  :data:`GC_THRESHOLDS` instead of Python's (700, 10, 10). A command imports xarray, pandas, numba and
  matplotlib: hundreds of thousands of objects that live as long as the process and that every full collection
  walks again (four of them in ``wecss run``, 0.2-0.3 s of CPU). Young reference cycles are still freed, after
  10,000 allocations instead of 700; the memory this holds is small beside a run's arrays.
- :func:`leave`: the process's objects are frozen (``gc.freeze``): the interpreter's exit then frees them by their
  reference counts alone instead of walking them again in its final collections (0.25-0.45 s of CPU).
"""

from __future__ import annotations

import gc

from .dask_free import keep_dask_out

GC_THRESHOLDS = (10_000, 50, 100)
"""``gc.set_threshold`` of the command's process: allocations before a young collection, young collections before
a middle one, middle ones before a full one."""

LONG_COMMANDS = ("sweep",)
"""The commands whose process is left as Python sets it up: they may run for hours, and use dask (``wecss sweep
--dask``)."""


def enter(command: str, *, allow_dask: bool = False) -> None:
    """Set up the process of the command ``command`` (a subcommand name) before it runs."""
    if command in LONG_COMMANDS:
        return
    if not allow_dask:
        keep_dask_out()
    gc.set_threshold(*GC_THRESHOLDS)


def leave() -> None:
    """The command is done and its process about to exit (its files are closed)."""
    gc.freeze()
