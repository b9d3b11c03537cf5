"""The M4 paper's explicit added mass (``solver.added_mass = "explicit"``, its section 5.2): the same solution as
wecss's added mass in the mass matrix, iteration counts reported, and clear errors where it cannot converge."""

from __future__ import annotations

import numpy as np
import pytest

import wecss.sim._explicit as explicit
from tests.sim.scenes import scene
from wecss.compiled.kernels import kinematics
from wecss.linear import linearize
from wecss.multibody import body_mass_matrix
from wecss.sim import SceneError, SimulationDiverged, compile_scene, simulate
from wecss.sim._explicit import iteration_factor


def _run(added_mass: str, **solver):
    sc = scene(
        "m4-134",
        sea={"duration": "8 Tp", "ramp": "2 Tp"},
        solver={"dt": "Tp/100", "added_mass": added_mass, **solver},
        radiation={"method": "convolution"},
    )
    return simulate(sc)


@pytest.fixture(scope="module")
def implicit():
    return _run("implicit")


def test_tight_iteration_converges_to_the_added_mass_in_the_mass_matrix(implicit):
    # both are the same equation at the iteration's fixed point: a tight tolerance leaves only round-off
    explicit = _run("explicit", corrector_tol=1e-10, max_corrector_iterations=200)
    scale = np.max(np.abs(implicit.angle.values))
    assert scale > 1e-3
    np.testing.assert_allclose(explicit.angle.values, implicit.angle.values, rtol=0.0, atol=1e-7 * scale)
    assert explicit.attrs["evaluations_per_step"] > 2 * implicit.attrs["evaluations_per_step"]


def test_paper_tolerance_stays_within_its_one_percent(implicit):
    explicit = _run("explicit", corrector_tol=0.01)
    error = np.sqrt(np.mean((explicit.angle.values - implicit.angle.values) ** 2))
    rms = np.sqrt(np.mean(implicit.angle.values**2))
    assert error < 0.01 * rms
    assert explicit.attrs["added_mass"] == "explicit"
    assert 1.0 < explicit.attrs["evaluations_per_step"] <= explicit.attrs["max_evaluations_per_step"]
    assert 0.0 < explicit.attrs["added_mass_iteration_factor"] < 1.0


def test_iteration_factor_is_the_spectral_radius_of_the_added_over_the_rigid_mass():
    compiled = compile_scene(scene("m4-134", radiation={"method": "convolution"}))
    # independently: the linear model's M* (with the scene's A_inf) against the rigid B'MB of the multibody model
    model = linearize(compiled)
    b = kinematics(compiled.plant, compiled.q0, np.zeros(model.mass.shape[0]))[2]
    rigid = b.T @ body_mass_matrix(compiled.device.model) @ b
    expected = np.max(np.abs(np.linalg.eigvals(np.linalg.solve(rigid, model.mass - rigid))))
    assert iteration_factor(compiled.plant, compiled.q0) == pytest.approx(expected, rel=1e-9)


def test_an_iteration_that_cannot_converge_is_refused_before_the_run(monkeypatch):
    monkeypatch.setattr(explicit, "MAX_ITERATION_FACTOR", 0.1)  # m4-134's factor is about 0.6
    with pytest.raises(SceneError, match=r"added-mass iteration cannot converge .* spectral radius"):
        _run("explicit")


def test_an_iteration_that_runs_out_of_iterations_stops_the_run():
    with pytest.raises(SimulationDiverged, match=r"explicit added-mass iteration .* did not reach"):
        _run("explicit", corrector_tol=1e-12, max_corrector_iterations=2)


@pytest.mark.parametrize(
    ("solver", "match"),
    [
        ({"method": "rk4", "added_mass": "explicit"}, "needs solver.method 'beeman'"),
        ({"added_mass": "iterated"}, "solver.added_mass: unknown 'iterated'; accepted: implicit, explicit"),
    ],
)
def test_bad_added_mass_choices_are_refused(solver, match):
    with pytest.raises(SceneError, match=match):
        scene("m4-111", solver=solver, radiation={"method": "state_space"})
