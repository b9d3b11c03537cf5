"""Scenes whose device has an elastic body (``flexible.dynamics = "elastic"``, issue 28): the NOTC device with its arm
elastic (the cylinder's end on the arm's node) compiles with the arm's modal coordinates in the plant; the explicit
schemes refuse a step its modes cannot take and say which step would; the linear model's mass is the multibody
core's at the equilibrium's deflection and its state matrix the kernels' Jacobian; a generalised-alpha run at the
wave step is the exact frequency-domain solution (the loads of such runs: ``test_elastic_loads.py``)."""

from __future__ import annotations

import re

import numpy as np
import pytest
from scipy.linalg import eigh

import wecss.hydro
from tests.linear.state_equations import central_jacobian, held_state_derivative, state_derivative
from wecss.control import ControlContext, Controller, Measurement, pto_control_force
from wecss.multibody import Dynamics
from wecss.scene import SceneError
from wecss.sim import compile_scene, linearize

from .scenes import elastic_notc_spec, scene

T = 6.2


@pytest.fixture(scope="module", autouse=True)
def _database():
    if "notc-10kw" not in wecss.hydro.available():
        pytest.skip("shipped database notc-10kw not generated yet")


@pytest.fixture(scope="module")
def elastic_spec(tmp_path_factory) -> str:
    """The NOTC spec with its arm elastic (its flexible table given ``dynamics = "elastic"``)."""
    return elastic_notc_spec(tmp_path_factory.mktemp("spec"))


def _scene(spec: str, method: str, dt: float):
    sea = {"kind": "regular", "height": 0.28, "period": T, "duration": 4 * T, "ramp": T}
    return scene(
        spec, sea=sea, controller={"name": "damping", "parameters": {}}, solver={"method": method, "dt": dt},
        radiation={"method": "state_space"},
    )  # fmt: skip


def test_the_elastic_arm_enters_the_plant(elastic_spec):
    compiled = compile_scene(_scene(elastic_spec, "beeman", 1e-4))
    model = compiled.device.model
    assert model.body("arm").elastic is not None
    assert model.velocity_names[:2] == ("pivot__pitch", "tip__pitch") and model.nv == 2 + model.body("arm").elastic.n
    assert compiled.plant.twists.shape[0] == model.nv
    # the static equilibrium deflects the arm (its weight and the float's load) and holds the core's forces at zero
    xi0 = compiled.q0[2:]
    assert np.abs(xi0).max() > 1e-4


@pytest.mark.parametrize("method", ["rk4", "beeman"])
def test_explicit_schemes_refuse_a_step_the_elastic_modes_cannot_take(elastic_spec, method):
    """At the wave step the arm's stiff modal coordinates make both explicit schemes unstable: refused, with the step
    that would do. The oracle: the eigenvalues s of the multibody core's equations linearised at the equilibrium
    (M*(q0) with the database's A_inf, the static stiffness, the cylinder's damping on its node and the arm's
    structural damping); RK4's largest step keeps
    every 1.1 s dt inside |R(z)| <= 1 (found here by bisection; the check also visits other configurations, so
    its step may only be shorter), Beeman's keeps 1.1 omega dt <= 2 for the undamped frequencies (its position
    step is explicit, like Stormer-Verlet's; damping goes through its implicit corrector)."""
    with pytest.raises(SceneError, match=r"elastic modes of \['arm'\]") as info:
        compile_and_check(_scene(elastic_spec, method, 0.05))
    limit = float(re.search(r"needs? dt <= ([0-9.e+-]+) s", str(info.value)).group(1))  # type: ignore[union-attr]
    compiled = compile_scene(_scene(elastic_spec, "beeman", 1e-4))
    model = compiled.device.model
    mass = Dynamics(model, compiled.coupling.added_mass_inf).terms(compiled.q0, np.zeros(model.nv)).mass
    if method == "beeman":
        expected = 2.0 / 1.1 / float(np.sqrt(eigh(compiled.stiffness, mass, eigvals_only=True).max()))
        assert limit == pytest.approx(expected, rel=0.01)
    else:
        from wecss.multibody import kinematics

        (cylinder,) = compiled.device.ptos  # its damping along its transmission from the core's kinematics
        _, g = cylinder.stroke(model, compiled.q0, kinematics(model, compiled.q0))
        damping = cylinder.damping * np.outer(g, g)
        flex = slice(model.mode_velocity_start[1], model.mode_velocity_start[2])  # the arm's structural damping
        damping[flex, flex] += model.body("arm").elastic.invariants.modal_damping  # type: ignore[union-attr]
        nv = model.nv
        a = np.block([[np.zeros((nv, nv)), np.eye(nv)], [-np.linalg.solve(mass, compiled.stiffness),
                                                          -np.linalg.solve(mass, damping)]])  # fmt: skip
        expected = _rk4_step(1.1 * np.linalg.eigvals(a))
        assert 0.9 * expected <= limit <= 1.01 * expected
    print(f"{method}: refused with dt <= {limit:.4g} s; at the equilibrium the largest stable step is {expected:.4g} s")


