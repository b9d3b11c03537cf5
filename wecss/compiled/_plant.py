"""The multibody device, its hydrostatics and its PTOs as flat arrays (the part of a compiled scene that the
equations of motion read).

Built once per scene from a :class:`~wecss.devices.Device` and its :class:`~wecss.multibody.HydroCoupling`; the
kernels in ``_kernels`` read only these arrays.
"""

from __future__ import annotations

from collections.abc import Sequence
from enum import IntEnum
from typing import NamedTuple

import numpy as np

from ..multibody import (
    PTO,
    ActuatorPTO,
    HydroCoupling,
    JointPTO,
    Multibody,
    body_mass_matrix,
    integrate,
    kinematics,
)
from ._body_exact import PressureArrays, no_pressure
from ._jit import inline_kernel, reshaped
from ._viscous import ViscousArrays, no_viscous


class PtoKind(IntEnum):
    """The ``pto_kind`` of a :class:`Plant`'s PTO (stored as int; numba compares the members)."""

    JOINT = 0
    ACTUATOR = 1


class Plant(NamedTuple):
    """Flat arrays of a device (all SI; Cartesian vectors hold each body's 6 rigid rows and then one row per
    generalised mode of the body, see ``wecss.multibody``).

    Tree (bodies in the model's order; ``order`` is the topological order)
        order, parent, free, col_start, n_cols, q_start : int arrays (n_body,) (the joints' columns and coordinates)
        com0 : (n_body, 3) centres of mass at the reference configuration [m]
        twists : (nv, 6) joint twists in the world frame at the reference configuration (unused for free joints,
        zero for the modes' columns)
        chain : (n_body, nv) 1.0 where a joint velocity moves the body's rigid rows (0 on the modes' columns)
    Cartesian rows (the only place that knows a body's rows; kernels never assume 6 per body)
        cart_start, cart_size : (n_body,) each body's first Cartesian row and its number of rows (6 + its modes)
        cart_body, cart_axis : (n_cart,) each row's body and axis (0-2 CoM velocity x, y, z in world axes, 3-5 body
        angular velocity, 6.. the body's generalised modes)
        cart_column, cart_coordinate : (n_cart,) a mode row's generalised velocity and coordinate (B is the identity
        on that column, Bdot zero), -1 on rigid rows
        mode_row : (n_mode,) the Cartesian row of each generalised mode
        mode_stiffness, mode_damping : (n_mode, n_mode) the modes' structural stiffness [N m] and damping
        [N m s] (generalised forces -K xi, -C xi_dot)
    Mass
        mass : (n_body,) [kg]; inertia : (n_body, 3, 3) [kg m^2]
        rigid_mass : (n_cart, n_cart) diag(m I3, J, M_modes) per body (the modes' generalised mass [kg m^2])
        total_mass : (n_cart, n_cart) rigid mass plus infinite-frequency added mass
        active : Cartesian rows that can move (found by probing the kinematics; all others stay zero in B)
        active_mass : total_mass on the active rows and columns
    Hydrostatics
        hydro_index : (n_h,) Cartesian row of each hydro DOF
        hydrostatic_stiffness : (n_h, n_h) about the centres of mass, the moorings' springs included [N/m, N m/rad, ...]
        static_force : (n_cart,) gravity plus equilibrium buoyancy, world axes [N]
    PTOs (n_pto)
        pto_kind : a :class:`PtoKind`; pto_coordinate, pto_velocity : joint coordinate / velocity index (joint PTOs)
        pto_body_a, pto_body_b : body index or -1 for the ground (actuators)
        pto_point_a, pto_point_b : (n_pto, 3) end point relative to the body's centre of mass in body axes, or the
        world point for the ground [m]
        pto_rest : stroke where the device spring is slack [m or rad]
        pto_spring : device spring stiffness, always present [N/m or N m/rad]
        pto_damping, pto_stiffness : gains of a linear controller applied inside the equations of motion
        pto_force_limit : largest |controller force|, inf for none [N or N m]
        pto_stroke_limit : largest |stroke from rest|, inf for none [m or rad]
        pto_stop_stiffness, pto_stop_damping : the end stop beyond the stroke limit (0: none, the run stops)
    Joints
        joint_damping : (nv,) the joints' own viscous damping per generalised velocity, a device loss (generalised
        force -joint_damping * v) [N m s/rad or N s/m]
    Moorings
        mooring_damping : (n_h, n_h) the moorings' dampers on the hydro DOFs' velocities (world axes, about the
        centres of mass) [N s/m, N m s/rad], or (0, 0) for a device without them (the time loop then skips them;
        :func:`mooring_damping_matrix` gives the full matrix either way); their springs are in
        ``hydrostatic_stiffness``
    Hydrodynamic terms beyond the linear database
        viscous : ``wecss.compiled._viscous.ViscousArrays`` (body drag, linear damping, Morison elements, and the
        incident wave they see; empty arrays when the scene asks for none); pressure:
        ``wecss.compiled._body_exact.PressureArrays`` (the body-exact hydrostatic and Froude-Krylov forces on the
        bodies' meshes; none when the scene asks for none)
    Flexible bodies
        n_elastic : their number (0 for a device of rigid bodies and generalised modes alone: the kernels then take
        the rigid path, which never reads the two arrays); elastic_index (int64) and elastic_data (float64): their
        :class:`ElasticArrays` packed into two 1-D arrays (:func:`pack_elastic`; two arrays rather than 23, since
        every opaque call of the time loop that takes the Plant counts each array it holds up and down; the
        elastic kernels take views of them, :func:`elastic_views`, and so does :attr:`Plant.elastic`). Their mass
        block M(xi) about the instantaneous centre of mass replaces the rigid one on their rotation and mode rows
        (so M* is rebuilt per configuration from ``active_mass`` plus M(xi) - M(0)), their centre of mass moves
        with the modes, and the children on their elastic attachments move with the modes' columns
    """

    order: np.ndarray
    parent: np.ndarray
    free: np.ndarray
    col_start: np.ndarray
    n_cols: np.ndarray
    q_start: np.ndarray
    com0: np.ndarray
    twists: np.ndarray
    chain: np.ndarray
    cart_start: np.ndarray
    cart_size: np.ndarray
    cart_body: np.ndarray
    cart_axis: np.ndarray
    cart_column: np.ndarray
    cart_coordinate: np.ndarray
    mode_row: np.ndarray
    mode_stiffness: np.ndarray
    mode_damping: np.ndarray
    mass: np.ndarray
    inertia: np.ndarray
    rigid_mass: np.ndarray
    total_mass: np.ndarray
    active: np.ndarray
    active_mass: np.ndarray
    hydro_index: np.ndarray
    hydrostatic_stiffness: np.ndarray
    static_force: np.ndarray
    pto_kind: np.ndarray
    pto_coordinate: np.ndarray
    pto_velocity: np.ndarray
    pto_body_a: np.ndarray
    pto_body_b: np.ndarray
    pto_point_a: np.ndarray
    pto_point_b: np.ndarray
    pto_rest: np.ndarray
    pto_spring: np.ndarray
    pto_damping: np.ndarray
    pto_stiffness: np.ndarray
    pto_force_limit: np.ndarray
    pto_stroke_limit: np.ndarray
    pto_stop_stiffness: np.ndarray
    pto_stop_damping: np.ndarray
    joint_damping: np.ndarray
    mooring_damping: np.ndarray
    viscous: ViscousArrays
    pressure: PressureArrays
    n_elastic: int
    elastic_index: np.ndarray
    elastic_data: np.ndarray

    @property
    def elastic(self) -> ElasticArrays:
        """The flexible bodies' arrays by name (views of ``elastic_index`` and ``elastic_data``; Python only, the
        kernels call :func:`elastic_views`)."""
        return _views(self.elastic_index, self.elastic_data)


