"""The one-DOF analytical model of a hinged-arm point absorber (Wang et al., paper 003, Eqs. 1-2 and 26-52):
an independent reference for the MFM model of ``notc-10kw``.

Geometry (paper Fig. 5, re-derived: the paper's angle conventions and Eqs. 1, 2, 36-37 and 51 carry typos):
the arm AD turns about pivot A; theta is its angle below the horizontal, so the float hinge D sits at
z = h - b sin(theta). The PTO runs from B, a distance a above A, to C on the arm at b1 from A:
c^2 = a^2 + b1^2 + 2 a b1 sin(theta). Then c_dot = alpha theta_dot and z_dot = beta theta_dot with

    alpha = a b1 cos(theta) / c,   beta = -b cos(theta),
    alpha_1 = d(alpha)/d(theta),   beta_1 = d(beta)/d(theta) = b sin(theta).

The paper's simplifications: the float only heaves (kinetic energy m z_dot^2 / 2), added mass lambda and
radiation damping mu at one frequency, heave excitation F3(t) = H/2 Re[F3^0 exp(i omega t)] at that frequency,
hydrostatic restoring rho g A_w (z - z0), PTO spring-damper K_P (c - c0) + mu_P c_dot, PTO mass and inertia
neglected (Eqs. 46-47), arm weight balanced at equilibrium. Energy balance (Eq. 33) gives

    (J + (m + lambda) beta^2) theta_ddot + (mu_P alpha^2 + mu beta^2) theta_dot + (m + lambda) beta beta_1 theta_dot^2
        + K_P (c - c0) alpha + rho g A_w (z - z0) beta = F3(t) beta.

Eq. 48 linearises the two restoring terms as K_hat (theta - theta0), K_hat = alpha^2 K_P + beta^2 rho g A_w (the
paper swaps K_P and rho g A_w, and omits g); ``linear_restoring=True`` gives that form.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp


@dataclass(frozen=True)
class HingedArmAnalytical:
    """Parameters of the one-DOF model (SI units).

    Parameters
    ----------
    arm_inertia : float
        J, the arm's moment of inertia about the pivot A [kg m^2].
    a, b1, b : float
        Distance A-B, A-C and A-D [m].
    h : float
        Height of A above still water [m].
    float_mass : float
        m [kg].
    added_mass, damping : float
        lambda_33 [kg] and mu_33 [N s/m] at the wave frequency.
    waterplane_area : float
        A_w [m^2].
    pto_stiffness, pto_damping : float
        K_P [N/m], mu_P [N s/m].
    theta0 : float
        Equilibrium angle [rad]; c0 and z0 are the PTO length and hinge height there.
    rho, g : float
        [kg/m^3], [m/s^2].
    """

    arm_inertia: float
    a: float
    b1: float
    b: float
    h: float
    float_mass: float
    added_mass: float
    damping: float
    waterplane_area: float
    pto_stiffness: float
    pto_damping: float
    theta0: float = 0.0
    rho: float = 1000.0
    g: float = 9.81

    def pto_length(self, theta: float) -> float:
        """c(theta) [m]."""
        return float(np.sqrt(self.a**2 + self.b1**2 + 2 * self.a * self.b1 * np.sin(theta)))

    def hinge_height(self, theta: float) -> float:
        """z(theta) of the float hinge D [m]."""
        return float(self.h - self.b * np.sin(theta))

    def alpha(self, theta: float) -> tuple[float, float]:
        """alpha = dc/dtheta and alpha_1 = d(alpha)/dtheta [m/rad, m/rad^2]."""
        c = self.pto_length(theta)
        alpha = self.a * self.b1 * np.cos(theta) / c
        return float(alpha), float(-self.a * self.b1 * np.sin(theta) / c - alpha**2 / c)

    def beta(self, theta: float) -> tuple[float, float]:
        """beta = dz/dtheta and beta_1 = d(beta)/dtheta [m/rad, m/rad^2]."""
        return float(-self.b * np.cos(theta)), float(self.b * np.sin(theta))

    def acceleration(self, theta: float, theta_dot: float, force: float, *, linear_restoring: bool = False) -> float:
        """theta_ddot [rad/s^2] for the heave excitation ``force`` [N]."""
        alpha, _ = self.alpha(theta)
        beta, beta1 = self.beta(theta)
        mass = self.float_mass + self.added_mass
        inertia = self.arm_inertia + mass * beta**2
        if linear_restoring:
            k_hat = alpha**2 * self.pto_stiffness + beta**2 * self.rho * self.g * self.waterplane_area
            restoring = k_hat * (theta - self.theta0)
        else:
            c0, z0 = self.pto_length(self.theta0), self.hinge_height(self.theta0)
            restoring = self.pto_stiffness * (self.pto_length(theta) - c0) * alpha + (
                self.rho * self.g * self.waterplane_area * (self.hinge_height(theta) - z0) * beta
            )
        damping = (self.pto_damping * alpha**2 + self.damping * beta**2) * theta_dot
        return (force * beta - damping - mass * beta * beta1 * theta_dot**2 - restoring) / inertia

    def simulate(
        self,
        times: np.ndarray,
        force: Callable[[float], float],
        *,
        linear_restoring: bool = False,
        rtol: float = 1e-10,
        atol: float = 1e-12,
    ) -> np.ndarray:
        """Arm angle theta(t) [rad] at ``times`` [s], starting at rest at theta0 (DOP853)."""

        def rhs(t: float, y: np.ndarray) -> np.ndarray:
            return np.array([y[1], self.acceleration(y[0], y[1], force(t), linear_restoring=linear_restoring)])

        sol = solve_ivp(
            rhs, (times[0], times[-1]), [self.theta0, 0.0], t_eval=times, method="DOP853", rtol=rtol, atol=atol
        )
        if not sol.success:
            raise RuntimeError(f"analytical model integration failed: {sol.message}")
        return sol.y[0]
