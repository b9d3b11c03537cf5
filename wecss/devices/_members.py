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

from ..structure import Material, Section, member_axes, von_mises

_MEMBER_KEYS = {"name", "body", "start", "end", "section", "hot_spots", "body_mass", "material", "nonstructural_mass"}
_OPTIONAL_KEYS = {"hot_spots", "body_mass", "material", "nonstructural_mass"}
_BODY_MASS = ("centre", "along")
_HOT_SPOT_KEYS = {"name", "at", "y", "z", "scf"}


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
    material: Material | None = None
    """The member's material (``wecss.structure.Material``): needed when its body is flexible; None otherwise."""
    nonstructural_mass: float = 0.0
    """Mass per length carried on the member's axis beyond density times area (fittings, lugs, ballast) [kg/m]; it
    counts only in a flexible body's structural model."""

    @property
    def length(self) -> float:
        """[m]."""
        return float(np.linalg.norm(self.end - self.start))

    @property
    def axes(self) -> np.ndarray:
        """Rows x, y, z of the local axes in the body's (reference world) axes [-]."""
        return member_axes(self.start, self.end)

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
        vm, signed = von_mises(sigma, tau)
        return {"normal": sigma, "shear": tau, "von_mises": vm, "signed_von_mises": signed}


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
        missing = sorted(_MEMBER_KEYS - _OPTIONAL_KEYS - set(entry))
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
        material = None if "material" not in entry else Material.from_spec(f"{where}.material", entry["material"])
        extra = entry.get("nonstructural_mass", 0.0)
        if isinstance(extra, bool) or not isinstance(extra, int | float) or not (np.isfinite(extra) and extra >= 0):
            raise ValueError(f"{where}: nonstructural_mass must be a number >= 0 [kg/m]; got {extra!r}")
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
        out.append(
            Member(
                str(entry["name"]),
                str(entry["body"]),
                start,
                end,
                section,
                tuple(spots),
                body_mass,
                material,
                float(extra),
            )
        )
    names = [m.name for m in out]
    if len(set(names)) != len(names):
        raise ValueError(f"device {device!r}: member names repeat: {names}")
    return tuple(out)
