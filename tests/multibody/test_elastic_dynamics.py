"""Flexible bodies in the Moving Frame Method: the energy identity at random states, energy conservation along the
flow with gravity and geometric stiffening, the spinning beams of Simo and Vu-Quoc (1987) and Kane et al. (1987)
against their published frequencies, the elastic attachment of a child body, the rigid limit and the refusals.
(The comparison with an independent Lagrange derivation is in ``test_flexible_lagrange.py``.)"""

from __future__ import annotations

import numpy as np
import pytest

from wecss.multibody import (
    Body,
    Dynamics,
    ElasticBody,
    Multibody,
    elastic_energy,
    gravity_force,
    integrate,
    kinematics,
    potential_energy,
    structural_force,
)
from wecss.multibody._se3 import so3_log
from wecss.structure import Invariants

from .elastic_models import LUG, C, arm_device, floating_arm, hinged_beam, l_arm


def _random_state(model: Multibody, seed: int, size: float = 0.3) -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    q = integrate(model, model.neutral_configuration(), size * rng.normal(size=model.nv))
    return q, rng.normal(size=model.nv)


def _mass_rate(dyn: Dynamics, q: np.ndarray, v: np.ndarray) -> np.ndarray:
    """dM*/dt along v: central differences at h, h/2, h/4 with two Richardson steps (error O(h^6))."""
    model = dyn.model

    def central(h: float) -> np.ndarray:
        plus = dyn.terms(integrate(model, q, h * v), v).mass
        minus = dyn.terms(integrate(model, q, -h * v), v).mass
        return (plus - minus) / (2 * h)

    d1, d2, d3 = central(2e-3), central(1e-3), central(5e-4)
    r1, r2 = (4 * d2 - d1) / 3, (4 * d3 - d2) / 3
    return (16 * r2 - r1) / 15


MODELS = {
    "hull on a free base": lambda: arm_device("free"),
    "hull on a planar base": lambda: arm_device("planar"),
    "hull fixed": lambda: arm_device("fixed"),
    "flexible arm on a free base": lambda: floating_arm("free"),
    "flexible arm on a planar base": lambda: floating_arm("planar"),
}


@pytest.mark.parametrize("base", list(MODELS))
def test_energy_identity_at_random_states(base: str) -> None:
    """d/dt (v' M* v / 2) = v' F*: the quadratic-velocity terms do no work, v' (dM*/dt - 2 N*) v = 0, for a hull
    carrying a flexible arm (24 modal coordinates) that carries a float on an oblique hinge and a welded lug, and
    for the arm itself as the base."""
    model = MODELS[base]()
    dyn = Dynamics(model)
    worst = 0.0
    for seed in range(3):
        q, v = _random_state(model, seed)
        m_dot = _mass_rate(dyn, q, v)
        work = float(v @ (m_dot - 2 * dyn.terms(q, v).nonlinear) @ v)
        worst = max(worst, abs(work) / abs(float(v @ m_dot @ v)))
    print(f"energy identity ({base} base): |v' (dM*/dt - 2 N*) v| / |v' dM*/dt v| = {worst:.1e}")
    assert worst < 1e-10


def _richardson(fun, h: float = 1e-3):  # type: ignore[no-untyped-def]
    """d/ds fun(s) at 0 by central differences at h and h/2 with one Richardson step (error O(h^4))."""
    d1 = (fun(h) - fun(-h)) / (2 * h)
    d2 = (fun(h / 2) - fun(-h / 2)) / h
    return (4 * d2 - d1) / 3


@pytest.mark.parametrize("base", list(MODELS))
def test_bdot_is_the_rate_of_b(base: str) -> None:
    """Bdot (the elastic columns of the centre of mass and the attachments' dS/dt included) is the derivative of
    B along the motion: the energy identity cannot see Bdot (it cancels there), this does."""
    model = MODELS[base]()
    q, v = _random_state(model, 31)
    bdot = kinematics(model, q, v).Bdot
    assert bdot is not None
    rate = _richardson(lambda h: kinematics(model, integrate(model, q, h * v)).B)
    np.testing.assert_allclose(bdot, rate, rtol=0, atol=1e-8 * np.abs(bdot).max())


