"""The body drag linearised in a sea state, so that the linear model and the frequency domain include it when a scene
asks for drag (``hydrodynamics.drag``).

Per drag DOF a of a body (body axes at the equilibrium), the relative velocity u_a = J_a xi_dot - U_a(t) (J_a the
row of the body's velocity Jacobian, U_a the undisturbed fluid's velocity at the equilibrium centre of mass, zero for
drag on the body's own velocity) meets the force -c_a |u_a| u_a - b_a u_a. It is replaced by -c_eq,a u_a with

    c_eq = b + c sqrt(8 / pi) sigma_u               (irregular seas: the Gaussian least-squares fit, stochastic
                                                      linearisation; sigma_u the standard deviation of u_a)
    c_eq = b + c 8 / (3 pi) |u_hat|                  (a regular wave: the describing function, the same energy
                                                      dissipated per cycle)

which adds sum_a c_eq,a J_a' J_a to the generalised damping and sum_a c_eq,a J_a' U_a to the forcing. The response and
the equivalent coefficients are found together by a fixed-point iteration on the frequency-domain solution. The
Morison elements are not linearised (their added mass is in the mass matrix; a linear run refuses their drag and
fluid inertia).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ..compiled import CompiledScene
from ..compiled.kernels import kinematics

MAX_ITERATIONS: int = 200
"""Most fixed-point iterations of the equivalent coefficients."""

TOLERANCE: float = 1e-10
"""The iteration stops when the equivalent coefficients change by less than this share of their size."""


@dataclass(frozen=True)
class LinearisedDrag:
    """The body drag of a scene linearised in its sea state.

    Attributes
    ----------
    damping : ndarray (nv, nv)
        The equivalent generalised damping sum_a c_eq,a J_a' J_a [SI].
    forcing : ndarray (nv, n_w) complex
        The generalised force amplitudes of the drag on the fluid's velocity, per wave component of the scene [SI].
    omega : ndarray (n_w,)
        The wave components' frequencies the forcing belongs to [rad/s].
    coefficients : ndarray (n_d, 6)
        c_eq per drag entry and body-axis DOF [N s/m, N m s/rad].
    iterations : int
    """

    damping: np.ndarray
    forcing: np.ndarray
    omega: np.ndarray
    coefficients: np.ndarray
    iterations: int


def _fluid_velocity(compiled: CompiledScene, rot0: np.ndarray, point: np.ndarray, keep: np.ndarray) -> np.ndarray:
    """The undisturbed fluid's linear velocity amplitudes (3, n_w), body axes of the rotation ``rot0``, at the world
    ``point`` (unstretched Airy at its mean position), for the wave components ``keep`` (a mask)."""
    wave = compiled.plant.viscous.wave
    omega, k, amp = wave.omega[keep], wave.k[keep], wave.amplitude[keep]
    along = point[0] * wave.heading[0] + point[1] * wave.heading[1]
    h = wave.depth[0]
    if np.isinf(h):
        horizontal = vertical = np.exp(k * point[2])
    else:
        horizontal = np.cosh(k * (point[2] + h)) / np.sinh(k * h)
        vertical = np.sinh(k * (point[2] + h)) / np.sinh(k * h)
    phase = amp * np.exp(-1j * k * along)
    u = omega * horizontal * phase
    world = np.array([u * wave.heading[0], u * wave.heading[1], 1j * omega * vertical * phase])
    return rot0.T @ world


def linearise_drag(
    compiled: CompiledScene, dynamic_stiffness: Callable[[np.ndarray], np.ndarray], hydro_jacobian: np.ndarray
) -> LinearisedDrag | None:
    """The scene's body drag linearised in its sea state, on the scene's excitation's wave components (None when it
    asks for no drag, has no body drag, or is calm).

    ``dynamic_stiffness(omega)`` is Z(omega) (n_w, nv, nv) of the linear model without the drag and
    ``hydro_jacobian`` its Bw: the response to the excitation X and the drag's forcing F with the extra damping D is
    xi = (Z + i omega D)^-1 (Bw' X + F).

    Raises
    ------
    ValueError
        If the device has Morison elements (not linearised).
    """
    scene = compiled.scene
    vis = compiled.plant.viscous
    if not scene.hydrodynamics.drag or vis.drag_body.size == 0:
        if scene.hydrodynamics.drag and vis.morison_body.size:
            raise ValueError("the Morison elements' drag and fluid inertia are not linearised: use a nonlinear runner")
        return None
    if vis.morison_body.size:
        raise ValueError("the Morison elements' drag and fluid inertia are not linearised: use a nonlinear runner")
    excitation = compiled.excitation
    if excitation is None or not excitation.omega.size:
        return None
    p = compiled.plant
    rot, _pos, b, _bdot, _omega = kinematics(p, compiled.q0, np.zeros(p.twists.shape[0]))
    nv = p.twists.shape[0]
    omega = excitation.omega
    keep = np.isin(vis.wave.omega, omega)
    zeta = dynamic_stiffness(omega)
    driving = (hydro_jacobian.T @ excitation.coefficients).T  # (n_w, nv)
    rows: list[np.ndarray] = []  # J_a (nv,) per drag DOF
    fluid: list[np.ndarray] = []  # U_a (n_w,) per drag DOF
    quadratic, linear = [], []
    for d, i in enumerate(vis.drag_body):
        start = p.cart_start[i]
        translation = rot[i].T @ b[start : start + 3]
        rotation = b[start + 3 : start + 6]
        u = _fluid_velocity(compiled, rot[i], vis.drag_point[d], keep) * vis.relative[0]
        for a in range(6):
            rows.append(translation[a] if a < 3 else rotation[a - 3])
            fluid.append(u[a] if a < 3 else np.zeros(omega.size, dtype=complex))
            quadratic.append(vis.drag_quadratic[d, a])
            linear.append(vis.drag_linear[d, a])
    jac = np.array(rows).reshape(-1, nv)
    fluid_hat = np.array(fluid).reshape(-1, omega.size)
    c, b_lin = np.array(quadratic), np.array(linear)
    regular = omega.size == 1
    factor = 8.0 / (3.0 * np.pi) if regular else np.sqrt(8.0 / np.pi)
    equivalent = b_lin.copy()
    forcing = np.zeros((nv, omega.size), dtype=complex)
    iterations = 0
    for iterations in range(1, MAX_ITERATIONS + 1):  # noqa: B007 (reported)
        damping = jac.T @ (equivalent[:, None] * jac)
        forcing = jac.T @ (equivalent[:, None] * fluid_hat)
        system = zeta + 1j * omega[:, None, None] * damping[None]
        xi = np.linalg.solve(system, (driving + forcing.T)[:, :, None])[:, :, 0].T
        rel = jac @ (1j * omega * xi) - fluid_hat  # (n_dof, n_w)
        size = np.abs(rel[:, 0]) if regular else np.sqrt(0.5 * np.sum(np.abs(rel) ** 2, axis=1))
        updated = b_lin + c * factor * size
        change = np.max(np.abs(updated - equivalent) / np.maximum(np.abs(updated), 1e-300), initial=0.0)
        equivalent = updated
        if change < TOLERANCE:
            break
    damping = jac.T @ (equivalent[:, None] * jac)
    forcing = jac.T @ (equivalent[:, None] * fluid_hat)
    return LinearisedDrag(damping, forcing, omega.copy(), equivalent.reshape(-1, 6), iterations)
