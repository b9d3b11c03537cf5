"""Geometric stiffness of a reduced basis from its own axial strain: the cubic strain energy of a floating frame.

A beam whose axis stretches by u' carries the axial force N = EA u', and a transverse slope v', w' or a twist theta'
then stores the extra strain energy 1/2 int N (v'^2 + w'^2 + (Ip / A) theta'^2) ds (the cubic term of the von Karman
strain energy 1/2 int EA (u' + (v'^2 + w'^2) / 2)^2 ds with Wagner's torsion term). With every field in one modal
basis, u = Phi xi, the element's axial force is linear in the modal coordinates, N_e(xi) = sum_m xi_m N_e,m, and so
is the geometric stiffness: the energy is

    U3(xi) = 1/2 sum_m xi_m xi' A_m xi,   A_m = Phi' K_G(N_m) Phi,

with K_G the frame's geometric stiffness (``Frame.geometric_stiffness``). Its generalised force
-dU3/dxi = -(sum_m xi_m A_m) xi - 1/2 (xi' A_j xi)_j holds the geometric stiffening of the current axial force and
the axial shortening of a bent beam that goes with it: a potential, so a free body keeps its energy. Linearised
about a preloaded state xi0, its stiffness is sum_m xi0_m A_m (K_G of the preload's axial force) plus
(A_j xi0)_k + (A_k xi0)_j, which vanish for a straight, purely axial preload (a spinning beam) and not for one that
also bends the beam (a weight's sag). The preload is in the basis when the basis holds the static response to it:
the inertia-relief and centrifugal vectors of ``craig_bampton`` (weight, rigid accelerations, a spin) and its
constraint modes (loads at the interfaces). The quartic term of the strain energy is left out: for moderate
deformations (the cubic energy alone is not bounded below).
"""

from __future__ import annotations

import numpy as np

from ._frame import Frame


def axial_forces(frame: Frame, displacements: np.ndarray) -> np.ndarray:
    """Axial force of each element (n_element, ...) [N, tension positive] for nodal displacements (n_dof, ...) [m,
    rad]: EA / L times the element's elongation (constant along a frame element, whose axial field is linear)."""
    d = np.asarray(displacements, dtype=float)
    if d.shape[:1] != (frame.n_dof,):
        raise ValueError(f"displacements must have n_dof = {frame.n_dof} rows; got shape {d.shape}")
    out = np.zeros((len(frame.elements), *d.shape[1:]))
    for k, e in enumerate(frame.elements):
        stretch = np.tensordot(e.axes[0], d[frame.node_dofs(e.j)[:3]] - d[frame.node_dofs(e.i)[:3]], axes=1)
        out[k] = e.material.youngs_modulus * e.section.area / e.length * stretch
    return out


def axial_geometric_stiffness(frame: Frame, basis: np.ndarray) -> np.ndarray:
    """A (n, n, n): A[m] = Phi' K_G(N_m) Phi, the geometric stiffness in the basis ``basis`` (n_dof, n) of the axial
    force N_m of a unit modal coordinate m [N m per 1] (see the module docstring).

    Raises
    ------
    ValueError
        If the basis does not have one row per DOF of the frame.
    """
    phi = frame.basis(basis)
    forces = axial_forces(frame, phi)  # (n_element, n)
    out = np.zeros((phi.shape[1],) * 3)
    for m in range(phi.shape[1]):
        k_g = frame.geometric_stiffness(list(forces[:, m]))
        out[m] = phi.T @ k_g @ phi
        out[m] = 0.5 * (out[m] + out[m].T)
    return out
