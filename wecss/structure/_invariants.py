"""The inertia invariants of a flexible body in a floating frame of reference.

The body frame sits at ``origin`` (the undeformed centre of mass); a material point at x (body axes, from the
origin) moves elastically by u(x) = sum_k S_k(x) q_k with the mode fields S_k of the basis. Kinetic energy,
momentum and angular momentum of the body then need the volume integrals (Shabana, Dynamics of Multibody Systems,
ch. 5; Wallrapp's standard input data), all of them here over the frame's mass points (``Frame.mass_points``), so
they agree exactly with its consistent mass matrix:

- mass m = int rho dV and first moment s0 = int rho x dV (m times the centre of mass);
- the inertia tensor J0 = int rho (|x|^2 I - x x') dV about the origin;
- translational coupling Ct = int rho S dV (3, n) and rotational coupling Cr = int rho x cross S dV (3, n);
- modal mass Phi' M Phi and stiffness Phi' K Phi;
- the inertia's derivatives with respect to the modal coordinates through P1_k = int rho x S_k' dV (n, 3, 3) and
  P2_kl = int rho S_k S_l' dV (n, n, 3, 3): with P(q) = P0 + sum_k q_k (P1_k + P1_k') + sum_kl q_k q_l P2_kl
  (P0 = int rho x x' dV) the inertia of the deformed body is J(q) = tr(P(q)) I - P(q), its first moment
  s(q) = s0 + Ct q;
- the gyroscopic coupling G_kl = int rho S_k cross S_l dV (n, n, 3): the angular momentum of the elastic motion is
  Cr q_dot + sum_kl q_k G_kl q_dot_l.

A beam's cross-section is not a point: its points sit at r from the axis and move by theta x r with the section's
rotation theta. Integrated over the section this adds, per mass point with rotary inertia J_p (the element's
section inertia, or a lumped mass's), the tensor S_p = tr(J_p) I / 2 - J_p (the section's int rho r r' dA) to P0,
-S_p hat(theta_k) to P1_k, -hat(theta_k) S_p hat(theta_l) to P2_kl, J_p theta_k to Cr and S_p (theta_k cross
theta_l) to G_kl.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ._frame import Frame, hat


@dataclass(frozen=True, eq=False)
class Invariants:
    """A flexible body's inertia invariants about ``origin`` in body axes (see the module docstring).

    Attributes
    ----------
    origin : ndarray (3,)
        [m].
    mass : float
        [kg].
    first_moment : ndarray (3,)
        s0 [kg m].
    inertia : ndarray (3, 3)
        J0 about the origin [kg m^2].
    translational_coupling, rotational_coupling : ndarray (3, n)
        Ct [kg m per 1], Cr [kg m^2 per 1] (S_k in m per 1).
    modal_mass, modal_stiffness, modal_damping : ndarray (n, n)
        [kg m^2, N m, N m s].
    second_moment : ndarray (3, 3)
        P0 = int rho x x' dV [kg m^2].
    inertia_first : ndarray (n, 3, 3)
        P1_k = int rho x S_k' dV [kg m^2].
    inertia_second : ndarray (n, n, 3, 3)
        P2_kl = int rho S_k S_l' dV [kg m^2].
    gyroscopic : ndarray (n, n, 3)
        G_kl = int rho S_k cross S_l dV [kg m^2].
    """

    origin: np.ndarray
    mass: float
    first_moment: np.ndarray
    inertia: np.ndarray
    translational_coupling: np.ndarray
    rotational_coupling: np.ndarray
    modal_mass: np.ndarray
    modal_stiffness: np.ndarray
    modal_damping: np.ndarray
    second_moment: np.ndarray
    inertia_first: np.ndarray
    inertia_second: np.ndarray
    gyroscopic: np.ndarray

    @property
    def center_of_mass(self) -> np.ndarray:
        """s0 / m + origin, body axes [m]."""
        return self.origin + self.first_moment / self.mass

    def first_moment_at(self, q: np.ndarray) -> np.ndarray:
        """s(q) = s0 + Ct q [kg m]."""
        return self.first_moment + self.translational_coupling @ np.asarray(q, dtype=float)

    def inertia_at(self, q: np.ndarray) -> np.ndarray:
        """J(q) about the origin of the body deformed by the modal coordinates q [kg m^2]."""
        q = np.asarray(q, dtype=float)
        linear = np.einsum("k,kab->ab", q, self.inertia_first)
        p = self.second_moment + linear + linear.T + np.einsum("k,l,klab->ab", q, q, self.inertia_second)
        return np.trace(p) * np.eye(3) - p


def invariants(
    frame: Frame, basis: np.ndarray, origin: np.ndarray | None = None, damping: np.ndarray | None = None
) -> Invariants:
    """The invariants of ``frame`` with the mode fields ``basis`` (n_dof, n) about ``origin`` (default: the
    frame's centre of mass), body axes. ``damping`` is the modal damping (n, n) to carry along (default zero).

    Raises
    ------
    ValueError
        If the basis does not have one row per DOF of the frame.
    """
    phi = frame.basis(basis)
    n = phi.shape[1]
    groups = frame.mass_points
    if origin is None:
        total = sum(float(g.masses.sum()) for g in groups)
        origin = sum((g.masses @ g.positions for g in groups), np.zeros(3)) / total
    origin = np.asarray(origin, dtype=float)
    mass = 0.0
    s0 = np.zeros(3)
    p0 = np.zeros((3, 3))
    ct = np.zeros((3, n))
    cr = np.zeros((3, n))
    p1 = np.zeros((n, 3, 3))
    p2 = np.zeros((n, n, 3, 3))
    gyro = np.zeros((n, n, 3))
    eye = np.eye(3)
    for g in groups:
        x = g.positions - origin
        m = g.masses
        sec = 0.5 * np.trace(g.inertias, axis1=1, axis2=2)[:, None, None] * eye - g.inertias
        u = np.einsum("pai,in->pan", g.nu, phi[g.dofs])
        th = np.einsum("pai,in->pan", g.ntheta, phi[g.dofs])
        th_hat = np.zeros((len(m), n, 3, 3))
        for p in range(len(m)):
            for k in range(n):
                th_hat[p, k] = hat(th[p, :, k])
        mass += float(m.sum())
        s0 += m @ x
        p0 += np.einsum("p,pa,pb->ab", m, x, x) + sec.sum(axis=0)
        ct += np.einsum("p,pan->an", m, u)
        cr += np.einsum("p,pan->an", m, np.cross(x[:, :, None], u, axis=1)) + np.einsum("pab,pbn->an", g.inertias, th)
        p1 += np.einsum("p,pa,pbk->kab", m, x, u) - np.einsum("pac,pkcb->kab", sec, th_hat)
        p2 += np.einsum("p,pak,pbl->klab", m, u, u) - np.einsum("pkac,pcd,pldb->klab", th_hat, sec, th_hat)
        cross_u = np.cross(u[:, :, :, None], u[:, :, None, :], axis=1)  # (p, 3, k, l)
        cross_t = np.cross(th[:, :, :, None], th[:, :, None, :], axis=1)
        gyro += np.einsum("p,pakl->kla", m, cross_u) + np.einsum("pab,pbkl->kla", sec, cross_t)
    inertia = np.trace(p0) * eye - p0
    modal_damping = np.zeros((n, n)) if damping is None else np.asarray(damping, dtype=float)
    return Invariants(
        origin, mass, s0, 0.5 * (inertia + inertia.T), ct, cr, phi.T @ frame.mass @ phi, phi.T @ frame.stiffness @ phi,
        modal_damping, 0.5 * (p0 + p0.T), p1, p2, gyro,
    )  # fmt: skip
