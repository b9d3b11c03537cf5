"""``wecss.linear.linear_inputs``: the linear model's input vector rebuilt from a result drives the model to the
run's outputs (exactly for a linear run, to the linearisation error for a nonlinear one)."""

from __future__ import annotations

import numpy as np
import pytest

from tests.sim.scenes import scene
from wecss.linear import linear_inputs, linearize
from wecss.sim import compile_scene, simulate

REPEAT = 24.0


def _compiled(method: str, height: float = 0.004):
    sea = {"height": height, "duration": REPEAT, "d_omega": 2 * np.pi / REPEAT, "ramp": 2.0}
    return compile_scene(
        scene(
            "m4-111",
            sea=sea,
            solver={"method": method},
            radiation={"method": "state_space"},
            outputs={"variables": ["motion", "pto", "excitation"]},
        )
    )


def _drive(model, u: np.ndarray, dt: float) -> np.ndarray:
    """Outputs of ``model`` from rest at the equilibrium under ``u`` (n_t, n_u), first-order hold."""
    phi, g0, g1 = model.discretise(dt, "foh")
    c = np.asarray(model.state_space.C)
    x = np.zeros(phi.shape[0])
    out = [c @ x]
    for k in range(u.shape[0] - 1):
        x = phi @ x + g0 @ u[k] + g1 @ u[k + 1]
        out.append(c @ x)
    return np.array(out)


def _strokes(model, y: np.ndarray) -> np.ndarray:
    nv, n_pto = model.mass.shape[0], model.pto_jacobian.shape[0]
    return model.pto_stroke[None] + y[:, 2 * nv : 2 * nv + n_pto]


def _relative(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.max(np.abs(a - b)) / np.max(np.abs(b - b.mean(0))))


@pytest.fixture(scope="module")
def linear_run():
    compiled = _compiled("linear")
    return compiled, simulate(compiled)


def test_inputs_are_labelled_in_the_models_order(linear_run):
    compiled, ds = linear_run
    model = linearize(compiled)
    u = linear_inputs(ds, compiled)
    assert u.dims == ("time", "input")
    assert list(u.input.values) == list(model.state_space.input_labels)
    assert u.sizes["time"] == ds.sizes["time"]


def test_inputs_reproduce_a_linear_run_exactly(linear_run):
    """The scene's own model holds the damping controller: the PTO inputs are zero and the excitation alone drives
    the model to the run's strokes and coordinates."""
    compiled, ds = linear_run
    model = linearize(compiled)
    u = linear_inputs(ds, compiled).values
    n_h = len(compiled.hydro.dofs)
    force_scale = np.max(np.abs(ds.pto_torque.values))
    assert np.max(np.abs(u[:, n_h:])) <= 1e-12 * force_scale
    y = _drive(model, u, compiled.dt)
    assert _relative(_strokes(model, y), ds.pto_angle.values) < 1e-9
    nv = model.mass.shape[0]
    names = list(compiled.device.model.velocity_names)
    hinge = names.index("hinge_3__pitch")
    q0 = compiled.q0[hinge]
    assert _relative(q0 + y[:, hinge], ds.angle.sel(dof_angular="hinge_3__pitch").values) < 1e-9
    assert _relative(y[:, nv + hinge], ds.angular_velocity.sel(dof_angular="hinge_3__pitch").values) < 1e-9


def test_the_open_plant_driven_by_the_controller_force_gives_the_same_run(linear_run):
    """Without the folded gains, the PTO input is the damping torque -c x_dot read from the result; the open plant
    then follows the run to the first-order hold of that feedback, O(dt^2)."""
    compiled, ds = linear_run
    open_plant = linearize(compiled).with_pto_gains()
    u = linear_inputs(ds, compiled, open_plant)
    np.testing.assert_allclose(u.sel(input="force__pto_3"), -6.0 * ds.pto_angular_velocity.sel(pto="pto_3"), rtol=1e-12)
    y = _drive(open_plant, u.values, compiled.dt)
    error = _relative(_strokes(open_plant, y), ds.pto_angle.values)
    assert error < 1e-3, error  # measured 2.0e-4


def test_inputs_of_a_nonlinear_run_drive_the_linear_plant_to_its_motion_in_small_waves():
    compiled = _compiled("beeman")
    ds = simulate(compiled)
    model = linearize(compiled)
    y = _drive(model, linear_inputs(ds, compiled, model).values, compiled.dt)
    error = _relative(_strokes(model, y), ds.pto_angle.values)
    assert error < 0.01, error  # measured 3.7e-3: linearisation and Beeman


def test_a_result_without_the_excitation_is_refused(linear_run):
    compiled, ds = linear_run
    with pytest.raises(ValueError, match=r"excitation_force.*'excitation'"):
        linear_inputs(ds.drop_vars(["excitation_force", "excitation_moment"]), compiled)
    with pytest.raises(TypeError, match="CompiledScene"):
        linear_inputs(ds, compiled.scene)
