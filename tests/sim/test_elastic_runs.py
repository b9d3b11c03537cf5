"""Scenes whose device has an elastic body (``flexible.dynamics = "elastic"``, issue 28): the NOTC device with its arm
elastic (the cylinder's end on the arm's node) compiles with the arm's modal coordinates in the plant; the explicit
schemes refuse a step its modes cannot take and say which step would; the linear model's mass is the multibody
core's at the equilibrium's deflection and its state matrix the kernels' Jacobian; a generalised-alpha run at the
wave step is the exact frequency-domain solution (the loads of such runs: ``test_elastic_loads.py``)."""

from __future__ import annotations

import re
from importlib import resources

import numpy as np
import pytest
from scipy.linalg import eigh

import wecss.hydro
from tests.linear.state_equations import central_jacobian, state_derivative
from wecss.multibody import Dynamics
from wecss.scene import SceneError
from wecss.sim import compile_scene, linearize

from .scenes import scene

T = 6.2


@pytest.fixture(scope="module", autouse=True)
def _database():
    if "notc-10kw" not in wecss.hydro.available():
        pytest.skip("shipped database notc-10kw not generated yet")


@pytest.fixture(scope="module")
def elastic_spec(tmp_path_factory) -> str:
    """The NOTC spec with its arm elastic (its flexible table given ``dynamics = "elastic"``)."""
    raw = (resources.files("wecss") / "data" / "devices" / "notc-10kw.toml").read_text()
    line = "flexible = { modes = 6, damping_ratio = 0.01, elements = 16 }"
    assert raw.count(line) == 1
    path = tmp_path_factory.mktemp("spec") / "notc-elastic.toml"
    path.write_text(raw.replace(line, line[:-2] + ', dynamics = "elastic" }'))
    return str(path)


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


def test_a_run_with_the_arm_held_quasi_static_is_the_exact_quasi_static_solution(elastic_spec, tmp_path):
    """All the arm's modal coordinates held quasi-static (``quasi_static_above = 0``): no method named, so
    generalised-alpha runs (an explicit runner named is refused, naming them). In the small regular wave, over the
    last two of twelve periods, the pivot angle and the arm's two largest modal coordinates follow the exact
    frequency-domain steady state of the quasi-static linear model: Z(omega) of the linear model with the held
    coordinates' columns of mass, added mass, damping and radiation damping left out (they have no rate and no
    acceleration in any equation), their columns of stiffness kept; to 2e-3 of the amplitudes."""
    from wecss.linear import linearize, steady_state
    from wecss.sim import simulate

    raw = open(elastic_spec).read()
    spec = tmp_path / "notc-held.toml"
    spec.write_text(raw.replace('dynamics = "elastic" }', 'dynamics = "elastic", quasi_static_above = 0 }'))
    sea = {"kind": "regular", "height": 0.02, "period": T, "duration": 12 * T, "ramp": 2 * T}
    kwargs = {"sea": sea, "controller": {"name": "damping", "parameters": {}}, "radiation": {"method": "state_space"}}
    with pytest.raises(SceneError, match=r"'beeman' does not solve .* \(arm__flex1, .*these do: generalized-alpha"):
        compile_scene(scene(str(spec), solver={"method": "beeman", "dt": 0.05}, **kwargs))
    compiled = compile_scene(scene(str(spec), solver={"dt": 0.05}, outputs={"variables": ["motion", "pto"]}, **kwargs))
    held = compiled.device.model.quasi_static_velocities
    assert held.sum() == compiled.device.model.nv - 2
    ds = simulate(compiled)
    assert ds.attrs["solver"] == "generalized-alpha"
    assert any("are held quasi-static" in note for note in ds.attrs["notes"].split("\n"))
    model = linearize(compiled)
    with pytest.raises(ValueError, match=r"steady_state: device .* holds modal coordinates quasi-static"):
        steady_state(compiled)  # the linear model keeps them dynamic: refused, not the wrong model's solution
    waves = compiled.excitation
    (omega,) = waves.omega
    z = model.dynamic_stiffness(waves.omega)[0]
    force = model.hydro_jacobian.T @ waves.coefficients[:, 0]  # the wave's generalised force amplitudes
    dynamic = np.linalg.solve(z, force)  # the dynamic model's steady state
    z[:, held] = model.stiffness[:, held]
    amplitude = np.linalg.solve(z, force)
    names = list(compiled.device.model.velocity_names)
    late = ds.time.values >= 10 * T
    t = ds.time.values[late]
    for name in ("pivot__pitch", "arm__flex1", "arm__flex2"):
        k = names.index(name)
        want = compiled.q0[k] + np.real(amplitude[k] * np.exp(1j * omega * t))
        series = ds.angle.sel(dof_angular=name) if name == "pivot__pitch" else \
            ds.generalised_coordinate.sel(dof_generalised=name)  # fmt: skip
        got = series.values[late]
        span = np.abs(amplitude[k])
        error = np.abs(got - want).max() / span
        apart = np.abs(amplitude[k] - dynamic[k]) / span
        print(f"{name}: {error:.2e} of the amplitude {span:.3g} (quasi-static against dynamic: {apart:.2e})")
        assert error < 2e-3