def _rk4_step(s: np.ndarray) -> float:
    """The largest h with |R(s h)| <= 1 for every eigenvalue s (RK4's stability function R), by bisection."""

    def stable(h: float) -> bool:
        z = s * h
        return bool(np.all(np.abs(1 + z + z**2 / 2 + z**3 / 6 + z**4 / 24) <= 1 + 1e-12))

    low, high = 0.0, 10.0 / np.abs(s).max()
    for _ in range(60):
        middle = 0.5 * (low + high)
        low, high = (middle, high) if stable(middle) else (low, middle)
    return low


def compile_and_check(sc) -> None:
    """Compile ``sc`` and run its runner's checks made before the clock starts."""
    compiled = compile_scene(sc)
    sc.runner.prepare(compiled)


def test_the_linear_model_takes_the_mass_at_the_equilibrium_s_deflection(elastic_spec):
    """The linear model's database mass is B'(M(xi0) + A_inf)B from the plant's kinematics and the deflected mass;
    the multibody core's M*(q0) is the oracle. The undeformed mass differs by more than the tolerance (the test can
    fail)."""
    compiled = compile_scene(_scene(elastic_spec, "beeman", 1e-4))
    model = linearize(compiled, cache=False)
    dev = compiled.device.model
    core = Dynamics(dev, compiled.coupling.added_mass_inf).terms(compiled.q0, np.zeros(dev.nv)).mass
    scale = np.abs(core).max()
    np.testing.assert_allclose(model.database_mass, core, rtol=0, atol=1e-12 * scale)
    undeformed = (
        Dynamics(dev, compiled.coupling.added_mass_inf)
        .terms(np.concatenate([compiled.q0[:2], np.zeros(dev.nv - 2)]), np.zeros(dev.nv))
        .mass
    )
    assert np.abs(undeformed - core).max() > 1e-9 * scale


def test_the_linear_model_s_state_matrix_is_the_jacobian_of_the_elastic_equations(elastic_spec):
    """The state matrix of the linear model (radiation states included) against central differences of the
    nonlinear right-hand side of the compiled plant (its kernels: M*(q) with the arm's M(xi), the quadratic-velocity
    terms, the cylinder on the arm's node, the geometric stiffening) about the equilibrium, to 1e-8 of its largest
    entry and of each
    block's (stiffness, damping, radiation coupling both ways). Central differences of step 1e-6 in the
    configuration and the velocities, 1 in the radiation states (the right-hand side is linear in them)."""
    compiled = compile_scene(_scene(elastic_spec, "generalized-alpha", 0.05))
    model = linearize(compiled, cache=False)
    nv, n = model.mass.shape[0], model.n_states
    rhs = state_derivative(compiled, model)
    rest = rhs(np.zeros(n))
    a = np.asarray(model.state_space.A)
    steps = np.where(np.arange(n) < 2 * nv, 1e-6, 1.0)  # the right-hand side is linear in the radiation states
    jac = central_jacobian(rhs, steps)
    error = np.max(np.abs(jac - a)) / np.max(np.abs(a))
    # and per block (stiffness, damping, radiation coupling rows and columns), each to its own largest entry
    blocks = [(slice(nv, 2 * nv), slice(0, nv)), (slice(nv, 2 * nv), slice(nv, 2 * nv)),
              (slice(nv, 2 * nv), slice(2 * nv, n)), (slice(2 * nv, n), slice(nv, 2 * nv))]  # fmt: skip
    each = [np.max(np.abs(jac[b] - a[b])) / np.max(np.abs(a[b])) for b in blocks]
    worst = max(each)
    print(f"per block: {worst:.2e}")
    assert worst <= 1e-8
    print(
        f"elastic NOTC: state matrix against the Jacobian {error:.2e} of its largest entry; "
        f"rest {np.abs(rest).max():.2e}"
    )
    assert np.abs(rest[nv : 2 * nv]).max() <= 1e-9 * np.abs(a[nv : 2 * nv]).max()  # the equilibrium is the kernels'
    assert error <= 1e-8


