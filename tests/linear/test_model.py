"""The linearised MFM model: its state matrix against the nonlinear right-hand side, and its exact discretisation
against the frequency domain (issue 6, first part)."""

from __future__ import annotations

import numpy as np
import pytest

from tests.linear.state_equations import central_jacobian, state_derivative
from tests.sim.scenes import held, scene
from wecss.linear import steady_state
from wecss.results import mean_power
from wecss.sim import compile_scene, linearize, simulate_linear


def _rms(x: np.ndarray) -> np.ndarray:
    return np.sqrt(np.mean(np.asarray(x) ** 2, axis=0))


def _compiled(device: str = "m4-111", **sea):
    repeat = 40.0
    sea = {"height": 0.004, "duration": 2 * repeat, "d_omega": 2 * np.pi / repeat, "ramp": "5 Tp", **sea}
    return compile_scene(scene(device, sea=sea, radiation={"method": "state_space"}, outputs={"variables": ["pto"]}))


@pytest.mark.parametrize("device", ["m4-111", "m4-134"])
def test_state_matrix_is_the_jacobian_of_the_nonlinear_equations(device):
    compiled = _compiled(device)
    model = linearize(compiled)
    p, nv = compiled.plant, model.mass.shape[0]
    n_h = p.hydro_index.size
    jac = central_jacobian(state_derivative(compiled, model), np.full(model.n_states, 1e-6))
    a = np.asarray(model.state_space.A)
    assert np.max(np.abs(jac - a)) <= 1e-6 * np.max(np.abs(a))
    assert (
        model.state_space.ninputs == n_h + p.pto_kind.size
        and model.state_space.noutputs == 2 * nv + 2 * p.pto_kind.size
    )


def _model_steady_state(model, compiled, time):
    """Steady-state PTO strokes of the linear model itself: C (i omega - A)^-1 B U at the wave components."""
    exc = compiled.excitation
    a, b = np.asarray(model.state_space.A), np.asarray(model.state_space.B)
    n_h, nv = model.hydro_jacobian.shape
    out = np.zeros((time.size, model.pto_jacobian.shape[0]))
    for w, coefficients in zip(exc.omega, exc.coefficients.T, strict=True):
        x = np.linalg.solve(1j * w * np.eye(a.shape[0]) - a, b[:, :n_h] @ coefficients)
        out += np.real(np.outer(np.exp(1j * w * time), model.pto_jacobian @ x[:nv]))
    return out


def test_linear_run_matches_the_frequency_domain_and_first_order_hold_is_second_order():
    compiled = _compiled()
    model = linearize(compiled)
    ds = simulate_linear(compiled, model)
    t = ds.time.values
    late = t >= 40.0
    # against the exact frequency-domain solution from A(omega), B(omega): within the radiation fit's error
    exact = steady_state(compiled, t).pto_angle.values
    error = _rms(ds.pto_angle.values[late] - exact[late]) / _rms(exact[late] - exact[late].mean(0))
    assert np.all(error <= 1e-3), error
    assert float(mean_power(ds).sum()) > 0
    # observed order against the linear model's own steady state (no fit error): FOH about 2, ZOH about 1
    errors = {"foh": [], "zoh": []}
    for dt in (0.024, 0.012, 0.006):
        sc = compiled.scene
        c = compile_scene(type(sc)(sc.device, sc.sea, sc.controller, type(sc.solver)(dt=dt), sc.radiation, sc.outputs))
        for hold in errors:
            run = simulate_linear(c, model, hold=hold)
            tt = run.time.values
            ref = _model_steady_state(model, c, tt) + run.pto_angle.values[0]
            sel = tt >= 40.0
            errors[hold].append(
                float(np.max(_rms(run.pto_angle.values[sel] - ref[sel]) / _rms(ref[sel] - ref[sel].mean(0))))
            )
    foh = np.log2(np.array(errors["foh"][:-1]) / np.array(errors["foh"][1:]))
    zoh = np.log2(np.array(errors["zoh"][:-1]) / np.array(errors["zoh"][1:]))
    assert np.all((foh > 1.7) & (foh < 2.3)), (errors, foh)
    assert np.all((zoh > 0.8) & (zoh < 1.3)), (errors, zoh)


