"""The linear Froude-Krylov force on a mesh: the incident pressure, linear and unstretched, over the mean wetted
surface (the mesh clipped at z = 0), per wave component.

Component k exerts Re[F_k exp(i omega_k t)] with

    F_k = -rho g A_k int_S Z_k(z) exp(-i k_k x') n dS,     M_k = -rho g A_k int_S Z_k(z) exp(-i k_k x') (r x n) dS,

x' = x cos(beta) + y sin(beta), Z_k the vertical profile (exp(k z) in deep water, cosh(k (z + h)) / cosh(k h) in
depth h), r measured from the centre of mass, world axes. The integrals are taken on every wet triangle by the
7-point rule of degree 5 (Strang and Fix; Dunavant 1985), which leaves the faceting of the mesh as the error.
This is what the per-step kernel's Froude-Krylov force tends to for small waves (in surface mode 0), so the
remainder formulation can subtract it.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np

from ..constants import GRAVITY, RHO_WATER
from ..hydro.mesh import area_vectors, clip_below

if TYPE_CHECKING:  # pragma: no cover
    from ..hydro.mesh import SurfaceMesh
    from ..waves import WaveComponents

_R15 = math.sqrt(15.0)
_A1, _B1 = (6.0 - _R15) / 21.0, (9.0 + 2.0 * _R15) / 21.0
_A2, _B2 = (6.0 + _R15) / 21.0, (9.0 - 2.0 * _R15) / 21.0
RULE_POINTS = np.array(
    [
        [1 / 3, 1 / 3, 1 / 3],
        [_B1, _A1, _A1],
        [_A1, _B1, _A1],
        [_A1, _A1, _B1],
        [_B2, _A2, _A2],
        [_A2, _B2, _A2],
        [_A2, _A2, _B2],
    ]
)
"""Barycentric coordinates of the 7-point rule of degree 5 on a triangle."""

RULE_WEIGHTS = np.array([9 / 40] + [(155 - _R15) / 1200] * 3 + [(155 + _R15) / 1200] * 3)
"""Its weights (sum 1; times the triangle's area)."""


def linear_froude_krylov(
    mesh: SurfaceMesh,
    pos: Any,
    rot: Any,
    components: WaveComponents,
    depth: float = math.inf,
    rho: float = RHO_WATER,
    g: float = GRAVITY,
    *,
    chunk: int = 64,
) -> np.ndarray:
    """The complex linear Froude-Krylov force and moment of every wave component (see the module docstring).

    Parameters
    ----------
    mesh : SurfaceMesh
    pos : (3,) float
        World position of the centre of mass [m].
    rot : (3, 3) float
        Rotation of the body (body axes to world axes).
    components : WaveComponents
    depth : float
        Water depth [m] (inf: deep water).
    rho, g : float
    chunk : int
        Components per batch (memory: 7 x wet triangles x chunk complex numbers).

    Returns
    -------
    complex ndarray (n_components, 6)
        F_k [N] and M_k about the centre of mass [N m] in world axes, for the amplitude A_k of each component:
        the force in time is sum_k Re[F_k exp(i omega_k t)].

    Raises
    ------
    ValueError
        On a non-positive depth.
    """
    from ..waves import wavenumber

    if not depth > 0:
        raise ValueError(f"depth must be positive or inf [m]; got {depth!r}")
    position = np.asarray(pos, dtype=float).reshape(3)
    pieces, _ = clip_below(mesh.posed(position, rot), 0.0)
    normal = area_vectors(pieces)  # (m, 3)
    points = np.einsum("qc,mcx->mqx", RULE_POINTS, pieces)  # (m, 7, 3)
    lever = np.cross(points - position, normal[:, None, :])  # (m, 7, 3): (r x N) at each point
    generalised = np.concatenate([np.broadcast_to(normal[:, None, :], lever.shape), lever], axis=2)  # (m, 7, 6)
    weighted = generalised * RULE_WEIGHTS[None, :, None]
    cb, sb = math.cos(components.direction), math.sin(components.direction)
    xp = points[..., 0] * cb + points[..., 1] * sb
    z = points[..., 2]
    omega = np.asarray(components.omega, dtype=float)
    k_all = np.asarray(wavenumber(omega, depth, g), dtype=float)
    out = np.zeros((omega.size, 6), dtype=complex)
    for start in range(0, omega.size, chunk):
        k = k_all[start : start + chunk, None, None]
        if math.isinf(depth):
            profile = np.exp(k * z[None])
        else:
            profile = np.exp(k * z[None]) * (1 + np.exp(-2 * k * (z[None] + depth))) / (1 + np.exp(-2 * k * depth))
        pressure = profile * np.exp(-1j * k * xp[None])  # (c, m, 7), per rho g A
        out[start : start + chunk] = -np.einsum("cmq,mqj->cj", pressure, weighted)
    return out * (rho * g) * np.asarray(components.amplitude, dtype=complex)[:, None]
