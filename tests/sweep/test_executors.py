"""Where a sweep's cases run: each executor gives the sequential run's results; settings that do not belong to the
chosen executor, bad values and the removed keyword arguments are refused before any case runs; the command's
flags map onto the executors."""

from __future__ import annotations

import inspect
import os
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from wecss.cli import build_parser, main, sweep_executor
from wecss.sweep import EXECUTORS, Sweep, run_sweep

from .cases import BASE, interrupting_work, statistics


@pytest.fixture(scope="module")
def sweep() -> Sweep:
    return Sweep(BASE, (("sea.period", (1.0, 1.4)), ("controller.parameters.damping", (3.0, 6.0))))


@pytest.fixture(scope="module")
def sequential(sweep: Sweep, tmp_path_factory: pytest.TempPathFactory) -> xr.Dataset:
    return run_sweep(sweep, tmp_path_factory.mktemp("sequential"), progress=None)


def test_the_executors_are_named():
    assert EXECUTORS == ("sequential", "processes", "dask")
    parameters = inspect.signature(run_sweep).parameters
    assert parameters["executor"].default == "sequential"
    assert "processes" not in parameters and "dask" not in parameters


def test_the_sequential_executor_is_the_default(sweep: Sweep, sequential: xr.Dataset, tmp_path: Path) -> None:
    named = run_sweep(sweep, tmp_path, executor="sequential", progress=None)
    assert list(np.unique(named.status.values)) == ["done"]
    xr.testing.assert_identical(statistics(named), statistics(sequential))


def test_a_process_pool_gives_the_results_of_the_sequential_run(
    sweep: Sweep, sequential: xr.Dataset, tmp_path: Path
) -> None:
    pool = run_sweep(sweep, tmp_path, executor="processes", workers=2, progress=None)
    assert list(np.unique(pool.status.values)) == ["done"]
    xr.testing.assert_identical(statistics(pool), statistics(sequential))


def test_a_local_dask_cluster_gives_the_results_of_the_sequential_run(
    sweep: Sweep, sequential: xr.Dataset, tmp_path: Path
) -> None:
    pytest.importorskip("dask.distributed")
    dask = run_sweep(sweep, tmp_path, executor="dask", workers=2, progress=None)
    assert list(np.unique(dask.status.values)) == ["done"]
    xr.testing.assert_identical(statistics(dask), statistics(sequential))


@pytest.mark.slow
def test_a_sweep_runs_on_an_existing_cluster_given_by_its_scheduler_address(tmp_path: Path) -> None:
    distributed = pytest.importorskip("dask.distributed")
    sweep = Sweep(BASE, (("sea.period", (1.0, 1.4)),))
    sequential = run_sweep(sweep, tmp_path / "one", progress=None)
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, dashboard_address=None) as cluster:
        remote = run_sweep(
            sweep, tmp_path / "remote", executor="dask", scheduler=cluster.scheduler_address, progress=None
        )
    xr.testing.assert_identical(statistics(remote), statistics(sequential))


@pytest.mark.parametrize(
    ("options", "message"),
    [
        ({"executor": "pool"}, "executor must be one of 'sequential', 'processes', 'dask'; got 'pool'"),
        ({"executor": None}, "executor must be one of 'sequential', 'processes', 'dask'; got None"),
        (
            {"workers": 2},
            "workers=2 is a setting of executor='processes' or executor='dask'; got executor='sequential'",
        ),
        (
            {"scheduler": "tcp://host:8786"},
            "scheduler='tcp://host:8786' is a setting of executor='dask'; got executor='sequential'",
        ),
        (
            {"executor": "processes", "scheduler": "tcp://host:8786"},
            "scheduler='tcp://host:8786' is a setting of executor='dask'; got executor='processes'",
        ),
        ({"executor": "processes", "workers": 0}, "workers must be an integer >= 1 (or None: one per core); got 0"),
        ({"executor": "dask", "workers": 1.5}, "workers must be an integer >= 1 (or None: one per core); got 1.5"),
        (
            {"executor": "processes", "workers": True},
            "workers must be an integer >= 1 (or None: one per core); got True",
        ),
        ({"executor": "dask", "scheduler": ""}, "scheduler must be the address of a Dask scheduler"),
        (
            {"executor": "dask", "workers": 2, "scheduler": "tcp://host:8786"},
            "workers=2 sets the size of a new Dask LocalCluster; the existing cluster at scheduler='tcp://host:8786' "
            "has its own workers",
        ),
    ],
)
def test_settings_that_do_not_belong_to_the_executor_and_bad_values_are_refused_before_any_run(
    options: dict[str, object], message: str, tmp_path: Path
) -> None:
    sweep = Sweep(BASE, (("sea.period", (1.0,)),))
    with pytest.raises(ValueError) as refused:
        run_sweep(sweep, tmp_path / "sweep", progress=None, **options)  # type: ignore[arg-type]
    assert message in str(refused.value)
    assert not (tmp_path / "sweep").exists()


@pytest.mark.parametrize(
    ("removed", "message"),
    [
        ({"processes": 2}, "run_sweep(processes=2) is now run_sweep(executor='processes', workers=2)"),
        ({"processes": 1}, "run_sweep(processes=1) is now run_sweep(executor='sequential')"),
        ({"dask": True}, "run_sweep(dask=True) is now run_sweep(executor='dask')"),
        ({"dask": False}, "run_sweep(dask=False) is now run_sweep(executor='sequential')"),
        ({"processes": 2, "dask": True}, "run_sweep(processes=2, dask=True) is now run_sweep(executor='dask')"),
    ],
)
def test_the_removed_keyword_arguments_are_refused_with_the_new_form(
    removed: dict[str, object], message: str, tmp_path: Path
) -> None:
    sweep = Sweep(BASE, (("sea.period", (1.0,)),))
    with pytest.raises(TypeError) as refused:
        run_sweep(sweep, tmp_path / "sweep", **removed)  # type: ignore[call-arg]
    assert str(refused.value).startswith(message + ";")
    assert not (tmp_path / "sweep").exists()