class ElasticArrays(NamedTuple):
    """The flexible bodies of a plant (``Body.elastic``, floating frame: ``wecss.multibody._elastic``) as padded
    arrays; all empty (first dimension 0) for a plant without them, whose kernels then never read them. ``n_el``
    flexible bodies with at most ``nm`` modal coordinates each, ``n_att`` elastic attachments (carrying a child or an
    actuator's end).

    Flexible bodies
        of_body : (n_body,) index of a body's elastic model, -1 for a rigid body; body : (n_el,) its body
        size : (n_el,) number of modal coordinates; column, coordinate : (n_el,) the first one's generalised
        velocity and coordinate (the others follow); row : (n_el,) the body's first Cartesian row
        mass : (n_el,) [kg]; first_moment : (n_el, 3) s0 about the undeformed centre of mass [kg m]
        coupling : (n_el, 3, nm) Ct [kg m]; rotational : (n_el, 3, nm) Cr [kg m^2]
        second_moment : (n_el, 3, 3) P0; inertia_first : (n_el, nm, 3, 3) P1_k + P1_k' (symmetric);
        inertia_second : (n_el, nm, 3, 3, nm) P2_kl + P2_lk, l last; gyroscopic : (n_el, nm, nm, 3) G; modal_mass :
        (n_el, nm, nm) [kg m^2] (``wecss.structure.Invariants``; the kernels need P1 and P2 only in these sums)
        geometric : (n_el, nm, nm, nm) the geometric stiffening's force tensor [N m]: -dU3/dxi_j =
        -sum_kl H_jkl xi_k xi_l with H_jkl = sym_kl(G_kjl + G_jkl / 2) from the tensor G of U3 = 1/2 sum G_mkl
        xi_m xi_k xi_l (zero without one)
        undeformed : (n_el, 3 + nm, 3 + nm) M(0), the block of ``rigid_mass`` on the rotation and mode rows
        active : (n_el, 3 + nm) position of each of those rows among the plant's ``active`` rows, -1 if inactive
    Elastic attachments (a child joint on its flexible parent's attachment of the same name)
        of_child : (n_body,) the attachment a body's joint rides on, -1 for none; child, parent : (n_att,) the bodies
        twists : (n_att, nm, 6) the attachment's twists psi_k (world axes at the reference configuration)
        on_path : (n_body, n_att) 1 where the attachment is on a body's path to the ground (the body or an ancestor
        is its child): the parent's mode columns then move the body
    Actuator PTOs' ends on flexible bodies (an end rides on its body's attachment ``pto:<name>``, appended to the
    attachments above with child -1, on no body's path)
        pto_end : (n_pto, 2) the attachment of each end (a, b), -1 for an end on a rigid body or the ground

    The plant holds them packed (:func:`pack_elastic`): ``Plant.elastic_index`` (int64) is a header
    (n_body, n_el, nm, n_att, m, n_cart, n_pto; m the plant's active rows, n_cart its Cartesian rows) and then the
    integer arrays flattened in the order of ``ELASTIC_INDEX_FIELDS`` (of_body and of_child first, so that the
    kernels read a body's entries without views: :func:`elastic_of_body`, :func:`elastic_of_child`);
    ``Plant.elastic_data`` (float64) the float arrays in the order of ``ELASTIC_DATA_FIELDS``. :func:`elastic_views`
    gives them back as views, by name.
    """

    of_body: np.ndarray
    body: np.ndarray
    size: np.ndarray
    column: np.ndarray
    coordinate: np.ndarray
    row: np.ndarray
    mass: np.ndarray
    first_moment: np.ndarray
    coupling: np.ndarray
    rotational: np.ndarray
    second_moment: np.ndarray
    inertia_first: np.ndarray
    inertia_second: np.ndarray
    gyroscopic: np.ndarray
    modal_mass: np.ndarray
    geometric: np.ndarray
    undeformed: np.ndarray
    active: np.ndarray
    of_child: np.ndarray
    child: np.ndarray
    parent: np.ndarray
    twists: np.ndarray
    on_path: np.ndarray
    pto_end: np.ndarray


