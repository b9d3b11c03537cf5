"""Bending natural frequencies of a straight Euler-Bernoulli beam by finite elements (cubic Hermite elements,
consistent mass), with point supports, a tip mass and a tip spring: the first bending mode of an arm carrying a
float, to set beside a structural model's modal frequencies."""

from __future__ import annotations

import numpy as np
from scipy.linalg import eigh


def beam_frequencies(
    length: float,
    bending_stiffness: float,
    mass_per_length: float,
    *,
    pinned: tuple[float, ...] = (),
    clamped: tuple[float, ...] = (),
    tip_mass: float = 0.0,
    tip_spring: float = 0.0,
    springs: tuple[tuple[float, float], ...] = (),
    n_elements: int = 96,
    n_modes: int = 3,
) -> np.ndarray:
    """Lowest bending natural frequencies [Hz] of a beam on [0, length] in one plane.

    Parameters
    ----------
    length : float
        [m].
    bending_stiffness : float
        E I [N m^2].
    mass_per_length : float
        [kg/m].
    pinned, clamped : tuple of float
        Positions of supports that hold the deflection (pinned) or deflection and slope (clamped) [m]; they are
        moved to the nearest node. Together with the springs they must stop rigid-body motion.
    tip_mass : float
        Point mass at ``length`` [kg].
    tip_spring : float
        Translational spring to ground at ``length`` [N/m] (e.g. a float's hydrostatic stiffness).
    springs : tuple of (position [m], stiffness [N/m])
        Further translational springs to ground (e.g. a PTO cylinder's stiffness across the beam), at the nearest node.
    n_elements, n_modes : int

    Raises
    ------
    ValueError
        On non-positive length, stiffness or mass per length, negative tip mass or spring, supports off the beam, or
        supports that leave the beam free to move as a rigid body.
    """
    for name, value in (
        ("length", length),
        ("bending_stiffness", bending_stiffness),
        ("mass_per_length", mass_per_length),
    ):
        if not (value > 0 and np.isfinite(value)):
            raise ValueError(f"{name} must be positive and finite, got {value!r}")
    if not (np.isfinite(tip_mass) and np.isfinite(tip_spring)) or tip_mass < 0 or tip_spring < 0:
        raise ValueError(f"tip_mass and tip_spring must be finite and not negative, got {tip_mass!r}, {tip_spring!r}")
    for _x, stiffness in springs:
        if not (np.isfinite(stiffness) and stiffness >= 0):
            raise ValueError(f"spring stiffness must be finite and not negative, got {stiffness!r}")
    for x in (*pinned, *clamped, *(x for x, _ in springs)):
        if not 0 <= x <= length:
            raise ValueError(f"support at {x} m is off the beam (0 .. {length} m)")
    h = length / n_elements
    ei, mu = bending_stiffness, mass_per_length
    k_e = (
        ei
        / h**3
        * np.array(
            [
                [12, 6 * h, -12, 6 * h],
                [6 * h, 4 * h**2, -6 * h, 2 * h**2],
                [-12, -6 * h, 12, -6 * h],
                [6 * h, 2 * h**2, -6 * h, 4 * h**2],
            ]
        )
    )
    m_e = (
        mu
        * h
        / 420
        * np.array(
            [
                [156, 22 * h, 54, -13 * h],
                [22 * h, 4 * h**2, 13 * h, -3 * h**2],
                [54, 13 * h, 156, -22 * h],
                [-13 * h, -3 * h**2, -22 * h, 4 * h**2],
            ]
        )
    )
    n_dof = 2 * (n_elements + 1)
    k = np.zeros((n_dof, n_dof))
    m = np.zeros((n_dof, n_dof))
    for e in range(n_elements):
        idx = slice(2 * e, 2 * e + 4)
        k[idx, idx] += k_e
        m[idx, idx] += m_e
    m[-2, -2] += tip_mass
    k[-2, -2] += tip_spring
    for x, stiffness in springs:
        k[2 * round(x / h), 2 * round(x / h)] += stiffness
    fixed = {2 * round(x / h) for x in pinned} | {2 * round(x / h) + d for x in clamped for d in (0, 1)}
    free = [i for i in range(n_dof) if i not in fixed]
    # the reciprocal problem M x = (1 / omega^2) K x: its largest values (the lowest modes) come with full relative
    # accuracy, where the direct problem loses the low modes of a stiff beam to round-off of its highest ones
    k_ff = k[np.ix_(free, free)]
    try:
        np.linalg.cholesky(k_ff)
    except np.linalg.LinAlgError:
        raise ValueError("the supports and springs do not stop rigid-body motion of the beam") from None
    values = np.sort(1.0 / eigh(m[np.ix_(free, free)], k_ff, eigvals_only=True))
    if not np.all(np.isfinite(values)) or values[0] <= 0:
        raise ValueError("the beam's eigenproblem is too ill-conditioned (springs far softer than the beam?)")
    return np.sqrt(values[:n_modes]) / (2 * np.pi)
