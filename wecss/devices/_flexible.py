"""Flexible bodies of a device: the spec's ``flexible = {...}`` table of a body and its ``[[masses]]``, the frame
of the body's members (``wecss.structure``) with its points, and the body's reduced model.

A flexible body's structural model is the frame of its members (their sections, materials and non-structural mass)
and of its lumped masses, meshed with ``elements`` elements per member and nodes at every point the body is joined
or loaded at. Its points (``body_points``):

- ``clamp``: where the body is held in its floating frame, the parent joint's point (a revolute joint's point;
  otherwise ``flexible.clamp`` must give it);
- ``joint:<name>`` for each joint whose parent is the body: the joint's point (the child's centre of mass for a
  joint without one), an interface that transmits forces and moments;
- ``pto:<name>`` for each actuator PTO with an end on the body: that end, an interface that transmits a force.

The reduced model (``flexible_body``) is the Craig-Bampton basis with inertia-relief vectors
(``wecss.structure.craig_bampton``), its floating-frame invariants about the body's centre of mass and its stress
modes at the members' hot spots (SCF applied) and at the default fibres of every node. The structural model must
carry the body's mass: its mass and centre of mass are checked against the body's (``check_structural_mass``).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..multibody import ActuatorPTO, ElasticBody, GeneralisedModes, JointPTO, Multibody
from ..structure import (
    THEORIES,
    Frame,
    Invariants,
    LumpedMass,
    MemberLine,
    ModalBasis,
    StressModes,
    StressPoint,
    build_frame,
    craig_bampton,
    default_points,
    invariants,
    stress_modes,
)
from ._members import Member

FLEXIBLE_KEYS = (
    "modes", "damping_ratio", "elements", "theory", "clamp", "inertia_relief", "centrifugal", "dynamics",
    "geometric_stiffness", "quasi_static_above",
)  # fmt: skip
"""Keys of a body's ``flexible`` table (all optional)."""
DYNAMICS = ("frozen", "elastic")
"""What a flexible body's modes do in the device's equations of motion: ``frozen`` (the body moves rigidly with the
spec's mass properties; the structural model gives stresses by the free-body cut and the modal analysis) or
``elastic`` (its modal coordinates join the generalised coordinates: ``Device.elastic_model``)."""
MASS_KEYS = ("name", "body", "point", "mass", "inertia")
"""Keys of a ``[[masses]]`` entry (``inertia`` optional)."""
MASS_TOLERANCE = 1e-3
"""Largest relative difference between a flexible body's mass and its structural model's, and between their centres
of mass relative to the size of the body's members [-]."""


def _integer(where: str, key: str, value: Any, smallest: int) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or value < smallest:
        raise ValueError(f"{where}: {key} must be an integer >= {smallest}; got {value!r}")
    return value


