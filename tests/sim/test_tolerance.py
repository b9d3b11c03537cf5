"""``solver.tolerance``: the step (and the integrator) chosen from an error estimate (``wecss.sim.choose_step``),
recorded in the result, checked against the reference solver; its conflicts and bad values refused."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from wecss.control import compile_scene
from wecss.scene import SceneError
from wecss.sim import Scene, choose_step, default_scene_path, simulate

TOLERANCE = 1e-3


def _scene(device: str = "m4-111", **solver) -> Scene:
    """A short run of the default sea (20 Tp, ramp 2 Tp), statistics only, with the ``solver`` fields given."""
    return Scene.from_dict(
        {
            "device": {"name": device},
            "sea": {"duration": "20 Tp", "ramp": "2 Tp"},
            "outputs": {"statistics_only": True, "variables": []},
            "solver": solver,
        }
    )


def _statistics(ds) -> np.ndarray:
    return np.stack([ds.mean_pto_power.values, ds.rms_pto_angle.values])


def _relative_error(run: np.ndarray, reference: np.ndarray) -> float:
    """Largest difference per statistic relative to the reference's largest value of that statistic."""
    return max(float(np.max(np.abs(run[i] - reference[i])) / np.max(np.abs(reference[i]))) for i in range(2))


@pytest.mark.parametrize(
    ("value", "message"),
    [
        (-1e-3, r"solver\.tolerance is a relative error in \(0, 0\.1\], such as 1e-3; got -0\.001"),
        (0, r"solver\.tolerance is a relative error in \(0, 0\.1\], such as 1e-3; got 0"),
        (0.0, r"got 0\.0"),
        (0.5, r"got 0\.5"),
        (float("nan"), r"got nan"),
        (float("inf"), r"got inf"),
        ("1e-3", r"solver\.tolerance must be a number; got '1e-3' \(str\)"),
        (True, r"solver\.tolerance must be a number; got True \(bool\)"),
        ([1e-3], r"solver\.tolerance must be a number; got \[0\.001\] \(list\)"),
    ],
)
def test_bad_tolerances_are_refused_naming_the_value(value, message):
    with pytest.raises(SceneError, match=message):
        _scene(tolerance=value)


def test_bad_tolerance_given_to_the_dataclass_directly_is_refused():
    from wecss.scene import Solver

    with pytest.raises(SceneError, match=r"solver\.tolerance is a relative error, a number in \(0, 0\.1\]"):
        Solver(tolerance="small")  # type: ignore[arg-type]


@pytest.mark.parametrize("dt", ["Tp/200", 0.01])
def test_a_step_and_a_tolerance_together_are_refused(dt):
    with pytest.raises(SceneError, match=r"solver\.dt \(.*\) and solver\.tolerance \(0\.001\) both given"):
        _scene(tolerance=TOLERANCE, dt=dt)


@pytest.mark.parametrize(
    ("method", "reason"),
    [
        ("reference", "its own tolerance, solver.reference_rtol"),
        ("frequency", "no step error"),
        ("beeman-explicit", "replicates the paper's method"),
    ],
)
def test_runners_without_a_step_to_choose_refuse_a_tolerance(method, reason):
    with pytest.raises(SceneError, match=rf"solver\.method '{method}' does not take it: .*{reason}"):
        _scene(method=method, tolerance=TOLERANCE)


def test_a_calm_sea_has_no_statistics_to_judge():
    scene = Scene.from_dict({"sea": {"kind": "calm", "duration": 12.0, "ramp": 0.0}, "solver": {"tolerance": 1e-3}})
    with pytest.raises(SceneError, match=r"this sea is calm: give solver\.dt"):
        simulate(scene)


def test_the_default_step_and_method_stay_when_no_tolerance_is_given():
    scene = _scene()
    assert scene.solver.method is None and scene.solver.dt is None
    assert scene.runner.name == "beeman" and scene.dt == pytest.approx(1.2 / 200)


def test_a_scene_with_a_tolerance_has_no_step_until_it_is_chosen():
    """Its step is not silently a default: asking for it, or compiling the scene, says how it gets one."""
    scene = _scene(tolerance=TOLERANCE)
    assert scene.candidates == ("rk4", "beeman")
    with pytest.raises(SceneError, match=r"solver\.dt of this scene is chosen from solver\.tolerance"):
        _ = scene.dt
    with pytest.raises(SceneError, match=r"chosen from solver\.tolerance when the run starts"):
        compile_scene(scene)
    conv = Scene.from_dict({"solver": {"tolerance": TOLERANCE}, "radiation": {"method": "convolution"}})
    assert conv.candidates == ("beeman",)  # RK4 does not run a convolution


def test_a_named_method_is_kept_and_its_step_chosen():
    choice = choose_step(_scene(method="beeman", tolerance=TOLERANCE))
    assert choice.method == "beeman" and choice.scene.solver.method == "beeman"
    assert choice.scene.solver.tolerance is None and choice.scene.dt == choice.dt
    steps = 24.0 / choice.dt  # the record repeats every 20 Tp: a whole number of steps (its excitation one FFT)
    assert steps == pytest.approx(round(steps), abs=1e-9)


