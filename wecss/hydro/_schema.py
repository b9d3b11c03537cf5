"""The layout of a wecss hydrodynamic database (one ``xarray.Dataset``).

Dimensions
----------
``omega``
    Angular frequency [rad/s], strictly increasing, finite (omega = 0 and infinity are kept apart in
    ``added_mass_zero`` and ``added_mass_inf``).
``influenced_dof`` and ``radiating_dof``
    Degrees of freedom named ``<body>__<Dof>`` as in Capytaine (``bow__Heave``); both hold the same
    names in the same order. ``Dof`` is a rigid-body DOF (Surge ... Yaw) or a body's generalised mode (any
    other name, such as ``barge__flex1``: a flexible or user-defined mode, WAMIT's modes 7.., Capytaine's custom
    DOFs); each body's rigid DOFs come before its generalised modes. A generalised coordinate is
    dimensionless (the mode shape gives the displacement [m] per unit coordinate), so its coefficients carry the
    units of a force times a length per unit coordinate: added mass [kg m^2] with another generalised mode,
    [kg m] with a translation, [kg m^2] with a rotation, and likewise for damping, stiffness and excitation
    ([J/m] per metre of wave amplitude on a mode). Transforms to another reference point leave them as they are.
    Matrices are stored with the influenced (force) index first, so ``ds.added_mass.values[k]`` is the matrix A
    with F_i = -A_ij xddot_j.
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

from collections.abc import Mapping, Sequence

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

"""Kinds of degree of freedom: a translation (Surge, Sway, Heave) [m], a rotation (Roll, Pitch, Yaw) [rad], or a
generalised mode of a body (a flexible or other user-defined mode, WAMIT's modes 7.., Capytaine's custom DOFs),
whose coordinate is dimensionless [1]: its mode shape gives the displacement [m] per unit coordinate."""

_LINEAR = frozenset(RIGID_BODY_DOFS[:3])
_FOLDED_RIGID = {d.lower(): d for d in RIGID_BODY_DOFS}


def check_mode_name(mode: str) -> str:
    """Return ``mode`` if it can name a generalised mode of a body.

    Raises
    ------
    ValueError
        If it is not a non-empty string, holds the separator ``__`` or surrounding blanks, or spells a rigid-body
        DOF (``Heave``, or ``heave``: ambiguous).
    """
    if not isinstance(mode, str) or not mode or mode != mode.strip() or DOF_SEPARATOR in mode:
        raise ValueError(
            f"generalised mode name {mode!r} must be a non-empty string without {DOF_SEPARATOR!r} or surrounding "
            "blanks (such as 'flex1')"
        )
    if mode.lower() in _FOLDED_RIGID:
        raise ValueError(
            f"generalised mode name {mode!r} spells the rigid-body DOF {_FOLDED_RIGID[mode.lower()]!r}; "
            "choose another name (such as 'flex1')"
        )
    return mode


def dof_name(body: str, dof: str) -> str:
    """Return the DOF name ``<body>__<Dof>``: ``dof`` is one of Surge, Sway, Heave, Roll, Pitch, Yaw, or the name
    of a generalised mode of the body (see :func:`check_mode_name`).

    Raises
    ------
    ValueError
        If ``dof`` is neither, or ``body`` is empty or contains the separator ``__``.
    """
    if dof not in RIGID_BODY_DOFS:
        try:
            check_mode_name(dof)
        except ValueError as err:
            raise ValueError(
                f"unknown DOF {dof!r}: neither a rigid-body DOF ({', '.join(RIGID_BODY_DOFS)}) nor a generalised "
                f"mode name ({err})"
            ) from None
    if not isinstance(body, str) or DOF_SEPARATOR in body or not body:
        raise ValueError(f"body name {body!r} must be non-empty and must not contain {DOF_SEPARATOR!r}")
    return f"{body}{DOF_SEPARATOR}{dof}"


def split_dof(name: str) -> tuple[str, str]:
    """Split ``<body>__<Dof>`` into ``(body, Dof)``; ``Dof`` is a rigid-body DOF or a generalised mode's name.

    Raises
    ------
    ValueError
        If the name has no ``__`` separator, or the DOF part is neither a rigid-body DOF nor a valid mode name.
    """
    body, sep, dof = str(name).rpartition(DOF_SEPARATOR)
    if sep and body and dof in RIGID_BODY_DOFS:
        return body, dof
    try:
        if not (sep and body):
            raise ValueError("no body part")
        check_mode_name(dof)
    except ValueError:
        raise ValueError(
            f"DOF name {name!r} is not of the form <body>__<Dof> with Dof in {', '.join(RIGID_BODY_DOFS)} or the "
            "name of a generalised mode (no '__', not a rigid-body DOF in another case)"
        ) from None
    return body, dof


def dof_index(dof: str) -> int:
    """Index 0..5 of a rigid-body DOF name (Surge = 0, ..., Yaw = 5).

    Raises
    ------
    ValueError
        If ``dof`` is not a rigid-body DOF (a generalised mode has no rigid index: see :func:`dof_kind`).
    """
    if dof not in RIGID_BODY_DOFS:
        raise ValueError(f"{dof!r} is not a rigid-body DOF ({', '.join(RIGID_BODY_DOFS)}); it has no rigid index")
    return RIGID_BODY_DOFS.index(dof)


def is_rigid_dof(dof: str) -> bool:
    """Whether ``dof`` (the DOF part, such as ``Heave``, or a full name ``<body>__<Dof>``) is a rigid-body DOF."""
    return dof_kind(dof) != "generalised"


def dof_kind(dof: str) -> str:
    """The kind of a DOF, given as its DOF part (``Heave``, ``flex1``) or its full name (``bow__Heave``):
    ``"linear"`` (Surge, Sway, Heave: [m], [N]), ``"angular"`` (Roll, Pitch, Yaw: [rad], [N m]) or
    ``"generalised"`` (a body's generalised mode: coordinate [1], force [J] = work per unit coordinate).

    Raises
    ------
    ValueError
        If ``dof`` is neither a rigid-body DOF, a valid mode name nor a full DOF name.
    """
    text = str(dof)
    part = split_dof(text)[1] if DOF_SEPARATOR in text else text
    if part not in RIGID_BODY_DOFS:
        check_mode_name(part)
    if part in _LINEAR:
        return "linear"
    if part in RIGID_BODY_DOFS:
        return "angular"
    return "generalised"


def dof_kinds(dofs: Sequence[str]) -> tuple[str, ...]:
    """:func:`dof_kind` of each DOF."""
    return tuple(dof_kind(d) for d in dofs)