class _HeldSpringDamper(Controller):
    """f = -c x_dot - k x from the measured stroke and rate, held over each step (no ``linear_gains``); it keeps
    the strokes it measured (``seen``: time, stroke)."""

    needs_state = False

    def __init__(self, damping: float, stiffness: float) -> None:
        self.c, self.k = np.array([damping]), np.array([stiffness])
        self.seen: list[tuple[float, float]] = []

    def setup(self, context: ControlContext) -> None:
        assert context.n_pto == 1

    def compute(self, t: float, measurement: Measurement) -> np.ndarray:
        self.seen.append((t, float(measurement.displacement[0])))
        return pto_control_force(0.0, self.c, self.k, measurement.displacement, measurement.velocity)


def test_a_linear_run_with_held_coordinates_is_the_generalised_alpha_run(tmp_path):
    """The arm above 30 Hz held quasi-static, the small regular wave (H 0.02 m, 12 periods): the linear runner
    (``solver.method = "linear"``, the condensed model stepped exactly) against generalised-alpha, the same scene.
    Open loop (the cylinder's damping folded into the model), at dt 0.05 s: over the last two periods the pivot
    angle, the cylinder's stroke, a kept and a held modal coordinate agree to 2e-3 of their amplitudes (the
    scheme's error at that step and the wave's nonlinearity). Closed loop (a spring-damper controller without
    linear gains, a tenth of the cylinder's damping and 20 kN/m, its force held over each step): the stroke the
    controller measured at each step is the one the run records there (the held coordinates' values fed through
    by the force of the step before), to 1e-12 of the stroke's range, in both runs; at dt 0.025 s the two runs
    agree to 5e-3 of the amplitudes (measured 4.1e-3, 2.4e-3, 1.8e-3 for the pivot at 0.05, 0.025, 0.0125 s:
    generalised-alpha's error on the held force's jumps, and the nonlinearity). The held coordinates' rates and
    accelerations are zero in every run; an initial displacement of a held coordinate is refused by the linear
    runner (its condensed model has no such state)."""
    import dataclasses

    from wecss.sim import simulate

    spec = _held_spec(tmp_path, 30.0)
    sea = {"kind": "regular", "height": 0.02, "period": T, "duration": 12 * T, "ramp": 2 * T}
    kwargs = {"sea": sea, "controller": {"name": "damping", "parameters": {}}, "radiation": {"method": "state_space"},
              "outputs": {"variables": ["motion", "pto"]}}  # fmt: skip
    runs = {}
    for method in ("linear", "generalized-alpha"):
        compiled = compile_scene(scene(spec, solver={"method": method, "dt": 0.05}, **kwargs))
        runs[method, "open"] = simulate(compiled)
        compiled = compile_scene(scene(spec, solver={"method": method, "dt": 0.025}, **kwargs))
        (damping,) = compiled.plant.pto_damping
        plant = compiled.plant._replace(pto_damping=np.zeros_like(compiled.plant.pto_damping))
        controller = _HeldSpringDamper(0.1 * float(damping), 2e4)  # 320 kN s/m held over a step is unstable
        closed = dataclasses.replace(compiled, plant=plant, controller=controller, linear_controller=False)
        runs[method, "closed"] = ds = simulate(closed)
        seen = np.array(controller.seen)
        recorded = ds.pto_displacement.isel(pto=0).values
        steps = np.rint(seen[:, 0] / 0.025).astype(int)
        assert steps.size == recorded.size - 1 and np.array_equal(steps, np.arange(steps.size))
        span = recorded.max() - recorded.min()
        assert np.abs(seen[:, 1] - recorded[:-1]).max() <= 1e-12 * span
    held = compiled.device.model.quasi_static_velocities
    names = list(compiled.device.model.velocity_names)
    held_names = [n for n, h in zip(names, held, strict=True) if h]
    for loop, tolerance in (("open", 2e-3), ("closed", 5e-3)):
        linear, alpha = runs["linear", loop], runs["generalized-alpha", loop]
        assert linear.attrs["solver"].startswith("linear")
        late = linear.time.values >= 10 * T
        pairs = {
            "pivot__pitch": (linear.angle.sel(dof_angular="pivot__pitch"), alpha.angle.sel(dof_angular="pivot__pitch")),
            "stroke": (linear.pto_displacement.isel(pto=0), alpha.pto_displacement.isel(pto=0)),
        }
        for name in ("arm__flex1", "arm__flex3"):
            pairs[name] = tuple(r.generalised_coordinate.sel(dof_generalised=name) for r in (linear, alpha))
        for name, (got, want) in pairs.items():
            got, want = got.values[late], want.values[late]
            span = 0.5 * (want.max() - want.min())
            error = np.abs(got - want).max() / span
            print(f"{loop} loop, {name}: linear against generalised-alpha {error:.2e} of the amplitude {span:.3g}")
            assert error < tolerance
        for run in (linear, alpha):
            for variable in ("generalised_velocity", "generalised_acceleration"):
                assert not np.any(run[variable].sel(dof_generalised=held_names).values)
    given = scene(spec, solver={"method": "linear", "dt": 0.05}, initial={"displacement": {"arm__flex3": 1e-4}},
                  **kwargs)  # fmt: skip
    with pytest.raises(SceneError, match=r"initial.displacement or initial.velocity gives \['arm__flex3'\] a value"):
        simulate(given)  # the condensed model has no such state: refused, not ignored


