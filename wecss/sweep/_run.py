"""Running a sweep: every case in a worker (this process, a pool of processes, or a Dask cluster), one netCDF file per
case written atomically by this process, resumable, failures recorded, and the combined dataset at the end.

The folder of a sweep holds ``sweep.json`` (the sweep, checked on resume), ``<case>.nc`` per finished case,
``<case>.failed.json`` per failed case (its error) and ``sweep.log``. A case counts as finished only when its file
exists, and files appear only complete (``wecss.netcdf.write_netcdf``), so a sweep killed at any point and started
again runs exactly the cases that have no file.
"""

from __future__ import annotations

import contextlib
import json
import os
import sys
import time
import traceback
from collections.abc import Callable, Iterator
from concurrent.futures import Future, ProcessPoolExecutor, as_completed
from dataclasses import dataclass
from multiprocessing import get_context
from pathlib import Path
from typing import Any, TextIO

import xarray as xr

from ..netcdf import write_netcdf
from ._combine import combine
from ._files import case_paths, case_status, write_text
from ._progress import Progress
from ._spec import Case, Sweep

BLAS_THREADS = {
    "OPENBLAS_NUM_THREADS": "1",
    "OMP_NUM_THREADS": "1",
    "MKL_NUM_THREADS": "1",
    "NUMBA_NUM_THREADS": "1",
}
"""Environment of every worker process: one BLAS thread per worker (the workers share the cores)."""

SWEEP_FILE = "sweep.json"
LOG_FILE = "sweep.log"
COMBINED_FILE = "combined.nc"


@dataclass(frozen=True)
class CaseOutcome:
    """What a worker sends back: the result (None on failure), the error text, and the compile and run times [s]."""

    result: xr.Dataset | None
    error: str | None
    compile_s: float
    run_s: float


def run_case(scene_json: str) -> CaseOutcome:
    """Compile and run one case (in a worker); any exception becomes a recorded failure.

    The compiled plant's parts that the case's swept values do not change are cached per process by
    ``wecss.compiled`` (device, hydrodynamic coupling, equilibrium, radiation kernel).
    """
    from ..control import compile_scene
    from ..scene import Scene
    from ..sim import simulate

    start = time.perf_counter()
    compiled_at = start
    try:
        scene = Scene.from_json(scene_json)
        compiled = compile_scene(scene)
        compiled_at = time.perf_counter()
        ds = simulate(compiled)
    except Exception as err:  # recorded with its traceback; the sweep goes on
        text = f"{type(err).__name__}: {err}\n" + "".join(traceback.format_exception(err)[-3:])
        return CaseOutcome(None, text, compiled_at - start, time.perf_counter() - compiled_at)
    end = time.perf_counter()
    ds.attrs["sweep_compile_time_s"] = compiled_at - start
    return CaseOutcome(ds, None, compiled_at - start, end - compiled_at)


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
        if json.loads(record.read_text()) != json.loads(text):
            raise ValueError(
                f"{str(path)!r} holds another sweep ({SWEEP_FILE} differs); give a new folder or remove that one"
            )
    else:
        write_text(record, text)
    return path


class _Log:
    def __init__(self, path: Path) -> None:
        self.path = path

    def write(self, text: str) -> None:
        stamp = time.strftime("%Y-%m-%dT%H:%M:%S")
        with self.path.open("a") as f:
            f.write(f"{stamp} {text}\n")


@contextlib.contextmanager
def _pinned_environment() -> Iterator[None]:
    """BLAS threads pinned to one in the environment that new worker processes inherit."""
    previous = {k: os.environ.get(k) for k in BLAS_THREADS}
    os.environ.update(BLAS_THREADS)
    try:
        yield
    finally:
        for key, value in previous.items():
            if value is None:
                os.environ.pop(key, None)
            else:
                os.environ[key] = value


Submit = Callable[[str], "Future[CaseOutcome]"]


def run_sweep(
    sweep: Sweep,
    folder: str | os.PathLike[str],
    *,
    processes: int = 1,
    dask: bool = False,
    scheduler: str | None = None,
    workers: int | None = None,
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
    processes : int
        Without Dask: 1 runs the cases in this process; more runs them in a pool of that many processes.
    dask : bool
        Run on Dask: a LocalCluster of ``workers`` processes (default: the cores), one thread each, or the cluster
        at ``scheduler``.
    scheduler : str, optional
        Address of an existing Dask scheduler (``tcp://host:8786``); implies ``dask``.
    workers : int, optional
        Workers of the LocalCluster (``dask`` only).
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
        On bad options, or a folder that holds another sweep.
    ImportError
        If Dask is asked for and not installed.
    """
    if not (isinstance(processes, int) and not isinstance(processes, bool) and processes >= 1):
        raise ValueError(f"processes must be an integer >= 1; got {processes!r}")
    use_dask = dask or scheduler is not None
    if workers is not None and not use_dask:
        raise ValueError("workers sets the size of a Dask LocalCluster; without Dask use processes")
    if workers is not None and scheduler is not None:
        raise ValueError("workers sets the size of a LocalCluster; an existing cluster (scheduler) has its own")
    if use_dask and processes != 1:
        raise ValueError("processes is for runs without Dask; give workers for a LocalCluster")
    if workers is not None and not (isinstance(workers, int) and workers >= 1):
        raise ValueError(f"workers must be an integer >= 1; got {workers!r}")
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
            write_netcdf(outcome.result, result, compress=compress, float32=float32)
            failure.unlink(missing_ok=True)
            log.write(f"done {case.name} (compile {outcome.compile_s:.3g} s, run {outcome.run_s:.3g} s)")
        else:
            error = outcome.error or "unknown error"
            write_text(failure, json.dumps({"case": case.name, "values": dict(case.values), "error": error}))
            log.write(f"FAILED {case.name}: {error.splitlines()[0]}")
        bar.update(outcome.result is not None)

    try:
        if use_dask:
            _run_dask(todo, finish, scheduler, workers)
        elif processes == 1:
            for case in todo:
                finish(case, run_case(case.scene.to_json()))
        else:
            _run_pool(todo, finish, processes)
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


def _run_pool(todo: list[Case], finish: Callable[[Case, CaseOutcome], None], processes: int) -> None:
    with _pinned_environment():
        pool = ProcessPoolExecutor(max_workers=processes, mp_context=get_context("spawn"))
    try:
        futures = {pool.submit(run_case, case.scene.to_json()): case for case in todo}
        for future in as_completed(futures):
            finish(futures[future], future.result())
    except BaseException:
        pool.shutdown(wait=False, cancel_futures=True)
        raise
    pool.shutdown()


def _run_dask(
    todo: list[Case], finish: Callable[[Case, CaseOutcome], None], scheduler: str | None, workers: int | None
) -> None:
    try:
        from dask.distributed import Client, LocalCluster
        from dask.distributed import as_completed as dask_completed
    except ImportError:
        raise ImportError(
            "sweeps on Dask need dask.distributed: pip install 'wecss[dask]' (or run with processes, without Dask)"
        ) from None
    with contextlib.ExitStack() as stack:
        if scheduler is not None:
            client = stack.enter_context(Client(scheduler))
        else:
            n = workers or os.cpu_count() or 1
            cluster = stack.enter_context(
                LocalCluster(
                    n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None, env=dict(BLAS_THREADS)
                )
            )
            client = stack.enter_context(Client(cluster))
        futures = {client.submit(run_case, case.scene.to_json(), pure=False): case for case in todo}
        try:
            for future in dask_completed(list(futures)):
                finish(futures[future], future.result())
        except BaseException:
            client.cancel(list(futures))
            raise