def test_the_chosen_run_is_within_the_tolerance_of_the_reference_solver_and_records_its_choice():
    """m4-111, 20 Tp of the default sea: the statistics of the run whose integrator and step were chosen for
    1e-3 lie within 1e-3 of the reference solver's (DOP853, rtol 1e-10) at the same steps; the recorded estimate
    is not below the error by more than a factor 4 (the pilot's window stands for the run's within a factor of
    about 3: ``wecss.sim._tolerance.SAFETY``)."""
    scene = _scene(tolerance=TOLERANCE)
    ds = simulate(scene)
    chosen = Scene.from_json(ds.attrs["scene"])  # the scene that ran: its method and step, no tolerance
    assert chosen.solver.tolerance is None and chosen.solver.method == ds.attrs["solver"] == chosen.runner.name
    assert chosen.dt == pytest.approx(ds.attrs["time_step"], rel=1e-12)
    assert ds.attrs["solver"] in ("rk4", "beeman")
    assert ds.attrs["solver_tolerance"] == TOLERANCE
    assert 0 < ds.attrs["tolerance_estimate"] <= 0.25 * TOLERANCE * (1 + 1e-12)
    assert f"solver.tolerance = 0.001: {ds.attrs['solver']}, dt = " in ds.attrs["tolerance_choice"]
    assert chosen.dt > 1.2 / 200  # coarser than the default fixed step
    reference = simulate(dataclasses.replace(chosen, solver=dataclasses.replace(chosen.solver, method="reference")))
    error = _relative_error(_statistics(ds), _statistics(reference))
    assert error <= TOLERANCE
    assert error <= 4 * ds.attrs["tolerance_estimate"]


def test_the_estimate_of_a_named_beeman_is_checked_against_the_reference_solver():
    """Beeman named, m4-111: the chosen step's statistics within the tolerance of the reference solver's."""
    choice = choose_step(_scene(method="beeman", tolerance=TOLERANCE))
    run = simulate(choice.scene)
    reference = simulate(
        dataclasses.replace(choice.scene, solver=dataclasses.replace(choice.scene.solver, method="reference"))
    )
    error = _relative_error(_statistics(run), _statistics(reference))
    assert error <= TOLERANCE
    assert error <= 4 * choice.estimate


def test_a_step_chosen_for_a_control_period_is_a_whole_fraction_of_it():
    """A controller called every Tp/10 (held force): the chosen step divides its period."""
    scene = Scene.from_dict(
        {
            "device": {"name": "m4-111"},
            "sea": {"duration": "20 Tp", "ramp": "2 Tp"},
            "controller": {"name": "optimal-damping", "dt": "Tp/10"},
            "outputs": {"statistics_only": True, "variables": []},
            "solver": {"method": "beeman", "tolerance": TOLERANCE},
        }
    )
    choice = choose_step(scene)
    steps = 0.12 / choice.dt
    assert steps == pytest.approx(round(steps), abs=1e-9) and round(steps) >= 1
    assert choice.scene.control_steps == round(steps)


def test_the_default_scene_takes_a_tolerance_as_an_override():
    """``wecss run --set solver.tolerance=1e-3``: the embedded default gives no step of its own to conflict with."""
    from wecss.sweep import apply_overrides

    default = Scene.from_toml(default_scene_path())
    assert default.runner.name == "beeman" and default.dt == pytest.approx(1.2 / 200)
    tolerant = apply_overrides(default, ["solver.tolerance=1e-3"])
    assert tolerant.solver.tolerance == 1e-3 and tolerant.candidates == ("rk4", "beeman")


def test_the_estimate_is_of_the_last_step_the_pilots_measured(monkeypatch):
    """Pilots that always ask for a far smaller step (an error estimate of 1): at most MAX_PILOTS pairs, and the
    recorded estimate scales the last measured pair's, at the step that pair was run at."""
    from wecss.sim import _tolerance

    measured: list[float] = []

    def fake_pilot(scene, method, dt, coarse, controller):
        if dt == coarse:
            measured.append(dt)
        statistics = np.ones((2, 1)) * (2.0 if dt == coarse else 1.5)  # relative difference 1/3: estimate 2/3
        return _tolerance._PilotRun(statistics, np.zeros((2, 1)))

    monkeypatch.setattr(_tolerance, "_pilot_run", fake_pilot)
    choice = choose_step(_scene(method="beeman", tolerance=TOLERANCE))
    assert len(measured) == _tolerance.MAX_PILOTS and measured == sorted(measured, reverse=True)
    assert choice.pilot_dt == measured[-1] and choice.pilot_estimate == pytest.approx(2 / 3)
    assert choice.estimate == pytest.approx(2 / 3 * (choice.dt / choice.pilot_dt) ** 2)
    assert choice.dt < choice.pilot_dt


@pytest.mark.slow
def test_the_linear_runners_chosen_step_is_within_the_tolerance_of_a_far_finer_one():
    """``linear`` (first-order hold, second order) with a tolerance on m4-134: its statistics within the tolerance
    of the same linear model at a sixteenth of the chosen step (measured 1.9e-4; the choice takes about 15 s on a
    loaded machine: each pilot step discretises the linear model)."""
    choice = choose_step(_scene("m4-134", method="linear", tolerance=TOLERANCE))
    assert choice.method == "linear"
    run = simulate(choice.scene)
    finer = dataclasses.replace(choice.scene, solver=dataclasses.replace(choice.scene.solver, dt=choice.dt / 16))
    error = _relative_error(_statistics(run), _statistics(simulate(finer)))
    assert error <= TOLERANCE
    assert error <= 4 * choice.estimate
