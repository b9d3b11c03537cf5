"""Closed meshes of axisymmetric floats: a meridian revolved about the z axis, keeping the volume.

The meridian runs from the top's centre (0, f) out to the rim (R, f), down the freeboard wall to the waterline
(R, 0), then along the float's profile (``wecss.hydro.bem.AxisymmetricProfile``: wall, then a flat, hemispherical,
rounded or conical bottom) to the lowest point (0, -T) on the axis. Revolving it with n sectors gives quadrilaterals
(two triangles each) and fans of triangles at the two axis points.

The revolution keeps the volume (volume-preserving, not merely area-preserving):

- every radius is scaled by sqrt(theta / sin theta), theta = 2 pi / n, so that each horizontal section of the
  faceted surface (a regular n-gon) has the area of the circle of the meridian's radius at that height: the
  waterplane area is exact and the volume is pi int r(z)^2 dz of the meridian polyline;
- the inner vertices of each arc of the meridian are moved out from the arc's centre by one common factor, chosen
  so that the polyline's volume of revolution pi int r^2 dz equals the arc's.

Straight pieces (walls, flat and conical bottoms, the top) are exact, so the volume of the whole float and the
volume below any waterline on its wall are those of the true shape, to rounding. The second moment of the
waterplane of an area-scaled n-gon differs from the circle's by a factor (theta / sin theta)(2 + cos theta) / 3 =
1 + theta^4 / 180 + ... (1.6e-6 at 48 sectors).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from .._polygon import radial_scale
from ._surface import SurfaceMesh

if TYPE_CHECKING:  # pragma: no cover
    from ..bem import AxisymmetricProfile

MIN_SECTORS: int = 16
"""Fewest sectors of a revolved mesh."""

PANELS_PER_RADIUS: float = 6.0
"""Default panel size: the waterline radius over this number."""

_GAUSS_NODES, _GAUSS_WEIGHTS = np.polynomial.legendre.leggauss(24)


def arc_points(
    center: tuple[float, float],
    radius: float,
    angle_start: float,
    angle_end: float,
    segments: int,
    *,
    preserve_volume: bool = True,
) -> np.ndarray:
    """Points (r, z) of an arc of the meridian split into ``segments`` chords, ends included.

    With ``preserve_volume`` the inner points are moved out from the centre by one factor so that the polyline's
    volume of revolution about the z axis, pi |int r^2 dz|, equals the arc's (the arc must keep r >= 0 and run
    monotonically in z, as the arcs of float profiles do).

    Parameters
    ----------
    center : (r, z)
        Centre of the arc [m].
    radius : float
        Its radius [m].
    angle_start, angle_end : float
        Angles [rad] of its ends, measured from the +r direction towards +z.
    segments : int
        Number of chords (>= 2 when ``preserve_volume``).
    """
    angles = np.linspace(angle_start, angle_end, segments + 1)
    points = np.column_stack([center[0] + radius * np.cos(angles), center[1] + radius * np.sin(angles)])
    if not preserve_volume or segments < 2:
        return points
    from scipy.optimize import brentq  # deferred: importing wecss loads no scipy.optimize (tests/test_imports.py)

    target = _arc_volume(center, radius, angle_start, angle_end)
    inner = points[1:-1] - np.asarray(center)

    def excess(factor: float) -> float:
        trial = points.copy()
        trial[1:-1] = np.asarray(center) + factor * inner
        return polyline_volume(trial) - target

    factor = brentq(excess, 1.0, 1.5, xtol=1e-15, rtol=4 * np.finfo(float).eps)
    points[1:-1] = np.asarray(center) + factor * inner
    return points


def polyline_volume(points: np.ndarray) -> float:
    """Volume of revolution pi |sum over segments of int r^2 dz| of a polyline of (r, z) points [m^3] (each segment
    a frustum: pi dz (r1^2 + r1 r2 + r2^2) / 3)."""
    r, z = points[:, 0], points[:, 1]
    return float(abs(np.sum(np.pi * np.diff(z) * (r[:-1] ** 2 + r[:-1] * r[1:] + r[1:] ** 2) / 3)))


def _arc_volume(center: tuple[float, float], radius: float, angle_start: float, angle_end: float) -> float:
    """pi |int r^2 dz| along an arc (Gauss-Legendre, exact to rounding for these trigonometric polynomials)."""
    s = 0.5 * (_GAUSS_NODES + 1.0)
    angle = angle_start + s * (angle_end - angle_start)
    r = center[0] + radius * np.cos(angle)
    dz = radius * np.cos(angle) * (angle_end - angle_start)
    return float(abs(np.pi * np.sum(0.5 * _GAUSS_WEIGHTS * r**2 * dz)))


def _line(start: tuple[float, float], end: tuple[float, float], size: float) -> np.ndarray:
    n = max(1, math.ceil(math.dist(start, end) / size - 1e-9))
    return np.linspace(start, end, n + 1)


def profile_meridian(profile: AxisymmetricProfile, freeboard: float, panel_size: float, top_size: float) -> np.ndarray:
    """The meridian (r, z) of a float from the top's centre to the lowest point, arcs volume-preserving (see the
    module docstring), about ``panel_size`` [m] apart below the rim and ``top_size`` apart across the top."""
    r, t = profile.radius, profile.draft
    z_wall = -profile.wall_height
    parts = [_line((0.0, freeboard), (r, freeboard), top_size), _line((r, freeboard), (r, 0.0), panel_size)]
    if profile.wall_height > 0:
        parts.append(_line((r, 0.0), (r, z_wall), panel_size))

    def arc(center: tuple[float, float], radius: float) -> np.ndarray:
        segments = max(2, math.ceil(radius * math.pi / 2 / panel_size - 1e-9))
        return arc_points(center, radius, 0.0, -math.pi / 2, segments)

    if profile.bottom == "flat":
        parts.append(_line((r, -t), (0.0, -t), panel_size))
    elif profile.bottom == "hemispherical":
        parts.append(arc((0.0, z_wall), r))
    elif profile.bottom == "rounded":
        rf = profile.fillet_radius
        parts.append(arc((r - rf, z_wall), rf))
        if r - rf > 0:
            parts.append(_line((r - rf, -t), (0.0, -t), panel_size))
    else:  # conical
        parts.append(_line((r, z_wall), (0.0, -t), panel_size))
    points = np.concatenate([parts[0], *(p[1:] for p in parts[1:])])
    points[-1] = (0.0, -t)
    return points


def revolve(points_rz: np.ndarray, sectors: int, *, name: str = "revolved", scale_radii: bool = True) -> SurfaceMesh:
    """Revolve a meridian polyline about the z axis into a closed mesh.

    Parameters
    ----------
    points_rz : ndarray (m, 2)
        The meridian [m], from a point on the axis (r = 0) over the top of the body to a point on the axis below,
        with r > 0 in between (the outward normal then points away from the body).
    sectors : int
        Number of sectors n (>= 3).
    name : str
        Mesh name.
    scale_radii : bool
        Scale every radius by :func:`radial_scale` (sections of the area of their circles).

    Raises
    ------
    ValueError
        If the meridian does not start and end on the axis with r > 0 between, or ``sectors`` < 3.
    """
    points = np.asarray(points_rz, dtype=float)
    if int(sectors) != sectors or sectors < 3:
        raise ValueError(f"sectors must be an integer >= 3; got {sectors!r}")
    if points.ndim != 2 or points.shape[1] != 2 or points.shape[0] < 3:
        raise ValueError(f"points_rz must have shape (m, 2) with m >= 3; got {points.shape}")
    r = points[:, 0]
    if r[0] != 0 or r[-1] != 0 or np.any(r[1:-1] <= 0):
        raise ValueError("the meridian must start and end on the axis (r = 0) with r > 0 between")
    n = int(sectors)
    if scale_radii:
        r = r * radial_scale(n)
    z = points[:, 1]
    rings = points.shape[0] - 2  # points off the axis, n vertices each
    angle = 2 * np.pi * np.arange(n) / n
    ring_r = r[1:-1, None]
    ring_vertices = np.stack(
        [ring_r * np.cos(angle), ring_r * np.sin(angle), np.broadcast_to(z[1:-1, None], (rings, n))], axis=-1
    ).reshape(-1, 3)
    top, bottom = rings * n, rings * n + 1
    vertices = np.concatenate([ring_vertices, [[0.0, 0.0, z[0]], [0.0, 0.0, z[-1]]]])
    s = np.arange(n)
    s_next = (s + 1) % n
    faces = [np.column_stack([np.full(n, top), s, s_next])]  # fan from the top's centre: (O, D, C)
    for j in range(rings - 1):
        a, b = j * n + s, j * n + s_next  # ring j
        d, c = (j + 1) * n + s, (j + 1) * n + s_next  # ring j + 1, further along the meridian
        faces.append(np.column_stack([a, d, c]))
        faces.append(np.column_stack([a, c, b]))
    last = (rings - 1) * n
    faces.append(np.column_stack([last + s, np.full(n, bottom), last + s_next]))  # fan to the lowest point
    return SurfaceMesh(vertices, np.concatenate(faces).astype(np.int64), name=name)


def revolve_profile(
    profile: AxisymmetricProfile,
    freeboard: float,
    *,
    center_of_mass_z: float,
    panel_size: float | None = None,
    sectors: int | None = None,
    aspect_ratio: float = 1.0,
    name: str | None = None,
) -> SurfaceMesh:
    """The closed, volume-preserving mesh of an axisymmetric float (see the module docstring).

    Parameters
    ----------
    profile : AxisymmetricProfile
        The float below its still water line.
    freeboard : float
        Height of the vertical wall above the still water line [m] (the float's top is flat at that height).
    center_of_mass_z : float
        Height of the body's centre of mass above the still water line [m] (negative below): the mesh is in the
        body frame, from the centre of mass.
    panel_size : float, optional
        Target panel length along the meridian [m] (default: the waterline radius / ``PANELS_PER_RADIUS``).
    sectors : int, optional
        Number of sectors (default: a multiple of 4, at least ``MIN_SECTORS``, giving panels about
        ``aspect_ratio * panel_size`` wide at the waterline).
    aspect_ratio : float
        Target panel width over panel length.
    name : str, optional

    Raises
    ------
    ValueError
        On a non-positive freeboard, panel size or aspect ratio, or fewer than 3 sectors.
    """
    if not (math.isfinite(freeboard) and freeboard > 0):
        raise ValueError(f"freeboard must be a positive height [m]; got {freeboard!r}")
    if not math.isfinite(center_of_mass_z):
        raise ValueError(f"center_of_mass_z must be finite [m]; got {center_of_mass_z!r}")
    size = profile.radius / PANELS_PER_RADIUS if panel_size is None else float(panel_size)
    if not (math.isfinite(size) and size > 0):
        raise ValueError(f"panel_size must be a positive length [m]; got {panel_size!r}")
    if not (math.isfinite(aspect_ratio) and aspect_ratio > 0):
        raise ValueError(f"aspect_ratio must be positive; got {aspect_ratio!r}")
    if sectors is None:
        width = aspect_ratio * size
        sectors = max(MIN_SECTORS, 4 * math.ceil(2 * math.pi * profile.radius / width / 4 - 1e-9))
    meridian = profile_meridian(profile, freeboard, size, profile.radius)
    meridian[:, 1] -= center_of_mass_z
    label = name or f"{profile.bottom} float R {profile.radius:g} m, T {profile.draft:g} m, freeboard {freeboard:g} m"
    return revolve(meridian, sectors, name=label)