@pytest.mark.parametrize("device", ["m4-111", "m4-132", "m4-134"])
def test_linear_model_response_matches_the_frequency_domain_in_the_fitted_band(device):
    """PTO stroke per unit wave amplitude from C (i omega - A)^-1 B against the solution built from A(omega), B(omega)
    directly: within 1 % of its peak from 1 rad/s to the start of the fit's roll-off (0.6 omega_max)."""
    from wecss.waves import excitation_coefficients

    compiled = _compiled(device)
    model = linearize(compiled)
    omega = compiled.hydro.omega
    omega = omega[(omega >= 1.0) & (omega <= compiled.scene.radiation.band * omega[-1])]
    h_data = model.frequency_response(omega)
    a, b = np.asarray(model.state_space.A), np.asarray(model.state_space.B)
    n_h, nv = model.hydro_jacobian.shape
    h_model = np.array([np.linalg.solve(1j * w * np.eye(a.shape[0]) - a, b[:, :n_h])[:nv] for w in omega])
    x = excitation_coefficients(compiled.hydro, omega)
    g = model.pto_jacobian
    data = np.einsum("pv,wvj,jw->wp", g, h_data, x)
    fitted = np.einsum("pv,wvj,jw->wp", g, h_model, x)
    error = np.max(np.abs(fitted - data), axis=0) / np.max(np.abs(data), axis=0)
    assert np.all(error <= 0.01), error


def test_linear_model_round_trips_through_netcdf(tmp_path):
    from wecss.results import open_result, save
    from wecss.sim import LinearModel

    model = linearize(_compiled())
    path = save(model.to_dataset(), tmp_path / "linear.nc")
    again = LinearModel.from_dataset(open_result(path))
    np.testing.assert_array_equal(np.asarray(again.state_space.A), np.asarray(model.state_space.A))
    np.testing.assert_array_equal(np.asarray(again.state_space.B), np.asarray(model.state_space.B))
    assert again.state_space.state_labels == model.state_space.state_labels
    assert again.state_space.input_labels == model.state_space.input_labels
    np.testing.assert_array_equal(again.radiation.C, model.radiation.C)
    for name in ("C", "D"):
        np.testing.assert_array_equal(
            np.asarray(getattr(again.state_space, name)), np.asarray(getattr(model.state_space, name))
        )
    for name in ("mass", "damping", "stiffness", "q0", "pto_jacobian", "hydro_jacobian"):
        np.testing.assert_array_equal(getattr(again, name), getattr(model, name))


def test_a_linear_model_without_radiation_states_round_trips_through_netcdf(tmp_path):
    from wecss.results import open_result, save
    from wecss.sim import LinearModel

    model = linearize(compile_scene(scene("m4-111", radiation={"method": "none"}, outputs={"variables": ["pto"]})))
    assert model.radiation.A.shape == (0, 0)
    again = LinearModel.from_dataset(open_result(save(model.to_dataset(), tmp_path / "linear.nc")))
    for name in ("A", "B", "C", "D"):
        np.testing.assert_array_equal(
            np.asarray(getattr(again.state_space, name)), np.asarray(getattr(model.state_space, name))
        )
    assert again.radiation.A.shape == (0, 0) and again.radiation.dofs == model.radiation.dofs
    for name in ("mass", "damping", "stiffness", "pto_jacobian", "hydro_jacobian"):
        np.testing.assert_array_equal(getattr(again, name), getattr(model, name))


