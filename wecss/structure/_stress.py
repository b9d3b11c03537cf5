"""Stress modes: the section loads and the stresses at points of the members' sections per modal coordinate, so that
a stress field is one matrix product with the modal coordinates.

Section load at a station of a member (the convention of ``wecss.devices.Member.internal_wrench``): the resultant,
about the section's centre and in the member's local axes, of the loads on the part beyond the cut (towards the
member's end): N (tension positive), Vy, Vz [N], T, My, Mz [N m]. In the finite-element model this is the force the
nodes exert on the element that starts at the station, with its sign changed: W = -(K_e u_e + M_e a_e - f_e) at
the element's first node, with u_e its elastic displacements, a_e their accelerations and f_e the element's own
loads in the body's rigid-body motion (weight and d'Alembert inertia, linear in the coordinates
``wecss.structure.RIGID_LOADS``). That is exact for the finite-element solution (element by element equilibrium),
whatever the mesh, so a cut at a node gives the free-body cut's value. At a member's end (no element starts there)
it is the force the last element carries into its end node, the point loads at that node included.

The d'Alembert loads of the element's mass points are those of their whole acceleration in the floating frame (body
axes, frame angular velocity w and acceleration alpha, elastic displacement u and section rotation theta):

    a = a_o + alpha x (x + u) + w x (w x (x + u)) + 2 w x u_dot + u_ddot

on a point's mass m, and on its rotary inertia J (its section's, rotating with it: J + [theta] J - J [theta]) the
moment -(J alpha + w x J w) - J theta_ddot less, to first order in the elastic motion,
(theta_dot x J w + J (w x theta_dot) + w x J theta_dot) + D alpha + w x D w with D = [theta] J - J [theta]. The rigid
terms are the rigid-motion loads (``section_rigid``), the accelerations' the modal masses' (``section_acceleration``);
the terms bilinear in the frame's motion and the elastic coordinates are ``section_motion`` (alpha and the products
of w, ``RIGID_LOADS[3:]``, times xi) and ``section_coriolis`` (w times xi_dot), the same terms as the floating
frame's equations of motion carry (``wecss.structure._invariants``).

With ``geometric`` (a body whose equations carry the geometric stiffening of its own axial strain,
``wecss.structure._geometric``) the element's force adds the gradient of its cubic strain energy U3_e = 1/2 N_e d'
G_e d (N_e = EA/L times its elongation, G_e its geometric stiffness per unit axial force, d its local
displacements): N_e G_e d on its transverse and torsion DOFs and -/+ 1/2 (EA/L) d' G_e d on its axial ones,
quadratic in the modal coordinates: the von Karman axial force EA (u' + (v'^2 + w'^2) / 2) and the transverse share
of the axial force on the slope, which the linear terms miss.

Stresses at a point (y, z) of the section, times the point's stress concentration factor: the normal stress
sigma = N / A + My z / Iy - Mz y / Iz and the torsional shear tau = T / W_t (the thin-walled value at the wall; the
shear of Vy and Vz, zero at the extreme fibres, is left out); von Mises sqrt(sigma^2 + 3 tau^2) and the signed von
Mises stress with the sign of sigma, the principal stress of largest magnitude in this plane stress state (paper
003, Eq. 53).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from ._frame import PAIRS, Frame, MassGroup, group_rigid_loads


@dataclass(frozen=True)
class StressPoint:
    """A point where stresses are recovered: ``member``, ``station`` (from the member's start, at a node) [m], ``y``,
    ``z`` on the section [m], ``scf`` the stress concentration factor [-] and a ``name``."""

    member: str
    station: float
    y: float
    z: float
    scf: float = 1.0
    name: str = ""


def von_mises(normal: np.ndarray, shear: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Von Mises stress sqrt(sigma^2 + 3 tau^2) and the signed von Mises stress (the sign of sigma, + at 0) [Pa]."""
    vm = np.sqrt(np.asarray(normal) ** 2 + 3 * np.asarray(shear) ** 2)
    return vm, np.where(np.asarray(normal) < 0, -vm, vm)


@dataclass(frozen=True, eq=False)
class StressModes:
    """Section loads and stresses per modal coordinate (see the module docstring).

    Attributes
    ----------
    stations : tuple of (member, station)
        The cuts [m from the member's start].
    points : tuple of StressPoint
    section, section_acceleration : ndarray (n_station, 6, n)
        Section loads per modal coordinate and per modal acceleration [N, N m per 1; per 1/s^2].
    section_rigid : ndarray (n_station, 6, 12)
        Section loads per rigid-motion load coordinate (``RIGID_LOADS``) [N, N m per m/s^2 ...].
    section_motion : ndarray (n_station, 6, 9, n)
        Section loads per product of a coordinate of ``RIGID_LOADS[3:]`` (alpha, the products of w) and a modal
        coordinate [N, N m per rad/s^2 ...].
    section_coriolis : ndarray (n_station, 6, 3, n)
        Section loads per product of a component of w and a modal rate [N, N m per rad/s per 1/s].
    normal, shear : ndarray (n_point, n)
        sigma and tau per modal coordinate [Pa per 1], SCF applied.
    normal_acceleration, shear_acceleration : ndarray (n_point, n)
    normal_rigid, shear_rigid : ndarray (n_point, 12)
    point_station : ndarray (n_point,) of int
        The index in ``stations`` of each point's cut.
    normal_section, shear_section : ndarray (n_point, 6)
        sigma and tau per section load of the point's cut [Pa per N, N m], SCF applied.
    section_geometric : ndarray (n_station, 6, n, n) or None
        The quadratic section loads (see the module docstring): q' section_geometric[s, j] q [N, N m per 1].
    normal_geometric, shear_geometric : ndarray (n_point, n, n) or None
    """

    stations: tuple[tuple[str, float], ...]
    points: tuple[StressPoint, ...]
    section: np.ndarray
    section_acceleration: np.ndarray
    section_rigid: np.ndarray
    normal: np.ndarray
    shear: np.ndarray
    normal_acceleration: np.ndarray
    shear_acceleration: np.ndarray
    normal_rigid: np.ndarray
    shear_rigid: np.ndarray
    section_motion: np.ndarray
    section_coriolis: np.ndarray
    point_station: np.ndarray
    normal_section: np.ndarray
    shear_section: np.ndarray
    section_geometric: np.ndarray | None = None
    normal_geometric: np.ndarray | None = None
    shear_geometric: np.ndarray | None = None

    def section_loads(
        self,
        q: np.ndarray,
        q_ddot: np.ndarray | None = None,
        rigid: np.ndarray | None = None,
        q_dot: np.ndarray | None = None,
        omega: np.ndarray | None = None,
        *,
        motion: bool = True,
    ) -> np.ndarray:
        """Section loads (..., n_station, 6) from modal coordinates q (..., n), their accelerations and the
        rigid-motion load coordinates (..., 12) (each optional but q); with ``rigid`` and ``motion`` also the loads
        of its angular acceleration and velocity products on the elastic displacements (``motion=False`` for a
        quasi-static response solved without them, a frozen body's), and with the modal rates ``q_dot`` (..., n)
        [1/s] and the frame's angular velocity ``omega`` (..., 3) [rad/s] (both or neither) the Coriolis loads
        (module docstring).

        Raises
        ------
        ValueError
            If one of ``q_dot`` and ``omega`` is given without the other.
        """
        out = np.einsum("sjn,...n->...sj", self.section, q)
        if q_ddot is not None:
            out = out + np.einsum("sjn,...n->...sj", self.section_acceleration, q_ddot)
        if rigid is not None:
            out = out + np.einsum("sjr,...r->...sj", self.section_rigid, rigid)
            if motion:
                out = out + np.einsum("sjcn,...c,...n->...sj", self.section_motion, np.asarray(rigid)[..., 3:], q)
        if _coriolis_given(q_dot, omega) and q_dot is not None and omega is not None:
            out = out + np.einsum("sjcn,...c,...n->...sj", self.section_coriolis, omega, q_dot)
        if self.section_geometric is not None:
            out = out + np.einsum("...m,sjmk,...k->...sj", q, self.section_geometric, q)
        return out

    def stresses(
        self,
        q: np.ndarray,
        q_ddot: np.ndarray | None = None,
        rigid: np.ndarray | None = None,
        q_dot: np.ndarray | None = None,
        omega: np.ndarray | None = None,
        *,
        motion: bool = True,
    ) -> dict[str, np.ndarray]:
        """``normal``, ``shear``, ``von_mises`` and ``signed_von_mises`` (..., n_point) [Pa] at the points (the
        arguments as :meth:`section_loads`'s).

        Raises
        ------
        ValueError
            If one of ``q_dot`` and ``omega`` is given without the other.
        """
        # matrix products (BLAS): eight times einsum's loops on (2000, 21) chunks of 500 points
        q = np.asarray(q, dtype=float)
        normal = q @ self.normal.T
        shear = q @ self.shear.T
        if q_ddot is not None:
            normal = normal + np.asarray(q_ddot, dtype=float) @ self.normal_acceleration.T
            shear = shear + np.asarray(q_ddot, dtype=float) @ self.shear_acceleration.T
        # the terms bilinear in the frame's rotation and the elastic motion at the cuts, then at the points (a cut
        # has six loads, and often tens of points)
        cuts = None
        if rigid is not None:
            rigid = np.asarray(rigid, dtype=float)
            normal = normal + rigid @ self.normal_rigid.T
            shear = shear + rigid @ self.shear_rigid.T
            if motion:
                cuts = _bilinear(rigid[..., 3:], q, self.section_motion)
        if _coriolis_given(q_dot, omega) and q_dot is not None and omega is not None:
            coriolis = _bilinear(np.asarray(omega, dtype=float), np.asarray(q_dot, dtype=float), self.section_coriolis)
            cuts = coriolis if cuts is None else cuts + coriolis
        if cuts is not None:
            extra_normal, extra_shear = self.at_points(cuts)
            normal = normal + extra_normal
            shear = shear + extra_shear
        if self.normal_geometric is not None and self.shear_geometric is not None:
            normal = normal + _quadratic(q, self.normal_geometric)
            shear = shear + _quadratic(q, self.shear_geometric)
        vm, signed = von_mises(normal, shear)
        return {"normal": normal, "shear": shear, "von_mises": vm, "signed_von_mises": signed}

    def at_points(self, loads: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The normal and shear stress (..., n_point) [Pa] at the points of section loads (..., n_station, 6) at the
        cuts [N, N m]."""
        flat = np.asarray(loads, dtype=float).reshape(*np.shape(loads)[:-2], -1)
        normal, shear = self._cut_to_points
        return flat @ normal, flat @ shear

    @cached_property
    def _cut_to_points(self) -> tuple[np.ndarray, np.ndarray]:
        """(n_station * 6, n_point) each: the normal and the shear stress at the points per section load at the
        cuts (six entries per point's column; as one matrix product, with no (..., n_point, 6) gather)."""
        out = []
        for rows in (self.normal_section, self.shear_section):
            full = np.zeros((len(self.stations), 6, len(self.points)))
            full[self.point_station, :, np.arange(len(self.points))] = rows
            out.append(full.reshape(len(self.stations) * 6, len(self.points)))
        return out[0], out[1]


def _coriolis_given(q_dot: np.ndarray | None, omega: np.ndarray | None) -> bool:
    """Whether the Coriolis loads are asked for: both ``q_dot`` and ``omega`` given (one alone is an error)."""
    if (q_dot is None) != (omega is None):
        raise ValueError(
            "the Coriolis loads need both the modal rates q_dot and the frame's angular velocity omega; got "
            f"{'q_dot' if omega is None else 'omega'} alone"
        )
    return q_dot is not None


def _bilinear(a: np.ndarray, q: np.ndarray, forms: np.ndarray) -> np.ndarray:
    """sum_cn a_c q_n forms[s, j, c, n] (..., n_station, 6) for a (..., c), q (..., n) and forms (n_station, 6, c,
    n), by one matrix product."""
    n_station, n_load, n_a, n = forms.shape
    products = (a[..., :, None] * q[..., None, :]).reshape(*q.shape[:-1], n_a * n)
    return (products @ forms.reshape(n_station * n_load, n_a * n).T).reshape(*q.shape[:-1], n_station, n_load)


def _quadratic(q: np.ndarray, forms: np.ndarray) -> np.ndarray:
    """q' forms[p] q (..., n_point) for q (..., n) and forms (n_point, n, n), by one matrix product."""
    n_point, n, _ = forms.shape
    half = (q @ forms.transpose(1, 0, 2).reshape(n, n_point * n)).reshape(*q.shape[:-1], n_point, n)
    return np.einsum("...pk,...k->...p", half, q)


def default_points(frame: Frame) -> tuple[StressPoint, ...]:
    """Every node of every member with its section's default fibres (``Section.fibres``), SCF 1."""
    out = []
    for member, elements in frame.members().items():
        stations = [e.station for e in elements] + [elements[-1].station + elements[-1].length]
        for s in stations:
            for k, (y, z) in enumerate(elements[0].section.fibres):
                out.append(StressPoint(member, float(s), y, z, 1.0, f"fibre{k}"))
    return tuple(out)


def stress_modes(
    frame: Frame,
    basis: np.ndarray,
    points: Sequence[StressPoint] | None = None,
    origin: np.ndarray | None = None,
    *,
    geometric: bool = False,
) -> StressModes:
    """Stress modes of ``frame`` for the mode fields ``basis`` (n_dof, n) at ``points`` (default
    :func:`default_points`); the rigid-motion loads about ``origin`` [m] (default: the frame's centre of mass, the
    body frame's origin); with ``geometric``, the quadratic terms of the cubic strain energy (module docstring).

    Raises
    ------
    ValueError
        On a point of an unknown member or at a station that is not a node of its member.
    """
    phi = np.asarray(basis, dtype=float)
    pts = default_points(frame) if points is None else tuple(points)
    members = frame.members()
    groups = frame.mass_points
    if origin is None:
        total = sum(float(g.masses.sum()) for g in groups)
        origin = sum((g.masses @ g.positions for g in groups), np.zeros(3)) / total
    index = {id(e): k for k, e in enumerate(frame.elements)}
    stations: list[tuple[str, float]] = []
    rows_u, rows_a, rows_r, rows_m, rows_c, rows_g = [], [], [], [], [], []
    where: dict[tuple[str, float], int] = {}
    for p in pts:
        if p.member not in members:
            raise ValueError(f"stress point {p.name!r}: member {p.member!r} is not in the frame: {sorted(members)}")
        elements = members[p.member]
        length = elements[-1].station + elements[-1].length
        tol = 1e-9 * max(1.0, length)
        ends = [e.station for e in elements] + [length]
        match = [k for k, s in enumerate(ends) if abs(s - p.station) <= tol]
        if not match:
            raise ValueError(
                f"stress point {p.name!r}: station {p.station} m of member {p.member!r} is not a node (nodes at "
                f"{np.round(ends, 6).tolist()} m); add it to the member's stations"
            )
        key = (p.member, ends[match[0]])
        if key in where:
            continue
        where[key] = len(stations)
        stations.append(key)
        k = match[0]
        last = k == len(elements)
        e = elements[k - 1] if last else elements[k]
        dofs = frame.element_dofs(e)
        t = e.transform
        loads = group_rigid_loads(groups[index[id(e)]], origin)
        part, sign = (slice(6, 12), 1.0) if last else (slice(0, 6), -1.0)
        ku = np.zeros((6, frame.n_dof))
        ma = np.zeros((6, frame.n_dof))
        ku[:, dofs] = sign * (e.local_stiffness @ t)[part]
        ma[:, dofs] = sign * (e.local_mass @ t)[part]
        rows_u.append(ku @ phi)
        rows_a.append(ma @ phi)
        rows_r.append(-sign * (t @ loads)[part])
        motion, coriolis = _elastic_motion_loads(groups[index[id(e)]], phi)
        rows_m.append(-sign * np.einsum("ij,jcn->icn", t, motion)[part])
        rows_c.append(-sign * np.einsum("ij,jcn->icn", t, coriolis)[part])
        if geometric:
            rows_g.append(sign * _element_geometric(frame, e, phi)[part])
    section = np.array(rows_u).reshape(len(stations), 6, phi.shape[1])
    section_a = np.array(rows_a).reshape(len(stations), 6, phi.shape[1])
    section_r = np.array(rows_r).reshape(len(stations), 6, 12)
    section_m = np.array(rows_m).reshape(len(stations), 6, 9, phi.shape[1])
    section_c = np.array(rows_c).reshape(len(stations), 6, 3, phi.shape[1])
    section_g = np.array(rows_g).reshape(len(stations), 6, phi.shape[1], phi.shape[1]) if geometric else None
    normal_rows, shear_rows = [], []
    for p in pts:
        s = members[p.member][0].section
        normal_rows.append(p.scf * np.array([1 / s.area, 0.0, 0.0, 0.0, p.z / s.iy, -p.y / s.iz]))
        shear_rows.append(p.scf * np.array([0.0, 0.0, 0.0, 1 / s.wt, 0.0, 0.0]))
    at = [where[(p.member, _snap(p, members))] for p in pts]
    a_n, a_t = np.array(normal_rows).reshape(-1, 6), np.array(shear_rows).reshape(-1, 6)
    sec_at = section[at] if at else np.zeros((0, 6, phi.shape[1]))
    sec_a_at = section_a[at] if at else np.zeros((0, 6, phi.shape[1]))
    sec_r_at = section_r[at] if at else np.zeros((0, 6, 12))
    forms: tuple[np.ndarray | None, ...] = (None, None, None)
    if section_g is not None:
        sec_g_at = section_g[at] if at else np.zeros((0, 6, phi.shape[1], phi.shape[1]))
        forms = (section_g, np.einsum("pj,pjmk->pmk", a_n, sec_g_at), np.einsum("pj,pjmk->pmk", a_t, sec_g_at))
    return StressModes(
        tuple(stations), pts, section, section_a, section_r,
        np.einsum("pj,pjn->pn", a_n, sec_at), np.einsum("pj,pjn->pn", a_t, sec_at),
        np.einsum("pj,pjn->pn", a_n, sec_a_at), np.einsum("pj,pjn->pn", a_t, sec_a_at),
        np.einsum("pj,pjr->pr", a_n, sec_r_at), np.einsum("pj,pjr->pr", a_t, sec_r_at),
        section_m, section_c, np.array(at, dtype=np.int64), a_n, a_t, *forms,
    )  # fmt: skip


def _elastic_motion_loads(group: MassGroup, phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The d'Alembert loads on a group's DOFs (k, 9, n) per coordinate of ``RIGID_LOADS[3:]`` (alpha, the products
    of w) times a modal coordinate, and (k, 3, n) per component of w times a modal rate, for the mode fields ``phi``
    (n_dof, n) (module docstring): on a mass point's mass -m (alpha x u + w x (w x u) + 2 w x u_dot), on its rotary
    inertia -(D alpha + w x D w) and -(theta_dot x J w + J (w x theta_dot) + w x J theta_dot)."""
    g = group
    field = phi[g.dofs]
    u = np.einsum("pai,in->pan", g.nu, field)  # (p, 3, n) displacement per modal coordinate
    theta = np.einsum("pai,in->pan", g.ntheta, field)  # and rotation
    mass = g.masses[:, None, None]
    inertia = g.inertias
    eye = np.eye(3)[:, None, :, None]  # eye[k]: e_k as (1, 3, 1)

    j_theta = np.einsum("pab,pbn->pan", inertia, theta)
    j_axis = [np.einsum("pab,xbn->pan", inertia, e) for e in eye]  # J e_k, (p, 3, 1)
    # spin[k] = D e_k = theta x (J e_k) - J (theta x e_k), (p, 3, n)
    spin = [_cross(theta, j_e) - np.einsum("pab,pbn->pan", inertia, _cross(theta, e)) for e, j_e in
            zip(eye, j_axis, strict=True)]  # fmt: skip

    forces = np.zeros((u.shape[0], 9, 3, u.shape[2]))
    moments = np.zeros_like(forces)
    for k in range(3):  # alpha_k
        forces[:, k] = -mass * _cross(eye[k], u)
        moments[:, k] = -spin[k]
    for c, (a, b) in enumerate(PAIRS):  # w_a w_b: -w x (w x u) = |w|^2 u - w (w . u), and -w x D w
        if a == b:
            forces[:, 3 + c] = mass * (u - eye[a] * u[:, a : a + 1])
            moments[:, 3 + c] = -_cross(eye[a], spin[a])
        else:
            forces[:, 3 + c] = -mass * (eye[a] * u[:, b : b + 1] + eye[b] * u[:, a : a + 1])
            moments[:, 3 + c] = -_cross(eye[a], spin[b]) - _cross(eye[b], spin[a])
    coriolis_forces = np.zeros((u.shape[0], 3, 3, u.shape[2]))
    coriolis_moments = np.zeros_like(coriolis_forces)
    for k in range(3):  # w_k times the rates
        coriolis_forces[:, k] = -2.0 * mass * _cross(eye[k], u)
        coriolis_moments[:, k] = -(
            _cross(theta, j_axis[k]) + np.einsum("pab,pbn->pan", inertia, _cross(eye[k], theta))
            + _cross(eye[k], j_theta)
        )  # fmt: skip
    motion = np.einsum("pai,pcan->icn", g.nu, forces) + np.einsum("pai,pcan->icn", g.ntheta, moments)
    coriolis = np.einsum("pai,pcan->icn", g.nu, coriolis_forces) + np.einsum("pai,pcan->icn", g.ntheta,
                                                                             coriolis_moments)  # fmt: skip
    return motion, coriolis


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """a x b along axis 1 of (p, 3, n)-shaped arrays (broadcast)."""
    return np.stack(
        [
            a[:, 1] * b[:, 2] - a[:, 2] * b[:, 1],
            a[:, 2] * b[:, 0] - a[:, 0] * b[:, 2],
            a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0],
        ],
        axis=1,
    )


def _element_geometric(frame: Frame, element, phi: np.ndarray) -> np.ndarray:
    """(12, n, n): the element's force from its cubic strain energy, local axes, as quadratic forms in the modal
    coordinates: N_e G_e d on every DOF, plus -/+ 1/2 (EA/L) d' G_e d on the axial DOFs 0 and 6 (module docstring)."""
    local = element.transform @ phi[frame.element_dofs(element)]  # d = local @ q, (12, n)
    unit = element.local_geometric_stiffness(1.0)
    stiffness = element.material.youngs_modulus * element.section.area / element.length
    axial = stiffness * (local[6] - local[0])  # N_e = axial @ q
    out = np.einsum("m,jk->jmk", axial, unit @ local)
    energy = 0.5 * stiffness * local.T @ unit @ local
    out[0] -= energy
    out[6] += energy
    return out


def _snap(point: StressPoint, members: dict) -> float:
    """The node station of the member that ``point`` lies at (checked before)."""
    elements = members[point.member]
    ends = [e.station for e in elements] + [elements[-1].station + elements[-1].length]
    return ends[int(np.argmin([abs(s - point.station) for s in ends]))]
