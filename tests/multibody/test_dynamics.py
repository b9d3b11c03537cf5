"""MFM dynamics against an independent Lagrange derivation, energy conservation and the power identity."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from wecss.multibody import Dynamics, configuration_rate, gravity_force, integrate, potential_energy

from .chains import m4_111_like, mixed_chain

sp = pytest.importorskip("sympy")


def _lagrange_111(model, added_mass_planar: np.ndarray):
    """Equations of motion of the 111 tree from Lagrange's equations (sympy), independent of the MFM code.

    Planar coordinates (x, z, theta, phi): bow surge, heave, pitch about the bow float's centre of mass, and the
    stern float's pitch relative to the front body about the hinge. The kinetic energy uses (x_dot, z_dot,
    theta_dot) of every float's centre of mass with the rigid mass plus a constant 9x9 added mass.
    Returns functions M(q) and h(q, v), with M q_ddot + h = Q, and the generalised-force map J(q)' (Cartesian
    force -> Q).
    """
    x, z, th, ph = sp.symbols("x z theta phi")
    xd, zd, thd, phd = sp.symbols("xd zd thetad phid")
    q, v = [x, z, th, ph], [xd, zd, thd, phd]

    def rot(a, dx, dz):  # rotation about +y of the (x, z) offset
        return sp.cos(a) * dx + sp.sin(a) * dz, -sp.sin(a) * dx + sp.cos(a) * dz

    c1, c2, c3 = (b.center_of_mass for b in model.bodies)
    hinge = (1.06, 0.25)
    p1 = (c1[0] + x, c1[2] + z)
    o2 = rot(th, c2[0] - c1[0], c2[2] - c1[2])
    p2 = (p1[0] + o2[0], p1[1] + o2[1])
    oh = rot(th, hinge[0] - c1[0], hinge[1] - c1[2])
    h = (p1[0] + oh[0], p1[1] + oh[1])
    o3 = rot(th + ph, c3[0] - hinge[0], c3[2] - hinge[1])
    p3 = (h[0] + o3[0], h[1] + o3[1])
    coords = sp.Matrix([p1[0], p1[1], th, p2[0], p2[1], th, p3[0], p3[1], th + ph])  # (x, z, pitch) per float
    jac = coords.jacobian(q)
    xdot = jac * sp.Matrix(v)
    mass = np.zeros((9, 9))
    for i, b in enumerate(model.bodies):
        mass[3 * i, 3 * i] = mass[3 * i + 1, 3 * i + 1] = b.mass
        mass[3 * i + 2, 3 * i + 2] = b.inertia[1, 1]
    total = sp.Matrix(mass + added_mass_planar)
    kinetic = (xdot.T * total * xdot)[0, 0] / 2
    m_mat = sp.hessian(kinetic, v)
    # h = d/dt(dT/dv) - M v_dot - dT/dq = sum_j (d(dT/dv)/dq_j) v_j - dT/dq
    dtdv = sp.Matrix([sp.diff(kinetic, vi) for vi in v])
    h_vec = dtdv.jacobian(q) * sp.Matrix(v) - sp.Matrix([sp.diff(kinetic, qi) for qi in q])
    args = (*q, *v)
    return (
        sp.lambdify(args, m_mat, "numpy"),
        sp.lambdify(args, h_vec, "numpy"),
        sp.lambdify(args, jac.T, "numpy"),
    )


def test_mfm_matches_lagrange_for_111() -> None:
    model = m4_111_like()
    rng = np.random.default_rng(11)
    planar = [0, 2, 4]  # surge, heave, pitch within each body's 6 Cartesian entries
    a = rng.normal(size=(9, 9))
    added_planar = a @ a.T + 9 * np.eye(9)
    added = np.zeros((18, 18))
    idx = [6 * i + k for i in range(3) for k in planar]
    added[np.ix_(idx, idx)] = added_planar
    dyn = Dynamics(model, added)
    m_fun, h_fun, jt_fun = _lagrange_111(model, added_planar)
    worst = 0.0
    for _ in range(5):
        q = rng.normal(size=4) * [0.1, 0.1, 0.4, 0.6]
        v = rng.normal(size=4)
        force6 = np.zeros(18)
        force_planar = rng.normal(size=9) * 10
        force6[idx] = force_planar
        # body-frame moment about y equals the world moment about y for planar motion
        q_ddot_mfm = dyn.accelerations(q, v, force6)
        args = (*q, *v)
        m_l = np.asarray(m_fun(*args), dtype=float)
        h_l = np.asarray(h_fun(*args), dtype=float).ravel()
        gen = np.asarray(jt_fun(*args), dtype=float) @ force_planar
        q_ddot_lagrange = np.linalg.solve(m_l, gen - h_l)
        worst = max(worst, float(np.max(np.abs(q_ddot_mfm - q_ddot_lagrange)) / np.max(np.abs(q_ddot_lagrange))))
    print(f"MFM vs Lagrange (111): largest relative difference in q_ddot {worst:.2e}")
    assert worst < 1e-10, worst


@pytest.mark.parametrize("base", ["planar", "free"])
def test_power_identity(base: str) -> None:
    """v' (dM*/dt - 2 N*) v = 0: the N* term does no work."""
    model = mixed_chain(base)
    dyn = Dynamics(model)
    rng = np.random.default_rng(5)
    q = integrate(model, model.neutral_configuration(), 0.4 * rng.normal(size=model.nv))
    v = rng.normal(size=model.nv)
    h = 1e-6
    m_plus = dyn.terms(integrate(model, q, h * v), v).mass
    m_minus = dyn.terms(integrate(model, q, -h * v), v).mass
    m_dot = (m_plus - m_minus) / (2 * h)
    terms = dyn.terms(q, v)
    scale = float(v @ m_dot @ v) if abs(v @ m_dot @ v) > 0 else 1.0
    assert abs(v @ (m_dot - 2 * terms.nonlinear) @ v) < 1e-7 * max(1.0, abs(scale))


@pytest.mark.parametrize("base", ["planar", "free", "fixed"])
def test_free_chain_conserves_energy(base: str) -> None:
    """Gravity only, no damping: kinetic + potential energy is constant (DOP853 at tight tolerance)."""
    model = mixed_chain(base)
    g = 9.81
    dyn = Dynamics(model)
    gravity = gravity_force(model, g)
    nq, nv = model.nq, model.nv
    rng = np.random.default_rng(2)
    q0 = integrate(model, model.neutral_configuration(), 0.3 * rng.normal(size=nv))
    v0 = rng.normal(size=nv)

    def rhs(_t: float, y: np.ndarray) -> np.ndarray:
        q, v = y[:nq], y[nq:]
        return np.concatenate([configuration_rate(model, q, v), dyn.accelerations(q, v, gravity)])

    def energy(y: np.ndarray) -> float:
        return dyn.kinetic_energy(y[:nq], y[nq:]) + potential_energy(model, y[:nq], g)

    sol = solve_ivp(rhs, (0.0, 20.0), np.concatenate([q0, v0]), method="DOP853", rtol=1e-12, atol=1e-12)
    e = np.array([energy(y) for y in sol.y.T])
    drift = np.max(np.abs(e - e[0])) / dyn.kinetic_energy(q0, v0)
    print(f"energy drift {base}: {drift:.2e} over {sol.t.size} steps")
    assert drift < 1e-8, drift