def test_the_condensed_state_matrix_is_the_jacobian_of_the_held_equations(tmp_path):
    """The arm's coordinates above 30 Hz held quasi-static (the two lowest kept): the linear model's states are the
    kept coordinates, their rates and the radiation states, and its state matrix is the Jacobian of the nonlinear
    equations the generalised-alpha runner solves (the compiled plant's kernels with the held coordinates' rates
    zero, their values solving their algebraic equations, the accelerations the kernels give them zero, at every
    perturbed state: ``tests.linear.state_equations.held_state_derivative``), by central differences (step 1e-6 in
    the kept coordinates and rates, 1 in the radiation states), to 1e-8 of each block's largest entry. Static
    condensation without the kept accelerations' inertia on the held rows (condensed mass M_rr in place of
    M_rr - K_rh K_hh^-1 M_hr) is farther from it than 1e-5: the test tells them apart."""
    spec = _held_spec(tmp_path, 30.0)
    compiled = compile_scene(_scene(spec, "generalized-alpha", 0.05))
    model = linearize(compiled, cache=False)
    held = compiled.device.model.quasi_static_velocities
    np.testing.assert_array_equal(model.held, held)
    n, n_r = model.n_states, model.n_kept
    assert n_r == 4 and n == 2 * n_r + model.radiation.n_states  # type: ignore[union-attr]
    assert list(model.state_space.state_labels[:n_r]) == ["pivot__pitch", "tip__pitch", "arm__flex1", "arm__flex2"]
    rhs = held_state_derivative(compiled, model)
    rest = rhs(np.zeros(n))
    a = np.asarray(model.state_space.A)
    jac = central_jacobian(rhs, np.where(np.arange(n) < 2 * n_r, 1e-6, 1.0))
    blocks = [(slice(n_r, 2 * n_r), slice(0, n_r)), (slice(n_r, 2 * n_r), slice(n_r, 2 * n_r)),
              (slice(n_r, 2 * n_r), slice(2 * n_r, n)), (slice(2 * n_r, n), slice(n_r, 2 * n_r))]  # fmt: skip
    each = [np.max(np.abs(jac[b] - a[b])) / np.max(np.abs(a[b])) for b in blocks]
    np.testing.assert_array_equal(jac[:n_r], a[:n_r])  # the kept coordinates' rates
    kept, out = ~held, held
    k, m = model.stiffness, model.mass
    transfer = k[np.ix_(kept, out)] @ np.linalg.inv(k[np.ix_(out, out)])
    condensed_k = k[np.ix_(kept, kept)] - transfer @ k[np.ix_(out, kept)]
    without = -np.linalg.solve(m[np.ix_(kept, kept)], condensed_k)  # no inertia of the kept motion on held rows
    stiffness_block = jac[n_r : 2 * n_r, :n_r]
    wrong = np.abs(without - stiffness_block).max() / np.abs(stiffness_block).max()
    print(f"held above 30 Hz: state matrix against the Jacobian, per block {[f'{e:.1e}' for e in each]}; rest "
          f"{np.abs(rest).max():.1e}; condensed without M_hr {wrong:.1e}")  # fmt: skip
    assert max(each) <= 1e-8
    assert np.abs(rest[n_r : 2 * n_r]).max() <= 1e-9 * np.abs(a[n_r : 2 * n_r]).max()
    assert wrong > 1e-5


