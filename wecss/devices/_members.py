"""Beam members on bodies and stress recovery at their hot spots (Euler-Bernoulli, thin-walled sections).

A member is a straight line on one body between two points (given in world axes in the reference configuration,
which are the body's axes), with a cross-section and hot spots. Its local axes: x from ``start`` to ``end``; z the
world z made perpendicular to x (world x if the member is vertical); y = z cross x.

The internal wrench at a station is the sum of the loads on the part beyond the cut (towards ``end``), taken about the
cut's centre: the resultant on the cut face whose outward normal is +x (quasi-static: the inertia and weight of the
member itself are not distributed along it; apply them as point loads if they matter). Components: N (tension
positive), shear Vy, Vz, torque T about x and bending moments My, Mz. Normal stress at (y, z) on the section:
sigma = N / A + My z / Iy - Mz y / Iz; torsional shear tau = T / W_t (the thin-walled value at the wall); the shear
from Vy, Vz is neglected (it vanishes at the extreme fibres where bending peaks). The hot-spot stresses are the nominal
ones times the hot spot's stress concentration factor. Von Mises: sqrt(sigma^2 + 3 tau^2); the signed von Mises
stress takes the sign of the principal stress of largest magnitude (paper 003, Eq. 53), which in this plane stress
state is the sign of sigma (+ when sigma is 0).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

_SECTION_KEYS = {
    "tube": {"kind", "outer_diameter", "thickness"},
    "box": {"kind", "width", "height", "thickness"},
    "given": {"kind", "area", "iy", "iz", "wy", "wz", "wt"},
}
_MEMBER_KEYS = {"name", "body", "start", "end", "section", "hot_spots", "body_mass"}
_BODY_MASS = ("centre", "along")
_HOT_SPOT_KEYS = {"name", "at", "y", "z", "scf"}


def _positive(where: str, **values: float) -> None:
    for key, value in values.items():
        if not (isinstance(value, int | float) and np.isfinite(value) and value > 0):
            raise ValueError(f"{where}: {key} must be a positive number, got {value!r}")


@dataclass(frozen=True)
class Section:
    """Cross-section properties of a beam.

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
    """

    kind: str
    area: float
    iy: float
    iz: float
    y_max: float
    z_max: float
    wt: float

    @classmethod
    def tube(cls, outer_diameter: float, thickness: float) -> Section:
        """Circular tube: outer diameter D and wall thickness t [m] (exact A and I; W_t = 2 J / D)."""
        _positive("tube section", outer_diameter=outer_diameter, thickness=thickness)
        if 2 * thickness > outer_diameter:
            raise ValueError(f"tube section: thickness {thickness} m exceeds the radius {outer_diameter / 2} m")
        d_in = outer_diameter - 2 * thickness
        area = np.pi / 4 * (outer_diameter**2 - d_in**2)
        inertia = np.pi / 64 * (outer_diameter**4 - d_in**4)
        r = outer_diameter / 2
        return cls("tube", float(area), float(inertia), float(inertia), r, r, float(2 * inertia / r))

    @classmethod
    def box(cls, width: float, height: float, thickness: float) -> Section:
        """Rectangular hollow section: width along y, height along z, uniform wall t [m] (exact A and I;
        Bredt's W_t = 2 A_m t with A_m the area inside the wall's mid-line)."""
        _positive("box section", width=width, height=height, thickness=thickness)
        if 2 * thickness >= min(width, height):
            raise ValueError(f"box section: wall {thickness} m too thick for {width} x {height} m")
        wi, hi = width - 2 * thickness, height - 2 * thickness
        area = width * height - wi * hi
        iy = (width * height**3 - wi * hi**3) / 12  # about y: bending in z
        iz = (height * width**3 - hi * wi**3) / 12
        mid_area = (width - thickness) * (height - thickness)
        return cls("box", area, iy, iz, width / 2, height / 2, 2 * mid_area * thickness)

    @classmethod
    def given(cls, area: float, iy: float, iz: float, wy: float, wz: float, wt: float) -> Section:
        """Given properties: A [m^2], Iy, Iz [m^4], elastic moduli Wy = Iy / z_max, Wz = Iz / y_max [m^3] and the
        torsional modulus W_t [m^3]."""
        _positive("given section", area=area, iy=iy, iz=iz, wy=wy, wz=wz, wt=wt)
        return cls("given", area, iy, iz, iz / wz, iy / wy, wt)

    @classmethod
    def from_spec(cls, where: str, entry: Mapping[str, Any]) -> Section:
        """From a spec table ``{kind = "tube", outer_diameter = ..., thickness = ...}`` (or box, given)."""
        kind = entry.get("kind")
        if kind not in _SECTION_KEYS:
            raise ValueError(f"{where}: section kind {kind!r}; accepted: {sorted(_SECTION_KEYS)}")
        keys = _SECTION_KEYS[kind]
        if set(entry) != keys:
            raise ValueError(f"{where}: a {kind} section takes exactly {sorted(keys)}, got {sorted(entry)}")
        args = {k: float(v) for k, v in entry.items() if k != "kind"}
        if kind == "tube":
            return cls.tube(**args)
        if kind == "box":
            return cls.box(**args)
        return cls.given(**args)


@dataclass(frozen=True)
class HotSpot:
    """A point on a member where stress is recovered.

    Attributes
    ----------
    name : str
    at : float
        Station: distance from the member's start along it [m].
    y, z : float
        Position on the section in the member's local axes [m] (e.g. z = z_max: the top fibre).
    scf : float
        Stress concentration factor [-] (1 for the nominal stress).
    """

    name: str
    at: float
    y: float
    z: float
    scf: float = 1.0


@dataclass(frozen=True, eq=False)
class Member:
    """A straight beam on a body, with its section and hot spots (see the module docstring for the conventions)."""

    name: str
    body: str
    start: np.ndarray
    end: np.ndarray
    section: Section
    hot_spots: tuple[HotSpot, ...]
    body_mass: str = "centre"
    """Where the body's own weight and inertia act for the member's free body: ``"centre"`` (one load at the body's
    centre of mass) or ``"along"`` (the body's mass spread uniformly along the member: for a body that is this
    beam); see :mod:`wecss.sim` (the ``loads`` group's section loads)."""

    @property
    def length(self) -> float:
        """[m]."""
        return float(np.linalg.norm(self.end - self.start))

    @property
    def axes(self) -> np.ndarray:
        """Rows x, y, z of the local axes in the body's (reference world) axes [-]."""
        x = (self.end - self.start) / self.length
        ref = np.array([0.0, 0.0, 1.0]) if abs(x[2]) < 0.999 else np.array([1.0, 0.0, 0.0])
        z = ref - (ref @ x) * x
        z /= np.linalg.norm(z)
        return np.array([x, np.cross(z, x), z])

    def internal_wrench(
        self, station: float, points: np.ndarray, forces: np.ndarray, moments: np.ndarray
    ) -> np.ndarray:
        """Internal wrench at ``station`` from point loads on the body.

        Parameters
        ----------
        station : float
            Distance of the cut from the start [m], 0 to ``length``.
        points : ndarray (k, 3)
            Where each load acts, in the body's axes (reference world coordinates) [m].
        forces, moments : ndarray (..., k, 3)
            The loads in the body's axes [N, N m]; leading axes (time) broadcast.

        Returns
        -------
        ndarray (..., 6)
            N, Vy, Vz [N], T, My, Mz [N m] in the member's local axes.
        """
        if not 0.0 <= station <= self.length:
            raise ValueError(f"member {self.name!r}: station {station} m outside 0 .. {self.length:.6g} m")
        pts = np.asarray(points, dtype=float).reshape(-1, 3)
        axes = self.axes
        cut = self.start + station * axes[0]
        f_all, m_all = np.asarray(forces, dtype=float), np.asarray(moments, dtype=float)
        if f_all.shape[-2:] != (len(pts), 3) or m_all.shape[-2:] != (len(pts), 3):
            raise ValueError(
                f"member {self.name!r}: {len(pts)} points need forces and moments of shape (..., {len(pts)}, 3), "
                f"got {f_all.shape} and {m_all.shape}"
            )
        beyond = (pts - self.start) @ axes[0] > station
        arm = pts[beyond] - cut
        f = f_all[..., beyond, :]
        m = m_all[..., beyond, :]
        force = f.sum(axis=-2)
        moment = (np.cross(arm, f) + m).sum(axis=-2)
        return np.concatenate([force @ axes.T, moment @ axes.T], axis=-1)

    def stress_components(self, spot: HotSpot, wrench: np.ndarray) -> dict[str, np.ndarray]:
        """The stress components at a hot spot, linear in the section load (so complex amplitudes work too).

        Returns
        -------
        dict of ndarray
            ``axial`` N / A, ``bending`` My z / Iy - Mz y / Iz, ``normal`` their sum sigma and ``shear`` T / W_t
            [Pa], SCF applied.
        """
        w = np.asarray(wrench)
        s = self.section
        axial = spot.scf * w[..., 0] / s.area
        bending = spot.scf * (w[..., 4] * spot.z / s.iy - w[..., 5] * spot.y / s.iz)
        return {"axial": axial, "bending": bending, "normal": axial + bending, "shear": spot.scf * w[..., 3] / s.wt}

    def stresses(self, spot: HotSpot, wrench: np.ndarray) -> dict[str, np.ndarray]:
        """Hot-spot stresses from the internal wrench at the spot's station.

        Returns
        -------
        dict of ndarray
            ``normal`` sigma, ``shear`` tau, ``von_mises`` and ``signed_von_mises`` [Pa], SCF applied.
        """
        parts = self.stress_components(spot, np.asarray(wrench, dtype=float))
        sigma, tau = parts["normal"], parts["shear"]
        vm = np.sqrt(sigma**2 + 3 * tau**2)
        return {"normal": sigma, "shear": tau, "von_mises": vm, "signed_von_mises": np.where(sigma < 0, -vm, vm)}


def read_members(device: str, entries: list[Mapping[str, Any]], body_names: list[str]) -> tuple[Member, ...]:
    """Members from the spec's ``[[members]]`` tables (see :mod:`wecss.devices._spec`).

    Raises
    ------
    ValueError
        On unknown keys, an unknown body, a zero-length member, a bad section or a hot spot off the member.
    """
    out = []
    for k, entry in enumerate(entries):
        where = f"device {device!r}, members[{k}]"
        unknown = sorted(set(entry) - _MEMBER_KEYS)
        missing = sorted(_MEMBER_KEYS - {"hot_spots", "body_mass"} - set(entry))
        if unknown or missing:
            raise ValueError(
                f"{where}: unknown keys {unknown}, missing keys {missing}; accepted: {sorted(_MEMBER_KEYS)}"
            )
        if entry["body"] not in body_names:
            raise ValueError(f"{where}: body {entry['body']!r} is not one of {body_names}")
        start, end = np.asarray(entry["start"], dtype=float), np.asarray(entry["end"], dtype=float)
        if start.shape != (3,) or end.shape != (3,) or np.linalg.norm(end - start) == 0.0:
            raise ValueError(f"{where}: start and end must be two different points [x, y, z] in m")
        section = Section.from_spec(f"{where}.section", entry["section"])
        body_mass = entry.get("body_mass", "centre")
        if body_mass not in _BODY_MASS:
            raise ValueError(f"{where}: body_mass {body_mass!r}; accepted: {list(_BODY_MASS)}")
        length = float(np.linalg.norm(end - start))
        spots = []
        for j, spot in enumerate(entry.get("hot_spots", [])):
            w = f"{where}.hot_spots[{j}]"
            bad = sorted(set(spot) - _HOT_SPOT_KEYS)
            if bad or not {"name", "at"} <= set(spot):
                raise ValueError(f"{w}: needs name and at; accepted keys: {sorted(_HOT_SPOT_KEYS)}, got {sorted(spot)}")
            hs = HotSpot(
                str(spot["name"]), float(spot["at"]), float(spot.get("y", 0.0)), float(spot.get("z", section.z_max)),
                float(spot.get("scf", 1.0)),
            )  # fmt: skip
            if not 0.0 <= hs.at <= length:
                raise ValueError(f"{w}: at = {hs.at} m is off the member (0 .. {length:.6g} m)")
            if abs(hs.y) > section.y_max * (1 + 1e-9) or abs(hs.z) > section.z_max * (1 + 1e-9):
                raise ValueError(
                    f"{w}: (y, z) = ({hs.y}, {hs.z}) m lies outside the section "
                    f"(|y| <= {section.y_max:.6g}, |z| <= {section.z_max:.6g})"
                )
            if not hs.scf > 0:
                raise ValueError(f"{w}: scf must be positive, got {hs.scf}")
            spots.append(hs)
        out.append(Member(str(entry["name"]), str(entry["body"]), start, end, section, tuple(spots), body_mass))
    names = [m.name for m in out]
    if len(set(names)) != len(names):
        raise ValueError(f"device {device!r}: member names repeat: {names}")
    return tuple(out)