def test_the_quadratic_velocity_terms_are_lagrange_s() -> None:
    """With joint and modal coordinates only (a fixed hull): N* v = dM*/dt v - dT/dq, T = v' M*(q) v / 2, by
    differences of T itself (a skew error in N*, invisible to the energy identity, shows here)."""
    model = arm_device("fixed")
    dyn = Dynamics(model)
    q, v = _random_state(model, 32)
    n_v = dyn.terms(q, v).nonlinear @ v
    m_dot_v = _richardson(lambda h: dyn.terms(integrate(model, q, h * v), v).mass) @ v
    grad = np.array([_richardson(lambda h, e=e: dyn.kinetic_energy(integrate(model, q, h * e), v))
                     for e in np.eye(model.nv)])  # fmt: skip
    np.testing.assert_allclose(n_v, m_dot_v - grad, rtol=0, atol=1e-7 * np.abs(n_v).max())


def test_energy_is_constant_along_the_flow_with_gravity_and_geometric_stiffening() -> None:
    """d/dt (T + V_gravity + U_strain) = 0 along the equations of motion (no damping), the cubic strain energy of
    the geometric stiffening included: the rate from central differences along the flow is at round-off against
    the rates of its parts."""
    model = arm_device("free", l_arm(2, soft=True))
    assert model.bodies[1].elastic is not None and model.bodies[1].elastic.geometric is not None
    dyn = Dynamics(model)
    g, nq = 9.81, model.nq

    def step(y: np.ndarray, h: float) -> np.ndarray:
        """A first-order step along the flow (enough for the rate at y by central differences)."""
        q, v = y[:nq], y[nq:]
        acceleration = dyn.accelerations(q, v, gravity_force(model, g) + structural_force(model, q))
        return np.concatenate([integrate(model, q, h * v), v + h * acceleration])

    parts = {
        "kinetic": lambda y: dyn.kinetic_energy(y[:nq], y[nq:]),
        "gravity": lambda y: potential_energy(model, y[:nq], g),
        "strain": lambda y: elastic_energy(model, y[:nq]),
    }
    for seed in range(3):
        q, v = _random_state(model, 10 + seed, size=0.05)
        y = np.concatenate([q, v])

        def rate(f, h: float, y: np.ndarray = y) -> float:  # type: ignore[no-untyped-def]
            return (f(step(y, h)) - f(step(y, -h))) / (2 * h)

        rates = {k: (4 * rate(f, 5e-6) - rate(f, 1e-5)) / 3 for k, f in parts.items()}  # Richardson: O(h^4)
        total = sum(rates.values())
        scale = max(abs(r) for r in rates.values())
        print(f"dE/dt = {total:.2e} W against parts up to {scale:.2e} W")
        assert abs(total) < 1e-9 * scale


def test_geometric_stiffness_is_a_potential() -> None:
    """The geometric force is minus the gradient of the cubic strain energy (central differences)."""
    elastic = l_arm(2)
    assert elastic.geometric is not None and np.abs(elastic.geometric).max() > 0
    rng = np.random.default_rng(3)
    xi = 0.01 * rng.normal(size=elastic.n)
    h = 1e-6
    gradient = np.array(
        [(elastic.elastic_energy(xi + h * e) - elastic.elastic_energy(xi - h * e)) / (2 * h) for e in np.eye(elastic.n)]
    )
    force = elastic.elastic_force(xi)
    np.testing.assert_allclose(force, -gradient, rtol=0, atol=1e-6 * np.abs(force).max())