@dataclass(frozen=True)
class Flexible:
    """A body's ``flexible`` table.

    Attributes
    ----------
    modes : int
        Fixed-interface normal modes kept (default 6).
    damping_ratio : float
        Structural damping ratio of every reduced coordinate [-] (default 0).
    elements : int
        Elements per member at least (default 8).
    theory : str
        ``"euler-bernoulli"`` (default) or ``"timoshenko"``.
    clamp : ndarray (3,) or None
        Where the body is held [m] (default: its parent joint's point).
    inertia_relief, centrifugal : bool
        The inertia-relief vectors (default True) and the angular-velocity ones (default False).
    dynamics : str
        One of :data:`DYNAMICS` (default ``"frozen"``).
    geometric_stiffness : bool
        With ``dynamics = "elastic"``, the geometric stiffening of the basis's own axial strain (default True;
        ``wecss.structure.axial_geometric_stiffness``).
    quasi_static_above : float or None
        With ``dynamics = "elastic"``, the reduced coordinates whose natural frequency (clamped) is above this [Hz]
        are held quasi-static: their rates and accelerations are neglected and their equations solved as
        algebraic ones at every step (the structure's static response to the loads of the moment, the inertia of
        the rigid motion among them; ``docs/flexible.md``). 0: all of them; None (default): none. The right choice
        when the body's first mode is far above the wave frequencies.
    """

    modes: int = 6
    damping_ratio: float = 0.0
    elements: int = 8
    theory: str = "euler-bernoulli"
    clamp: np.ndarray | None = None
    inertia_relief: bool = True
    centrifugal: bool = False
    dynamics: str = "frozen"
    geometric_stiffness: bool = True
    quasi_static_above: float | None = None

    @classmethod
    def from_spec(cls, where: str, value: Any) -> Flexible:
        """From the spec's ``flexible = {modes = 6, damping_ratio = 0.01, elements = 16}``.

        Raises
        ------
        ValueError
            On unknown keys or bad values (the message names the field, the value and what is accepted).
        """
        if not isinstance(value, Mapping):
            raise ValueError(f"{where}: flexible must be a table {{{', '.join(FLEXIBLE_KEYS)}}}; got {value!r}")
        unknown = sorted(set(value) - set(FLEXIBLE_KEYS))
        if unknown:
            raise ValueError(f"{where}: flexible has unknown keys {unknown}; accepted: {list(FLEXIBLE_KEYS)}")
        modes = _integer(where, "flexible.modes", value.get("modes", 6), 0)
        elements = _integer(where, "flexible.elements", value.get("elements", 8), 1)
        ratio = value.get("damping_ratio", 0.0)
        if isinstance(ratio, bool) or not isinstance(ratio, int | float) or not 0.0 <= ratio < 1.0:
            raise ValueError(f"{where}: flexible.damping_ratio must be a number in [0, 1); got {ratio!r}")
        theory = value.get("theory", "euler-bernoulli")
        if theory not in THEORIES:
            raise ValueError(f"{where}: flexible.theory {theory!r}; accepted: {list(THEORIES)}")
        clamp = value.get("clamp")
        if clamp is not None:
            try:
                clamp = np.asarray(clamp, dtype=float)
            except (TypeError, ValueError):
                clamp = None
            if clamp is None or clamp.shape != (3,) or not np.all(np.isfinite(clamp)):
                raise ValueError(f"{where}: flexible.clamp must be a point [x, y, z] [m]; got {value['clamp']!r}")
        flags = {}
        for key, default in (("inertia_relief", True), ("centrifugal", False), ("geometric_stiffness", True)):
            flag = value.get(key, default)
            if not isinstance(flag, bool):
                raise ValueError(f"{where}: flexible.{key} must be true or false; got {flag!r}")
            flags[key] = flag
        dynamics = value.get("dynamics", "frozen")
        if dynamics not in DYNAMICS:
            raise ValueError(f"{where}: flexible.dynamics {dynamics!r}; accepted: {list(DYNAMICS)}")
        above = value.get("quasi_static_above")
        if above is not None:
            if isinstance(above, bool) or not isinstance(above, int | float) or not 0.0 <= above < np.inf:
                raise ValueError(f"{where}: flexible.quasi_static_above must be a frequency >= 0 [Hz]; got {above!r}")
            if dynamics != "elastic":
                raise ValueError(
                    f"{where}: flexible.quasi_static_above ({above!r} Hz) holds modal coordinates of the equations "
                    f"of motion quasi-static, and flexible.dynamics is {dynamics!r}; give dynamics = 'elastic', or "
                    "leave quasi_static_above out"
                )
            above = float(above)
        return cls(modes, float(ratio), elements, theory, clamp, dynamics=dynamics, quasi_static_above=above, **flags)


@dataclass(frozen=True, eq=False)
class BodyMass:
    """A lumped mass on a flexible body (``[[masses]]``): ``name``, ``body``, ``point`` (its centre, world axes of
    the reference configuration) [m], ``mass`` [kg] and ``inertia`` (3, 3) about its centre [kg m^2]."""

    name: str
    body: str
    point: np.ndarray
    mass: float
    inertia: np.ndarray


def read_masses(device: str, entries: Sequence[Mapping[str, Any]], flexible: Sequence[str]) -> tuple[BodyMass, ...]:
    """The spec's ``[[masses]]``.

    Raises
    ------
    ValueError
        On unknown or missing keys, a body that is not flexible, a bad point, mass or inertia, repeated names.
    """
    out = []
    for k, entry in enumerate(entries):
        where = f"device {device!r}, masses[{k}]"
        if not isinstance(entry, Mapping):
            raise ValueError(f"{where}: must be a table {{{', '.join(MASS_KEYS)}}}; got {entry!r}")
        unknown = sorted(set(entry) - set(MASS_KEYS))
        missing = sorted({"name", "body", "point", "mass"} - set(entry))
        if unknown or missing:
            raise ValueError(f"{where}: unknown keys {unknown}, missing keys {missing}; accepted: {list(MASS_KEYS)}")
        if entry["body"] not in flexible:
            raise ValueError(
                f"{where}: body {entry['body']!r} is not flexible (flexible bodies: {list(flexible)}); a lumped mass "
                "belongs to a flexible body's structural model (give the body a flexible = {...} table)"
            )
        point = np.asarray(entry["point"], dtype=float) if isinstance(entry["point"], list | tuple) else None
        if point is None or point.shape != (3,) or not np.all(np.isfinite(point)):
            raise ValueError(f"{where}: point must be [x, y, z] [m]; got {entry['point']!r}")
        mass = entry["mass"]
        if isinstance(mass, bool) or not isinstance(mass, int | float) or not (np.isfinite(mass) and mass > 0):
            raise ValueError(f"{where}: mass must be a positive number [kg]; got {mass!r}")
        try:
            inertia = np.asarray(entry.get("inertia", [0.0, 0.0, 0.0]), dtype=float)
        except (TypeError, ValueError):
            inertia = np.full((1,), np.nan)
        if inertia.shape == (3,):
            inertia = np.diag(inertia)
        if (
            inertia.shape != (3, 3)
            or not np.all(np.isfinite(inertia))
            or not np.allclose(inertia, inertia.T)
            or np.linalg.eigvalsh(0.5 * (inertia + inertia.T)).min() < -1e-12 * max(1.0, np.abs(inertia).max())
        ):
            raise ValueError(
                f"{where}: inertia must be 3 diagonal values or a symmetric positive semi-definite 3x3 matrix about "
                f"the mass's centre [kg m^2]; got {entry.get('inertia')!r}"
            )
        out.append(BodyMass(str(entry["name"]), str(entry["body"]), point, float(mass), 0.5 * (inertia + inertia.T)))
    names = [m.name for m in out]
    if len(set(names)) != len(names):
        raise ValueError(f"device {device!r}: mass names repeat: {names}")
    return tuple(out)


