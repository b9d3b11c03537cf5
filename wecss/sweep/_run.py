"""Running a sweep: every case on its executor (this process, a pool of processes or a Dask cluster), one netCDF
file per case written atomically by this process, resumable, failures recorded, and the combined dataset at the end.

The folder of a sweep holds ``sweep.json`` (the sweep, checked on resume), ``<case>.nc`` per finished case,
``<case>.failed.json`` per failed case (its error) and ``sweep.log``. A case counts as finished only when its file
exists, and files appear only complete (``wecss.netcdf.write_netcdf``), so a sweep killed at any point and started
again runs exactly the cases that have no file. An interrupt (Ctrl-C, SIGTERM under the command) is no failure: it
stops the sweep, the cases being computed stay pending and the finished ones are kept.
"""

from __future__ import annotations

import functools
import json
import os
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any, ParamSpec, TextIO, TypeVar

import xarray as xr

from ..compiled import scene_inputs
from ..files import refuse_overwrite
from ..netcdf import write_netcdf
from ..provenance import with_relative_paths
from ._case import CaseOutcome
from ._combine import combine
from ._executors import Executor, check_executor, execute
from ._files import case_paths, case_status, write_text
from ._progress import Progress
from ._spec import Case, Sweep

P = ParamSpec("P")
R = TypeVar("R")

SWEEP_FILE = "sweep.json"
LOG_FILE = "sweep.log"
COMBINED_FILE = "combined.nc"


def _definition(sweep: Sweep) -> dict[str, Any]:
    return {"name": sweep.name, "mode": sweep.mode, "axes": [[p, list(v)] for p, v in sweep.axes], "base": sweep.base}


def prepare_folder(sweep: Sweep, folder: str | os.PathLike[str]) -> Path:
    """Create the sweep's folder with its ``sweep.json``, or check that an existing one holds the same sweep.

    Raises
    ------
    ValueError
        If the folder holds another sweep (results of different cases must not be mixed).
    """
    path = Path(folder)
    path.mkdir(parents=True, exist_ok=True)
    record = path / SWEEP_FILE
    text = json.dumps(_definition(sweep), sort_keys=True, indent=1)
    if record.is_file():
        try:
            recorded = json.loads(record.read_text(encoding="utf-8"))
        except (json.JSONDecodeError, UnicodeDecodeError) as err:
            raise ValueError(
                f"{record}: not a readable sweep record ({type(err).__name__}: {err}); this file, written when a "
                "sweep starts in the folder, lets a resume check it is the same sweep: give a new folder, or remove "
                f"the damaged {SWEEP_FILE} if the folder holds this same sweep (its finished cases are then kept)"
            ) from None
        if recorded != json.loads(text):
            raise ValueError(
                f"{str(path)!r} holds another sweep ({SWEEP_FILE} differs); give a new folder or remove that one"
            )
    else:
        write_text(record, text)
    return path


def check_outputs(sweep: Sweep, folder: str | os.PathLike[str]) -> None:
    """Refuse, before any file is written, a folder where a sweep's files (``sweep.json``, the log, the combined
    dataset, each case's result and failure record) would overwrite an input of one of its cases (the device spec
    and the files it names, the database, ``sea.file``) or lie in the radiation-fit cache.

    Raises
    ------
    wecss.files.OverwriteError
        (a ValueError) Naming the file, the input's field and the case.
    """
    path = Path(folder)
    outputs = {
        "sweep record": path / SWEEP_FILE,
        "sweep log": path / LOG_FILE,
        "combined dataset": path / COMBINED_FILE,
    }
    for case in sweep.cases:
        result, failure = case_paths(path, case)
        outputs[f"result file of case {case.name}"] = result
        outputs[f"failure record of case {case.name}"] = failure
    inputs: dict[str, Path] = {}
    seen: set[tuple[object, ...]] = set()
    for case in sweep.cases:  # the inputs depend on these fields only: read once per combination
        scene = case.scene
        key = (scene.device.name, scene.device.hydro, scene.sea.kind, scene.sea.file)
        if key not in seen:
            seen.add(key)
            inputs.update({f"{label} in case {case.name}": p for label, p in scene_inputs(scene).items()})
    refuse_overwrite(outputs, inputs)


class _Log:
    def __init__(self, path: Path) -> None:
        self.path = path

    def write(self, text: str) -> None:
        stamp = time.strftime("%Y-%m-%dT%H:%M:%S")
        with self.path.open("a") as f:
            f.write(f"{stamp} {text}\n")


REMOVED_KEYWORDS = ("processes", "dask")
"""Keyword arguments of ``run_sweep`` replaced by ``executor=`` (issue 25); each is refused naming the new form."""


def _new_form(removed: dict[str, object]) -> str:
    """How a call with the removed keyword arguments is written now."""
    old = ", ".join(f"{name}={value!r}" for name, value in removed.items())
    if removed.get("dask"):
        new = "executor='dask'"
    elif "processes" in removed and removed["processes"] != 1:
        new = f"executor='processes', workers={removed['processes']!r}"
    else:
        new = "executor='sequential'"
    return (
        f"run_sweep({old}) is now run_sweep({new}); executor is 'sequential' (the default), 'processes' or 'dask', "
        "with workers= (processes and dask) and scheduler= (dask) as its settings"
    )


