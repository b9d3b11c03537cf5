"""The small sweep cases of the sweep tests, and the combined dataset without what differs between runs."""

from __future__ import annotations

import threading

import xarray as xr

# the frequency-domain solution: a case costs a compile and a few hundredths of a second
BASE = {
    "device": {"name": "m4-111"},
    "sea": {"kind": "jonswap", "height": 0.04, "period": 1.2, "duration": 30.0, "ramp": 0.0},
    "solver": {"method": "frequency", "dt": 0.01},
    "outputs": {"statistics_only": True, "variables": []},
}
TIMINGS = ["run_time", "compile_time"]


def statistics(ds: xr.Dataset) -> xr.Dataset:
    """The combined dataset without what differs between runs (timings, the run's counts)."""
    out = ds.drop_vars(TIMINGS)
    out.attrs = {k: v for k, v in ds.attrs.items() if k != "sweep_run"}
    return out


PIDS_ENV = "WECSS_TEST_SWEEP_FOLDER"
"""Environment variable: the folder where :func:`interrupting_work` leaves its markers."""


def interrupting_work(scene_json: str) -> object:
    """A worker's case for the pool's Ctrl-C test: periods below 1.3 s finish at once; the others write their process
    id and sleep, and the case of period 1.4 s first sends SIGINT to the parent once the parent has handed the fast
    cases to ``finish`` (markers ``done-<period>``), as Ctrl-C in the terminal would."""
    import json
    import os
    import signal
    import time
    from pathlib import Path

    from wecss.sweep._case import CaseOutcome

    folder = Path(os.environ[PIDS_ENV])
    period = json.loads(scene_json)["sea"]["period"]
    if period < 1.3:
        return CaseOutcome(None, f"fast {period}", 0.0, 0.0)
    (folder / f"pid-{os.getpid()}").write_text(str(period))
    if period == 1.4:
        deadline = time.monotonic() + 60
        while not all((folder / f"done-{p}").exists() for p in (1.0, 1.2)) and time.monotonic() < deadline:
            time.sleep(0.01)
        os.kill(os.getppid(), signal.SIGINT)
    time.sleep(60)  # a long case: stopped by the parent, or the test fails on a live worker
    return CaseOutcome(None, "slow", 0.0, 0.0)


DASK_RELEASE = threading.Event()
"""Set to let the slow cases of :func:`dask_work` return (the Dask Ctrl-C test's in-process cluster)."""
DASK_RETURNED: list[float] = []
"""The periods of the fast cases :func:`dask_work` returned."""


def dask_work(scene_json: str) -> object:
    """A case for the Dask Ctrl-C test on an in-process cluster (threads share this module): periods below 1.3 s
    return at once, the others wait for :data:`DASK_RELEASE` (at most a minute)."""
    import json

    from wecss.sweep._case import CaseOutcome

    period = json.loads(scene_json)["sea"]["period"]
    if period < 1.3:
        DASK_RETURNED.append(period)
        return CaseOutcome(None, f"fast {period}", 0.0, 0.0)
    DASK_RELEASE.wait(60.0)
    return CaseOutcome(None, "slow", 0.0, 0.0)
