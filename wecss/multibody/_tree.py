"""Bodies, joints and the tree they form.

Everything is described in the world frame at the reference configuration (all coordinates zero): body
frames sit at the centres of mass with axes parallel to the world axes, joint axes and points are world
vectors. This is the product-of-exponentials description of a kinematic tree (each joint a constant
twist), from which the MFM's B-matrix follows (see ``_kinematics``).

Cartesian rows. A body has its six rigid rows (CoM velocity x, y, z in world axes, then the body angular
velocity) followed by one row per generalised mode (``_modes``); the model's Cartesian vectors (velocities X,
loads F, the mass matrix) hold the bodies' rows one body after the other. ``Multibody.cart_start`` and
``cart_size`` say where each body's rows are and ``cart_body``, ``cart_axis`` which body and axis each row is
(0-5 rigid, 6.. the body's modes): code outside the model goes through them, never through 6 rows per body.
Generalised coordinates: the joints' (in topological order), then the modes of every body (in the bodies' order).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any, Literal

import numpy as np

from ._elastic import ElasticBody, check_elastic_body
from ._modes import NO_MODES, GeneralisedModes
from ._vectors import vector3

JointKind = Literal["fixed", "planar", "free", "revolute", "prismatic", "weld"]
BASE_KINDS: tuple[str, ...] = ("fixed", "planar", "free")
CHILD_KINDS: tuple[str, ...] = ("revolute", "prismatic", "weld")

_AXIS_LABELS = {"revolute": ("roll", "pitch", "yaw"), "prismatic": ("surge", "sway", "heave")}


@dataclass(frozen=True, eq=False)
class Body:
    """A rigid body.

    Parameters
    ----------
    name : str
        Unique name.
    mass : float
        Mass [kg], positive.
    inertia : array_like of shape (3, 3)
        Rotational inertia about the centre of mass, in body axes (parallel to the world axes at the reference
        configuration) [kg m^2]; symmetric positive semi-definite.
    center_of_mass : array_like of shape (3,)
        Position of the centre of mass at the reference configuration, in the world frame [m]. The body frame sits here.
    hydro_body : str or None
        Name of the body in the hydrodynamic database that acts on this body (None: no hydrodynamics).
    modes : GeneralisedModes, or its device-spec form (see ``GeneralisedModes.from_spec``), optional
        The body's generalised modes beyond its six rigid-body DOFs (default none: a rigid body), with no inertial
        coupling to the rigid motion (see ``wecss.multibody._modes``).
    elastic : ElasticBody, optional
        A flexible body's floating-frame model (``wecss.multibody._elastic``): its modal coordinates are the
        body's modes, inertially coupled to its rigid motion through the invariants, and its attachments carry
        child bodies. Its invariants must hold the body's mass, centre of mass and inertia. Not with ``modes``.

    Raises
    ------
    ValueError
        On a non-positive mass, a non-symmetric or indefinite inertia, principal moments that break the triangle
        inequality (one larger than the sum of the other two), a malformed vector, bad modes, or an elastic model
        that disagrees with the body or comes with ``modes``.
    """

    name: str
    mass: float
    inertia: np.ndarray
    center_of_mass: np.ndarray
    hydro_body: str | None = None
    modes: GeneralisedModes = NO_MODES
    elastic: ElasticBody | None = None

    def __post_init__(self) -> None:
        if not self.name or "__" in self.name:
            raise ValueError(f"body name {self.name!r} must be non-empty and must not contain '__'")
        if not (np.isfinite(self.mass) and self.mass > 0):
            raise ValueError(f"body {self.name!r}: mass must be positive [kg]; got {self.mass!r}")
        inertia = np.asarray(self.inertia, dtype=float)
        if inertia.shape == (3,):
            inertia = np.diag(inertia)
        if inertia.shape != (3, 3) or not np.allclose(
            inertia, inertia.T, rtol=0, atol=1e-12 * max(1, abs(inertia).max())
        ):
            raise ValueError(
                f"body {self.name!r}: inertia must be a symmetric 3x3 matrix [kg m^2]; got {self.inertia!r}"
            )
        principal = np.linalg.eigvalsh(inertia)  # ascending
        if principal[0] < -1e-12 * max(1.0, float(np.abs(inertia).max())):
            raise ValueError(f"body {self.name!r}: inertia must be positive semi-definite; got {inertia.tolist()}")
        if principal[0] + principal[1] < principal[2] * (1 - TRIANGLE_TOL):
            raise ValueError(
                f"body {self.name!r}: the principal moments of inertia {np.round(principal, 6).tolist()} kg m^2 break "
                f"the triangle inequality ({principal[0]:.6g} + {principal[1]:.6g} < {principal[2]:.6g}): no mass "
                "distribution has them; accepted: each principal moment at most the sum of the other two"
            )
        object.__setattr__(self, "mass", float(self.mass))
        object.__setattr__(self, "inertia", inertia)
        object.__setattr__(self, "center_of_mass", vector3(self.center_of_mass, f"body {self.name!r} center_of_mass"))
        modes: Any = self.modes
        if self.elastic is not None:
            if modes is not NO_MODES:
                raise ValueError(
                    f"body {self.name!r}: give its modes or its elastic model, not both (an elastic body's modes are "
                    "its modal coordinates)"
                )
            if self.hydro_body is not None:
                raise ValueError(
                    f"body {self.name!r}: a flexible body in a floating frame must be dry (it has the hydro body "
                    f"{self.hydro_body!r}; the wetted modes of a flexible body are not modelled): make the float a "
                    "rigid child"
                )
            check_elastic_body(self.name, self.mass, inertia, self.center_of_mass, self.elastic)
            modes = self.elastic.modes(self.name)
        elif not isinstance(modes, GeneralisedModes) or modes.body != self.name:
            modes = GeneralisedModes.from_spec(self.name, modes)
            if modes.n:
                modes = GeneralisedModes(modes.names, modes.mass, modes.stiffness, modes.damping, self.name)
        object.__setattr__(self, "modes", modes)


def _check_attachments(bodies: Sequence[Body], joints: Sequence[Joint]) -> None:
    """Every joint whose parent is a flexible body rides on one of its attachments, named as the joint, at the
    joint's point (a revolute joint).

    Raises
    ------
    ValueError
        Naming the joint, the body and the attachments it has, or the two points.
    """
    by_name = {b.name: b for b in bodies}
    for joint in joints:
        parent = by_name.get(joint.parent) if joint.parent is not None else None
        if parent is None or parent.elastic is None:
            continue
        attachments = parent.elastic.attachments
        if joint.name not in attachments:
            raise ValueError(
                f"joint {joint.name!r}: its parent {parent.name!r} is flexible, and the joint needs the body's "
                f"attachment {joint.name!r} (the node it rides on); attachments: {sorted(attachments)}"
            )
        point = attachments[joint.name].point
        if joint.point is not None and not np.allclose(
            point, joint.point, rtol=0, atol=1e-9 * max(1.0, abs(point).max())
        ):
            raise ValueError(
                f"joint {joint.name!r}: its point {np.round(joint.point, 9).tolist()} m is not where its attachment on "
                f"{parent.name!r} is, {np.round(point, 9).tolist()} m"
            )


TRIANGLE_TOL: float = 1e-9
"""Relative tolerance of the triangle inequality I_1 + I_2 >= I_3 of a body's principal moments of inertia (equality:
a flat body)."""


@dataclass(frozen=True, eq=False)
class Joint:
    """A joint between a parent (None: the ground) and a child body.

    Parameters
    ----------
    name : str
        Unique name; generalised coordinates are called ``<name>__<label>``.
    kind : {"fixed", "planar", "free", "revolute", "prismatic", "weld"}
        Base joints (parent None): ``fixed`` (no motion), ``planar`` (surge, heave, pitch of the child's
        centre of mass in the x-z plane), ``free`` (6 DOF; rotation on SO(3), coordinates x, y, z and a unit
        quaternion, velocities the world velocity of the centre of mass and the body angular velocity).
        Child joints: ``revolute`` (rotation about ``axis`` through ``point``), ``prismatic`` (translation along
        ``axis``), ``weld`` (rigid).
    child : str
        Child body name.
    parent : str or None
        Parent body name, or None for the base joint.
    axis : array_like of shape (3,), optional
        Joint axis in the world frame at the reference configuration (revolute, prismatic); normalised.
    point : array_like of shape (3,), optional
        A point on a revolute joint's axis, world frame at the reference configuration [m].
    label : str, optional
        Name of the coordinate of a one-DOF joint (default from the axis: roll/pitch/yaw for revolute joints,
        surge/sway/heave for prismatic joints, "angle"/"displacement" for oblique axes).
    damping : float, optional
        Linear viscous damping of a revolute or prismatic joint's coordinate [N m s/rad or N s/m] (default 0): a
        loss of the device itself, such as bearing friction, that acts whatever the controller does and is not
        PTO power.
    """

    name: str
    kind: JointKind
    child: str
    parent: str | None = None
    axis: np.ndarray | None = None
    point: np.ndarray | None = None
    label: str | None = None
    damping: float = 0.0

    def __post_init__(self) -> None:
        if not self.name or "__" in self.name:
            raise ValueError(f"joint name {self.name!r} must be non-empty and must not contain '__'")
        kinds = BASE_KINDS + CHILD_KINDS
        if self.kind not in kinds:
            raise ValueError(f"joint {self.name!r}: unknown kind {self.kind!r}; accepted: {', '.join(kinds)}")
        if self.parent is None and self.kind not in BASE_KINDS:
            raise ValueError(
                f"joint {self.name!r}: a joint to the ground must be one of {', '.join(BASE_KINDS)}; got {self.kind!r}"
            )
        if self.parent is not None and self.kind not in CHILD_KINDS:
            raise ValueError(
                f"joint {self.name!r}: a joint between bodies must be one of {', '.join(CHILD_KINDS)}; "
                f"got {self.kind!r}"
            )
        if self.kind in ("revolute", "prismatic"):
            if self.axis is None:
                raise ValueError(f"joint {self.name!r}: a {self.kind} joint needs an axis")
            axis = vector3(self.axis, f"joint {self.name!r} axis", "unit vector")
            norm = float(np.linalg.norm(axis))
            if norm == 0:
                raise ValueError(f"joint {self.name!r}: axis must not be zero")
            object.__setattr__(self, "axis", axis / norm)
        if not (isinstance(self.damping, int | float) and np.isfinite(self.damping) and self.damping >= 0):
            raise ValueError(
                f"joint {self.name!r}: damping must be a finite number >= 0 [N m s/rad or N s/m]; got {self.damping!r}"
            )
        if self.damping and self.kind not in ("revolute", "prismatic"):
            raise ValueError(
                f"joint {self.name!r}: only revolute and prismatic joints take a damping; it is {self.kind}"
            )
        object.__setattr__(self, "damping", float(self.damping))
        if self.kind == "revolute":
            if self.point is None:
                raise ValueError(f"joint {self.name!r}: a revolute joint needs a point on its axis [m]")
            object.__setattr__(self, "point", vector3(self.point, f"joint {self.name!r} point"))

    @cached_property
    def labels(self) -> tuple[str, ...]:
        """Names of this joint's generalised velocities (its DOFs), without the joint-name prefix (computed once: the
        joint is frozen, and the statics ask for it thousands of times)."""
        if self.kind in ("fixed", "weld"):
            return ()
        if self.kind == "planar":
            return ("surge", "heave", "pitch")
        if self.kind == "free":
            return ("surge", "sway", "heave", "roll", "pitch", "yaw")
        if self.label is not None:
            return (self.label,)
        assert self.axis is not None
        aligned = np.flatnonzero(np.isclose(np.abs(self.axis), 1.0))
        if aligned.size == 1:
            return (_AXIS_LABELS[self.kind][int(aligned[0])],)
        return ("angle",) if self.kind == "revolute" else ("displacement",)

    @property
    def nv(self) -> int:
        """Number of generalised velocities of this joint."""
        return len(self.labels)

    @property
    def nq(self) -> int:
        """Number of configuration coordinates (7 for a free joint: position and unit quaternion)."""
        return 7 if self.kind == "free" else self.nv

    @property
    def twists(self) -> np.ndarray:
        """Constant joint twists (v, w) in the world frame at the reference configuration, shape (nv, 6).

        For a free joint these are not used (its Jacobian depends on the pose, see ``_kinematics``).
        """
        if self.kind == "revolute":
            assert self.axis is not None and self.point is not None
            return np.concatenate([np.cross(self.point, self.axis), self.axis])[None, :]
        if self.kind == "prismatic":
            assert self.axis is not None
            return np.concatenate([self.axis, np.zeros(3)])[None, :]
        return np.zeros((self.nv, 6))


@dataclass(frozen=True, eq=False)
class Multibody:
    """A tree of rigid bodies joined by joints, in topological order (every parent before its children).

    Parameters
    ----------
    bodies : sequence of Body
    joints : sequence of Joint
        Exactly one joint per body, naming it as child; exactly one base joint (parent None).

    Attributes
    ----------
    order : tuple of int
        Body indices in topological order.
    parent : tuple of int
        Index of each body's parent (-1 for the base).
    coordinate_names, velocity_names : tuple of str
        ``<joint>__<label>``; a free base has 7 coordinates (``x, y, z, qw, qx, qy, qz``) and 6 velocities; then
        the generalised modes, ``<body>__<mode>``, one coordinate and one velocity each.
    cart_start, cart_size : tuple of int
        Per body, its first Cartesian row and its number of rows (6 plus its modes); ``n_cart`` rows in all.

    Raises
    ------
    ValueError
        On duplicate names (bodies, joints, generalised coordinates), unknown bodies, a body without a joint or
        with two, several base joints, or a cycle.
    """

    bodies: tuple[Body, ...]
    joints: tuple[Joint, ...]
    order: tuple[int, ...] = field(init=False)
    parent: tuple[int, ...] = field(init=False)
    joint_of: tuple[int, ...] = field(init=False)

    def __init__(self, bodies: Sequence[Body], joints: Sequence[Joint]) -> None:
        object.__setattr__(self, "bodies", tuple(bodies))
        object.__setattr__(self, "joints", tuple(joints))
        names = [b.name for b in self.bodies]
        if len(set(names)) != len(names):
            raise ValueError(f"duplicate body names in {names}")
        jnames = [j.name for j in self.joints]
        if len(set(jnames)) != len(jnames):
            raise ValueError(f"duplicate joint names in {jnames}")
        joint_of = [-1] * len(names)
        for k, joint in enumerate(self.joints):
            for role, body in (("child", joint.child), ("parent", joint.parent)):
                if body is not None and body not in names:
                    raise ValueError(f"joint {joint.name!r}: unknown {role} body {body!r}; bodies: {', '.join(names)}")
            c = names.index(joint.child)
            if joint_of[c] >= 0:
                raise ValueError(
                    f"body {joint.child!r} is the child of two joints: {jnames[joint_of[c]]!r}, {joint.name!r}"
                )
            joint_of[c] = k
        orphans = [names[i] for i, k in enumerate(joint_of) if k < 0]
        if orphans:
            raise ValueError(f"bodies {orphans} have no joint; every body needs exactly one joint to its parent")
        bases = [j.name for j in self.joints if j.parent is None]
        if len(bases) != 1:
            raise ValueError(f"need exactly one base joint (parent None); got {bases}")
        parent_names = [self.joints[joint_of[i]].parent for i in range(len(names))]
        parent = [-1 if p is None else names.index(p) for p in parent_names]
        order: list[int] = []
        placed: set[int] = set()
        while len(order) < len(names):
            ready = [i for i in range(len(names)) if i not in placed and (parent[i] < 0 or parent[i] in placed)]
            if not ready:
                stuck = [names[i] for i in range(len(names)) if i not in placed]
                raise ValueError(f"the joints form a cycle among bodies {stuck}")
            for i in ready:
                order.append(i)
                placed.add(i)
        object.__setattr__(self, "order", tuple(order))
        object.__setattr__(self, "parent", tuple(parent))
        object.__setattr__(self, "joint_of", tuple(joint_of))
        _check_attachments(self.bodies, self.joints)
        velocities = self.velocity_names
        repeated = sorted({v for v in velocities if velocities.count(v) > 1})
        if repeated:
            raise ValueError(
                f"generalised coordinates {repeated} are named twice (a joint's <joint>__<label> and a body's "
                "<body>__<mode>); rename the joint or the mode"
            )

    # --- Cartesian rows ----------------------------------------------------------------------------
    @cached_property
    def cart_size(self) -> tuple[int, ...]:
        """Number of Cartesian rows of each body (model order): 6 rigid plus one per generalised mode."""
        return tuple(6 + b.modes.n for b in self.bodies)

    @cached_property
    def cart_start(self) -> tuple[int, ...]:
        """First Cartesian row of each body (model order)."""
        return tuple(int(x) for x in np.concatenate([[0], np.cumsum(self.cart_size)[:-1]]))

    @property
    def n_cart(self) -> int:
        """Number of Cartesian rows of the model."""
        return sum(self.cart_size)

    @cached_property
    def cart_body(self) -> tuple[int, ...]:
        """Body index of each Cartesian row."""
        return tuple(i for i, size in enumerate(self.cart_size) for _ in range(size))

    @cached_property
    def cart_axis(self) -> tuple[int, ...]:
        """Axis of each Cartesian row within its body: 0-2 the CoM velocity (world x, y, z), 3-5 the body angular
        velocity (body axes), 6.. the body's generalised modes in their order."""
        return tuple(a for size in self.cart_size for a in range(size))

    @property
    def cartesian_labels(self) -> tuple[str, ...]:
        """``<body>__<Dof>`` of each Cartesian row (Surge ... Yaw, then the mode names), for messages."""
        rigid = ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")
        return tuple(f"{b.name}__{d}" for b in self.bodies for d in (*rigid, *b.modes.names))

    # --- generalised modes -------------------------------------------------------------------------
    @cached_property
    def elastic_bodies(self) -> tuple[int, ...]:
        """Indices of the bodies with an elastic model (``Body.elastic``)."""
        return tuple(i for i, b in enumerate(self.bodies) if b.elastic is not None)

    @property
    def n_modes(self) -> int:
        """Number of generalised modes of all bodies."""
        return sum(b.modes.n for b in self.bodies)

    @property
    def mode_names(self) -> tuple[str, ...]:
        """Generalised coordinates of the modes, ``<body>__<mode>``, in the bodies' order."""
        return tuple(f"{b.name}__{m}" for b in self.bodies for m in b.modes.names)

    @property
    def mode_rows(self) -> np.ndarray:
        """Cartesian row of each mode (n_modes,) (int)."""
        return np.array(
            [
                a + 6
                for i, b in enumerate(self.bodies)
                for a in range(self.cart_start[i], self.cart_start[i] + b.modes.n)
            ],
            dtype=np.int64,
        )

    @property
    def mode_velocities(self) -> np.ndarray:
        """Index in the generalised velocities of each mode (n_modes,): after the joints' velocities."""
        first = sum(j.nv for j in self.joints)
        return np.arange(first, first + self.n_modes, dtype=np.int64)

    @property
    def mode_coordinates(self) -> np.ndarray:
        """Index in the generalised coordinates of each mode (n_modes,): after the joints' coordinates."""
        first = sum(j.nq for j in self.joints)
        return np.arange(first, first + self.n_modes, dtype=np.int64)

    @cached_property
    def mode_velocity_start(self) -> tuple[int, ...]:
        """Index in the generalised velocities of each body's first mode, and one past the last body's (n_body + 1):
        body i's modes are ``mode_velocity_start[i]:mode_velocity_start[i + 1]``."""
        first = sum(j.nv for j in self.joints)
        return tuple(int(x) for x in first + np.concatenate([[0], np.cumsum([b.modes.n for b in self.bodies])]))

    @cached_property
    def quasi_static_velocities(self) -> np.ndarray:
        """(nv,) bool: the generalised velocities of the elastic bodies' modal coordinates held quasi-static
        (``ElasticBody.quasi_static``: their rates and accelerations neglected, their equations algebraic)."""
        out = np.zeros(self.nv, dtype=bool)
        for i in self.elastic_bodies:
            elastic = self.bodies[i].elastic
            assert elastic is not None
            out[self.mode_velocity_start[i] : self.mode_velocity_start[i + 1]] = elastic.quasi_static
        out.flags.writeable = False
        return out

    @cached_property
    def mode_coordinate_start(self) -> tuple[int, ...]:
        """As :attr:`mode_velocity_start`, in the generalised coordinates."""
        first = sum(j.nq for j in self.joints)
        return tuple(int(x) for x in first + np.concatenate([[0], np.cumsum([b.modes.n for b in self.bodies])]))

    def _mode_blocks(self, field: str) -> np.ndarray:
        out = np.zeros((self.n_modes, self.n_modes))
        k = 0
        for body in self.bodies:
            n = body.modes.n
            out[k : k + n, k : k + n] = getattr(body.modes, field)
            k += n
        return out

    @property
    def mode_mass(self) -> np.ndarray:
        """Generalised mass of the modes (n_modes, n_modes), block diagonal by body [kg m^2]."""
        return self._mode_blocks("mass")

    @property
    def mode_stiffness(self) -> np.ndarray:
        """Structural stiffness of the modes (n_modes, n_modes), block diagonal by body [N m]: the generalised
        force -K xi on the modal coordinates xi."""
        return self._mode_blocks("stiffness")

    @property
    def mode_damping(self) -> np.ndarray:
        """Structural damping of the modes (n_modes, n_modes), block diagonal by body [N m s]: the generalised
        force -C xi_dot."""
        return self._mode_blocks("damping")

    # --- sizes and names -------------------------------------------------------------------------
    @property
    def body_names(self) -> tuple[str, ...]:
        """Body names in the order given."""
        return tuple(b.name for b in self.bodies)

    @property
    def ordered_joints(self) -> tuple[Joint, ...]:
        """Joints in the topological order of their child bodies: the order of the generalised coordinates."""
        return tuple(self.joints[self.joint_of[i]] for i in self.order)

    @property
    def velocity_names(self) -> tuple[str, ...]:
        """Generalised velocity names, ``<joint>__<label>``, then the modes' ``<body>__<mode>``."""
        return tuple(f"{j.name}__{lab}" for j in self.ordered_joints for lab in j.labels) + self.mode_names

    @property
    def velocity_kinds(self) -> tuple[str, ...]:
        """For each generalised velocity its kind: ``"angular"`` (a rotation: revolute joints, the rotations of
        planar and free bases; [rad], [rad/s], [N m]), ``"linear"`` (a translation; [m], [m/s], [N]) or
        ``"generalised"`` (a body's generalised mode: coordinate [1], rate [1/s], acceleration [1/s^2], force [J],
        mass [kg m^2]; see ``wecss.multibody._modes``). The kinds of ``wecss.hydro.DOF_KINDS``."""
        out: list[str] = []
        for joint in self.ordered_joints:
            if joint.kind == "revolute":
                out.append("angular")
            elif joint.kind == "planar":
                out += ["linear", "linear", "angular"]
            elif joint.kind == "free":
                out += ["linear"] * 3 + ["angular"] * 3
            else:
                out += ["linear"] * joint.nv
        return tuple(out) + ("generalised",) * self.n_modes

    @property
    def angular_velocities(self) -> tuple[bool, ...]:
        """For each generalised velocity, whether it is a rotation [rad/s] (``velocity_kinds`` "angular"): revolute
        joints and the rotations of planar and free bases. False for translations and generalised modes (see
        ``velocity_kinds`` to tell those apart)."""
        return tuple(kind == "angular" for kind in self.velocity_kinds)

    @property
    def coordinate_names(self) -> tuple[str, ...]:
        """Generalised coordinate names (a free base has x, y, z, qw, qx, qy, qz), then the modes'."""
        out: list[str] = []
        for j in self.ordered_joints:
            labels = ("x", "y", "z", "qw", "qx", "qy", "qz") if j.kind == "free" else j.labels
            out.extend(f"{j.name}__{lab}" for lab in labels)
        return tuple(out) + self.mode_names

    @property
    def nv(self) -> int:
        """Number of generalised velocities (degrees of freedom): the joints' and the modes'."""
        return sum(j.nv for j in self.joints) + self.n_modes

    @property
    def joint_damping(self) -> np.ndarray:
        """The joints' own viscous damping per generalised velocity (nv,), in the order of ``velocity_names``
        [N m s/rad or N s/m]: the generalised force -diag(joint_damping) v (zero on base joints and on the modes,
        whose damping is ``mode_damping``)."""
        joints = [j.damping for j in self.ordered_joints for _ in j.labels]
        return np.array(joints + [0.0] * self.n_modes, dtype=float)

    @property
    def nq(self) -> int:
        """Number of configuration coordinates: the joints' and the modes'."""
        return sum(j.nq for j in self.joints) + self.n_modes

    def body(self, name: str) -> Body:
        """The body called ``name``."""
        for b in self.bodies:
            if b.name == name:
                return b
        raise ValueError(f"unknown body {name!r}; bodies: {', '.join(self.body_names)}")

    def joint(self, name: str) -> Joint:
        """The joint called ``name``."""
        for j in self.joints:
            if j.name == name:
                return j
        raise ValueError(f"unknown joint {name!r}; joints: {', '.join(j.name for j in self.joints)}")

    def neutral_configuration(self) -> np.ndarray:
        """The reference configuration q0 (zeros; identity quaternion for a free base)."""
        q = np.zeros(self.nq)
        k = 0
        for j in self.ordered_joints:
            if j.kind == "free":
                q[k + 3] = 1.0
            k += j.nq
        return q