def test_modal_table_periods_are_roots_of_the_undamped_impedance():
    """At every finite natural period, K - omega^2 (M* + Bw'(A(omega) - A_inf) Bw) is singular."""
    from wecss.compiled import interpolate_matrices
    from wecss.linear import modal_table
    from wecss.sim import Scene

    calm = {"kind": "calm", "period": None, "duration": 10.0, "ramp": 0.0}
    sc = Scene.from_dict(
        {"device": {"name": "m4-134"}, "sea": calm, "solver": {"dt": 0.01}, "radiation": {"method": "none"}}
    )
    compiled = compile_scene(sc)
    table = modal_table(compiled)
    lin = linearize(compiled, radiation=_empty_radiation(compiled))
    ds, bw = compiled.hydro.dataset, lin.hydro_jacobian
    finite = np.isfinite(table.period.values)
    assert finite.sum() == 6 and np.isinf(table.period.values[0])  # the free surge
    assert table.converged.values.all()
    assert np.unique(np.round(table.period.values[finite], 6)).size == 6  # six distinct modes, none found twice
    for period in table.period.values[finite]:
        omega = 2 * np.pi / period
        added = interpolate_matrices(compiled.hydro.omega, ds.added_mass.values, np.array([omega]))[0]
        mass = lin.mass + bw.T @ (added - ds.added_mass_inf.values) @ bw
        singular = np.linalg.svd(lin.stiffness - omega**2 * mass, compute_uv=False)
        assert singular[-1] <= 1e-8 * singular[0]
    assert np.all((table.damping_ratio.values[finite] > 0) & (table.damping_ratio.values[finite] < 1))


def _empty_radiation(compiled):
    from wecss.radiation import RadiationStateSpace

    n = len(compiled.hydro.dofs)
    return RadiationStateSpace(np.zeros((0, 0)), np.zeros((0, n)), np.zeros((n, 0)), tuple(compiled.hydro.dofs))


def test_closed_loop_linear_run_matches_the_nonlinear_run_in_small_waves():
    """A controller without linear gains closes the loop of the linear model (force held over each step, as in the
    nonlinear simulator). At Hs 0.004 m the two differ by what linearisation leaves out (measured 0.165 % RMS of
    the hinge angle), the same for Beeman and RK4 and at dt 6 and 3 ms: neither integrator adds an error of its own
    at the held force's jumps (Beeman's history is moved by each jump; before that it added a first-order error of
    about 0.3 % at 6 ms)."""
    import dataclasses

    from wecss.sim import simulate

    differences = []
    for method, dt in (("beeman", 0.006), ("beeman", 0.003), ("rk4", 0.006)):
        compiled = _compiled(duration=30.0)
        sc = compiled.scene
        compiled = compile_scene(dataclasses.replace(sc, solver=dataclasses.replace(sc.solver, dt=dt, method=method)))
        closed = held(compiled)
        linear = simulate_linear(closed)
        nonlinear = simulate(closed)
        a, b = linear.pto_angle.values, nonlinear.pto_angle.values
        differences.append(float(np.max(_rms(a - b) / _rms(b))))
        # the torque recorded at t_k is the one that acted over the step ending there, as in the nonlinear run:
        # the controller's from the rate at the step's start
        for run in (linear, nonlinear):
            rate, torque = run.pto_angular_velocity.values, run.pto_torque.values
            np.testing.assert_allclose(torque[1:], -6.0 * rate[:-1], rtol=1e-12, atol=1e-15)
            assert np.all(torque[0] == 0.0)
    assert max(differences) <= 0.003, differences
    assert max(differences) <= 1.05 * min(differences), differences


def test_linear_models_are_cached_by_scene_fingerprint():
    """A recompiled scene, or one with other outputs, gets the same model; another sea state gets a new one."""
    import dataclasses

    compiled = _compiled()
    model = linearize(compiled)
    sc = compiled.scene
    assert linearize(compile_scene(sc)) is model
    assert linearize(compile_scene(dataclasses.replace(sc, outputs=type(sc.outputs)(variables=("motion",))))) is model
    other = compile_scene(dataclasses.replace(sc, sea=dataclasses.replace(sc.sea, height=0.008)))
    assert other.fingerprint != compiled.fingerprint
    assert linearize(other) is not model
    assert linearize(compiled, cache=False) is not model
    # a compiled scene changed after compilation (the damping moved out of the equations) is another model
    changed = linearize(held(compiled))
    assert changed is not model and np.all(changed.damping == 0.0) and np.any(model.damping != 0.0)


