"""An independent Lagrange oracle for a planar flexible pendulum (floating frame of reference), in sympy.

The system: a slender beam of length L [m] (line mass rho_A [kg/m], bending stiffness EI [N m^2], no rotary inertia of
the section) pinned at the world origin by a revolute joint about world +y. The body frame turns with the joint angle
theta [rad] by R_y(theta) = [[c, 0, s], [0, 1, 0], [-s, 0, c]] (a point at +x moves towards -z for positive theta) and
is clamped to the beam at x = 0; the beam axis is body x in [0, L] and it deflects along body z by

    w(x, t) = phi_1(x) xi_1(t) + phi_2(x) xi_2(t),  phi_1 = (x / L)^2,  phi_2 = (x / L)^3   (xi_k [m])

with no axial displacement and no foreshortening. A material point sits at r(x, t) = R_y(theta) (x, 0, w) and

    T = 1/2 int_0^L rho_A |dr/dt|^2 dx = 1/2 int rho_A (theta_dot^2 (x^2 + w^2) - 2 theta_dot x w_dot + w_dot^2) dx,
    V = int_0^L rho_A g r_z dx + 1/2 xi' K xi,  r_z = -x sin(theta) + w cos(theta),  K_kl = int EI phi_k'' phi_l'' dx,

gravity g [m/s^2] along world -z, no damping. Lagrange's equations in q = (theta, xi_1, xi_2) give
M(q) q_ddot + h(q, v) = 0 with M = d^2 T / dv^2, solved for the accelerations in closed form by sympy (a float solve
of M would lose two to three digits: cond(M) ~ 7e3 for the near-collinear modes x^2, x^3).

``pendulum_invariants`` is a separate, numpy-only route to the floating-frame invariants of the same beam
(Gauss-Legendre quadrature of the continuous fields) for ``wecss.structure.Invariants``; nothing here uses
``wecss.multibody``.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
import sympy as sp

from wecss.structure import Invariants

#: The issue's numbers: L [m], rho_A [kg/m], EI [N m^2], g [m/s^2].
LENGTH, MASS_PER_LENGTH, EI, G = 2.0, 3.0, 50.0, 9.81


def _integrate(expr, x, length):
    """int_0^L expr dx of a polynomial in x (sympy's Poly route, much faster than ``sp.integrate``)."""
    return sp.expand(sp.Poly(sp.expand(expr), x).integrate().as_expr().subs(x, length))


@lru_cache(maxsize=1)
def _derivation():
    """The symbolic T, V, Lagrange terms and accelerations, lambdified once with the parameters as arguments.

    Returns (mass(q, p), accelerations(q, v, p), energy(q, v, p), exact) with p = (L, rho_A, EI, g), mass the 3x3
    M(q) = d^2 T / dv^2 and accelerations the symbolic solution of M q_ddot = -h(q, v) (solved and cancelled in
    sympy: the float solve of the 3x3 system loses two to three digits to the near-collinear modes, the closed form
    does not); ``exact`` holds the sympy objects for the high-precision self-check.
    """
    x = sp.Symbol("x", real=True)
    length, rho, ei, g = sp.symbols("L rho_A EI g", positive=True)
    theta, xi1, xi2 = sp.symbols("theta xi1 xi2", real=True)
    thetad, xi1d, xi2d = sp.symbols("thetad xi1d xi2d", real=True)
    c, s = sp.symbols("c s", real=True)  # cos(theta), sin(theta): polynomial algebra, then c^2 + s^2 = 1
    q, v = [theta, xi1, xi2], [thetad, xi1d, xi2d]
    phi = [(x / length) ** 2, (x / length) ** 3]
    w = phi[0] * xi1 + phi[1] * xi2
    w_dot = phi[0] * xi1d + phi[1] * xi2d
    rot = sp.Matrix([[c, 0, s], [0, 1, 0], [-s, 0, c]])  # R_y(theta)
    rot_dot = (rot.diff(c) * -s + rot.diff(s) * c) * thetad  # dR/dt with dc/dt = -s theta_dot, ds/dt = c theta_dot
    body = sp.Matrix([x, 0, w])
    r = rot * body
    r_dot = rot_dot * body + rot * sp.Matrix([0, 0, w_dot])
    speed2 = sp.expand(sp.expand((r_dot.T * r_dot)[0, 0]).subs(s**2, 1 - c**2))
    assert not speed2.has(c, s), "|dr/dt|^2 must not depend on theta"
    kinetic = _integrate(rho * speed2 / 2, x, length)
    stiffness = sp.Matrix(2, 2, lambda k, m: _integrate(ei * phi[k].diff(x, 2) * phi[m].diff(x, 2), x, length))
    xi = sp.Matrix([xi1, xi2])
    potential = _integrate(rho * g * r[2], x, length) + (xi.T * stiffness * xi)[0, 0] / 2
    potential = sp.expand(potential.subs({c: sp.cos(theta), s: sp.sin(theta)}))
    mass = sp.hessian(kinetic, v)
    # d/dt (dT/dv_i) - dT/dq_i + dV/dq_i = M q_ddot + h; h collects the velocity terms and the potential's gradient
    momentum = [kinetic.diff(vi) for vi in v]
    h = sp.Matrix(
        [
            sp.expand(
                sum(momentum[i].diff(qj) * vj for qj, vj in zip(q, v, strict=True))
                - kinetic.diff(q[i])
                + potential.diff(q[i])
            )
            for i in range(3)
        ]
    )
    accelerations = mass.LUsolve(-h).applyfunc(sp.cancel)
    params = [length, rho, ei, g]
    mass_f = sp.lambdify([q, params], mass, modules="numpy", cse=True)
    acc_f = sp.lambdify([q, v, params], accelerations, modules="numpy", cse=True)
    energy_f = sp.lambdify([q, v, params], kinetic + potential, modules="numpy", cse=True)
    exact = {"q": q, "v": v, "params": params, "mass": mass, "h": h, "kinetic": kinetic, "potential": potential}
    return mass_f, acc_f, energy_f, exact


def _params(length: float, mass_per_length: float, ei: float, g: float) -> list[float]:
    return [float(length), float(mass_per_length), float(ei), float(g)]


def pendulum_mass_matrix(
    q, *, length: float = LENGTH, mass_per_length: float = MASS_PER_LENGTH, ei: float = EI, g: float = G
) -> np.ndarray:
    """Lagrange mass matrix M(q) = d^2 T / dv^2 (3, 3) in (theta, xi_1, xi_2) [kg m^2, kg m, kg] (``ei``, ``g``
    unused, accepted for a uniform signature)."""
    mass_f = _derivation()[0]
    return np.array(mass_f(list(np.asarray(q, dtype=float)), _params(length, mass_per_length, ei, g)), dtype=float)


def pendulum_accelerations(
    q, v, *, length: float = LENGTH, mass_per_length: float = MASS_PER_LENGTH, ei: float = EI, g: float = G
) -> np.ndarray:
    """Accelerations (theta_ddot [rad/s^2], xi_1_ddot, xi_2_ddot [m/s^2]) at q = (theta [rad], xi_1, xi_2 [m]),
    v = their rates, from Lagrange's equations M(q) q_ddot = -h(q, v)."""
    acc_f = _derivation()[1]
    p = _params(length, mass_per_length, ei, g)
    q, v = list(np.asarray(q, dtype=float)), list(np.asarray(v, dtype=float))
    return np.array(acc_f(q, v, p), dtype=float).reshape(3)


def pendulum_energy(
    q, v, *, length: float = LENGTH, mass_per_length: float = MASS_PER_LENGTH, ei: float = EI, g: float = G
) -> float:
    """Total energy T + V [J] (gravity's zero at z = 0, strain energy's at xi = 0)."""
    energy_f = _derivation()[2]
    p = _params(length, mass_per_length, ei, g)
    return float(energy_f(list(np.asarray(q, dtype=float)), list(np.asarray(v, dtype=float)), p))


def pendulum_accelerations_exact(
    q, v, *, length: float = LENGTH, mass_per_length: float = MASS_PER_LENGTH, ei: float = EI, g: float = G, digits=40
) -> np.ndarray:
    """The accelerations from the symbolic M and h with the numbers substituted as exact rationals and solved at
    ``digits`` significant digits (slow, for checking the float path)."""
    ex = _derivation()[3]
    values = [*q, *v, length, mass_per_length, ei, g]
    subs = {sym: sp.Rational(float(val)) for sym, val in zip([*ex["q"], *ex["v"], *ex["params"]], values, strict=True)}
    mass = ex["mass"].subs(subs).evalf(digits + 10)
    h = ex["h"].subs(subs).evalf(digits + 10)
    return np.array(mass.LUsolve(-h).evalf(digits), dtype=float).reshape(3)


def _gauss(length: float, points: int = 8) -> tuple[np.ndarray, np.ndarray]:
    """Gauss-Legendre nodes and weights on [0, length] (exact for polynomials up to degree 2 points - 1)."""
    t, w = np.polynomial.legendre.leggauss(points)
    return 0.5 * length * (t + 1.0), 0.5 * length * w


def pendulum_invariants(length: float = LENGTH, mass_per_length: float = MASS_PER_LENGTH, ei: float = EI) -> Invariants:
    """The beam's floating-frame invariants (``wecss.structure.Invariants``, see its module for the definitions)
    about the undeformed centre of mass (L/2, 0, 0) in body axes, by Gauss-Legendre quadrature of the continuous
    fields (exact here: the integrands are polynomials of degree <= 6).

    The mode fields are S_k(x) = phi_k(x) e_z [m per 1] with x measured from the origin; the section has no rotary
    inertia, so J0 = diag(0, rho_A L^3 / 12, rho_A L^3 / 12) [kg m^2] and the gyroscopic coupling is zero (all S_k
    are parallel). No modal damping.
    """
    xs, ws = _gauss(length)
    rho = ws * mass_per_length  # mass of each quadrature point [kg]
    origin = np.array([0.5 * length, 0.0, 0.0])
    pos = np.zeros((xs.size, 3))
    pos[:, 0] = xs - origin[0]  # from the origin [m]
    u = np.zeros((xs.size, 3, 2))
    u[:, 2, 0] = (xs / length) ** 2
    u[:, 2, 1] = (xs / length) ** 3
    curvature = np.stack([2.0 / length**2 * np.ones_like(xs), 6.0 * xs / length**3], axis=1)  # phi_k'' [1/m]
    mass = float(rho.sum())
    s0 = rho @ pos
    p0 = np.einsum("p,pa,pb->ab", rho, pos, pos)
    eye = np.eye(3)
    inertia = np.trace(p0) * eye - p0
    ct = np.einsum("p,pan->an", rho, u)
    cr = np.einsum("p,pan->an", rho, np.cross(pos[:, :, None], u, axis=1))
    modal_mass = np.einsum("p,pak,pal->kl", rho, u, u)
    stiffness = ei * np.einsum("p,pk,pl->kl", ws, curvature, curvature)
    p1 = np.einsum("p,pa,pbk->kab", rho, pos, u)
    p2 = np.einsum("p,pak,pbl->klab", rho, u, u)
    gyro = np.einsum("p,pakl->kla", rho, np.cross(u[:, :, :, None], u[:, :, None, :], axis=1))
    return Invariants(
        origin=origin,
        mass=mass,
        first_moment=s0,
        inertia=inertia,
        translational_coupling=ct,
        rotational_coupling=cr,
        modal_mass=modal_mass,
        modal_stiffness=stiffness,
        modal_damping=np.zeros((2, 2)),
        second_moment=p0,
        inertia_first=p1,
        inertia_second=p2,
        gyroscopic=gyro,
    )