def _spinning_frequencies(model: Multibody, spin: float) -> tuple[np.ndarray, np.ndarray, list[str]]:
    """Eigenvalues of the modal coordinates' motion about their steady state at the prescribed hub speed ``spin``
    [rad/s] (the hub's acceleration held at zero), with each mode's plane ("in": along y, in the plane of rotation;
    "out": along z)."""
    elastic = model.bodies[1].elastic
    assert elastic is not None
    dyn, n = Dynamics(model), elastic.n

    def acceleration(xi: np.ndarray, xi_dot: np.ndarray) -> np.ndarray:
        q, v = np.concatenate([[0.0], xi]), np.concatenate([[spin], xi_dot])
        terms = dyn.terms(q, v)
        rhs = terms.state.B.T @ structural_force(model, q, v) - terms.nonlinear @ v
        return np.linalg.solve(terms.mass[1:, 1:], rhs[1:])

    def jacobian(fun, x: np.ndarray, h: float = 1e-7) -> np.ndarray:  # type: ignore[no-untyped-def]
        return np.array([(fun(x + h * e) - fun(x - h * e)) / (2 * h) for e in np.eye(len(x))]).T

    zero = np.zeros(n)
    xi = zero.copy()
    for _ in range(20):  # the steady stretch of the spinning beam
        step = np.linalg.solve(jacobian(lambda x: acceleration(x, zero), xi), -acceleration(xi, zero))
        xi = xi + step
        if np.abs(step).max() < 1e-14:
            break
    stiffness = jacobian(lambda x: acceleration(x, zero), xi)
    damping = jacobian(lambda x: acceleration(xi, x), zero)
    eigenvalues, vectors = np.linalg.eig(np.block([[np.zeros((n, n)), np.eye(n)], [stiffness, damping]]))
    order = np.argsort(np.abs(eigenvalues))
    basis = _nodal_basis(model)
    planes = []
    for k in order:
        shape = basis @ vectors[:n, k]
        planes.append("in" if np.abs(shape[1::6]).max() > np.abs(shape[2::6]).max() else "out")
    return eigenvalues[order], vectors[:, order], planes


def _nodal_basis(model: Multibody) -> np.ndarray:
    elastic = model.bodies[1].elastic
    assert elastic is not None
    return np.concatenate([elastic.attachments[k].shapes for k in sorted(elastic.attachments)], axis=0)


@pytest.mark.parametrize(
    ("name", "length", "ei", "mass_per_length", "ea", "spin", "in_plane", "out_of_plane"),
    [
        ("Simo and Vu-Quoc", 10.0, 1.4e4, 1.2, 2.8e7, 6.0, 4.5125, 7.5075),
        ("Kane et al.", 8.0, 566.6, 0.2019, 5.033e6, 4.0, 3.3467, 5.2154),
    ],
)
def test_spinning_beam_frequencies(name, length, ei, mass_per_length, ea, spin, in_plane, out_of_plane) -> None:  # type: ignore[no-untyped-def]
    """A beam spinning at constant speed about a prescribed hub: the first in-plane and out-of-plane frequencies in
    the rotating frame within 1e-3 of the published ones (geometric stiffening of the centrifugal tension, spin
    softening in the plane); without the geometric stiffness the in-plane motion is unstable (Omega above the
    beam's first bending frequency), as theory says."""
    model = hinged_beam(length, ei, mass_per_length, ea, probes=32)
    eigenvalues, _, planes = _spinning_frequencies(model, spin)
    assert np.abs(eigenvalues.real).max() < 1e-9 * np.abs(eigenvalues).max()
    first = {p: float(abs(eigenvalues[planes.index(p)].imag)) for p in ("in", "out")}
    print(f"{name}: in plane {first['in']:.6f} rad/s (published {in_plane}), out of plane {first['out']:.6f} "
          f"(published {out_of_plane})")  # fmt: skip
    assert first["in"] == pytest.approx(in_plane, rel=1e-3)
    assert first["out"] == pytest.approx(out_of_plane, rel=1e-3)
    soft = hinged_beam(length, ei, mass_per_length, ea, geometric=False, probes=32)
    eigenvalues, _, planes = _spinning_frequencies(soft, spin)
    growing = [p for lam, p in zip(eigenvalues, planes, strict=True) if lam.real > 1e-6 * np.abs(lam)]
    assert growing == ["in"]


def test_a_child_rides_on_its_node() -> None:
    """The float's hinge point moves with the arm's tip: displaced by the tip's shape per modal coordinate (to first
    order), and the float turns with the tip's rotation."""
    elastic = l_arm()
    model = arm_device("fixed", elastic)
    tip = elastic.attachments["float_hinge"]
    xi = 1e-9 * np.random.default_rng(4).normal(size=elastic.n)  # second-order terms below 1e-6 of the first
    q = model.neutral_configuration()
    q[model.mode_coordinate_start[1] : model.mode_coordinate_start[2]] = xi
    st, st0 = kinematics(model, q), kinematics(model, model.neutral_configuration())
    i = model.body_names.index("float")
    hinge = st.position[i] + st.rotation[i] @ (C - model.bodies[i].center_of_mass)
    expected = tip.shapes[:3] @ xi
    np.testing.assert_allclose(hinge - C, expected, rtol=0, atol=1e-6 * np.abs(expected).max())
    np.testing.assert_allclose(so3_log(st.rotation[i]), tip.shapes[3:] @ xi, rtol=1e-6)
    assert np.allclose(st0.position[i], model.bodies[i].center_of_mass)
    j = model.body_names.index("lug")
    lug_point = st.position[j] + st.rotation[j] @ (LUG - model.bodies[j].center_of_mass)
    expected = elastic.attachments["lug_weld"].shapes[:3] @ xi
    np.testing.assert_allclose(lug_point - LUG, expected, rtol=0, atol=1e-6 * np.abs(expected).max())


