"""Exact frequency-domain solution of the MFM equations linearised about the static equilibrium.

With xi the generalised displacement from the equilibrium q0 (tangent coordinates):

    [-omega^2 (M* + Bw' (A(omega) - A_inf) Bw) + i omega (C + Bw' B(omega) Bw) + K*] xi_hat = Bw' F_hat(omega)

M* = B(q0)' (M + A_inf) B(q0), Bw the world-frame Jacobian of the hydro DOFs at q0, K* the static stiffness
(hydrostatics, gravity and PTO springs, with the geometric stiffness of the static loads) plus any controller
stiffness, C = G' diag(c) G the linear PTO damping through the PTO transmissions G. A(omega) and B(omega) are
interpolated linearly between the database's frequencies, as the excitation is.

This is the reference the nonlinear simulator must reproduce in small waves (same hydro data, same record).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..multibody._dynamics import body_mass_matrix
from ..waves._elevation import evaluate
from ._compile import CompiledScene
from ._kernels import kinematics, pto_strokes, world_jacobian
from ._radiation import interpolate_matrices


@dataclass(frozen=True)
class LinearisedMFM:
    """Matrices of the linearised equations (generalised coordinates, ``velocity_names`` order).

    Attributes
    ----------
    mass, damping, stiffness : ndarray (nv, nv)
        M* (with A_inf), the PTO damping C and K* [SI per coordinate].
    hydro_jacobian : ndarray (n_h, nv)
        Bw at the equilibrium: hydro DOF velocities per generalised velocity.
    pto_jacobian : ndarray (n_pto, nv)
        PTO stroke rates per generalised velocity.
    """

    mass: np.ndarray
    damping: np.ndarray
    stiffness: np.ndarray
    hydro_jacobian: np.ndarray
    pto_jacobian: np.ndarray


def equilibrium_maps(compiled: CompiledScene) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """At the static equilibrium: B (6n, nv), the world-frame Jacobian of the hydro DOFs Bw (n_h, nv), the PTO
    transmissions G (n_pto, nv) and the PTO strokes from their rest positions (n_pto,)."""
    p = compiled.plant
    rot, pos, b, _, _ = kinematics(p, compiled.q0, np.zeros(p.twists.shape[0]))
    stroke, g = pto_strokes(p, compiled.q0, rot, pos, b)
    return b, world_jacobian(rot, b)[p.hydro_index], g, stroke - p.pto_rest


def linearise(compiled: CompiledScene) -> LinearisedMFM:
    """The linearised MFM matrices about the scene's static equilibrium (linear controllers only).

    Raises
    ------
    ValueError
        If the scene's controller offers no linear gains.
    """
    if not compiled.linear_controller:
        raise ValueError("the frequency-domain solution needs a controller with linear gains (such as 'damping')")
    p = compiled.plant
    b, bw, g, _ = equilibrium_maps(compiled)
    # the database's own A_inf: A(omega) - A_inf is added below (the simulator's A_inf correction is not wanted here)
    total = body_mass_matrix(compiled.device.model) + compiled.coupling.added_mass_inf
    mass = b.T @ total @ b
    stiffness = compiled.stiffness  # device springs and the controller's stiffness included
    damping = g.T @ np.diag(p.pto_damping) @ g
    return LinearisedMFM(0.5 * (mass + mass.T), damping, stiffness, bw, g)


def frequency_response(compiled: CompiledScene, omega: np.ndarray) -> tuple[np.ndarray, LinearisedMFM]:
    """Transfer matrix H(omega) (n_omega, nv, n_h) from hydro-DOF forces to generalised displacements, and the
    linearised matrices."""
    lin = linearise(compiled)
    ds = compiled.hydro.dataset
    omega = np.atleast_1d(np.asarray(omega, dtype=float))
    data_omega = compiled.hydro.omega
    added = interpolate_matrices(data_omega, ds.added_mass.values, omega) - ds.added_mass_inf.values[None]
    damping = interpolate_matrices(data_omega, ds.radiation_damping.values, omega)
    bw = lin.hydro_jacobian
    z = (
        -(omega**2)[:, None, None] * (lin.mass[None] + bw.T @ added @ bw)
        + 1j * omega[:, None, None] * (lin.damping[None] + bw.T @ damping @ bw)
        + lin.stiffness[None]
    )
    return np.linalg.solve(z, np.broadcast_to(bw.T, (omega.size, *bw.T.shape)).astype(complex)), lin


def steady_state(compiled: CompiledScene, time: np.ndarray) -> dict[str, np.ndarray]:
    """Steady-state linear response to the scene's waves (no ramp) at ``time`` [s].

    Returns
    -------
    dict
        ``displacement`` (n_t, nv) generalised displacements from the equilibrium; ``pto`` (n_t, n_pto) PTO
        strokes from the equilibrium; ``amplitudes`` (nv, n_components) complex.
    """
    if compiled.excitation is None:
        raise ValueError("calm water: the steady state is the equilibrium")
    exc = compiled.excitation
    h, lin = frequency_response(compiled, exc.omega)
    amplitudes = np.einsum("wvj,jw->vw", h, exc.coefficients)
    xi = np.real(evaluate(amplitudes, exc.omega, np.asarray(time, dtype=float))).T
    return {"displacement": xi, "pto": xi @ lin.pto_jacobian.T, "amplitudes": amplitudes}