ELASTIC_HEADER = 7
"""Entries of ``Plant.elastic_index`` before its arrays: n_body, n_el, nm, n_att, m, n_cart, n_pto."""
ELASTIC_INDEX_FIELDS = (
    "of_body",
    "of_child",
    "body",
    "size",
    "column",
    "coordinate",
    "row",
    "active",
    "child",
    "parent",
    "pto_end",
)
"""The integer arrays of :class:`ElasticArrays` in their order in ``Plant.elastic_index`` (after the header)."""
ELASTIC_DATA_FIELDS = (
    "mass", "first_moment", "coupling", "rotational", "second_moment", "inertia_first", "inertia_second",
    "gyroscopic", "modal_mass", "geometric", "undeformed", "twists", "on_path",
)  # fmt: skip
"""The float arrays of :class:`ElasticArrays` in their order in ``Plant.elastic_data``."""


def pack_elastic(el: ElasticArrays, m: int, n_cart: int) -> tuple[int, np.ndarray, np.ndarray]:
    """``el`` packed for the plant: the number of flexible bodies, ``elastic_index`` (int64: the header, then the
    integer arrays) and ``elastic_data`` (float64) (``m``: the plant's active rows, ``n_cart``: its Cartesian
    rows; layout in :class:`ElasticArrays`)."""
    n_el, nm = el.modal_mass.shape[0], el.modal_mass.shape[1]
    sizes = [el.of_body.shape[0], n_el, nm, el.child.shape[0], m, n_cart, el.pto_end.shape[0]]
    header = np.array(sizes, dtype=np.int64)
    index = np.concatenate(
        [header, *(np.asarray(getattr(el, f), dtype=np.int64).ravel() for f in ELASTIC_INDEX_FIELDS)]
    )
    data = np.concatenate(
        [np.zeros(0), *(np.asarray(getattr(el, f), dtype=float).ravel() for f in ELASTIC_DATA_FIELDS)]
    )
    return n_el, np.ascontiguousarray(index), np.ascontiguousarray(data)


