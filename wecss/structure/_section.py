"""Cross-sections of beams: area, second moments, torsion constant, shear areas and fibre points.

Local axes of a member (``member_axes``): x from its start to its end; z the body's (reference world) z made
perpendicular to x (the body's x for a vertical member); y = z cross x. A section lies in the y-z plane: a box's
width is along y and its height along z. Second moments: Iy = integral of z^2 dA (bending about y, deflection
along z), Iz = integral of y^2 dA. The polar moment Ip = Iy + Iz gives the section's rotary inertia about x;
the torsion constant J gives the torsional stiffness G J (equal to Ip for a circular tube only). A shear area
A_s gives the shear stiffness G A_s of a Timoshenko beam (shear_area_y for the shear force along y).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

_SECTION_KEYS = {
    "tube": ({"kind", "outer_diameter", "thickness"}, set()),
    "box": ({"kind", "width", "height", "thickness"}, set()),
    "given": (
        {"kind", "area", "iy", "iz", "wy", "wz", "wt"},
        {"torsion_constant", "shear_area_y", "shear_area_z"},
    ),
}
"""Per section kind: the keys it needs and the keys it may take."""


def member_axes(start: np.ndarray, end: np.ndarray) -> np.ndarray:
    """Rows x, y, z of a member's local axes in the body's (reference world) axes [-].

    x from ``start`` to ``end``; z the body's z made perpendicular to x (the body's x when the member is within
    about 2.6 degrees of vertical); y = z cross x.

    Raises
    ------
    ValueError
        If the two points coincide.
    """
    d = np.asarray(end, dtype=float) - np.asarray(start, dtype=float)
    length = float(np.linalg.norm(d))
    if not length > 0:
        raise ValueError(f"a member needs two different points; got start {start!r} and end {end!r}")
    x = d / length
    ref = np.array([0.0, 0.0, 1.0]) if abs(x[2]) < 0.999 else np.array([1.0, 0.0, 0.0])
    z = ref - (ref @ x) * x
    z /= np.linalg.norm(z)
    return np.array([x, np.cross(z, x), z])


def _positive(where: str, **values: float) -> None:
    for key, value in values.items():
        if not (isinstance(value, int | float) and np.isfinite(value) and value > 0):
            raise ValueError(f"{where}: {key} must be a positive number, got {value!r}")


@dataclass(frozen=True)
class Section:
    """Cross-section properties of a beam (local axes: see the module docstring).

    Attributes
    ----------
    kind : str
        ``"tube"``, ``"box"`` or ``"given"``.
    area : float
        A [m^2].
    iy, iz : float
        Second moments of area about the local y and z axes [m^4].
    y_max, z_max : float
        Distance of the extreme fibre from the centroid along y and z [m].
    wt : float
        Torsional section modulus, tau = T / W_t at the wall [m^3].
    torsion_constant : float or None
        Saint-Venant torsion constant J [m^4] (G J is the torsional stiffness); None when not known (a given
        section without it: it cannot be a finite element).
    shear_area_y, shear_area_z : float or None
        Shear areas for the shear forces along y and z [m^2] (Timoshenko beams); None: rigid in shear.
    fibres : tuple of (y, z)
        Points on the section where stresses are recovered by default [m]: the tube's wall at every 45 degrees
        from the top, a box's corners and mid-sides, a given section's extreme fibres on its axes.
    """

    kind: str
    area: float
    iy: float
    iz: float
    y_max: float
    z_max: float
    wt: float
    torsion_constant: float | None = None
    shear_area_y: float | None = None
    shear_area_z: float | None = None
    fibres: tuple[tuple[float, float], ...] = ()

    @property
    def polar(self) -> float:
        """Polar second moment of area Ip = Iy + Iz [m^4] (the section's rotary inertia about x is rho Ip)."""
        return self.iy + self.iz

    @classmethod
    def tube(cls, outer_diameter: float, thickness: float) -> Section:
        """Circular tube: outer diameter D and wall thickness t [m] (exact A, I and J = 2 I; W_t = 2 J / D; shear
        area A / 2, the thin-walled value)."""
        _positive("tube section", outer_diameter=outer_diameter, thickness=thickness)
        if 2 * thickness > outer_diameter:
            raise ValueError(f"tube section: thickness {thickness} m exceeds the radius {outer_diameter / 2} m")
        d_in = outer_diameter - 2 * thickness
        area = float(np.pi / 4 * (outer_diameter**2 - d_in**2))
        inertia = float(np.pi / 64 * (outer_diameter**4 - d_in**4))
        r = outer_diameter / 2
        angles = np.radians(np.arange(0, 360, 45))
        fibres = tuple((float(r * np.sin(a)), float(r * np.cos(a))) for a in angles)
        return cls(
            "tube", area, inertia, inertia, r, r, 2 * inertia / r, 2 * inertia, area / 2, area / 2, fibres
        )  # fmt: skip

    @classmethod
    def box(cls, width: float, height: float, thickness: float) -> Section:
        """Rectangular hollow section: width along y, height along z, uniform wall t [m] (exact A and I; Bredt's
        J = 4 A_m^2 t / p_m and W_t = 2 A_m t with A_m the area inside the wall's mid-line and p_m its length;
        shear areas of the walls parallel to the shear force, 2 t (h - t) along z and 2 t (b - t) along y)."""
        _positive("box section", width=width, height=height, thickness=thickness)
        if 2 * thickness >= min(width, height):
            raise ValueError(f"box section: wall {thickness} m too thick for {width} x {height} m")
        wi, hi = width - 2 * thickness, height - 2 * thickness
        area = width * height - wi * hi
        iy = (width * height**3 - wi * hi**3) / 12  # about y: bending in z
        iz = (height * width**3 - hi * wi**3) / 12
        bm, hm = width - thickness, height - thickness
        mid_area = bm * hm
        torsion = 4 * mid_area**2 * thickness / (2 * (bm + hm))
        b, h = width / 2, height / 2
        fibres = ((0.0, h), (b, h), (b, 0.0), (b, -h), (0.0, -h), (-b, -h), (-b, 0.0), (-b, h))
        return cls(
            "box", area, iy, iz, b, h, 2 * mid_area * thickness, torsion, 2 * thickness * bm, 2 * thickness * hm,
            fibres,
        )  # fmt: skip

    @classmethod
    def given(
        cls,
        area: float,
        iy: float,
        iz: float,
        wy: float,
        wz: float,
        wt: float,
        torsion_constant: float | None = None,
        shear_area_y: float | None = None,
        shear_area_z: float | None = None,
    ) -> Section:
        """Given properties: A [m^2], Iy, Iz [m^4], elastic moduli Wy = Iy / z_max, Wz = Iz / y_max [m^3], the
        torsional modulus W_t [m^3]; optionally the torsion constant J [m^4] (needed for a finite element) and the
        shear areas [m^2] (a Timoshenko beam)."""
        _positive("given section", area=area, iy=iy, iz=iz, wy=wy, wz=wz, wt=wt)
        optional = {"torsion_constant": torsion_constant, "shear_area_y": shear_area_y, "shear_area_z": shear_area_z}
        _positive("given section", **{k: v for k, v in optional.items() if v is not None})
        y_max, z_max = iz / wz, iy / wy
        fibres = ((0.0, z_max), (y_max, 0.0), (0.0, -z_max), (-y_max, 0.0))
        return cls(
            "given", area, iy, iz, y_max, z_max, wt, torsion_constant, shear_area_y, shear_area_z, fibres
        )  # fmt: skip

    @classmethod
    def from_spec(cls, where: str, entry: Mapping[str, Any]) -> Section:
        """From a spec table ``{kind = "tube", outer_diameter = ..., thickness = ...}`` (or box, given).

        Raises
        ------
        ValueError
            On an unknown kind, missing or unknown keys, or values the constructors refuse (the message says
            where, what was given and what is accepted).
        """
        kind = entry.get("kind")
        if kind not in _SECTION_KEYS:
            raise ValueError(f"{where}: section kind {kind!r}; accepted: {sorted(_SECTION_KEYS)}")
        needed, optional = _SECTION_KEYS[kind]
        if not needed <= set(entry) <= needed | optional:
            accepted = sorted(needed) + ([f"optional {sorted(optional)}"] if optional else [])
            raise ValueError(f"{where}: a {kind} section takes {accepted}, got {sorted(entry)}")
        args = {}
        for key, value in entry.items():
            if key == "kind":
                continue
            if isinstance(value, bool) or not isinstance(value, int | float):
                raise ValueError(f"{where}: {key} must be a number [SI], got {value!r}")
            args[key] = float(value)
        if kind == "tube":
            return cls.tube(**args)
        if kind == "box":
            return cls.box(**args)
        return cls.given(**args)
