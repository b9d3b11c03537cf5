"""Capytaine meshes of axisymmetric floats: the hull revolved from its meridian, and a lid at z = 0.

Both are ``RotationSymmetricMesh`` objects with the same number of sectors, so that a single float at
the origin keeps its rotation symmetry in the solver. Two Capytaine 3.0 pitfalls are avoided here:
``generate_lid()`` returns an empty lid on symmetric meshes (the lid is revolved from a radial line
instead), and hydrostatics computed on a ``RotationSymmetricMesh`` fail (use ``.merged()`` for them).

By default the vertices lie on the true surface (the usual BEM mesh; the polygon then encloses a little
less volume than the float). With ``preserve_area`` the radial coordinates are scaled by
sqrt(theta / sin(theta)), theta = 2 pi / n, so that every horizontal section of the polygonal mesh has the
area of the true circle, and arcs of the meridian are treated alike: waterplane area and displaced volume
of the mesh then match the true float (to 1e-5 at usual resolutions). That suits hydrostatics; for the BEM
it is worse (the heaving hemisphere's added mass moves 0.6-0.8 % further from Hulme's at 1800 panels).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .._polygon import radial_scale as _radial_scale
from ._lazy import import_capytaine
from ._profile import AxisymmetricProfile

MIN_SECTORS = 24
"""Fewest sectors around a float.

An inscribed n-gon lacks a fraction 1 - sin(2 pi/n) / (2 pi/n) of the circle's area: 4.5 % at 12 sides, 1.1 % at
24. On a flat-bottomed float that deficit shows directly in heave: with 12 sectors the M4 bow float's heave
damping came out 10 % below a converged mesh's, with 24 the worst diagonal entry of the 111 layout is within 3 %.
"""

DEFAULT_ASPECT_RATIO = 3.0
"""Default ratio of a hull panel's width (around the float) to its height (along the meridian).