def body_points(
    model: Multibody, ptos: Sequence[JointPTO | ActuatorPTO], body: str, flexible: Flexible
) -> tuple[dict[str, np.ndarray], dict[str, str]]:
    """The named points of a flexible body (see the module docstring) and the kind of each interface.

    Raises
    ------
    ValueError
        If the body's clamp cannot be found (its joint has no point and ``flexible.clamp`` is not given).
    """
    joint = model.joints[model.joint_of[model.body_names.index(body)]]
    if flexible.clamp is not None:
        clamp = flexible.clamp
    elif joint.kind == "revolute" and joint.point is not None:
        clamp = joint.point
    else:
        raise ValueError(
            f"body {body!r}: flexible.clamp: its joint {joint.name!r} ({joint.kind}) has no point to hold the body "
            "at; give clamp = [x, y, z] [m] in its flexible table"
        )
    points = {"clamp": np.asarray(clamp, dtype=float)}
    kinds: dict[str, str] = {}
    for j in model.joints:
        if j.parent == body:
            name = f"joint:{j.name}"
            points[name] = j.point if j.point is not None else model.body(j.child).center_of_mass
            kinds[name] = "joint"
    for pto in ptos:
        if isinstance(pto, ActuatorPTO):
            for end, point in ((pto.body_a, pto.point_a), (pto.body_b, pto.point_b)):
                if end == body:
                    points[f"pto:{pto.name}"] = point
                    kinds[f"pto:{pto.name}"] = "force"
    return points, kinds


def _lines(members: Sequence[Member], body: str) -> list[MemberLine]:
    out = []
    for m in members:
        if m.body != body:
            continue
        if m.material is None:
            raise ValueError(
                f"member {m.name!r} of the flexible body {body!r} has no material; give material = 'S355' or a "
                "table {E = ..., nu = ..., density = ...}"
            )
        stations = tuple(sorted({s.at for s in m.hot_spots}))
        out.append(MemberLine(m.name, m.start, m.end, m.section, m.material, m.nonstructural_mass, stations))
    if not out:
        raise ValueError(f"the flexible body {body!r} has no members ([[members]] with body = {body!r})")
    return out


def check_structural_mass(model: Multibody, members: Sequence[Member], masses: Sequence[BodyMass], body: str) -> None:
    """Check that a flexible body's members and lumped masses carry its mass and centre of mass.

    Raises
    ------
    ValueError
        If the masses differ by more than :data:`MASS_TOLERANCE` (relative) or the centres by more than that times
        the extent of the members (the message gives both and how to reconcile them).
    """
    lines = _lines(members, body)
    weights = [(m.material.density * m.section.area + m.nonstructural_mass) * float(np.linalg.norm(m.end - m.start))
               for m in lines]  # fmt: skip
    centres = [(m.start + m.end) / 2 for m in lines]
    weights += [m.mass for m in masses if m.body == body]
    centres += [m.point for m in masses if m.body == body]
    total = float(sum(weights))
    centre = sum((w * c for w, c in zip(weights, centres, strict=True)), np.zeros(3)) / total
    declared = model.body(body)
    ends = np.array([p for m in lines for p in (m.start, m.end)])
    size = float(np.ptp(ends, axis=0).max())
    if abs(total - declared.mass) > MASS_TOLERANCE * declared.mass:
        raise ValueError(
            f"body {body!r}: its structural model (members and masses) weighs {total:.6g} kg, the body "
            f"{declared.mass:.6g} kg; a flexible body's members must carry its mass (within {MASS_TOLERANCE:g}): add "
            "the difference as the members' nonstructural_mass [kg/m] or as [[masses]]"
        )
    if np.linalg.norm(centre - declared.center_of_mass) > MASS_TOLERANCE * size:
        raise ValueError(
            f"body {body!r}: its structural model's centre of mass {np.round(centre, 6).tolist()} m differs from the "
            f"body's {np.round(declared.center_of_mass, 6).tolist()} m by more than {MASS_TOLERANCE:g} of its size "
            f"{size:.4g} m"
        )


