"""Physical constants and defaults used throughout wecss (SI units).

Every dataset records the ``rho`` and ``g`` it was made with; these are only the defaults
for data that wecss makes itself (DESIGN.md, "Physics conventions").
"""

from __future__ import annotations

RHO_WATER: float = 1000.0
"""Default water density [kg/m^3] (fresh water, as in the model-scale tanks, Capytaine and WEC-Sim)."""

GRAVITY: float = 9.81
"""Default gravitational acceleration [m/s^2]."""

TIME_CONVENTION: str = "exp(+i omega t)"
"""Complex amplitudes X mean Re[X exp(+i omega t)] (WAMIT, Falnes)."""

RIGID_BODY_DOFS: tuple[str, ...] = ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")
"""Names of the six rigid-body degrees of freedom, in Capytaine's spelling and order."""

DOF_KINDS: tuple[str, str, str] = ("linear", "angular", "generalised")
"""The kinds of a degree of freedom (a generalised coordinate, a hydrodynamic DOF): a translation [m, N], a rotation
[rad, N m], or a body's generalised mode (coordinate [1], force [J] = work per unit coordinate)."""