def test_the_condensed_model_is_the_full_equations_with_the_held_columns_out(tmp_path):
    """The condensed state space (arm above 30 Hz held) keeps every coordinate among its outputs: its static gain
    -C A^-1 B + D is the full static solution K^-1 [Bw', G'] of every coordinate, the held ones through the
    feedthrough D (to 1e-12); and its transfer function C (i w - A)^-1 B + D at 0.3, 1 and 3 rad/s is the solution
    of the full equations written here, -w^2 M[:, r] + i w (C[:, r] + Bw' K_r(w) Bw[:, r]) + K with the radiation
    fit's K_r(w) = C_r (i w - A_r)^-1 B_r (the held columns of inertia and damping out), for the coordinates, and
    i w times the kept ones' for their rates, zero for the held ones' (to 1e-9). ``coordinate_maps`` gives the same
    held values from a state and a force; the model made again with its own radiation states or PTO gains is the
    same, and written for netCDF and read back keeps its mask. Control design's PTO admittance
    (``wecss.control.design.pto_response``) is the stroke rate of the kept coordinates of the same equations, from
    the database's A(omega) and B(omega) (to 1e-12)."""
    from wecss.control.design import pto_response
    from wecss.linear import LinearModel

    spec = _held_spec(tmp_path, 30.0)
    model = linearize(compile_scene(_scene(spec, "generalized-alpha", 0.05)), cache=False)
    system, rad, held = model.state_space, model.radiation, model.held
    assert rad is not None and held is not None
    a, b, c, d = (np.asarray(x) for x in (system.A, system.B, system.C, system.D))
    nv = held.size
    forces = np.hstack([model.hydro_jacobian.T, model.pto_jacobian.T])
    static = -c @ np.linalg.solve(a, b) + d
    full = np.linalg.solve(model.stiffness, forces)
    assert np.abs(static[:nv] - full).max() <= 1e-12 * np.abs(full).max()
    assert np.abs(d[:nv][held]).max() > 1e-3 * np.abs(full[held]).max()  # the held values feed through
    bw, kept = model.hydro_jacobian, (~held).astype(float)
    for w in (0.3, 1.0, 3.0):
        memory = rad.C @ np.linalg.solve(1j * w * np.eye(rad.n_states) - rad.A, rad.B)
        z = -(w**2) * model.mass * kept + 1j * w * (model.damping * kept + bw.T @ memory @ bw * kept) + model.stiffness
        xi = np.linalg.solve(z, forces)
        response = c @ np.linalg.solve(1j * w * np.eye(a.shape[0]) - a, b) + d
        want = np.vstack([xi, 1j * w * xi * kept[:, None]])
        error = np.abs(response[: 2 * nv] - want).max() / np.abs(want).max()
        print(f"{w} rad/s: {error:.1e}")
        assert error <= 1e-9
    # the PTO admittance of control design: the stroke rate of the kept coordinates, from the database's Z
    omega = np.array([0.7, 1.3])
    _, admittance = pto_response(model, omega, np.ones((bw.shape[0], omega.size)))
    added, radiation = model.hydro.at(omega)
    g = model.pto_jacobian
    for j, w in enumerate(omega):
        inertia = (model.database_mass + bw.T @ added[j] @ bw) * kept
        losses = (model.damping + bw.T @ radiation[j] @ bw) * kept
        xi = np.linalg.solve(-(w**2) * inertia + 1j * w * losses + model.stiffness, g.T)
        want = 1j * w * (g * kept) @ xi
        assert np.abs(admittance[j] - want).max() <= 1e-12 * np.abs(want).max()
        assert np.abs(want - 1j * w * g @ xi).max() > 1e-6 * np.abs(want).max()  # the held part moves the stroke
    rng = np.random.default_rng(5)
    x, f = rng.normal(size=a.shape[0]), rng.normal(size=nv)
    x_map, y_map = model.coordinate_maps()
    u = np.linalg.lstsq(forces, f, rcond=None)[0]  # inputs whose generalised force is f's projection
    f = forces @ u
    np.testing.assert_allclose(x_map @ x + y_map @ f, (c @ x + d @ u)[:nv], rtol=1e-12, atol=1e-14)
    same = model.with_radiation(rad).state_space  # made again with the same radiation states: the same system
    for mine, theirs in zip((same.A, same.B, same.C, same.D), (a, b, c, d), strict=True):
        np.testing.assert_array_equal(np.asarray(mine), theirs)
    folded = model.with_pto_gains(model.pto_damping, model.pto_stiffness).state_space  # the same gains folded in
    np.testing.assert_allclose(np.asarray(folded.A), a, rtol=0, atol=1e-9 * np.abs(a).max())
    np.testing.assert_allclose(np.asarray(folded.D), d, rtol=0, atol=1e-9 * np.abs(d).max())
    back = LinearModel.from_dataset(model.to_dataset())  # the netCDF layout keeps the mask and the matrices
    np.testing.assert_array_equal(back.held, held)
    np.testing.assert_array_equal(np.asarray(back.state_space.D), d)
    np.testing.assert_array_equal(back.force_input, model.force_input)