def body_frame(
    model: Multibody,
    ptos: Sequence[JointPTO | ActuatorPTO],
    members: Sequence[Member],
    masses: Sequence[BodyMass],
    body: str,
    flexible: Flexible,
) -> Frame:
    """The frame of a flexible body's members and masses with its named points (see the module docstring)."""
    points, _ = body_points(model, ptos, body, flexible)
    lumped = [LumpedMass(m.name, m.point, m.mass, m.inertia) for m in masses if m.body == body]
    return build_frame(
        _lines(members, body), elements=flexible.elements, points=points, masses=lumped, theory=flexible.theory
    )


@dataclass(frozen=True, eq=False)
class FlexibleBody:
    """A flexible body's reduced model.

    Attributes
    ----------
    name : str
    flexible : Flexible
    frame : Frame
    basis : ModalBasis
        Craig-Bampton with inertia-relief vectors, mass-orthonormal, held at the point ``clamp``.
    invariants : Invariants
        About the body's centre of mass (the body frame's origin), body axes.
    stresses : StressModes
        At the members' hot spots (named ``<member>.<spot>``, SCF applied), then at the default fibres of every
        node (``<member>@<station>.fibre<k>``); rigid-motion loads about the body's centre of mass.
    interfaces : mapping of str to str
        The interface points and their kinds.
    """

    name: str
    flexible: Flexible
    frame: Frame
    basis: ModalBasis
    invariants: Invariants
    stresses: StressModes
    interfaces: Mapping[str, str]

    @property
    def mode_names(self) -> tuple[str, ...]:
        """``flex1``, ``flex2``, ... one per reduced coordinate."""
        return tuple(f"flex{k + 1}" for k in range(self.basis.n))

    def elastic_body(self) -> ElasticBody:
        """The body's floating-frame model for the equations of motion (``wecss.multibody.ElasticBody``): its
        invariants about the structural model's own centre of mass (the structure carries the body's mass), an
        attachment per interface (a child joint's under the joint's name, a PTO end's under ``pto:<name>``) and,
        with ``flexible.geometric_stiffness``, the geometric tensor of the basis's own axial strain; with
        ``flexible.quasi_static_above``, its coordinates above that frequency held quasi-static."""
        attachments = {name.removeprefix("joint:"): name for name in self.interfaces}
        return ElasticBody.from_basis(
            self.basis,
            attachments,
            geometric=self.flexible.geometric_stiffness,
            names=self.mode_names,
            quasi_static_above=self.flexible.quasi_static_above,
        )

    def generalised_modes(self) -> GeneralisedModes:
        """The reduced coordinates as a body's generalised modes: unit mass, stiffness omega^2, damping
        2 zeta omega (the inertial coupling to the rigid motion is in :attr:`invariants`)."""
        b = self.basis
        return GeneralisedModes(self.mode_names, np.ones(b.n), b.omega**2, 2 * b.damping_ratio * b.omega, self.name)


def flexible_body(
    model: Multibody,
    ptos: Sequence[JointPTO | ActuatorPTO],
    members: Sequence[Member],
    masses: Sequence[BodyMass],
    body: str,
    flexible: Flexible,
) -> FlexibleBody:
    """Reduce a flexible body (see the module docstring and :class:`FlexibleBody`)."""
    frame = body_frame(model, ptos, members, masses, body, flexible)
    _, kinds = body_points(model, ptos, body, flexible)
    basis = craig_bampton(
        frame, "clamp", kinds, flexible.modes, inertia_relief=flexible.inertia_relief,
        centrifugal=flexible.centrifugal, damping_ratio=flexible.damping_ratio,
    )  # fmt: skip
    origin = model.body(body).center_of_mass
    geometric = flexible.dynamics == "elastic" and flexible.geometric_stiffness  # its stresses as its equations
    spots = [
        StressPoint(m.name, s.at, s.y, s.z, s.scf, f"{m.name}.{s.name}")
        for m in members
        if m.body == body
        for s in m.hot_spots
    ]
    fibres = [StressPoint(p.member, p.station, p.y, p.z, p.scf, f"{p.member}@{p.station:.6g}.{p.name}")
              for p in default_points(frame)]  # fmt: skip
    return FlexibleBody(
        body, flexible, frame, basis, invariants(frame, basis.basis, origin, basis.damping),
        stress_modes(frame, basis.basis, spots + fibres, origin, geometric=geometric), kinds,
    )  # fmt: skip