def test_an_unknown_keyword_argument_is_pythons_own_type_error(tmp_path: Path) -> None:
    sweep = Sweep(BASE, (("sea.period", (1.0,)),))
    with pytest.raises(TypeError, match="unexpected keyword argument 'worker'"):
        run_sweep(sweep, tmp_path, executor="processes", worker=2)  # type: ignore[call-arg]


@pytest.mark.parametrize(
    ("flags", "call"),
    [
        ([], {"executor": "sequential"}),
        (["--processes", "1"], {"executor": "sequential"}),
        (["--processes", "3"], {"executor": "processes", "workers": 3}),
        (["--dask"], {"executor": "dask", "workers": None, "scheduler": None}),
        (["--dask", "--workers", "2"], {"executor": "dask", "workers": 2, "scheduler": None}),
        (["--scheduler", "tcp://host:8786"], {"executor": "dask", "workers": None, "scheduler": "tcp://host:8786"}),
    ],
)
def test_the_command_flags_map_onto_the_executors(flags: list[str], call: dict[str, object]) -> None:
    args = build_parser().parse_args(["sweep", "matrix.toml", *flags])
    assert sweep_executor(args) == call


@pytest.mark.parametrize(
    ("flags", "message"),
    [
        (["--workers", "2"], "--workers 2 sets the size of the Dask LocalCluster (--dask)"),
        (["--processes", "0"], "--processes must be an integer >= 1; got 0"),
        (["--scheduler", "tcp://host:8786", "--workers", "2"], "the existing cluster at scheduler='tcp://host:8786'"),
    ],
)
def test_the_command_refuses_flags_that_do_not_fit_together(
    flags: list[str], message: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    spec = tmp_path / "matrix.toml"
    spec.write_text('[sweep]\n[sweep.axes]\n"sea.period" = [1.0]\n[scene]\ndevice.name = "m4-111"\n')
    assert main(["sweep", str(spec), "-o", str(tmp_path / "out"), "-q", *flags]) == 2
    assert message in capsys.readouterr().err
    assert not (tmp_path / "out").exists()


def test_the_command_takes_one_executor_flag(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as stopped:
        build_parser().parse_args(["sweep", "matrix.toml", "--processes", "2", "--dask"])
    assert stopped.value.code == 2
    assert "not allowed with argument --processes" in capsys.readouterr().err


@pytest.mark.skipif(os.name != "posix", reason="signals")
def test_ctrl_c_stops_a_process_pool_at_once_and_keeps_every_finished_case(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from wecss.sweep._executors import _run_pool

    from .cases import PIDS_ENV

    monkeypatch.setenv(PIDS_ENV, str(tmp_path))
    sweep = Sweep(BASE, (("sea.period", (1.0, 1.2, 1.4, 1.6, 1.8)),))
    finished: list[float] = []

    def finish(case, outcome):  # type: ignore[no-untyped-def]
        period = dict(case.values)["sea.period"]
        finished.append(period)
        (tmp_path / f"done-{period}").write_text(outcome.error)

    with pytest.raises(KeyboardInterrupt):
        _run_pool(list(sweep.cases), finish, 2, work=interrupting_work)
    assert sorted(finished) == [1.0, 1.2]  # the finished cases were kept, the long ones not taken as done
    pids = [int(p.name.split("-")[1]) for p in tmp_path.glob("pid-*")]
    assert pids, "a long case must have started"
    for pid in pids:  # the workers were stopped, not left computing
        with pytest.raises(ProcessLookupError):
            os.kill(pid, 0)


def test_ctrl_c_on_dask_keeps_the_finished_cases_and_cancels_the_others() -> None:
    """Three fast cases and two that would run for a minute, on an in-process Dask cluster (threads): Ctrl-C
    (a KeyboardInterrupt in this process, raised by ``finish`` once every fast case has returned) hands the fast
    cases not yet handed to ``finish``, cancels the slow ones and returns at once."""
    import time

    distributed = pytest.importorskip("dask.distributed")
    from wecss.sweep._executors import _run_dask

    from .cases import DASK_RELEASE, DASK_RETURNED, dask_work

    DASK_RELEASE.clear()
    DASK_RETURNED.clear()
    finished: list[float] = []

    def finish(case, outcome):  # type: ignore[no-untyped-def]
        finished.append(dict(case.values)["sea.period"])
        if len(finished) == 1:  # Ctrl-C once every fast case returned (their futures finish just after)
            deadline = time.monotonic() + 30
            while len(DASK_RETURNED) < 3 and time.monotonic() < deadline:
                time.sleep(0.01)
            time.sleep(0.5)
            raise KeyboardInterrupt

    sweep = Sweep(BASE, (("sea.period", (1.0, 1.1, 1.2, 1.4, 1.6)),))
    with distributed.LocalCluster(
        n_workers=1, threads_per_worker=5, processes=False, dashboard_address=None
    ) as cluster:
        start = time.monotonic()
        try:
            with pytest.raises(KeyboardInterrupt):
                _run_dask(list(sweep.cases), finish, cluster.scheduler_address, None, work=dask_work)
            took = time.monotonic() - start
        finally:
            DASK_RELEASE.set()
    assert sorted(finished) == [1.0, 1.1, 1.2]  # every finished case kept, the slow ones never handed
    assert took < 20.0  # not waiting for the slow cases (60 s)