def _views(index: np.ndarray, data: np.ndarray) -> ElasticArrays:
    """:func:`elastic_views` (plain; the kernels call it compiled and inlined)."""
    n, n_el, nm, n_att = index[0], index[1], index[2], index[3]
    k = 3 + nm
    o = ELASTIC_HEADER
    of_body = index[o : o + n]
    o += n
    of_child = index[o : o + n]
    o += n
    body = index[o : o + n_el]
    o += n_el
    size = index[o : o + n_el]
    o += n_el
    column = index[o : o + n_el]
    o += n_el
    coordinate = index[o : o + n_el]
    o += n_el
    row = index[o : o + n_el]
    o += n_el
    active = reshaped(index[o : o + n_el * k], (n_el, k))
    o += n_el * k
    child = index[o : o + n_att]
    o += n_att
    parent = index[o : o + n_att]
    o += n_att
    pto_end = reshaped(index[o : o + 2 * index[6]], (index[6], 2))
    f = 0
    mass = data[f : f + n_el]
    f += n_el
    first_moment = reshaped(data[f : f + n_el * 3], (n_el, 3))
    f += n_el * 3
    coupling = reshaped(data[f : f + n_el * 3 * nm], (n_el, 3, nm))
    f += n_el * 3 * nm
    rotational = reshaped(data[f : f + n_el * 3 * nm], (n_el, 3, nm))
    f += n_el * 3 * nm
    second_moment = reshaped(data[f : f + n_el * 9], (n_el, 3, 3))
    f += n_el * 9
    inertia_first = reshaped(data[f : f + n_el * nm * 9], (n_el, nm, 3, 3))
    f += n_el * nm * 9
    inertia_second = reshaped(data[f : f + n_el * nm * nm * 9], (n_el, nm, 3, 3, nm))
    f += n_el * nm * nm * 9
    gyroscopic = reshaped(data[f : f + n_el * nm * nm * 3], (n_el, nm, nm, 3))
    f += n_el * nm * nm * 3
    modal_mass = reshaped(data[f : f + n_el * nm * nm], (n_el, nm, nm))
    f += n_el * nm * nm
    geometric = reshaped(data[f : f + n_el * nm * nm * nm], (n_el, nm, nm, nm))
    f += n_el * nm * nm * nm
    undeformed = reshaped(data[f : f + n_el * k * k], (n_el, k, k))
    f += n_el * k * k
    twists = reshaped(data[f : f + n_att * nm * 6], (n_att, nm, 6))
    f += n_att * nm * 6
    on_path = reshaped(data[f : f + n * n_att], (n, n_att))
    return ElasticArrays(
        of_body, body, size, column, coordinate, row, mass, first_moment, coupling, rotational, second_moment,
        inertia_first, inertia_second, gyroscopic, modal_mass, geometric, undeformed, active, of_child, child, parent,
        twists, on_path, pto_end,
    )  # fmt: skip


elastic_views = inline_kernel(_views)
"""The :class:`ElasticArrays` of a plant's ``elastic_index`` and ``elastic_data`` (views of them, numba-compiled
and inlined into the elastic kernels; ``Plant.elastic`` in Python)."""


