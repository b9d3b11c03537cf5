"""Scenes whose device has an elastic body (``flexible.dynamics = "elastic"``, issue 28): the NOTC device with its arm
elastic compiles with the arm's modal coordinates in the plant; the explicit schemes refuse a step its modes cannot
take and say which step would; the linear model's mass is the multibody core's at the equilibrium's deflection."""

from __future__ import annotations

import re
from importlib import resources

import numpy as np
import pytest
from scipy.linalg import eigh

import wecss.hydro
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


def _fastest_undamped(compiled) -> float:
    """The largest natural frequency [rad/s] of the multibody core's equations at the equilibrium: its M*(q0) with
    the database's A_inf and the static stiffness."""
    model = compiled.device.model
    mass = Dynamics(model, compiled.coupling.added_mass_inf).terms(compiled.q0, np.zeros(model.nv)).mass
    return float(np.sqrt(eigh(compiled.stiffness, mass, eigvals_only=True).max()))


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
    """At the wave step the arm's stiffest modal coordinates (about 2e4 rad/s) make both explicit schemes unstable:
    refused, with the step that would do, which is each scheme's stability limit over the fastest mode (the radius
    of RK4's region in the left half-plane, 2.62 to 2.96 by the angle of the mode's eigenvalue, found here by
    bisection on |R(z)| = 1; Beeman's position step, like Stormer-Verlet's, 2 for an undamped mode), with the
    margin 1.1."""
    with pytest.raises(SceneError, match=r"elastic modes of \['arm'\]") as info:
        compile_and_check(_scene(elastic_spec, method, 0.05))
    limit = float(re.search(r"needs? dt <= ([0-9.e+-]+) s", str(info.value)).group(1))  # type: ignore[union-attr]
    rate = _fastest_undamped(compile_scene(_scene(elastic_spec, "beeman", 1e-4)))
    reach = {"rk4": _rk4_radii(), "beeman": (2.0, 2.0)}[method]
    low, high = (r / 1.1 / rate for r in reach)
    print(f"{method}: refused with dt <= {limit:.4g} s; stability limit over the fastest mode {low:.4g}-{high:.4g} s")
    assert 0.99 * low <= limit <= 1.01 * high


def _rk4_radii() -> tuple[float, float]:
    """The smallest and largest radius of RK4's stability region over the left half-plane's angles."""
    from scipy.optimize import brentq

    def gain(z: complex) -> float:
        return abs(1 + z + z**2 / 2 + z**3 / 6 + z**4 / 24)

    def radius(angle: float) -> float:
        return brentq(lambda r: gain(r * np.exp(1j * angle)) - 1, 1.0, 4.0)

    radii = [radius(a) for a in np.linspace(np.pi / 2, np.pi, 181)]
    return min(radii), max(radii)


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


def test_loads_are_refused_for_an_elastic_device(elastic_spec):
    sc = _scene(elastic_spec, "beeman", 1e-4)
    sc = type(sc).from_dict({**sc.to_dict(), "outputs": {"variables": ["motion", "loads"]}})
    with pytest.raises(SceneError, match=r"'loads'.*elastic bodies \['arm'\].*leave 'loads' out"):
        compile_scene(sc)


def test_the_linear_model_s_state_matrix_is_the_jacobian_of_the_elastic_equations(elastic_spec):
    """The state matrix of the linear model (radiation states included) against central differences of the
    nonlinear right-hand side of the compiled plant (its kernels: M*(q) with the arm's M(xi), the quadratic-velocity
    terms, the cylinder on the arm's node, the geometric stiffening) about the equilibrium, to 1e-8 of its largest
    entry. The differences are taken per state with the step scaled to the state's size in the slowest mode..."""
    from wecss.compiled.kernels import accelerations, integrate_configuration

    compiled = compile_scene(_scene(elastic_spec, "generalized-alpha", 0.05))
    model = linearize(compiled, cache=False)
    p, rad = compiled.plant, model.radiation
    assert rad is not None
    nv, n_h = model.mass.shape[0], p.hydro_index.size

    def rhs(x: np.ndarray) -> np.ndarray:
        xi, rate, r = x[:nv], x[nv : 2 * nv], x[2 * nv :]
        q = integrate_configuration(p, compiled.q0, xi)
        a, u, *_ = accelerations(p, q, rate, -(rad.C @ r), np.zeros((n_h, n_h)), np.zeros(p.pto_kind.size))
        return np.concatenate([rate, a, rad.A @ r + rad.B @ u])

    rest = rhs(np.zeros(model.n_states))
    a = np.asarray(model.state_space.A)
    n = model.n_states
    jac = np.zeros((n, n))
    for k in range(n):
        step = np.zeros(n)
        step[k] = 1e-6
        jac[:, k] = (rhs(step) - rhs(-step)) / 2e-6
    error = np.max(np.abs(jac - a)) / np.max(np.abs(a))
    print(
        f"elastic NOTC: state matrix against the Jacobian {error:.2e} of its largest entry; "
        f"rest {np.abs(rest).max():.2e}"
    )
    assert np.abs(rest[nv : 2 * nv]).max() <= 1e-9 * np.abs(a[nv : 2 * nv]).max()  # the equilibrium is the kernels'
    assert error <= 1e-8