def test_an_elastic_body_without_modes_is_the_rigid_body() -> None:
    """An elastic model with no modal coordinates gives the rigid body's M* and N* (to round-off)."""
    elastic = l_arm()
    inv = elastic.invariants
    empty = Invariants(
        inv.origin, inv.mass, inv.first_moment, inv.inertia, np.zeros((3, 0)), np.zeros((3, 0)), np.zeros((0, 0)),
        np.zeros((0, 0)), np.zeros((0, 0)), inv.second_moment, np.zeros((0, 3, 3)), np.zeros((0, 0, 3, 3)),
        np.zeros((0, 0, 3)),
    )  # fmt: skip
    from wecss.multibody import Attachment

    points = {name: a.point for name, a in elastic.attachments.items()}
    flexible = arm_device(
        "free", ElasticBody((), empty, {n: Attachment(p, np.zeros((6, 0))) for n, p in points.items()})
    )
    bodies = list(flexible.bodies)
    bodies[1] = Body("arm", inv.mass, inv.inertia, inv.origin)
    rigid = Multibody(bodies, flexible.joints)
    q, v = _random_state(rigid, 7)
    a, b = Dynamics(flexible).terms(q, v), Dynamics(rigid).terms(q, v)
    np.testing.assert_allclose(a.mass, b.mass, rtol=0, atol=1e-13 * np.abs(b.mass).max())
    np.testing.assert_allclose(a.nonlinear, b.nonlinear, rtol=0, atol=1e-13 * np.abs(b.nonlinear).max())


def test_an_elastic_model_that_disagrees_with_its_body_is_refused() -> None:
    elastic = l_arm()
    inv = elastic.invariants
    with pytest.raises(ValueError, match=r"body 'arm': its elastic model's invariants disagree.*mass"):
        Body("arm", 1.01 * inv.mass, inv.inertia, inv.origin, elastic=elastic)
    with pytest.raises(ValueError, match=r"body 'arm'.*centre of mass"):
        Body("arm", inv.mass, inv.inertia, inv.origin + 0.01, elastic=elastic)
    with pytest.raises(ValueError, match="give its modes or its elastic model, not both"):
        Body("arm", inv.mass, inv.inertia, inv.origin, modes=[{"name": "f", "mass": 1.0}], elastic=elastic)
    with pytest.raises(ValueError, match=r"shapes \(6, 24\)"):
        ElasticBody(elastic.names, inv, {"x": type(elastic.attachments["lug_weld"])(np.zeros(3), np.zeros((6, 2)))})