@inline_kernel
def elastic_of_body(index: np.ndarray, i: int) -> int:
    """``of_body[i]`` of a plant's ``elastic_index`` (no view: a kernel without flexible bodies' views pays no
    reference counts for it)."""
    return index[ELASTIC_HEADER + i]


@inline_kernel
def elastic_of_child(index: np.ndarray, i: int) -> int:
    """``of_child[i]`` of a plant's ``elastic_index`` (see :func:`elastic_of_body`)."""
    return index[ELASTIC_HEADER + index[0] + i]


def elastic_arrays(model: Multibody, active: np.ndarray, ptos: Sequence[PTO] = ()) -> ElasticArrays:
    """The :class:`ElasticArrays` of ``model`` (``active``: the plant's active Cartesian rows; ``ptos``: the
    plant's, whose actuators' ends on a flexible body ride on its attachment ``pto:<name>``)."""
    n = len(model.bodies)
    bodies = list(model.elastic_bodies)
    n_el = len(bodies)
    nm = max([model.bodies[i].modes.n for i in bodies], default=0)
    of_body = np.full(n, -1, dtype=np.int64)
    size = np.zeros(n_el, dtype=np.int64)
    column = np.zeros(n_el, dtype=np.int64)
    coordinate = np.zeros(n_el, dtype=np.int64)
    row = np.zeros(n_el, dtype=np.int64)
    mass = np.zeros(n_el)
    first_moment = np.zeros((n_el, 3))
    coupling = np.zeros((n_el, 3, nm))
    rotational = np.zeros((n_el, 3, nm))
    second_moment = np.zeros((n_el, 3, 3))
    inertia_first = np.zeros((n_el, nm, 3, 3))
    inertia_second = np.zeros((n_el, nm, 3, 3, nm))
    gyroscopic = np.zeros((n_el, nm, nm, 3))
    modal_mass = np.zeros((n_el, nm, nm))
    geometric = np.zeros((n_el, nm, nm, nm))
    undeformed = np.zeros((n_el, 3 + nm, 3 + nm))
    position = np.full(model.n_cart, -1, dtype=np.int64)
    position[active] = np.arange(active.size)
    active_rows = np.full((n_el, 3 + nm), -1, dtype=np.int64)
    for e, i in enumerate(bodies):
        el = model.bodies[i].elastic
        assert el is not None
        inv, k = el.invariants, el.n
        of_body[i] = e
        size[e], column[e], coordinate[e] = k, model.mode_velocity_start[i], model.mode_coordinate_start[i]
        row[e] = model.cart_start[i]
        mass[e], first_moment[e] = inv.mass, inv.first_moment
        coupling[e, :, :k], rotational[e, :, :k] = inv.translational_coupling, inv.rotational_coupling
        second_moment[e] = inv.second_moment
        inertia_first[e, :k] = inv.inertia_first + inv.inertia_first.transpose(0, 2, 1)
        p2 = inv.inertia_second + inv.inertia_second.transpose(1, 0, 2, 3)  # P2_kl + P2_lk
        inertia_second[e, :k, :, :, :k] = p2.transpose(0, 2, 3, 1)
        gyroscopic[e, :k, :k] = inv.gyroscopic
        modal_mass[e, :k, :k] = inv.modal_mass
        if el.geometric is not None:
            g = np.asarray(el.geometric)
            h = g.transpose(1, 0, 2) + 0.5 * g
            geometric[e, :k, :k, :k] = 0.5 * (h + h.transpose(0, 2, 1))
        undeformed[e, : 3 + k, : 3 + k] = el.relative_mass(np.zeros(k))[0]
        active_rows[e, : 3 + k] = position[model.cart_start[i] + 3 : model.cart_start[i] + 6 + k]
    attached = [
        i
        for i in model.order
        if model.parent[i] >= 0
        and (el := model.bodies[model.parent[i]].elastic) is not None
        and model.joints[model.joint_of[i]].name in el.attachments
    ]
    n_att = len(attached)
    of_child = np.full(n, -1, dtype=np.int64)
    twists = np.zeros((n_att, nm, 6))
    on_path = np.zeros((n, n_att))
    for a, i in enumerate(attached):
        par = model.parent[i]
        el = model.bodies[par].elastic
        assert el is not None
        of_child[i] = a
        twists[a, : el.n] = el.attachment(model.joints[model.joint_of[i]].name).twists
    for i in model.order:  # parents first: a body inherits its parent's path
        if model.parent[i] >= 0:
            on_path[i] = on_path[model.parent[i]]
        if of_child[i] >= 0:
            on_path[i, of_child[i]] = 1.0
    # actuators' ends on flexible bodies: attachments of their own (no child, on no path)
    pto_end = np.full((len(ptos), 2), -1, dtype=np.int64)
    children, parents, extra = list(attached), [model.parent[i] for i in attached], []
    for k, pto in enumerate(ptos):
        if not isinstance(pto, ActuatorPTO):
            continue
        for end, name in enumerate((pto.body_a, pto.body_b)):
            if name is None or (el := model.body(name).elastic) is None:
                continue
            pto_end[k, end] = len(children)
            children.append(-1)
            parents.append(model.body_names.index(name))
            shapes = np.zeros((nm, 6))
            shapes[: el.n] = el.attachment(f"pto:{pto.name}").twists
            extra.append(shapes)
    if extra:
        twists = np.concatenate([twists, np.array(extra)])
        on_path = np.concatenate([on_path, np.zeros((n, len(extra)))], axis=1)
    return ElasticArrays(
        of_body=of_body,
        body=np.asarray(bodies, dtype=np.int64),
        size=size,
        column=column,
        coordinate=coordinate,
        row=row,
        mass=mass,
        first_moment=first_moment,
        coupling=coupling,
        rotational=rotational,
        second_moment=second_moment,
        inertia_first=inertia_first,
        inertia_second=inertia_second,
        gyroscopic=gyroscopic,
        modal_mass=modal_mass,
        geometric=geometric,
        undeformed=undeformed,
        active=active_rows,
        of_child=of_child,
        child=np.asarray(children, dtype=np.int64),
        parent=np.asarray(parents, dtype=np.int64),
        twists=twists,
        on_path=on_path,
        pto_end=pto_end,
    )