def test_a_device_without_held_coordinates_keeps_its_linear_model(elastic_spec):
    """No coordinate held: no condensation (``held`` None, every coordinate a state), and the state matrix, input
    matrix, force input and Z(omega) are exactly (bit for bit) those of the uncondensed formulas."""
    compiled = compile_scene(_scene(elastic_spec, "generalized-alpha", 0.05))
    model = linearize(compiled, cache=False)
    assert model.held is None and model.n_kept == model.mass.shape[0]
    nv, rad = model.mass.shape[0], model.radiation
    assert rad is not None
    minv = np.linalg.inv(model.mass)
    a = np.asarray(model.state_space.A)
    np.testing.assert_array_equal(a[nv : 2 * nv, :nv], -minv @ model.stiffness)
    np.testing.assert_array_equal(a[nv : 2 * nv, nv : 2 * nv], -minv @ model.damping)
    np.testing.assert_array_equal(a[nv : 2 * nv, 2 * nv :], -minv @ model.hydro_jacobian.T @ rad.C)
    np.testing.assert_array_equal(np.asarray(model.state_space.B)[nv : 2 * nv, : rad.dofs.__len__()],
                                  minv @ model.hydro_jacobian.T)  # fmt: skip
    np.testing.assert_array_equal(np.asarray(model.state_space.D), 0.0)
    np.testing.assert_array_equal(model.force_input[nv : 2 * nv], minv)
    omega = np.array([0.5, 1.0])
    added, damping = model.hydro.at(omega)
    bw = model.hydro_jacobian
    z = (-(omega**2)[:, None, None] * (model.database_mass[None] + bw.T @ added @ bw)
         + 1j * omega[:, None, None] * (model.damping[None] + bw.T @ damping @ bw) + model.stiffness[None])  # fmt: skip
    np.testing.assert_array_equal(model.dynamic_stiffness(omega), z)
    x_map, y_map = model.coordinate_maps()
    np.testing.assert_array_equal(x_map, np.eye(nv, model.n_states))
    assert not np.any(y_map)