def _refuse_removed_keywords(function: Callable[P, R]) -> Callable[P, R]:
    """``function`` refusing the keyword arguments of ``REMOVED_KEYWORDS`` with a ``TypeError`` that gives the new
    form of the call (any other unknown keyword fails as Python's own ``TypeError``)."""

    @functools.wraps(function)
    def refusing(*args: P.args, **kwargs: P.kwargs) -> R:
        removed = {name: kwargs[name] for name in REMOVED_KEYWORDS if name in kwargs}
        if removed:
            raise TypeError(_new_form(removed))
        return function(*args, **kwargs)

    return refusing


@_refuse_removed_keywords
def run_sweep(
    sweep: Sweep,
    folder: str | os.PathLike[str],
    *,
    executor: Executor = "sequential",
    workers: int | None = None,
    scheduler: str | None = None,
    retry_failed: bool = False,
    progress: TextIO | None = sys.stderr,
    compress: int = 0,
    float32: bool = False,
) -> xr.Dataset:
    """Run every case of ``sweep`` that has no result in ``folder`` and return the combined dataset (also written to
    ``folder/combined.nc``).

    Parameters
    ----------
    sweep : Sweep
    folder : path
        Where the case files, the failure records, the log and the combined dataset go (created if needed).
    executor : {"sequential", "processes", "dask"}
        Where the cases run: in this process (the default), in a pool of worker processes, or on Dask (a new
        LocalCluster of worker processes with one thread each, or the existing cluster at ``scheduler``). Worker
        processes run with one BLAS thread each (``BLAS_THREADS``).
    workers : int, optional
        Worker processes of the pool (``"processes"``) or of the LocalCluster (``"dask"``); default: one per core.
    scheduler : str, optional
        Address of an existing Dask scheduler, e.g. ``tcp://host:8786`` (``"dask"`` only; its cluster has its own
        workers).
    retry_failed : bool
        Run again the cases that failed before (default: they stay failed and are skipped).
    progress : text stream or None
        Where the progress line goes.
    compress, float32 : int, bool
        Storage of the case files and the combined dataset (:func:`wecss.netcdf.write_netcdf`): zlib level 0 (none)
        to 9, and floating-point variables in single precision.

    Returns
    -------
    xarray.Dataset
        The combined dataset (:func:`wecss.sweep.combine`); ``attrs["sweep_run"]`` (JSON) holds this call's counts,
        wall time and each case's compile and run times [s] in the order they finished.

    Raises
    ------
    ValueError
        On an unknown executor, a setting given to an executor it does not belong to (the message names the one it
        belongs to), bad setting values, a folder that holds another sweep, or one whose files would overwrite an
        input of a case (``wecss.files.OverwriteError``, before anything is written).
    TypeError
        On the keyword arguments this function no longer takes (``processes=``, ``dask=``): the message gives the
        new form of the call, e.g. ``run_sweep(processes=2)`` is now ``run_sweep(executor='processes', workers=2)``.
    ImportError
        If Dask is asked for and not installed.
    """
    check_executor(executor, workers=workers, scheduler=scheduler)
    check_outputs(sweep, folder)
    path = prepare_folder(sweep, folder)
    log = _Log(path / LOG_FILE)
    todo = []
    for case in sweep.cases:
        status = case_status(path, case)
        if status == "pending" or (status == "failed" and retry_failed):
            todo.append(case)
    skipped = len(sweep.cases) - len(todo)
    log.write(f"start: {len(todo)} cases to run, {skipped} skipped (finished or failed before)")
    bar = Progress(len(todo), progress)
    compile_s: list[float] = []
    run_s: list[float] = []
    start = time.perf_counter()

    def finish(case: Case, outcome: CaseOutcome) -> None:
        result, failure = case_paths(path, case)
        compile_s.append(outcome.compile_s)
        run_s.append(outcome.run_s)
        if outcome.result is not None:
            outcome.result.attrs = with_relative_paths(outcome.result.attrs, result)  # inputs from the case file
            write_netcdf(outcome.result, result, compress=compress, float32=float32)
            failure.unlink(missing_ok=True)
            log.write(f"done {case.name} (compile {outcome.compile_s:.3g} s, run {outcome.run_s:.3g} s)")
        else:
            error = outcome.error or "unknown error"
            write_text(failure, json.dumps({"case": case.name, "values": dict(case.values), "error": error}))
            log.write(f"FAILED {case.name}: {error.splitlines()[0]}")
        bar.update(outcome.result is not None)

    try:
        execute(executor, todo, finish, workers=workers, scheduler=scheduler)
    except KeyboardInterrupt:
        log.write(f"interrupted after {bar.done + bar.failed} of {len(todo)} cases; start again to resume")
        raise
    wall = time.perf_counter() - start
    log.write(f"end: {bar.done} done, {bar.failed} failed in {wall:.3g} s")
    ds = combine(sweep, path)
    ds.attrs["sweep_run"] = json.dumps(
        {
            "ran": bar.done,
            "failed": bar.failed,
            "skipped": skipped,
            "wall_time_s": wall,
            "compile_time_s": compile_s,
            "run_time_s": run_s,
        },
        sort_keys=True,
    )
    write_netcdf(ds, path / COMBINED_FILE, compress=compress, float32=float32)
    return ds