def _tree_arrays(model: Multibody) -> dict[str, np.ndarray]:
    n = len(model.bodies)
    col_start = np.zeros(n, dtype=np.int64)
    n_cols = np.zeros(n, dtype=np.int64)
    q_start = np.zeros(n, dtype=np.int64)
    free = np.zeros(n, dtype=np.int64)
    twists = np.zeros((model.nv, 6))
    iq = iv = 0
    for i in model.order:
        joint = model.joints[model.joint_of[i]]
        col_start[i], n_cols[i], q_start[i] = iv, joint.nv, iq
        if joint.kind == "free":
            free[i] = 1
        elif joint.kind == "planar":
            c0 = model.bodies[i].center_of_mass
            twists[iv] = [1.0, 0, 0, 0, 0, 0]
            twists[iv + 1] = [0, 0, 1.0, 0, 0, 0]
            twists[iv + 2] = [*np.cross(c0, [0.0, 1.0, 0.0]), 0.0, 1.0, 0.0]
        elif joint.nv:
            twists[iv : iv + joint.nv] = joint.twists
        iq += joint.nq
        iv += joint.nv
    chain = np.zeros((n, model.nv))
    for i in model.order:
        if model.parent[i] >= 0:
            chain[i] = chain[model.parent[i]]
        chain[i, col_start[i] : col_start[i] + n_cols[i]] = 1.0
    return {
        "order": np.asarray(model.order, dtype=np.int64),
        "parent": np.asarray(model.parent, dtype=np.int64),
        "free": free,
        "col_start": col_start,
        "n_cols": n_cols,
        "q_start": q_start,
        "com0": np.array([b.center_of_mass for b in model.bodies]),
        "twists": twists,
        "chain": chain,
    }