def test_a_generalised_alpha_run_of_the_elastic_arm_is_the_exact_frequency_domain_solution(elastic_spec):
    """A small regular wave (H 0.02 m, T 6.2 s), the arm elastic, run with generalised-alpha at the wave step
    (dt 0.05 s, where no explicit step can carry the arm's modes): over the last two of twelve periods, the pivot angle
    and the arm's two largest modal coordinates follow the exact frequency-domain steady state (the database's
    A(omega) and B(omega), no radiation fit, no time stepping) to 2e-3 of their amplitudes (measured 6.4e-4, 3.5e-4,
    3.5e-4: the radiation fit, the scheme's error and the wave's nonlinearity)."""
    from wecss.linear import steady_state
    from wecss.sim import simulate

    sea = {"kind": "regular", "height": 0.02, "period": T, "duration": 12 * T, "ramp": 2 * T}
    sc = scene(
        elastic_spec, sea=sea, controller={"name": "damping", "parameters": {}}, radiation={"method": "state_space"},
        solver={"dt": 0.05}, outputs={"variables": ["motion", "pto"]},
    )  # fmt: skip
    compiled = compile_scene(sc)
    ds = simulate(compiled)
    assert ds.attrs["solver"] == "generalized-alpha"  # chosen: no method named, Beeman cannot carry the modes
    notes = ds.attrs["notes"].split("\n")
    assert any("generalized-alpha chosen" in note for note in notes)
    assert any("generalised-alpha damps the modes far above 1/dt" in note for note in notes)
    late = ds.time.values >= 10 * T
    exact = steady_state(compiled, ds.time.values)
    pairs = [(ds.angle.sel(dof_angular="pivot__pitch"), exact.angle.sel(dof_angular="pivot__pitch"))]
    pairs += [(ds.generalised_coordinate.sel(dof_generalised=n), exact.generalised_coordinate.sel(dof_generalised=n))
              for n in ("arm__flex1", "arm__flex2")]  # fmt: skip
    for got, want in pairs:
        got, want = got.values[late], want.values[late]
        amplitude = np.abs(want - want.mean()).max()
        error = np.abs(got - want).max() / amplitude
        print(f"{got.size} steps: {error:.2e} of the amplitude {amplitude:.3g}")
        assert error < 2e-3


def test_the_cylinder_rides_on_the_arm_s_node_in_the_kernels(elastic_spec):
    """The cylinder's end on the elastic arm (its attachment ``pto:cylinder``): the kernels' stroke and
    transmission equal the multibody core's (``ActuatorPTO.stroke``, the attachment's product of exponentials and
    its Jacobian) at random deformed states, to 1e-12; and they differ from an end fixed to the undeformed arm."""
    from wecss.compiled.kernels import kinematics as kernel_kinematics
    from wecss.compiled.kernels import pto_strokes
    from wecss.multibody import kinematics

    compiled = compile_scene(_scene(elastic_spec, "beeman", 1e-4))
    model, p = compiled.device.model, compiled.plant
    (cylinder,) = compiled.device.ptos
    rng = np.random.default_rng(3)
    moved = 0.0
    for _ in range(3):
        q = compiled.q0 + np.concatenate([rng.normal(0, 0.1, 2), rng.normal(0, 0.01, model.nv - 2)])
        rot, pos, b, _, _ = kernel_kinematics(p, q, np.zeros(model.nv))
        x, g = pto_strokes(p, q, rot, pos, b)
        stroke, transmission = cylinder.stroke(model, q, kinematics(model, q))
        assert x[0] == pytest.approx(stroke, rel=1e-12)
        np.testing.assert_allclose(g[0], transmission, rtol=0, atol=1e-12 * np.abs(transmission).max())
        undeformed = np.concatenate([q[:2], np.zeros(model.nv - 2)])
        rigid, _ = cylinder.stroke(model, undeformed, kinematics(model, undeformed))
        moved = max(moved, abs(stroke - rigid))
    assert moved > 1e-4  # the node's elastic displacement changes the stroke: the test can tell


def _held_spec(directory, above: float) -> str:
    """The elastic NOTC spec with ``quasi_static_above = above`` [Hz] (0: every modal coordinate held; 30: the two
    lowest, near 14 Hz, kept and the rest, from 88 Hz, held)."""
    return elastic_notc_spec(directory, f", quasi_static_above = {above}", f"notc-held-{above:g}.toml")