Axisymmetric floats gain most from a fine meridian: for the heaving hemisphere at about 1600 panels,
panels three times wider than tall roughly halve the added-mass error of square ones (tests/hydro/test_bem.py).
"""


def sectors_for(radius: float, panel_size: float) -> int:
    """Number of sectors (a multiple of 4, at least :data:`MIN_SECTORS`) giving panels about ``panel_size`` wide.

    Raises
    ------
    ValueError
        If ``radius`` or ``panel_size`` is not positive and finite.
    """
    for name, value in (("radius", radius), ("panel_size", panel_size)):
        if not (np.isfinite(value) and value > 0):
            raise ValueError(f"{name} must be a positive finite number [m]; got {value!r}")
    n = 4 * int(np.ceil(2 * np.pi * radius / panel_size / 4 - 1e-9))
    return max(MIN_SECTORS, n)


def radial_scale(n_sectors: int) -> float:
    """Factor on radii that gives a regular ``n_sectors``-gon the area of its circle (the surface meshes' own,
    ``wecss.hydro._polygon.radial_scale``)."""
    return _radial_scale(n_sectors)


def revolve(points_rz: np.ndarray, n_sectors: int, *, preserve_area: bool = False, name: str | None = None) -> Any:
    """Revolve a polyline of (r, z) points about the z axis into a ``capytaine.RotationSymmetricMesh``.

    Parameters
    ----------
    points_rz : array of shape (m, 2)
        The polyline [m]. Quads face outwards (to the right of the direction of travel in the (r, z)
        plane), so a hull meridian runs from the waterline down to the axis.
    n_sectors : int
        Number of sectors (rotation order of the mesh), at least 3.
    preserve_area : bool
        Scale the radii by :func:`radial_scale`.
    name : str, optional
        Mesh name.

    Raises
    ------
    ValueError
        If the points are not an (m, 2) array with m >= 2 and r >= 0, or ``n_sectors`` < 3.
    ImportError
        If Capytaine is not installed.
    """
    cpt = import_capytaine()
    points = np.asarray(points_rz, dtype=float)
    if points.ndim != 2 or points.shape[1] != 2 or points.shape[0] < 2:
        raise ValueError(f"points_rz must have shape (m, 2) with m >= 2; got {points.shape}")
    if np.any(points[:, 0] < 0):
        raise ValueError("points_rz must have r >= 0")
    if int(n_sectors) != n_sectors or n_sectors < 3:
        raise ValueError(f"n_sectors must be an integer >= 3; got {n_sectors!r}")
    n_sectors = int(n_sectors)
    r = points[:, 0] * (radial_scale(n_sectors) if preserve_area else 1.0)
    angle = 2 * np.pi / n_sectors
    first = np.column_stack([r, np.zeros_like(r), points[:, 1]])
    second = np.column_stack([r * np.cos(angle), r * np.sin(angle), points[:, 1]])
    m = len(points)
    faces = np.array([(i, i + 1, m + i + 1, m + i) for i in range(m - 1)])
    wedge = cpt.Mesh(vertices=np.concatenate([first, second]), faces=faces)
    return cpt.RotationSymmetricMesh(wedge=wedge, n=n_sectors, name=name)


def hull_mesh(
    profile: AxisymmetricProfile,
    panel_size: float,
    *,
    aspect_ratio: float = DEFAULT_ASPECT_RATIO,
    n_sectors: int | None = None,
    preserve_area: bool = False,
    name: str | None = None,
) -> Any:
    """Immersed hull of ``profile`` as a ``RotationSymmetricMesh`` centred on the z axis.

    Parameters
    ----------
    profile : AxisymmetricProfile
    panel_size : float
        Target panel height along the meridian [m].
    aspect_ratio : float
        Target panel width around the float at the waterline, in units of ``panel_size``.
    n_sectors : int, optional
        Number of sectors; by default :func:`sectors_for` the waterline radius and the panel width.
    preserve_area : bool
        Keep waterplane area and volume of the true shape (see module docstring).
    name : str, optional

    Raises
    ------
    ValueError
        If ``panel_size`` or ``aspect_ratio`` is not positive and finite.
    ImportError
        If Capytaine is not installed.
    """
    n = _sectors(profile, panel_size, aspect_ratio, n_sectors)
    return revolve(profile.meridian(panel_size, preserve_area=preserve_area), n, preserve_area=preserve_area, name=name)


def lid_mesh(
    profile: AxisymmetricProfile,
    panel_size: float,
    *,
    aspect_ratio: float = DEFAULT_ASPECT_RATIO,
    n_sectors: int | None = None,
    preserve_area: bool = False,
    name: str | None = None,
) -> Any:
    """Disc at z = 0 closing the waterplane of ``profile`` (a lid against irregular frequencies).

    Same arguments as :func:`hull_mesh`, whose ``n_sectors`` and ``preserve_area`` it should share so that
    the lid's rim matches the hull's waterline. Its rings are ``aspect_ratio * panel_size`` apart (the
    panel width at the rim): the lid only has to suppress the irregular modes, which vary on the scale
    of the waterplane radius.

    Raises
    ------
    ValueError
        If ``panel_size`` or ``aspect_ratio`` is not positive and finite.
    ImportError
        If Capytaine is not installed.
    """
    n = _sectors(profile, panel_size, aspect_ratio, n_sectors)
    n_rings = max(1, int(np.ceil(profile.radius / (aspect_ratio * panel_size) - 1e-9)))
    radii = np.linspace(profile.radius, 0.0, n_rings + 1)  # rim to centre: normals point down, into the body
    return revolve(np.column_stack([radii, np.zeros_like(radii)]), n, preserve_area=preserve_area, name=name)


def _sectors(profile: AxisymmetricProfile, panel_size: float, aspect_ratio: float, n_sectors: int | None) -> int:
    if not (np.isfinite(aspect_ratio) and aspect_ratio > 0):
        raise ValueError(f"aspect_ratio must be a positive finite number; got {aspect_ratio!r}")
    if not (np.isfinite(panel_size) and panel_size > 0):
        raise ValueError(f"panel_size must be a positive finite number [m]; got {panel_size!r}")
    return sectors_for(profile.radius, aspect_ratio * panel_size) if n_sectors is None else n_sectors