def _cartesian_arrays(model: Multibody) -> dict[str, np.ndarray]:
    """The Cartesian rows of ``model``: where each body's are, which body and axis each is, and the modes'."""
    n_cart = model.n_cart
    column = np.full(n_cart, -1, dtype=np.int64)
    coordinate = np.full(n_cart, -1, dtype=np.int64)
    rows = model.mode_rows
    column[rows] = model.mode_velocities
    coordinate[rows] = model.mode_coordinates
    return {
        "cart_start": np.asarray(model.cart_start, dtype=np.int64),
        "cart_size": np.asarray(model.cart_size, dtype=np.int64),
        "cart_body": np.asarray(model.cart_body, dtype=np.int64),
        "cart_axis": np.asarray(model.cart_axis, dtype=np.int64),
        "cart_column": column,
        "cart_coordinate": coordinate,
        "mode_row": np.ascontiguousarray(rows, dtype=np.int64),
        "mode_stiffness": np.ascontiguousarray(model.mode_stiffness),
        "mode_damping": np.ascontiguousarray(model.mode_damping),
    }


def _pto_arrays(model: Multibody, ptos: tuple[PTO, ...]) -> dict[str, np.ndarray]:
    n = len(ptos)
    out = {
        "pto_kind": np.full(n, PtoKind.JOINT, dtype=np.int64),
        "pto_coordinate": np.full(n, -1, dtype=np.int64),
        "pto_velocity": np.full(n, -1, dtype=np.int64),
        "pto_body_a": np.full(n, -1, dtype=np.int64),
        "pto_body_b": np.full(n, -1, dtype=np.int64),
        "pto_point_a": np.zeros((n, 3)),
        "pto_point_b": np.zeros((n, 3)),
        "pto_rest": np.zeros(n),
        "pto_spring": np.zeros(n),
        "pto_force_limit": np.array([np.inf if p.force_limit is None else p.force_limit for p in ptos], dtype=float),
        "pto_stroke_limit": np.array([np.inf if p.stroke_limit is None else p.stroke_limit for p in ptos], dtype=float),
        "pto_stop_stiffness": np.array([p.end_stop_stiffness for p in ptos], dtype=float),
        "pto_stop_damping": np.array([p.end_stop_damping for p in ptos], dtype=float),
    }
    names = model.body_names
    for k, pto in enumerate(ptos):
        out["pto_spring"][k] = pto.stiffness
        out["pto_rest"][k] = pto.rest
        if isinstance(pto, JointPTO):
            joint = model.joint(pto.joint)
            if joint.kind not in ("revolute", "prismatic"):
                raise ValueError(
                    f"PTO {pto.name!r}: joint {pto.joint!r} is {joint.kind}; it needs a revolute or prismatic joint"
                )
            label = f"{joint.name}__{joint.labels[0]}"
            out["pto_coordinate"][k] = model.coordinate_names.index(label)
            out["pto_velocity"][k] = model.velocity_names.index(label)
        elif isinstance(pto, ActuatorPTO):
            out["pto_kind"][k] = PtoKind.ACTUATOR
            for end, body, point in (("a", pto.body_a, pto.point_a), ("b", pto.body_b, pto.point_b)):
                if body is None:
                    out[f"pto_point_{end}"][k] = point
                else:
                    i = names.index(body)
                    out[f"pto_body_{end}"][k] = i
                    out[f"pto_point_{end}"][k] = point - model.bodies[i].center_of_mass
    return out


def moving_rows(model: Multibody, probes: int = 4) -> np.ndarray:
    """Cartesian rows of B and Bdot that are non-zero at some configuration: evaluated at random configurations and
    velocities, where a row that can move does so generically (a generalised mode's row always moves)."""
    rng = np.random.default_rng(0)
    moving = np.zeros(model.n_cart, dtype=bool)
    for _ in range(probes):
        q = integrate(model, model.neutral_configuration(), rng.uniform(-1.0, 1.0, model.nv))
        st = kinematics(model, q, rng.standard_normal(model.nv))
        assert st.Bdot is not None
        moving |= (np.abs(st.B) > 1e-12).any(axis=1) | (np.abs(st.Bdot) > 1e-12).any(axis=1)
    return np.flatnonzero(moving).astype(np.int64)


