"""Sweeps: cases from dotted scene paths, resumable runs (a real kill of the sweep process), failures recorded,
``wecss run --set``. The executors are tested in ``test_executors.py``."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from wecss.cli import main
from wecss.scene import Scene, SceneError, default_scene_path
from wecss.sweep import Sweep, apply_overrides, case_paths, case_status, run_sweep

from .cases import BASE, statistics

ROOT = Path(__file__).resolve().parents[2]


def _sweep_file(tmp_path: Path, periods: list[float], name: str = "sweep.toml") -> Path:
    """A sweep file over sea.period and sea.height with the base scene BASE written as TOML tables."""
    lines = ["[sweep]", 'name = "test"', "[sweep.axes]", f'"sea.period" = {periods}', '"sea.height" = [0.04, 0.08]']
    for section, table in BASE.items():
        lines.append(f"[scene.{section}]")
        lines.extend(f"{key} = {json.dumps(value)}" for key, value in table.items())
    path = tmp_path / name
    path.write_text("\n".join(lines) + "\n")
    return path


# ---- cases and --set -------------------------------------------------------------------------------------------


def test_grid_expands_every_combination_and_names_cases_by_their_values() -> None:
    sweep = Sweep(BASE, (("sea.period", (1.0, 1.2, 1.4)), ("controller.parameters.damping", (3.0, 6.0))))
    assert len(sweep.cases) == 6
    case = sweep.cases[5]
    assert case.scene.sea.period == 1.4
    assert case.scene.controller.parameters["damping"] == 6.0
    assert case.name == "c0005_sea.period=1.4_controller.parameters.damping=6.0"
    assert len({c.name for c in sweep.cases}) == 6


def test_list_mode_pairs_values_and_needs_axes_of_one_length() -> None:
    sweep = Sweep(BASE, (("sea.period", (1.0, 1.4)), ("sea.height", (0.04, 0.06))), mode="list")
    assert [(c.scene.sea.period, c.scene.sea.height) for c in sweep.cases] == [(1.0, 0.04), (1.4, 0.06)]
    with pytest.raises(SceneError, match="one length"):
        Sweep(BASE, (("sea.period", (1.0, 1.4)), ("sea.height", (0.04,))), mode="list")


def test_a_bad_case_is_refused_before_any_run_with_the_scene_message() -> None:
    with pytest.raises(SceneError, match=r"case 1 .*sea.period must be positive"):
        Sweep(BASE, (("sea.period", (1.0, -1.0)),))
    with pytest.raises(SceneError, match=r"unknown keys \['perod'\]"):
        Sweep(BASE, (("sea.perod", (1.0,)),))


def test_set_overrides_a_scene_value_and_refuses_bad_paths_and_values() -> None:
    scene = Scene.from_toml(default_scene_path())
    changed = apply_overrides(scene, ["sea.period=1.4", "controller.parameters.damping=3", 'device.name="m4-111"'])
    assert (changed.sea.period, changed.controller.parameters["damping"], changed.device.name) == (1.4, 3, "m4-111")
    assert changed.sea.height == scene.sea.height
    with pytest.raises(SceneError, match=r"\[sea\]: unknown keys \['perod'\]; accepted: kind, height, period"):
        apply_overrides(scene, ["sea.perod=1.4"])
    with pytest.raises(SceneError, match="unknown sections"):
        apply_overrides(scene, ["waves.period=1.4"])
    with pytest.raises(SceneError, match=r"sea\.period must be positive"):
        apply_overrides(scene, ["sea.period=-1"])
    with pytest.raises(SceneError, match=r"solver\.method: unknown 'euler'"):
        apply_overrides(scene, ["solver.method=euler"])
    with pytest.raises(SceneError, match=r"sea\.seed must be int"):
        apply_overrides(scene, ["sea.seed=1.5"])
    with pytest.raises(SceneError, match="path=value"):
        apply_overrides(scene, ["sea.period"])
    with pytest.raises(SceneError, match="is a value"):
        apply_overrides(scene, ["sea.period.x=1"])


def test_run_command_reports_a_bad_set_without_a_traceback(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["run", "--set", "sea.perod=1.4"]) == 2
    err = capsys.readouterr().err
    assert "unknown keys ['perod']" in err and "Traceback" not in err


# ---- runs ------------------------------------------------------------------------------------------------------


def test_a_failing_case_is_recorded_and_the_others_run(tmp_path: Path) -> None:
    # 0.25 s lies outside the database's periods (0.29-63 s): the scene is valid, the compile refuses it
    sweep = Sweep(BASE, (("sea.period", (1.0, 0.25, 1.4)),))
    ds = run_sweep(sweep, tmp_path, progress=None)
    assert list(ds.status.values) == ["done", "failed", "done"]
    assert "lies outside the hydrodynamic database" in str(ds.error.values[1])
    assert np.isnan(ds.total_power.values[1]) and np.all(ds.total_power.values[[0, 2]] > 0)
    assert ds.attrs["cases_failed"] == 1
    failure = case_paths(tmp_path, sweep.cases[1])[1]
    assert "SceneError" in json.loads(failure.read_text())["error"]
    assert "FAILED c0001" in (tmp_path / "sweep.log").read_text()
    # started again: the failed case stays failed (not run again) unless asked
    again = run_sweep(sweep, tmp_path, progress=None)
    assert json.loads(again.attrs["sweep_run"])["skipped"] == 3
    retried = run_sweep(sweep, tmp_path, retry_failed=True, progress=None)
    assert json.loads(retried.attrs["sweep_run"])["failed"] == 1
    assert list(retried.status.values) == ["done", "failed", "done"]


def test_combined_dataset_has_the_axes_as_dimensions_and_matches_single_runs(tmp_path: Path) -> None:
    from wecss.sim import simulate

    sweep = Sweep(BASE, (("sea.period", (1.0, 1.4)), ("sea.height", (0.04, 0.08))))
    ds = run_sweep(sweep, tmp_path, progress=None)
    assert ds.total_power.dims == ("sea.period", "sea.height")
    assert ds.mean_pto_power.dims == ("sea.period", "sea.height", "pto")
    single = simulate(sweep.cases[3].scene)  # period 1.4, height 0.08, run here without the sweep
    np.testing.assert_array_equal(ds.mean_pto_power.values[1, 1], single.mean_pto_power.values)
    # linear waves: power grows with H^2
    np.testing.assert_allclose(ds.total_power.sel({"sea.height": 0.08}), 4 * ds.total_power.sel({"sea.height": 0.04}))
    stored = xr.open_dataset(tmp_path / "combined.nc").load()
    np.testing.assert_array_equal(stored.total_power.values, ds.total_power.values)


def test_a_folder_of_another_sweep_is_refused(tmp_path: Path) -> None:
    run_sweep(Sweep(BASE, (("sea.period", (1.0,)),)), tmp_path, progress=None)
    with pytest.raises(ValueError, match="holds another sweep"):
        run_sweep(Sweep(BASE, (("sea.period", (1.2,)),)), tmp_path, progress=None)


def test_a_killed_sweep_resumes_to_the_uninterrupted_result(tmp_path: Path) -> None:
    periods = [round(0.8 + 0.05 * i, 2) for i in range(12)]
    spec = _sweep_file(tmp_path, periods)
    sweep = Sweep.from_toml(spec)
    killed = tmp_path / "killed"
    env = {**os.environ, "PYTHONPATH": str(ROOT), "OPENBLAS_NUM_THREADS": "1"}
    command = [sys.executable, "-m", "wecss.cli", "sweep", str(spec), "-o", str(killed), "-q"]
    process = subprocess.Popen(command, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and process.poll() is None:
        if killed.is_dir() and len(list(killed.glob("c[0-9]*.nc"))) >= 2:
            break
        time.sleep(0.01)
    process.send_signal(signal.SIGKILL)  # no clean-up: as a lost machine or `kill -9`
    process.wait()
    finished = {p.name for p in killed.glob("c[0-9]*.nc")}
    assert 2 <= len(finished) < len(sweep.cases), "the sweep must be killed mid-way"
    for name in finished:  # every file counted as finished is complete
        xr.open_dataset(killed / name).close()
    # a half-written file left by a writer that died is never taken for a finished case
    pending = sweep.cases[-1]
    stale = killed / f".{pending.name}.nc.999999999.abc.tmp"
    stale.write_bytes(b"CDF\x01 half")
    assert case_status(killed, pending) == "pending"
    resumed = run_sweep(sweep, killed, progress=None)
    counts = json.loads(resumed.attrs["sweep_run"])
    assert counts["skipped"] == len(finished) and counts["ran"] == len(sweep.cases) - len(finished)
    assert not stale.exists()
    whole = run_sweep(sweep, tmp_path / "whole", progress=None)
    xr.testing.assert_identical(statistics(resumed), statistics(whole))


def test_the_cli_runs_a_sweep_file(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    spec = _sweep_file(tmp_path, [1.0, 1.2])
    assert main(["sweep", str(spec), "-o", str(tmp_path / "out"), "-q"]) == 0
    assert "4 done, 0 failed, 0 pending" in capsys.readouterr().out
    assert (tmp_path / "out" / "combined.nc").is_file()


def test_the_cli_stores_a_sweep_compressed_in_single_precision(tmp_path: Path) -> None:
    import netCDF4

    spec = _sweep_file(tmp_path, [1.0])
    assert main(["sweep", str(spec), "-o", str(tmp_path / "out"), "-q", "--compress", "5", "--float32"]) == 0
    cases = sorted((tmp_path / "out").glob("c[0-9]*.nc"))
    assert cases
    for path in [*cases, tmp_path / "out" / "combined.nc"]:
        with netCDF4.Dataset(path) as nc:
            floats = [
                v for v in nc.variables.values() if getattr(v.dtype, "kind", "") == "f" and v.name not in nc.dimensions
            ]
            assert floats and all(v.dtype == np.float32 for v in floats), path.name


def test_cases_that_change_only_the_sea_reuse_the_device_and_give_the_results_of_a_fresh_compile() -> None:
    from wecss.compiled import clear_compile_cache, compile_plant
    from wecss.sim import simulate

    first, second = (
        Scene.from_dict({**BASE, "sea": {**BASE["sea"], "period": p}, "solver": {"method": "beeman", "dt": 0.01}})
        for p in (1.0, 1.3)
    )
    plant = compile_plant(first)
    cached = compile_plant(second)
    assert cached.coupling is plant.coupling and cached.device is plant.device  # built once
    assert cached.radiation is plant.radiation  # same step: the same kernel arrays
    clear_compile_cache()
    fresh = compile_plant(second)
    assert fresh.coupling is not plant.coupling
    np.testing.assert_array_equal(fresh.q0, cached.q0)
    np.testing.assert_array_equal(fresh.stiffness, cached.stiffness)
    short = {"sea": {**BASE["sea"], "period": 1.3, "duration": 5.0}, "solver": {"method": "beeman", "dt": 0.01}}
    scene = Scene.from_dict({**BASE, **short})
    a = simulate(scene)
    b = simulate(scene)  # the second compile from the cache
    clear_compile_cache()
    c = simulate(scene)
    np.testing.assert_array_equal(a.mean_pto_power.values, b.mean_pto_power.values)
    np.testing.assert_array_equal(a.mean_pto_power.values, c.mean_pto_power.values)


def test_progress_in_a_log_prints_a_line_now_and_then_not_per_case() -> None:
    import io

    from wecss.sweep import Progress

    log = io.StringIO()  # not a terminal
    bar = Progress(50, log)
    for i in range(50):
        bar.update(ok=i != 7)
    lines = log.getvalue().splitlines()
    assert len(lines) == 2  # the first case (no line printed before) and the last
    assert lines[-1].endswith("50/50 cases: 49 done, 1 failed, ETA 0s")
    assert "\r" not in log.getvalue()


def test_a_case_interrupted_in_a_sequential_sweep_is_not_done_never_failed_and_a_resume_computes_it(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from tests.sim.test_interrupts import numba_interrupt
    from wecss.sim._frequency import FrequencyDomain

    sweep = Sweep(BASE, (("sea.period", (1.0, 1.2, 1.4)),))
    run = FrequencyDomain.run
    calls: list[int] = []

    def interrupted_second(self, controlled, **kwargs):  # type: ignore[no-untyped-def]
        calls.append(1)
        if len(calls) == 2:
            raise numba_interrupt()  # Ctrl-C inside a compiled call, as numba reports it
        return run(self, controlled, **kwargs)

    monkeypatch.setattr(FrequencyDomain, "run", interrupted_second)
    with pytest.raises(KeyboardInterrupt):
        run_sweep(sweep, tmp_path, progress=None)
    assert len(calls) == 2  # the sweep stopped: the third case did not run
    assert [case_status(tmp_path, case) for case in sweep.cases] == ["done", "pending", "pending"]
    assert "FAILED" not in (tmp_path / "sweep.log").read_text()
    assert "interrupted after 1 of 3 cases" in (tmp_path / "sweep.log").read_text()
    monkeypatch.setattr(FrequencyDomain, "run", run)
    resumed = run_sweep(sweep, tmp_path, progress=None)
    assert list(resumed.status.values) == ["done", "done", "done"]
    assert json.loads(resumed.attrs["sweep_run"])["ran"] == 2


def test_a_sweep_file_with_a_utf8_byte_order_mark_is_read(tmp_path: Path) -> None:
    """Issue 31: a sweep file saved by an editor that writes a byte-order mark was refused as invalid TOML."""
    plain = _sweep_file(tmp_path, [1.0, 1.2])
    bom = tmp_path / "bom.toml"
    bom.write_bytes(b"\xef\xbb\xbf" + plain.read_bytes())
    assert Sweep.from_toml(bom).cases == Sweep.from_toml(plain).cases


def test_a_case_with_a_tolerance_has_its_step_chosen_as_simulate_does(tmp_path: Path) -> None:
    """A sweep over sea.height with solver.tolerance: every case runs (not refused at compile time for lack of a
    step) and records the choice, as a lone ``simulate`` would."""
    base = {
        "device": {"name": "m4-111"},
        "sea": {"kind": "jonswap", "height": 0.04, "period": 1.2, "duration": "12 Tp", "ramp": "2 Tp"},
        "solver": {"method": "beeman", "tolerance": 1e-2},
        "outputs": {"statistics_only": True, "variables": []},
    }
    sweep = Sweep.of(Scene.from_dict(base), {"sea.height": [0.04, 0.05]})
    ds = run_sweep(sweep, tmp_path / "out")
    assert ds.sizes["sea.height"] == 2 and np.all(np.isfinite(ds.mean_pto_power.values))
    paths = sorted((tmp_path / "out").glob("c[0-9]*.nc"))  # the cases, not combined.nc
    assert len(paths) == 2
    for path in paths:
        with xr.open_dataset(path) as case:
            assert case.attrs["solver_tolerance"] == 1e-2 and case.attrs["solver"] == "beeman"
            assert Scene.from_json(case.attrs["scene"]).solver.tolerance is None  # the scene that ran
