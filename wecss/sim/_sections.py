"""Section loads at the hot spots of the device's beam members, from the loads recovered after a run.

Free body. A member lies on one body. The body is cut at the hot spot's station (a plane normal to the member
through the point ``start + at * x``); the section load is the resultant, about the cut's centre and in the member's
local axes (N, Vy, Vz [N], T, My, Mz [N m]), of every load on the part of the body beyond the cut (towards the
member's ``end``; a load belongs there when its point's projection on the member lies beyond the station):

- the joint loads: the reaction of the body's own joint (from its parent) and minus the reaction of each child's
  joint, at the joint points (a hinge's point; else the child's centre of mass);
- the PTO loads on the body, at their attachment points (a joint PTO's torque at the joint);
- the body's own loads: gravity, buoyancy and hydrostatic restoring, wave excitation and radiation, and its
  d'Alembert inertia -(M + A_inf) a - w x (J w), as one load at its centre of mass; with the member's
  ``body_mass = "along"`` the rigid-body weight and inertia are instead spread uniformly along the member (the
  member is the body: the NOTC arm) and only the rest stays at the centre of mass.

The loads on the whole body balance (the inertia included), so the section load at a station equals minus the
resultant of the loads on the other side; at a member's start on the body's own joint it is minus that joint's
reaction. The line load of a uniform member in a rigid motion is affine along the member, so its resultant beyond
a cut is integrated exactly by two Gauss points.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..devices import HotSpot, Member

_GAUSS = (0.5 - 0.5 / np.sqrt(3.0), 0.5 + 0.5 / np.sqrt(3.0))


@dataclass
class BodyHistory:
    """What one member-carrying body feels at the saved steps, in its own axes.

    points : (n_t, k, 3) where each point load acts, body reference coordinates (the world coordinates of the
    reference configuration) [m]; forces, moments : (n_t, k, 3) the point loads (moments about their points) [N, N m];
    gravity : (n_t, 3) g in body axes [m/s^2]; acceleration, alpha, omega : (n_t, 3) centre-of-mass acceleration
    [m/s^2], angular acceleration [rad/s^2] and velocity [rad/s] in body axes. The last point load is the body's own
    load at its centre of mass.
    """

    points: np.ndarray
    forces: np.ndarray
    moments: np.ndarray
    gravity: np.ndarray
    acceleration: np.ndarray
    alpha: np.ndarray
    omega: np.ndarray


def hot_spots(members: tuple[Member, ...]) -> list[tuple[Member, HotSpot]]:
    """Every (member, hot spot) pair in the device's order."""
    return [(m, s) for m in members for s in m.hot_spots]


def hot_spot_names(members: tuple[Member, ...]) -> list[str]:
    """Labels ``member.spot`` of :func:`hot_spots`."""
    return [f"{m.name}.{s.name}" for m, s in hot_spots(members)]


def _line_loads(
    member: Member, centre: np.ndarray, mass: float, history: BodyHistory, s0: float
) -> tuple[np.ndarray, np.ndarray]:
    """Two Gauss point loads (points (2, 3), forces (n_t, 2, 3)) carrying the weight and d'Alembert inertia of the
    body's mass spread uniformly along the member from station ``s0`` to its end."""
    axis = member.axes[0]
    span = member.length - s0
    points = np.array([member.start + (s0 + u * span) * axis for u in _GAUSS])
    forces = np.zeros((history.gravity.shape[0], 2, 3))
    for k, r in enumerate(points):
        arm = r - centre
        w, al = history.omega, history.alpha
        acc = history.acceleration + np.cross(al, arm) + np.cross(w, np.cross(w, arm))
        forces[:, k] = mass / member.length * 0.5 * span * (history.gravity - acc)
    return points, forces


def section_loads(members: tuple[Member, ...], body_index: dict[str, int], bodies, histories) -> np.ndarray:
    """Section loads at every hot spot (n_t, n_spot, 6): N, Vy, Vz [N], T, My, Mz [N m] in member axes.

    ``bodies`` holds the model's bodies (for the centre of mass and the mass); ``histories`` maps body index to its
    :class:`BodyHistory`.
    """
    out = []
    for member, spot in hot_spots(members):
        i = body_index[member.body]
        h: BodyHistory = histories[i]
        centre, mass = bodies[i].center_of_mass, bodies[i].mass
        points = h.points[0]
        # the loads' points as fixed points of the body (a child on a slider moves): shift their moments
        moments = h.moments + np.cross(h.points - points[None], h.forces)
        forces = h.forces
        if member.body_mass == "along":
            # the rigid weight and inertia leave the centre-of-mass load and spread along the member
            whole_p, whole_f = _line_loads(member, centre, mass, h, 0.0)
            own_f = forces[:, -1] - whole_f.sum(axis=1)
            own_m = moments[:, -1] - np.cross(whole_p - centre, whole_f).sum(axis=1)
            forces = np.concatenate([forces[:, :-1], own_f[:, None]], axis=1)
            moments = np.concatenate([moments[:, :-1], own_m[:, None]], axis=1)
            line_p, line_f = _line_loads(member, centre, mass, h, spot.at)
            points = np.vstack([points, line_p])
            forces = np.concatenate([forces, line_f], axis=1)
            moments = np.concatenate([moments, np.zeros_like(line_f)], axis=1)
        out.append(member.internal_wrench(spot.at, points, forces, moments))
    n_t = next(iter(histories.values())).forces.shape[0] if histories else 0
    return np.stack(out, axis=1) if out else np.zeros((n_t, 0, 6))


def hot_spot_stresses(members: tuple[Member, ...], sections: np.ndarray) -> dict[str, np.ndarray]:
    """Stresses (n, n_spot) [Pa] at every hot spot from its section loads (n, n_spot, 6), SCF applied (see
    :meth:`wecss.devices.Member.stress_components`): ``axial``, ``bending``, ``normal``, ``shear`` (torsion), and for
    real loads ``von_mises`` and ``signed_von_mises``; complex amplitudes give the linear components only."""
    linear = ("axial", "bending", "normal", "shear")
    keys = linear if np.iscomplexobj(sections) else (*linear, "von_mises", "signed_von_mises")
    cols: dict[str, list[np.ndarray]] = {k: [] for k in keys}
    for k, (member, spot) in enumerate(hot_spots(members)):
        parts = member.stress_components(spot, sections[:, k])
        if "von_mises" in keys:
            parts.update(member.stresses(spot, sections[:, k]))
        for key in keys:
            cols[key].append(parts[key])
    return {k: np.stack(v, axis=1) if v else np.zeros(sections.shape[:1]) for k, v in cols.items()}
