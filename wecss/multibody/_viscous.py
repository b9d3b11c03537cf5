"""Viscous forces of a device outside its hydrodynamic database: quadratic drag and linear damping per rigid-body
DOF of a body, and Morison elements (cylinder segments on a body).

Body drag acts per DOF in the body's axes, at its centre of mass, on the velocity u of the DOF (the body's own, or
relative to the undisturbed fluid at its centre of mass): F_a = -c_a |u_a| u_a - b_a u_a, with the quadratic
coefficient c_a = 1/2 rho Cd_a A_a (or given directly) [N s^2/m^2 for translations, N m s^2/rad^2 for rotations] and
the linear b_a [N s/m, N m s/rad] (as WEC-Sim's ``quadDrag`` and ``linearDamping``).

A Morison element is a circular cylinder from ``start`` to ``end`` (on its body, given in world axes at the
reference configuration) of diameter D, split into segments; per unit length, normal to its axis, the fluid's
inertia rho (1 + Ca) pi D^2/4 du_n/dt and the drag 1/2 rho Cd D |u_rel,n| u_rel,n act on the submerged part, and the
added mass rho Ca pi D^2/4 of the body's own normal acceleration (taken constant, at the equilibrium immersion, into
the mass matrix).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..constants import RIGID_BODY_DOFS

DRAG_KEYS = ("body", "coefficient", "cd", "area", "linear")
MORISON_KEYS = ("body", "start", "end", "diameter", "cd", "ca", "segments")


def _per_dof(where: str, label: str, values: Any) -> np.ndarray:
    """A table DOF name -> value as 6 values in the order Surge ... Yaw (0 for the DOFs not named)."""
    if not isinstance(values, Mapping):
        raise ValueError(
            f"{where}: {label} must be a table of DOF name -> value, such as {{Heave = 1.0}}; got {values!r}"
        )
    out = np.zeros(6)
    names = {d.lower(): k for k, d in enumerate(RIGID_BODY_DOFS)}
    for dof, value in values.items():
        k = names.get(str(dof).lower())
        if k is None:
            raise ValueError(f"{where}: unknown DOF {dof!r} in {label}; accepted: {', '.join(RIGID_BODY_DOFS)}")
        if isinstance(value, bool) or not isinstance(value, int | float) or not (np.isfinite(value) and value >= 0):
            raise ValueError(f"{where}: {label} of {RIGID_BODY_DOFS[k]} must be a finite number >= 0; got {value!r}")
        out[k] = float(value)
    return out


@dataclass(frozen=True)
class BodyDrag:
    """Quadratic drag and linear damping on one body's rigid-body DOFs, body axes, at its centre of mass.

    Attributes
    ----------
    body : str
    coefficient : ndarray (6,)
        Quadratic coefficients given directly [N s^2/m^2, N m s^2/rad^2].
    cd, area : ndarray (6,)
        Drag coefficients [-] and reference areas [m^2; m^5 for rotations, so that 1/2 rho Cd A is a moment
        coefficient]; their product adds 1/2 rho Cd A to ``coefficient``.
    linear : ndarray (6,)
        Linear damping [N s/m, N m s/rad].
    """

    body: str
    coefficient: np.ndarray = field(default_factory=lambda: np.zeros(6))
    cd: np.ndarray = field(default_factory=lambda: np.zeros(6))
    area: np.ndarray = field(default_factory=lambda: np.zeros(6))
    linear: np.ndarray = field(default_factory=lambda: np.zeros(6))

    @classmethod
    def from_spec(cls, entry: Mapping[str, Any]) -> BodyDrag:
        """From a spec's ``[[drag]]`` table: ``body``, and any of ``coefficient``, ``cd`` with ``area``,
        ``linear``, each a table DOF -> value (``{Heave = 1.0}``).

        Raises
        ------
        ValueError
            On unknown keys or DOFs, negative or non-finite values, ``cd`` without ``area`` (or the reverse), or
            an entry that sets nothing.
        """
        unknown = sorted(set(entry) - set(DRAG_KEYS))
        if unknown or "body" not in entry:
            raise ValueError(f"drag: unknown keys {unknown} or no body; accepted: {', '.join(DRAG_KEYS)}")
        where = f"drag of body {entry['body']!r}"
        parts = {key: _per_dof(where, key, entry[key]) for key in DRAG_KEYS[1:] if key in entry}
        if ("cd" in parts) != ("area" in parts):
            raise ValueError(f"{where}: cd and area go together (1/2 rho Cd A per DOF); got only {sorted(parts)}")
        if not any(np.any(v) for v in parts.values()):
            raise ValueError(f"{where}: sets no coefficient; give coefficient, cd and area, or linear")
        return cls(str(entry["body"]), **parts)

    def quadratic(self, rho: float) -> np.ndarray:
        """The quadratic coefficients c_a per DOF [N s^2/m^2, N m s^2/rad^2] at the water density ``rho``."""
        return self.coefficient + 0.5 * rho * self.cd * self.area

    def to_dict(self) -> dict[str, Any]:
        """The spec's table (what the result's attributes record)."""
        out: dict[str, Any] = {"body": self.body}
        for key in DRAG_KEYS[1:]:
            values = getattr(self, key)
            if np.any(values):
                out[key] = {d: float(v) for d, v in zip(RIGID_BODY_DOFS, values, strict=True) if v}
        return out


@dataclass(frozen=True)
class MorisonElement:
    """A Morison cylinder on a body (see the module docstring).

    Attributes
    ----------
    body : str
    start, end : ndarray (3,)
        Its axis's ends, world axes at the reference configuration [m].
    diameter : float
        D [m].
    cd, ca : float
        Drag and added-mass coefficients [-] (the inertia coefficient is 1 + Ca).
    segments : int
        Segments the force is integrated over (midpoint rule).
    """

    body: str
    start: np.ndarray
    end: np.ndarray
    diameter: float
    cd: float = 1.0
    ca: float = 1.0
    segments: int = 10

    @classmethod
    def from_spec(cls, entry: Mapping[str, Any]) -> MorisonElement:
        """From a spec's ``[[morison]]`` table.

        Raises
        ------
        ValueError
            On unknown or missing keys, a zero-length axis, a non-positive diameter or segment count, negative
            coefficients.
        """
        unknown = sorted(set(entry) - set(MORISON_KEYS))
        missing = sorted({"body", "start", "end", "diameter"} - set(entry))
        if unknown or missing:
            raise ValueError(f"morison: unknown keys {unknown}, missing {missing}; accepted: {', '.join(MORISON_KEYS)}")
        where = f"morison element on body {entry['body']!r}"
        start, end = (np.asarray(entry[k], dtype=float) for k in ("start", "end"))
        if start.shape != (3,) or end.shape != (3,) or not np.all(np.isfinite([*start, *end])):
            raise ValueError(
                f"{where}: start and end must be 3 finite numbers [m]; got {entry['start']!r}, {entry['end']!r}"
            )
        if np.linalg.norm(end - start) == 0:
            raise ValueError(f"{where}: start and end are the same point")
        diameter = entry["diameter"]
        if isinstance(diameter, bool) or not isinstance(diameter, int | float) or not diameter > 0:
            raise ValueError(f"{where}: diameter must be a positive length [m]; got {diameter!r}")
        values = {k: entry.get(k, default) for k, default in (("cd", 1.0), ("ca", 1.0))}
        for key, value in values.items():
            if isinstance(value, bool) or not isinstance(value, int | float) or not (np.isfinite(value) and value >= 0):
                raise ValueError(f"{where}: {key} must be a finite number >= 0; got {value!r}")
        segments = entry.get("segments", 10)
        if isinstance(segments, bool) or not isinstance(segments, int) or segments < 1:
            raise ValueError(f"{where}: segments must be an integer >= 1; got {segments!r}")
        return cls(str(entry["body"]), start, end, float(diameter), float(values["cd"]), float(values["ca"]), segments)

    def segment_points(self) -> tuple[np.ndarray, np.ndarray, float]:
        """Midpoints (segments, 3) [m, world axes at the reference configuration], the unit axis (3,) and the
        segment length [m]."""
        axis = self.end - self.start
        length = float(np.linalg.norm(axis))
        fractions = (np.arange(self.segments) + 0.5) / self.segments
        return self.start + fractions[:, None] * axis, axis / length, length / self.segments

    def to_dict(self) -> dict[str, Any]:
        """The spec's table."""
        return {
            "body": self.body, "start": self.start.tolist(), "end": self.end.tolist(), "diameter": self.diameter,
            "cd": self.cd, "ca": self.ca, "segments": self.segments,
        }  # fmt: skip