def test_kinetic_energy_of_the_mass_points() -> None:
    """1/2 m |v_c|^2 + 1/2 Y' M(xi) Y equals the kinetic energy summed over the structure's mass points (the
    elements' quadrature points and the lumped mass, each a rigid section of rotary inertia J_p turned by its small
    rotation theta: 1/2 m |V|^2 + 1/2 tr(A S A') with A = hat(w) (I + hat(theta)) + hat(theta_dot) and
    S = tr(J) I / 2 - J), for a deformed body in 3D motion: an independent sum over the frame, not the invariants."""
    from wecss.multibody._se3 import hat

    elastic = l_arm(3)
    frame_basis = _l_arm_basis()
    frame, phi = frame_basis.frame, frame_basis.basis
    inv = elastic.invariants
    rng = np.random.default_rng(8)
    for _ in range(3):
        xi, xi_dot = 0.05 * rng.normal(size=elastic.n), rng.normal(size=elastic.n)
        omega, v_c = rng.normal(size=3), rng.normal(size=3)
        block, _ = elastic.relative_mass(xi)
        y = np.concatenate([omega, xi_dot])
        model_energy = 0.5 * inv.mass * v_c @ v_c + 0.5 * y @ block @ y
        s = inv.first_moment_at(xi)
        v_origin = v_c - (np.cross(omega, s) + inv.translational_coupling @ xi_dot) / inv.mass  # body axes, R = I
        points_energy = 0.0
        for group in frame.mass_points:
            u = np.einsum("pai,i->pa", group.nu, phi[group.dofs] @ xi)
            u_dot = np.einsum("pai,i->pa", group.nu, phi[group.dofs] @ xi_dot)
            theta = np.einsum("pai,i->pa", group.ntheta, phi[group.dofs] @ xi)
            theta_dot = np.einsum("pai,i->pa", group.ntheta, phi[group.dofs] @ xi_dot)
            x = group.positions - inv.origin
            for p in range(len(group.masses)):
                velocity = v_origin + np.cross(omega, x[p] + u[p]) + u_dot[p]
                section = 0.5 * np.trace(group.inertias[p]) * np.eye(3) - group.inertias[p]
                a = hat(omega) @ (np.eye(3) + hat(theta[p])) + hat(theta_dot[p])
                points_energy += 0.5 * group.masses[p] * velocity @ velocity + 0.5 * np.trace(a @ section @ a.T)
        print(f"kinetic energy: model {model_energy:.12g} J, mass points {points_energy:.12g} J")
        assert model_energy == pytest.approx(points_energy, rel=1e-12)


def _l_arm_basis():  # type: ignore[no-untyped-def]
    """The basis ``l_arm(3)`` is made of (rebuilt: ElasticBody keeps the invariants, not the frame)."""
    from wecss.structure import craig_bampton

    from .elastic_models import l_arm_frame

    return craig_bampton(l_arm_frame(), "root", {"pto": "force", "tip": "joint"}, n_modes=3, centrifugal=True)


def test_an_actuator_end_rides_on_its_node() -> None:
    """An actuator from the hull to the arm's node at LUG (attachment ``pto:cylinder``): its transmission g is the
    derivative of its length along the motion (central differences with a Richardson step), the arm's modes
    included; an end on a flexible body without its attachment is refused."""
    from wecss.multibody import ActuatorPTO

    model = arm_device("free")
    pto = ActuatorPTO("cylinder", "hull", np.array([-0.3, 0.0, 0.4]), "arm", LUG)
    q, v = _random_state(model, 21, size=0.2)
    _, transmission = pto.stroke(model, q, kinematics(model, q))

    def at(h: float) -> float:
        moved = integrate(model, q, h * v)
        return pto.stroke(model, moved, kinematics(model, moved))[0]

    d1 = (at(1e-4) - at(-1e-4)) / 2e-4
    d2 = (at(5e-5) - at(-5e-5)) / 1e-4
    rate = (4 * d2 - d1) / 3
    assert transmission @ v == pytest.approx(rate, rel=1e-9)
    assert np.abs(transmission[model.mode_velocity_start[1] : model.mode_velocity_start[2]]).max() > 0
    with pytest.raises(ValueError, match="needs the body's attachment 'pto:other'"):
        ActuatorPTO("other", "hull", np.array([-0.3, 0.0, 0.4]), "arm", LUG).stroke(model, q, kinematics(model, q))


def test_a_child_of_a_flexible_body_needs_its_attachment() -> None:
    elastic = l_arm()
    inv = elastic.invariants
    shapes = elastic.attachments["float_hinge"].shapes
    from wecss.multibody import Attachment

    missing = ElasticBody(elastic.names, inv, {"lug_weld": elastic.attachments["lug_weld"]})
    with pytest.raises(
        ValueError, match=r"joint 'float_hinge': its parent 'arm' is flexible.*attachments: \['lug_weld'\]"
    ):
        arm_device("free", missing)
    moved = ElasticBody(elastic.names, inv, {**elastic.attachments, "float_hinge": Attachment(C + 1.0, shapes)})
    with pytest.raises(ValueError, match=r"joint 'float_hinge': its point .* is not where its attachment"):
        arm_device("free", moved)
    with pytest.raises(ValueError, match="must be dry"):
        Body("arm", inv.mass, inv.inertia, inv.origin, "arm_hydro", elastic=elastic)