def test_free_surge_has_an_exactly_zero_stiffness_column():
    """No static load depends on the surge of m4-134's bow: its column is round-off, set to zero, which makes the
    surge displacement an exact integrator of the linear model (split off by the modal runs)."""
    compiled = _compiled("m4-134")
    assert np.all(compiled.stiffness[:, 0] == 0.0)
    assert np.all(np.asarray(linearize(compiled).state_space.A)[:, 0] == 0.0)


def test_controller_is_called_at_its_control_rate_in_both_simulators():
    """controller.dt = 4 steps: the force is the controller's at the start of each period and held over it, in the
    linear and in the nonlinear run; a period that is not a whole number of steps is refused."""
    import dataclasses

    from wecss.sim import SceneError, simulate

    compiled = _compiled(duration=12.0)
    sc = compiled.scene
    periodic = held(compile_scene(dataclasses.replace(sc, controller=dataclasses.replace(sc.controller, dt="Tp/50"))))
    assert periodic.scene.control_steps == 4
    for run in (simulate_linear(periodic), simulate(periodic)):
        torque, rate = run.pto_torque.values, run.pto_angular_velocity.values
        # recorded at t_k: the torque that acted over the step ending at t_k, set at the period's start
        start = 4 * ((np.arange(1, torque.shape[0]) - 1) // 4)
        np.testing.assert_allclose(torque[1:], -6.0 * rate[start], rtol=1e-12, atol=1e-15)
        assert "every 4 steps" in run.attrs["notes"]
    with pytest.raises(SceneError, match="whole number of solver steps"):
        dataclasses.replace(sc, controller=dataclasses.replace(sc.controller, dt=0.01))


def _two_coordinates(held: np.ndarray | None):
    """A hand-made linear model of two coordinates (no hydro DOF, no radiation state), M = [[2, 0.3], [0.3, 1]],
    C = [[0.1, 0.02], [0.02, 0.05]], K = [[5, -2], [-2, 40]], one PTO with transmission G = [1, 0.5] and no gain;
    ``held`` the coordinates held quasi-static."""
    from functools import partial

    from wecss.linear import HydroResponse, LinearModel
    from wecss.linear._model import _Labels, _state_space
    from wecss.radiation import RadiationStateSpace

    mass = np.array([[2.0, 0.3], [0.3, 1.0]])
    damping = np.array([[0.1, 0.02], [0.02, 0.05]])
    stiffness = np.array([[5.0, -2.0], [-2.0, 40.0]])
    bw, g = np.zeros((0, 2)), np.array([[1.0, 0.5]])
    rad = RadiationStateSpace(np.zeros((0, 0)), np.zeros((0, 0)), np.zeros((0, 0)), (), "none")
    hydro = HydroResponse(np.array([0.0, 10.0]), np.zeros((2, 0, 0)), np.zeros((2, 0, 0)))
    labels = _Labels(("a", "b"), ("pto",), (), "two")
    build = partial(_state_space, labels, rad, mass, damping, stiffness, bw, g, held)
    return LinearModel(
        mass, damping, stiffness, mass, bw, g, hydro, np.zeros(2), np.zeros(1), np.zeros(1), np.zeros(1), rad, None,
        build, None, held,
    )  # fmt: skip


def test_a_held_coordinate_is_condensed_as_the_closed_form_says():
    """Two coordinates, the second held quasi-static (no rate, no acceleration): by hand, its row
    0.3 a1 + 0.02 v1 - 2 x1 + 40 x2 = f2 gives x2, and the first row becomes (2 + 0.3 * 2/40) a1 + (0.1 + 0.02 *
    2/40) v1 + (5 - 4/40) x1 = f1 + f2 * 2/40: m = 2.015, c = 0.101, k = 4.9. The condensed state matrix has the
    eigenvalues of m s^2 + c s + k (natural frequency sqrt(4.9 / 2.015) rad/s undamped); a unit PTO force (generalised
    force [1, 0.5]) gives, at rest, x2 = (0.5 - 0.3 * 1.025 / 2.015) / 40 through the feedthrough (and the stroke
    0.5 x2), and statically
    the full solution K^-1 [1, 0.5] = [41, 4.5] / 196; Z(omega) solves to the same response as the condensed
    system's transfer function. A PTO stiffness of 3 N/m folded in (with_pto_gains) condenses K + 3 G'G: k = 8 -
    0.25 / 40.75, m = 2 + 0.15 / 40.75, c = 0.1 + 0.01 / 40.75. The same model with nothing held has 4 states."""
    model = _two_coordinates(np.array([False, True]))
    system = model.state_space
    a, b, c, d = (np.asarray(x) for x in (system.A, system.B, system.C, system.D))
    assert a.shape == (2, 2) and model.n_kept == 1 and list(system.state_labels) == ["a", "a__rate"]
    m, cc, k = 2.015, 0.101, 4.9
    np.testing.assert_allclose(np.sort_complex(np.linalg.eigvals(a)), np.sort_complex(np.roots([m, cc, k])), rtol=1e-14)
    print(f"condensed natural frequency {np.sqrt(k / m):.6f} rad/s (undamped)")
    np.testing.assert_allclose(np.abs(np.linalg.eigvals(a)), np.sqrt(k / m), rtol=1e-14)  # |s| = sqrt(k / m)
    x2 = (0.5 - 0.3 * 1.025 / 2.015) / 40
    np.testing.assert_allclose(d[:, 0], [0.0, x2, 0.0, 0.0, 0.5 * x2, 0.0], rtol=1e-14, atol=1e-16)
    static = -c @ np.linalg.solve(a, b) + d  # outputs: a, b, their rates, the stroke and its rate
    np.testing.assert_allclose(static[:, 0], [41 / 196, 4.5 / 196, 0, 0, (41 + 0.5 * 4.5) / 196, 0], atol=1e-15)
    w = 0.8
    transfer = c @ np.linalg.solve(1j * w * np.eye(2) - a, b) + d
    xi = np.linalg.solve(model.dynamic_stiffness(np.array([w]))[0], model.pto_jacobian.T[:, 0])
    np.testing.assert_allclose(transfer[:2, 0], xi, rtol=1e-13)
    np.testing.assert_allclose(transfer[2:4, 0], [1j * w * xi[0], 0.0], rtol=1e-13)  # the held rate is zero
    # by hand: Z's held column keeps its stiffness only
    z = np.array([[-(w**2) * 2 + 1j * w * 0.1 + 5, -2], [-(w**2) * 0.3 + 1j * w * 0.02 - 2, 40]])
    np.testing.assert_allclose(xi, np.linalg.solve(z, [1.0, 0.5]), rtol=1e-14)
    stiffer = model.with_pto_gains(0.0, 3.0).state_space
    m2, c2, k2 = 2 + 0.15 / 40.75, 0.1 + 0.01 / 40.75, 8 - 0.25 / 40.75
    np.testing.assert_allclose(np.sort_complex(np.linalg.eigvals(np.asarray(stiffer.A))),
                               np.sort_complex(np.roots([m2, c2, k2])), rtol=1e-14)  # fmt: skip
    assert list(stiffer.output_labels) == list(system.output_labels)
    assert _two_coordinates(None).state_space.nstates == 4


def test_a_model_with_held_coordinates_is_refused_where_its_states_must_be_every_coordinate():
    """The MPC horizon model and the excitation estimator take the coordinates as the first states: a condensed
    model is refused by name, not run on the wrong states."""
    from wecss.control.mpc import HorizonModel

    model = _two_coordinates(np.array([False, True]))
    with pytest.raises(ValueError, match=r"the MPC horizon model: the linear model condenses 1 modal coordinates "
                                         r"held quasi-static .*velocities \[1\]"):  # fmt: skip
        HorizonModel.of(model, 0.1, 3)
