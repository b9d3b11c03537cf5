"""The layout of a wecss hydrodynamic database (one ``xarray.Dataset``).

Dimensions
----------
``omega``
    Angular frequency [rad/s], strictly increasing, finite (omega = 0 and infinity are kept apart in
    ``added_mass_zero`` and ``added_mass_inf``).
``influenced_dof`` and ``radiating_dof``
    Degrees of freedom named ``<body>__<Dof>`` as in Capytaine (``bow__Heave``); both hold the same
    names in the same order. Matrices are stored with the influenced (force) index first, so
    ``ds.added_mass.values[k]`` is the matrix A with F_i = -A_ij xddot_j.
``wave_direction``
    Direction of wave propagation [rad] (0: waves travelling along +x).
``body``, ``axis`` (x, y, z) and ``axis_col`` (x, y, z)
    Per-body properties.

All complex amplitudes follow Re[X exp(+i omega t)]; readers convert from other conventions.
``hydrostatic_stiffness`` is the stiffness of the hydrostatic pressure force alone (no gravity term)
about each body's ``reference_point``; gravity acts at the centre of mass and is handled by the
multibody model.
"""

from __future__ import annotations

from collections.abc import Mapping

from ..constants import RIGID_BODY_DOFS

MATRIX_DIMS: tuple[str, str] = ("influenced_dof", "radiating_dof")
FREQUENCY_MATRIX_DIMS: tuple[str, str, str] = ("omega", "influenced_dof", "radiating_dof")
FORCE_DIMS: tuple[str, str, str] = ("omega", "wave_direction", "influenced_dof")
AXES: tuple[str, str, str] = ("x", "y", "z")

REQUIRED_VARIABLES: Mapping[str, tuple[str, ...]] = {
    "added_mass": FREQUENCY_MATRIX_DIMS,
    "radiation_damping": FREQUENCY_MATRIX_DIMS,
    "added_mass_inf": MATRIX_DIMS,
    "excitation": FORCE_DIMS,
    "hydrostatic_stiffness": MATRIX_DIMS,
    "mass": ("body",),
    "inertia": ("body", "axis", "axis_col"),
    "center_of_mass": ("body", "axis"),
    "center_of_buoyancy": ("body", "axis"),
    "displaced_volume": ("body",),
    "reference_point": ("body", "axis"),
}
"""Variables every database holds, with their dimensions in this order."""

OPTIONAL_VARIABLES: Mapping[str, tuple[str, ...]] = {
    "added_mass_zero": MATRIX_DIMS,
    "froude_krylov": FORCE_DIMS,
    "diffraction": FORCE_DIMS,
}
"""Variables a database may hold."""

COMPLEX_VARIABLES: frozenset[str] = frozenset({"excitation", "froude_krylov", "diffraction"})
"""Variables whose values are complex amplitudes."""

REQUIRED_ATTRS: tuple[str, ...] = ("rho", "g", "water_depth", "source", "convention")
"""Dataset attributes every database holds (``water_depth`` is ``inf`` for deep water)."""

DOF_SEPARATOR = "__"


def dof_name(body: str, dof: str) -> str:
    """Return the DOF name ``<body>__<Dof>`` (``dof`` is one of Surge, Sway, Heave, Roll, Pitch, Yaw).

    Raises
    ------
    ValueError
        If ``dof`` is not a rigid-body DOF name or ``body`` contains the separator ``__``.
    """
    if dof not in RIGID_BODY_DOFS:
        raise ValueError(f"unknown DOF {dof!r}; accepted: {', '.join(RIGID_BODY_DOFS)}")
    if DOF_SEPARATOR in body or not body:
        raise ValueError(f"body name {body!r} must be non-empty and must not contain {DOF_SEPARATOR!r}")
    return f"{body}{DOF_SEPARATOR}{dof}"


def split_dof(name: str) -> tuple[str, str]:
    """Split ``<body>__<Dof>`` into ``(body, Dof)``.

    Raises
    ------
    ValueError
        If the name has no ``__`` separator or the DOF part is not a rigid-body DOF.
    """
    body, sep, dof = str(name).rpartition(DOF_SEPARATOR)
    if not sep or not body or dof not in RIGID_BODY_DOFS:
        raise ValueError(f"DOF name {name!r} is not of the form <body>__<Dof> with Dof in {', '.join(RIGID_BODY_DOFS)}")
    return body, dof


def dof_index(dof: str) -> int:
    """Index 0..5 of a rigid-body DOF name (Surge = 0, ..., Yaw = 5)."""
    return RIGID_BODY_DOFS.index(dof)