@pytest.mark.parametrize("above", [0.0, 30.0])
def test_a_run_with_the_arm_held_quasi_static_is_the_exact_quasi_static_solution(tmp_path, above):
    """The arm's modal coordinates held quasi-static: all of them (``quasi_static_above = 0``) or those above
    30 Hz (the two lowest kept). No method named, so generalised-alpha runs at dt 0.05 s (an explicit runner named
    is refused, naming them). The frequency-domain solution (``steady_state``) is the condensed linear model's:
    it equals Z(omega) of the full equations written here with the held coordinates' columns of mass, added mass,
    damping and radiation damping left out (no rate, no acceleration), their columns of stiffness kept, to 1e-12;
    and in the small regular wave, over the last two of twelve periods, the run's pivot angle, a kept modal
    coordinate (the mixed case) and held ones follow it to 2e-3 of the amplitudes (the radiation fit, the scheme's
    error at that step); the steady state's rates of the held coordinates are zero, as the run's, and the
    frequency-domain runner (``solver.method = "frequency"``) takes the device and gives that steady state."""
    from wecss.linear import linearize, steady_state
    from wecss.sim import simulate

    spec = _held_spec(tmp_path, above)
    sea = {"kind": "regular", "height": 0.02, "period": T, "duration": 12 * T, "ramp": 2 * T}
    kwargs = {"sea": sea, "controller": {"name": "damping", "parameters": {}}, "radiation": {"method": "state_space"}}
    with pytest.raises(
        SceneError, match=r"'beeman' does not solve .* \(arm__flex\d+, .*these do: frequency, generalized-alpha, linear"
    ):
        compile_scene(scene(spec, solver={"method": "beeman", "dt": 0.05}, **kwargs))
    compiled = compile_scene(scene(spec, solver={"dt": 0.05}, outputs={"variables": ["motion", "pto"]}, **kwargs))
    held = compiled.device.model.quasi_static_velocities
    assert held.sum() == compiled.device.model.nv - (2 if above == 0 else 4)
    ds = simulate(compiled)
    assert ds.attrs["solver"] == "generalized-alpha"
    assert any("are held quasi-static" in note for note in ds.attrs["notes"].split("\n"))
    model = linearize(compiled)
    waves = compiled.excitation
    (omega,) = waves.omega
    added, damping = model.hydro.at(waves.omega)
    bw = model.hydro_jacobian
    inertia = model.database_mass + bw.T @ added[0] @ bw
    losses = model.damping + bw.T @ damping[0] @ bw
    z = -(omega**2) * inertia + 1j * omega * losses + model.stiffness
    force = bw.T @ waves.coefficients[:, 0]  # the wave's generalised force amplitudes
    dynamic = np.linalg.solve(z, force)  # the dynamic model's steady state
    z[:, held] = model.stiffness[:, held]
    amplitude = np.linalg.solve(z, force)
    exact = steady_state(compiled, ds.time.values)
    names = list(compiled.device.model.velocity_names)
    modal = [n for n in names if n.startswith("arm__")]
    got_amplitudes = np.concatenate(
        [
            exact.angle_amplitude.sel(dof_angular=["pivot__pitch", "tip__pitch"]).values[0],
            exact.generalised_coordinate_amplitude.sel(dof_generalised=modal).values[0],
        ]
    )
    assert np.abs(got_amplitudes - amplitude).max() <= 1e-12 * np.abs(amplitude).max()
    held_names = [n for n, h in zip(names, held, strict=True) if h]
    rates = exact.generalised_velocity.sel(dof_generalised=held_names)
    assert not np.any(rates.values) and np.abs(exact.angular_velocity).max() > 0
    # the frequency-domain runner takes held coordinates: the same steady state, their rates and accelerations zero
    outputs = {"variables": ["motion", "pto"]}
    freq = simulate(compile_scene(scene(spec, solver={"method": "frequency", "dt": 0.05}, outputs=outputs, **kwargs)))
    for variable in ("angle", "generalised_coordinate", "generalised_velocity"):
        span = float(np.abs(exact[variable] - exact[variable].mean("time")).max())
        assert float(np.abs(freq[variable] - exact[variable]).max()) <= 1e-12 * span
    assert not np.any(freq.generalised_acceleration.sel(dof_generalised=held_names).values)
    late = ds.time.values >= 10 * T
    t = ds.time.values[late]
    checked = (
        ["pivot__pitch", "arm__flex1", "arm__flex2"] if above == 0 else ["pivot__pitch", "arm__flex1", "arm__flex3"]
    )
    for name in checked:
        k = names.index(name)
        assert (name == "pivot__pitch" or held[k]) == (name != "arm__flex1" or above == 0)
        want = compiled.q0[k] + np.real(amplitude[k] * np.exp(1j * omega * t))
        series = ds.angle.sel(dof_angular=name) if name == "pivot__pitch" else \
            ds.generalised_coordinate.sel(dof_generalised=name)  # fmt: skip
        got = series.values[late]
        span = np.abs(amplitude[k])
        error = np.abs(got - want).max() / span
        apart = np.abs(amplitude[k] - dynamic[k]) / span
        print(f"held above {above} Hz, {name} ({'held' if held[k] else 'kept'}): {error:.2e} of the amplitude "
              f"{span:.3g} (quasi-static against dynamic: {apart:.2e})")  # fmt: skip
        assert error < 2e-3