def build_plant(
    model: Multibody,
    coupling: HydroCoupling | None,
    ptos: tuple[PTO, ...],
    g: float,
    *,
    damping: np.ndarray | None = None,
    stiffness: np.ndarray | None = None,
    added_mass_correction: np.ndarray | None = None,
    viscous: ViscousArrays | None = None,
    pressure: PressureArrays | None = None,
    extra_mass: np.ndarray | None = None,
) -> Plant:
    """Flat arrays of ``model`` with its hydrostatics (None: none), gravity ``g`` [m/s^2] and PTOs.

    ``damping`` and ``stiffness`` (one per PTO) are the gains of a linear controller applied inside the
    equations of motion (default zero: the controller's force is held over each step instead).
    ``added_mass_correction`` (n_h, n_h) is added to A_inf (see ``_radiation.added_mass_correction``).
    ``viscous``: the scene's viscous terms (default none), ``extra_mass`` (n_cart, n_cart) a further added mass
    (the Morison elements', ``wecss.compiled._terms.viscous_arrays``); ``pressure`` the body-exact pressure forces
    (default none, ``wecss.compiled._terms.pressure_arrays``).
    """
    n = len(model.bodies)
    inertia = np.array([b.inertia for b in model.bodies])
    mass = np.array([b.mass for b in model.bodies])
    rigid = body_mass_matrix(model)
    static = coupling.buoyancy.copy() if coupling is not None else np.zeros(model.n_cart)
    for i in range(n):
        static[model.cart_start[i] + 2] -= mass[i] * g
    index = np.asarray(coupling.index if coupling is not None else [], dtype=np.int64)
    added = coupling.added_mass_inf if coupling is not None else 0.0
    if added_mass_correction is not None and coupling is not None:
        added = added + coupling.expand(added_mass_correction)
    stiffness_h = coupling.restoring[np.ix_(index, index)] if coupling is not None else np.zeros((0, 0))
    mooring_h = coupling.mooring_damping[np.ix_(index, index)] if coupling is not None else np.zeros((0, 0))
    if not np.any(mooring_h):  # no dampers: an empty matrix, which the time loop skips
        mooring_h = np.zeros((0, 0))
    n_pto = len(ptos)
    total = rigid + added
    if extra_mass is not None:
        total = total + extra_mass
    active = moving_rows(model)
    elastic = elastic_arrays(model, active, ptos)
    n_elastic, elastic_index, elastic_data = pack_elastic(elastic, active.size, model.n_cart)
    return Plant(
        **_tree_arrays(model),
        **_cartesian_arrays(model),
        mass=mass,
        inertia=inertia,
        rigid_mass=rigid,
        total_mass=total,
        active=active,
        active_mass=np.ascontiguousarray(total[np.ix_(active, active)]),
        hydro_index=index,
        hydrostatic_stiffness=np.ascontiguousarray(stiffness_h),
        static_force=static,
        **_pto_arrays(model, ptos),
        pto_damping=np.zeros(n_pto) if damping is None else np.asarray(damping, dtype=float),
        pto_stiffness=np.zeros(n_pto) if stiffness is None else np.asarray(stiffness, dtype=float),
        joint_damping=model.joint_damping,
        mooring_damping=np.ascontiguousarray(mooring_h),
        viscous=no_viscous() if viscous is None else viscous,
        pressure=no_pressure() if pressure is None else pressure,
        n_elastic=n_elastic,
        elastic_index=elastic_index,
        elastic_data=elastic_data,
    )


def mooring_damping_matrix(p: Plant) -> np.ndarray:
    """The moorings' dampers on the hydro DOFs (n_h, n_h) [N s/m, N m s/rad]: ``p.mooring_damping``, or zeros for
    a plant without them (stored empty)."""
    n_h = p.hydro_index.shape[0]
    if p.mooring_damping.shape != (n_h, n_h):
        return np.zeros((n_h, n_h))
    return p.mooring_damping


def linear_damping(p: Plant, gmat: np.ndarray, bw: np.ndarray) -> np.ndarray:
    """Generalised damping (nv, nv) of the linear PTO gains, the joints' own losses, the moorings' dampers and the
    modes' structural damping at a configuration with PTO transmissions ``gmat`` (n_pto, nv) and hydro rows of the
    world Jacobian ``bw`` (n_h, nv): G' diag(pto_damping) G + diag(joint_damping) + Bw' D_mooring Bw + C_modes
    [N s/m, N m s/rad, N m s]."""
    out = gmat.T @ np.diag(p.pto_damping) @ gmat + np.diag(p.joint_damping) + bw.T @ mooring_damping_matrix(p) @ bw
    if p.mode_row.size:
        columns = p.cart_column[p.mode_row]
        out[np.ix_(columns, columns)] += p.mode_damping
    return out
