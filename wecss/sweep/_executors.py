"""Where a sweep's cases run: the executors ``"sequential"`` (this process), ``"processes"`` (a pool of worker
processes) and ``"dask"`` (a Dask LocalCluster, or an existing cluster given by its scheduler's address), each with
the settings that belong to it, checked before any case runs."""

from __future__ import annotations

import contextlib
import os
import signal
from collections.abc import Callable, Iterator
from concurrent.futures import Future, ProcessPoolExecutor, as_completed
from multiprocessing import get_context
from typing import Literal

from ._case import CaseOutcome, run_case
from ._spec import Case

Executor = Literal["sequential", "processes", "dask"]

EXECUTORS: tuple[Executor, ...] = ("sequential", "processes", "dask")
"""The executors of ``run_sweep(..., executor=...)``."""

SETTINGS: dict[str, tuple[Executor, ...]] = {"workers": ("processes", "dask"), "scheduler": ("dask",)}
"""Each executor setting of ``run_sweep`` and the executors it belongs to."""

BLAS_THREADS = {
    "OPENBLAS_NUM_THREADS": "1",
    "OMP_NUM_THREADS": "1",
    "MKL_NUM_THREADS": "1",
    "NUMBA_NUM_THREADS": "1",
}
"""Environment of every worker process: one BLAS thread per worker (the workers share the cores)."""

Finish = Callable[[Case, CaseOutcome], None]

STOP_GRACE_S: float = 10.0
"""Time [s] a worker process has to end after SIGTERM when a pool is stopped, before it is killed."""


def check_executor(executor: object, *, workers: object, scheduler: object) -> None:
    """Refuse an unknown executor, a setting given to an executor it does not belong to, and bad setting values.

    Parameters
    ----------
    executor : str
        One of ``EXECUTORS``.
    workers : int or None
        Worker processes of the pool (``"processes"``) or of a new Dask LocalCluster (``"dask"``).
    scheduler : str or None
        Address of an existing Dask scheduler (``"dask"``).

    Raises
    ------
    ValueError
        Saying what was received and what is accepted, and naming the executor a misplaced setting belongs to.
    """
    if executor not in EXECUTORS:
        accepted = ", ".join(repr(e) for e in EXECUTORS)
        raise ValueError(f"executor must be one of {accepted}; got {executor!r}")
    given = {"workers": workers, "scheduler": scheduler}
    for name, owners in SETTINGS.items():
        if given[name] is not None and executor not in owners:
            belongs = " or ".join(f"executor={owner!r}" for owner in owners)
            raise ValueError(f"{name}={given[name]!r} is a setting of {belongs}; got executor={executor!r}")
    if workers is not None and not (isinstance(workers, int) and not isinstance(workers, bool) and workers >= 1):
        raise ValueError(f"workers must be an integer >= 1 (or None: one per core); got {workers!r}")
    if scheduler is not None and not (isinstance(scheduler, str) and scheduler):
        raise ValueError(f"scheduler must be the address of a Dask scheduler (tcp://host:8786); got {scheduler!r}")
    if workers is not None and scheduler is not None:
        raise ValueError(
            f"workers={workers!r} sets the size of a new Dask LocalCluster; the existing cluster at "
            f"scheduler={scheduler!r} has its own workers: give one of them"
        )


def execute(
    executor: Executor, todo: list[Case], finish: Finish, *, workers: int | None, scheduler: str | None
) -> None:
    """Run every case of ``todo`` on ``executor`` (settings checked by :func:`check_executor`), calling
    ``finish(case, outcome)`` in this process as each one ends (in the order they end)."""
    if executor == "sequential":
        for case in todo:
            finish(case, run_case(case.scene.to_json()))
    elif executor == "processes":
        _run_pool(todo, finish, workers or os.cpu_count() or 1)
    else:
        _run_dask(todo, finish, scheduler, workers)


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


def ignore_interrupts() -> None:
    """Initializer of the pool's worker processes: Ctrl-C (SIGINT to the terminal's process group) is the parent's
    to handle; the parent stops the workers."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)


def _run_pool(todo: list[Case], finish: Finish, processes: int, work: Callable[[str], CaseOutcome] = run_case) -> None:
    """The cases on a pool of ``processes`` worker processes (``work``: what a worker runs on a case's scene JSON).

    On Ctrl-C (or any error in this process) the queued cases are cancelled and the workers stopped at once (their
    cases stay to be done), the cases that had finished are handed to ``finish``, and the exception is raised.
    """
    with _pinned_environment():
        pool = ProcessPoolExecutor(
            max_workers=processes, mp_context=get_context("spawn"), initializer=ignore_interrupts
        )
    futures = {pool.submit(work, case.scene.to_json()): case for case in todo}
    handed: set[Future[CaseOutcome]] = set()
    try:
        for future in as_completed(futures):
            handed.add(future)
            finish(futures[future], future.result())
    except BaseException:
        stop_workers(pool)
        for future, case in futures.items():  # finished before the workers were stopped: kept
            if future not in handed and future.done() and not future.cancelled() and future.exception() is None:
                handed.add(future)
                finish(case, future.result())
        raise
    pool.shutdown()


def stop_workers(pool: ProcessPoolExecutor) -> None:
    """Cancel the queued work of ``pool`` and terminate its worker processes now (what
    ``ProcessPoolExecutor.terminate_workers`` does from Python 3.14; before, through the pool's processes)."""
    terminate = getattr(pool, "terminate_workers", None)
    if terminate is not None:  # pragma: no cover - Python 3.14+
        terminate()
        return
    processes = dict(getattr(pool, "_processes", None) or {})
    pool.shutdown(wait=False, cancel_futures=True)
    for process in processes.values():
        with contextlib.suppress(ValueError, ProcessLookupError):  # closed or gone already
            if process.is_alive():
                process.terminate()
    for process in processes.values():
        with contextlib.suppress(ValueError):
            process.join(STOP_GRACE_S)
            if process.is_alive():
                process.kill()
                process.join()


def _run_dask(
    todo: list[Case],
    finish: Finish,
    scheduler: str | None,
    workers: int | None,
    work: Callable[[str], CaseOutcome] = run_case,
) -> None:
    """The cases on Dask: a new LocalCluster of ``workers`` processes, or the cluster at ``scheduler``
    (``work``: what a worker runs on a case's scene JSON).

    On Ctrl-C (or any error in this process) the cases that had finished are handed to ``finish``, every other
    future is cancelled (a case running on a worker of an existing cluster runs to its end there, its result
    dropped; a LocalCluster of this call is closed, its worker processes with it) and the exception is raised.
    """
    try:
        from dask.distributed import Client, LocalCluster
        from dask.distributed import as_completed as dask_completed
    except ImportError:
        raise ImportError(
            "sweeps on Dask need dask.distributed: pip install 'wecss[dask]' (or run with executor='processes')"
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
        futures = {client.submit(work, case.scene.to_json(), pure=False): case for case in todo}
        handed: set[object] = set()
        try:
            for future in dask_completed(list(futures)):
                handed.add(future)
                finish(futures[future], future.result())
        except BaseException:
            client.cancel([f for f in futures if f.status != "finished"])
            for future, case in futures.items():  # finished before the interrupt: kept
                if future not in handed and future.status == "finished":
                    handed.add(future)
                    finish(case, future.result())
            raise
