"""The undisturbed incident wave at points, inside the kernels: elevation, velocity and acceleration of the fluid
(Airy, Wheeler-stretched, zero above the surface), from the wave components and their phasors at the evaluation's
time.

With the phasors P_k = r(t) A_k exp(i omega_k t) (``r`` the start ramp) and x' = x cos(beta) + y sin(beta) the
position along the direction of propagation:

    eta   = Re sum P_k exp(-i k x')
    u     = Re sum omega P_k F_k(z') exp(-i k x')       (horizontal, along beta)
    w     = Re sum i omega P_k G_k(z') exp(-i k x')
    du/dt = Re sum i omega^2 P_k F_k exp(-i k x'),  dw/dt = -Re sum omega^2 P_k G_k exp(-i k x')

with F = G = exp(k z') in deep water, F = cosh(k (z' + h)) / sinh(k h) and G = sinh(k (z' + h)) / sinh(k h) in
depth h, and the stretched height z' = (z - eta) h / (h + eta) (z - eta in deep water): the linear kinematics at
the still water level act at the instantaneous surface (Wheeler 1970). Above the surface everything is zero.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ._jit import inline_kernel


class WaveArrays(NamedTuple):
    """The incident wave for the kernels (empty arrays: no waves, or no term that needs them).

    ``omega`` (n_w,) [rad/s], ``k`` (n_w,) [rad/m], ``amplitude`` (n_w,) complex A_k at the origin [m],
    ``heading`` (2,) cos and sin of the direction of propagation, ``depth`` (1,) [m] (inf: deep water), ``ramp``
    (1,) the start ramp's duration [s] (0: none).
    """

    omega: np.ndarray
    k: np.ndarray
    amplitude: np.ndarray
    heading: np.ndarray
    depth: np.ndarray
    ramp: np.ndarray


def no_waves() -> WaveArrays:
    """Empty wave arrays."""
    return WaveArrays(
        np.zeros(0), np.zeros(0), np.zeros(0, dtype=complex), np.array([1.0, 0.0]), np.array([np.inf]), np.zeros(1)
    )


@inline_kernel
def wave_phasors(wave: WaveArrays, t: float, out: np.ndarray) -> None:
    """P_k = r(t) A_k exp(i omega_k t) into ``out`` (n_w,) complex."""
    ramp = 1.0
    if wave.ramp[0] > 0.0 and t < wave.ramp[0]:
        ramp = 0.5 * (1.0 - np.cos(np.pi * max(t, 0.0) / wave.ramp[0]))
    for j in range(wave.omega.shape[0]):
        phase = wave.omega[j] * t
        out[j] = ramp * wave.amplitude[j] * complex(np.cos(phase), np.sin(phase))


@inline_kernel
def wave_point(wave: WaveArrays, phasor: np.ndarray, x: float, y: float, z: float, out: np.ndarray) -> bool:
    """The fluid's velocity (3,) and acceleration (3,) [m/s, m/s^2], world axes, at the point (x, y, z) into ``out``
    (6,); returns whether the point is below the incident surface (else ``out`` is zero)."""
    cb, sb = wave.heading[0], wave.heading[1]
    along = x * cb + y * sb
    n_w = wave.omega.shape[0]
    eta = 0.0
    for j in range(n_w):
        arg = -wave.k[j] * along
        eta += phasor[j].real * np.cos(arg) - phasor[j].imag * np.sin(arg)
    for a in range(6):
        out[a] = 0.0
    if z > eta:
        return False
    h = wave.depth[0]
    deep = not np.isfinite(h)
    zs = z - eta if deep else (z - eta) * h / (h + eta)
    u = w_ = du = dw = 0.0
    for j in range(n_w):
        kj, om = wave.k[j], wave.omega[j]
        if deep:
            f = np.exp(kj * zs)
            g_ = f
        else:
            s = np.sinh(kj * h)
            f = np.cosh(kj * (zs + h)) / s
            g_ = np.sinh(kj * (zs + h)) / s
        arg = -kj * along
        c, s_ = np.cos(arg), np.sin(arg)
        re = phasor[j].real * c - phasor[j].imag * s_  # Re[P e^{-ikx'}]
        im = phasor[j].real * s_ + phasor[j].imag * c  # Im[P e^{-ikx'}]
        u += om * f * re
        w_ -= om * g_ * im  # Re[i z] = -Im z
        du -= om * om * f * im
        dw -= om * om * g_ * re
    out[0], out[1], out[2] = u * cb, u * sb, w_
    out[3], out[4], out[5] = du * cb, du * sb, dw
    return True
