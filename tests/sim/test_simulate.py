"""``simulate`` is the one entry point: the scene's ``solver.method`` chooses a nonlinear, linear or
frequency-domain run, and every run describes its own solver in the result (issue 12)."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from tests.sim.scenes import HeldDamping, scene
from wecss.linear import linearize, steady_state
from wecss.sim import SceneError, compile_scene, simulate, simulate_linear

REPEAT = 24.0  # 4000 steps of Tp/200: the record repeats exactly over the run
SEA = {"height": 0.004, "duration": REPEAT, "d_omega": 2 * np.pi / REPEAT, "ramp": 2.0}


def _sc(method: str, **solver):
    radiation = {"method": "state_space" if method == "linear" else "convolution"}
    return scene(
        "m4-111",
        sea=SEA,
        solver={"method": method, **solver},
        radiation=radiation,
        outputs={"variables": ["motion", "pto", "radiation"], "window": 1.0},
    )


def test_linear_method_is_simulate_linear():
    compiled = compile_scene(_sc("linear"))
    ds = simulate(compiled)
    direct = simulate_linear(compiled)
    xr.testing.assert_identical(ds.drop_attrs(), direct.drop_attrs())
    assert ds.attrs["solver"].startswith("linear (foh")
    assert "evaluations_per_step" not in ds.attrs
    zoh = simulate(compile_scene(_sc("linear", hold="zoh")))
    assert zoh.attrs["solver"].startswith("linear (zoh")
    assert not np.allclose(zoh.pto_angle.values, ds.pto_angle.values, rtol=1e-9, atol=0)


def test_each_nonlinear_run_reports_its_own_solver():
    beeman = simulate(_sc("beeman"))
    assert beeman.attrs["solver"] == "beeman" and 2.0 < beeman.attrs["evaluations_per_step"] < 4.0
    rk4 = simulate(scene("m4-111", sea=SEA, solver={"method": "rk4"}, radiation={"method": "none"}))
    assert rk4.attrs["solver"] == "rk4" and "evaluations_per_step" not in rk4.attrs


def test_frequency_method_gives_the_steady_state_and_its_closed_form_power():
    """Over the whole periodic record (window 1.0: one period of n steps), the mean absorbed power of each PTO is
    exactly c sum_k |omega_k (G a_k)|^2 / 2, and the mean power the memory force takes is
    sum_k Re(u_k^H B(omega_k) u_k) / 2 (the added-mass part is reactive), both from the amplitudes alone."""
    compiled = compile_scene(_sc("frequency"))
    ds = simulate(compiled)
    model = linearize(compiled)
    exc = compiled.excitation
    amplitudes = np.einsum("wvj,jw->vw", model.frequency_response(exc.omega), exc.coefficients)
    exact = steady_state(compiled, compiled.time).pto_angle.values
    np.testing.assert_allclose(ds.pto_angle.values, exact, rtol=0, atol=1e-12 * np.abs(exact).max())
    c = compiled.plant.pto_damping
    rate = exc.omega * (model.pto_jacobian @ amplitudes)  # |omega G a| per PTO and component
    power = c * 0.5 * np.sum(np.abs(rate) ** 2, axis=1)
    np.testing.assert_allclose(ds.mean_pto_power.values, power, rtol=1e-9)
    u = 1j * exc.omega * (model.hydro_jacobian @ amplitudes)
    damping = model.hydro.at(exc.omega)[1]
    radiated = 0.5 * np.real(np.einsum("iw,wij,jw->", u.conj(), damping, u))
    force = np.concatenate([ds.radiation_force.values, ds.radiation_moment.values], axis=1)
    names = [*ds.hydro_dof_linear.values, *ds.hydro_dof_angular.values]
    force = force[:, [names.index(d) for d in compiled.hydro.dofs]]
    v = np.concatenate([ds.velocity.values, ds.angular_velocity.values], axis=1)
    dofs = [*ds.dof_linear.values, *ds.dof_angular.values]
    v = v[:, [dofs.index(d) for d in compiled.device.model.velocity_names]]
    velocity = v @ model.hydro_jacobian.T  # the linear hydro-DOF velocities Bw v
    mean = -np.mean(np.sum(force[1:] * velocity[1:], axis=1))
    assert mean == pytest.approx(radiated, rel=1e-9)
    assert "no ramp" in ds.attrs["solver"] and "frequency domain" in ds.attrs["radiation"]


def test_frequency_method_needs_linear_gains():
    with pytest.raises(SceneError, match="'frequency' needs a controller with linear gains"):
        simulate(_sc("frequency"), controller=HeldDamping())
