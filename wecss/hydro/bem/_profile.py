"""Meridian profiles of axisymmetric floats below the still water line (pure geometry, no BEM).

A profile is the curve, in the half-plane (r >= 0, z), from the waterline point (R, 0) down to the
axis point (0, -T): a vertical wall, then a bottom that is flat, hemispherical, rounded (flat with a
fillet of radius r_f at the bilge) or conical. Volumes and centres of buoyancy are integrals over this
curve (Green's theorem in the (r, z) plane, Gauss-Legendre quadrature on each line or arc piece, so
exact to rounding), not closed forms per shape: the tests compare them with the closed forms.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal, get_args

import numpy as np

BottomKind = Literal["flat", "hemispherical", "rounded", "conical"]
BOTTOM_KINDS: tuple[str, ...] = get_args(BottomKind)
"""Accepted bottom shapes."""

_GAUSS_NODES, _GAUSS_WEIGHTS = np.polynomial.legendre.leggauss(24)


@dataclass(frozen=True)
class _Line:
    start: tuple[float, float]
    end: tuple[float, float]

    @property
    def length(self) -> float:
        return float(np.hypot(self.end[0] - self.start[0], self.end[1] - self.start[1]))

    def at(self, s: np.ndarray) -> np.ndarray:
        """Points (r, z) at fractions ``s`` in [0, 1] of the piece."""
        s = np.asarray(s, dtype=float)[:, None]
        return (1.0 - s) * np.asarray(self.start) + s * np.asarray(self.end)

    def derivative(self, s: np.ndarray) -> np.ndarray:
        return np.broadcast_to(np.subtract(self.end, self.start), (np.size(s), 2))


@dataclass(frozen=True)
class _Arc:
    center: tuple[float, float]
    radius: float
    angle_start: float
    angle_end: float

    @property
    def length(self) -> float:
        return abs(self.angle_end - self.angle_start) * self.radius

    def at(self, s: np.ndarray) -> np.ndarray:
        angle = self.angle_start + np.asarray(s, dtype=float) * (self.angle_end - self.angle_start)
        return np.column_stack(
            [self.center[0] + self.radius * np.cos(angle), self.center[1] + self.radius * np.sin(angle)]
        )

    def derivative(self, s: np.ndarray) -> np.ndarray:
        sweep = self.angle_end - self.angle_start
        angle = self.angle_start + np.asarray(s, dtype=float) * sweep
        return np.column_stack([-self.radius * np.sin(angle) * sweep, self.radius * np.cos(angle) * sweep])


_Piece = _Line | _Arc


@dataclass(frozen=True)
class AxisymmetricProfile:
    """Immersed shape of a float with a vertical axis: a vertical wall above a bottom of some kind.

    Parameters
    ----------
    radius : float
        Waterline radius R [m] (half the diameter).
    draft : float
        Depth T of the lowest point below the still water line [m].
    bottom : {"flat", "hemispherical", "rounded", "conical"}
        Shape of the bottom: a flat disc; a hemisphere of radius R; a flat disc joined to the wall by a
        quarter-circle fillet of radius ``fillet_radius``; a cone of height ``cone_height`` with its apex
        on the axis.
    fillet_radius : float
        Fillet radius r_f [m], for ``bottom="rounded"`` only (0 < r_f <= R).
    cone_height : float
        Height of the cone [m], for ``bottom="conical"`` only (0 < h <= T).

    Raises
    ------
    ValueError
        If a dimension is not positive and finite, the bottom kind is unknown, a parameter is given that
        the bottom kind does not use, or the bottom does not fit below the waterline (draft shorter than
        the bottom's height).

    Examples
    --------
    >>> p = AxisymmetricProfile.with_volume(5.312e-3, radius=0.125, bottom="hemispherical")
    >>> round(p.draft, 4)
    0.1499
    """

    radius: float
    draft: float
    bottom: BottomKind = "flat"
    fillet_radius: float = 0.0
    cone_height: float = 0.0

    def __post_init__(self) -> None:
        if self.bottom not in BOTTOM_KINDS:
            raise ValueError(f"unknown bottom kind {self.bottom!r}; accepted: {', '.join(BOTTOM_KINDS)}")
        for name in ("radius", "draft"):
            value = getattr(self, name)
            if not (np.isfinite(value) and value > 0):
                raise ValueError(f"{name} must be a positive finite number [m]; got {value!r}")
        if self.bottom == "rounded":
            if not (np.isfinite(self.fillet_radius) and 0 < self.fillet_radius <= self.radius):
                raise ValueError(
                    f"a rounded bottom needs 0 < fillet_radius <= radius ({self.radius} m); got {self.fillet_radius!r}"
                )
        elif self.fillet_radius != 0:
            raise ValueError(
                f"fillet_radius is only used by bottom='rounded'; got {self.fillet_radius!r} with {self.bottom!r}"
            )
        if self.bottom == "conical":
            if not (np.isfinite(self.cone_height) and self.cone_height > 0):
                raise ValueError(f"a conical bottom needs a positive cone_height [m]; got {self.cone_height!r}")
        elif self.cone_height != 0:
            raise ValueError(
                f"cone_height is only used by bottom='conical'; got {self.cone_height!r} with {self.bottom!r}"
            )
        if self.wall_height < -1e-12 * self.draft:
            raise ValueError(
                f"draft {self.draft} m is shorter than the {self.bottom} bottom's height {self.bottom_height} m; "
                "the bottom would pierce the waterline"
            )

    # --- constructors -------------------------------------------------------------------------------
    @classmethod
    def with_volume(
        cls,
        volume: float,
        *,
        radius: float,
        bottom: BottomKind = "flat",
        fillet_radius: float = 0.0,
        cone_height: float = 0.0,
    ) -> AxisymmetricProfile:
        """Return the profile whose displaced volume is ``volume`` [m^3] (solving for the draft).

        The volume grows by pi R^2 per metre of wall, so the draft follows in closed form from the volume
        of the bottom alone.

        Raises
        ------
        ValueError
            If the volume is not positive, or smaller than the bottom's own volume (the waterline would cut
            the bottom, which is not a wall-sided float).
        """
        if not (np.isfinite(volume) and volume > 0):
            raise ValueError(f"volume must be a positive finite number [m^3]; got {volume!r}")
        height = _bottom_height(bottom, radius, fillet_radius, cone_height)
        bottom_volume = cls(radius, height, bottom, fillet_radius, cone_height).volume if height > 0 else 0.0
        extra = volume - bottom_volume
        if extra < -1e-12 * volume:
            raise ValueError(
                f"volume {volume:.6g} m^3 is smaller than the {bottom} bottom's own volume {bottom_volume:.6g} m^3 "
                f"at radius {radius} m; choose a larger volume or a smaller bottom"
            )
        draft = height + max(extra, 0.0) / (np.pi * radius**2)
        return cls(radius, draft, bottom, fillet_radius, cone_height)

    # --- shape ----------------------------------------------------------------------------------------
    @property
    def bottom_height(self) -> float:
        """Height of the bottom part above the lowest point [m] (0 for a flat bottom)."""
        return _bottom_height(self.bottom, self.radius, self.fillet_radius, self.cone_height)

    @property
    def wall_height(self) -> float:
        """Height of the vertical wall below the waterline [m]."""
        return self.draft - self.bottom_height

    def _pieces(self) -> list[_Piece]:
        """Lines and arcs from (R, 0) to (0, -T), in that order."""
        r, t = self.radius, self.draft
        z_wall = -self.wall_height
        pieces: list[_Piece] = []
        if self.wall_height > 0:
            pieces.append(_Line((r, 0.0), (r, z_wall)))
        if self.bottom == "flat":
            pieces.append(_Line((r, -t), (0.0, -t)))
        elif self.bottom == "hemispherical":
            pieces.append(_Arc((0.0, z_wall), r, 0.0, -np.pi / 2))
        elif self.bottom == "rounded":
            rf = self.fillet_radius
            pieces.append(_Arc((r - rf, z_wall), rf, 0.0, -np.pi / 2))
            if r - rf > 0:
                pieces.append(_Line((r - rf, -t), (0.0, -t)))
        else:  # conical
            pieces.append(_Line((r, z_wall), (0.0, -t)))
        return pieces

    def _integrate(self, integrand: str) -> float:
        """Line integral along the profile (Gauss-Legendre on each piece)."""
        s = 0.5 * (_GAUSS_NODES + 1.0)
        w = 0.5 * _GAUSS_WEIGHTS
        total = 0.0
        for piece in self._pieces():
            rz = piece.at(s)
            d = piece.derivative(s)
            r, z = rz[:, 0], rz[:, 1]
            dr, dz = d[:, 0], d[:, 1]
            if integrand == "volume":  # integral of r dA = -int r^2/2 dz (profile runs clockwise)
                values = -0.5 * r**2 * dz
            elif integrand == "moment_z":  # integral of r z dA = -int r^2 z/2 dz
                values = -0.5 * r**2 * z * dz
            else:  # area: integral of r ds
                values = r * np.hypot(dr, dz)
            total += float(np.sum(w * values))
        return total

    # --- hydrostatic properties -------------------------------------------------------------------------
    @property
    def volume(self) -> float:
        """Displaced volume [m^3]."""
        return 2.0 * np.pi * self._integrate("volume")

    @property
    def center_of_buoyancy_z(self) -> float:
        """Height of the centre of buoyancy [m] (negative: below the still water line)."""
        return self._integrate("moment_z") / self._integrate("volume")

    @property
    def wetted_area(self) -> float:
        """Area of the immersed hull surface [m^2]."""
        return 2.0 * np.pi * self._integrate("area")

    @property
    def waterplane_area(self) -> float:
        """Waterplane area pi R^2 [m^2]."""
        return float(np.pi * self.radius**2)

    @property
    def waterplane_second_moment(self) -> float:
        """Second moment of the waterplane area about a diameter, pi R^4 / 4 [m^4]."""
        return float(np.pi * self.radius**4 / 4.0)

    # --- discretisation ---------------------------------------------------------------------------------
    def meridian(self, panel_size: float, *, preserve_area: bool = False) -> np.ndarray:
        """Points (r, z) along the profile from (R, 0) to (0, -T), about ``panel_size`` apart.

        Corners between pieces are always vertices. With ``preserve_area``, the inner vertices of each
        arc are moved outwards (the same distance for all) so that the polygon encloses the same area
        as the arc; the mesh then keeps the displaced volume to second order in the panel size.

        Parameters
        ----------
        panel_size : float
            Target distance between consecutive points [m].
        preserve_area : bool
            Move the inner vertices of arcs outwards as described above.

        Returns
        -------
        ndarray of shape (n, 2)

        Raises
        ------
        ValueError
            If ``panel_size`` is not positive and finite.
        """
        if not (np.isfinite(panel_size) and panel_size > 0):
            raise ValueError(f"panel_size must be a positive finite number [m]; got {panel_size!r}")
        points = [np.array([[self.radius, 0.0]])]
        for piece in self._pieces():
            n = max(1, int(np.ceil(piece.length / panel_size - 1e-9)))
            if isinstance(piece, _Arc) and n < 2:
                n = 2  # an arc needs at least one inner vertex
            nodes = piece.at(np.linspace(0.0, 1.0, n + 1))
            if isinstance(piece, _Arc) and preserve_area:
                nodes[1:-1] = _push_arc_vertices(piece, nodes[1:-1], n)
            points.append(nodes[1:])
        out = np.concatenate(points)
        out[-1] = (0.0, -self.draft)  # exactly on the axis
        return out


def _bottom_height(bottom: str, radius: float, fillet_radius: float, cone_height: float) -> float:
    if bottom == "hemispherical":
        return float(radius)
    if bottom == "rounded":
        return float(fillet_radius)
    if bottom == "conical":
        return float(cone_height)
    return 0.0


def _push_arc_vertices(arc: _Arc, inner: np.ndarray, n: int) -> np.ndarray:
    """Move the n - 1 inner vertices of an arc split into n chords so the polygon keeps the arc's area.

    With end points on the circle (radius a) and inner points at radius b, the fan of triangles from the
    centre has area sin(d) (2 a b + (n - 2) b^2) / 2, d the angle per chord; it equals the sector area
    n d a^2 / 2 for the positive root b of that quadratic.
    """
    a = arc.radius
    step = abs(arc.angle_end - arc.angle_start) / n
    sector = n * step * a**2 / np.sin(step)
    if n == 2:
        b = sector / (2 * a)
    else:
        b = (-2 * a + np.sqrt(4 * a**2 + 4 * (n - 2) * sector)) / (2 * (n - 2))
    center = np.asarray(arc.center)
    return center + (inner - center) * (b / a)
