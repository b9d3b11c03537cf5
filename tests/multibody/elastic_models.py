"""Flexible bodies for the tests: an L-shaped arm with a lumped mass carrying a float and a welded lug, a spinning
beam, and a pinned beam (pendulum)."""

from __future__ import annotations

import numpy as np

from wecss.multibody import Body, ElasticBody, Joint, Multibody
from wecss.structure import MATERIALS, Frame, LumpedMass, Material, MemberLine, Section, build_frame, craig_bampton

A, B, C = np.array([0.0, 0.0, 0.0]), np.array([1.5, 0.0, 0.0]), np.array([1.5, 0.8, 0.6])
LUG = np.array([0.9, 0.0, 0.0])


def l_arm_frame(*, soft: bool = False) -> Frame:
    """Two members (a tube A-B, a box B-C) and a lumped mass, with the points ``root`` (A), ``pto`` (LUG) and
    ``tip`` (C). ``soft``: a material 1000 times more compliant than steel (slow modes, for time integration)."""
    steel = MATERIALS["S355"] if not soft else Material("soft", 2.1e8, 0.8e8, 7850.0)
    members = [
        MemberLine("a", A, B, Section.tube(0.12, 0.006), steel, 20.0),
        MemberLine("b", B, C, Section.box(0.08, 0.12, 0.005), steel),
    ]
    mass = LumpedMass("lug", np.array([0.9, 0.05, -0.04]), 30.0, np.diag([0.2, 0.3, 0.4]))
    return build_frame(members, elements=4, points={"root": A, "pto": LUG, "tip": C}, masses=[mass])


def l_arm(n_modes: int = 3, *, geometric: bool = True, soft: bool = False) -> ElasticBody:
    """The L frame (:func:`l_arm_frame`) held at A, reduced with ``n_modes`` normal modes; a float's hinge at C and
    a lug at LUG."""
    frame = l_arm_frame(soft=soft)
    basis = craig_bampton(frame, "root", {"pto": "force", "tip": "joint"}, n_modes=n_modes, centrifugal=True)
    attachments = {"float_hinge": "tip", "lug_weld": "pto", "pto:cylinder": "pto"}
    return ElasticBody.from_basis(basis, attachments, geometric=geometric)


_ARM_CHILDREN = (
    (
        Body("float", 8.0, [0.3, 0.4, 0.5], C + np.array([0.2, 0.1, -0.3])),
        Body("lug", 2.0, [0.1, 0.1, 0.1], LUG + np.array([0.0, 0.0, -0.2])),
    ),
    (
        Joint("float_hinge", "revolute", "float", "arm", axis=[0.0, 1.0, 0.2], point=C),
        Joint("lug_weld", "weld", "lug", "arm"),
    ),
)
"""The arm's children, the float on an oblique hinge at the tip C and a lug welded at LUG: bodies, joints."""


def arm_device(base: str = "free", elastic: ElasticBody | None = None) -> Multibody:
    """A hull on ``base``, the flexible arm hinged to it at A, a float hinged at the arm's tip on an oblique axis and a
    lug welded to the arm at LUG."""
    el = l_arm() if elastic is None else elastic
    inv = el.invariants
    bodies = [
        Body("hull", 40.0, [3.0, 4.0, 5.0], [-0.5, 0.0, -0.2]),
        Body("arm", inv.mass, inv.inertia, inv.origin, elastic=el),
        *_ARM_CHILDREN[0],
    ]
    joints = [
        Joint("base", base, "hull"),  # type: ignore[arg-type]
        Joint("arm_hinge", "revolute", "arm", "hull", axis=[0.0, 1.0, 0.0], point=A),
        *_ARM_CHILDREN[1],
    ]
    return Multibody(bodies, joints)


def hinged_beam(
    length: float,
    ei: float,
    mass_per_length: float,
    ea: float,
    *,
    axis: tuple[float, float, float] = (0.0, 0.0, 1.0),
    elements: int = 32,
    n_modes: int = 8,
    geometric: bool = True,
    inertia_relief: bool = True,
    centrifugal: bool = True,
    probes: int = 0,
) -> Multibody:
    """A uniform Euler-Bernoulli beam along x from the origin (bending stiffness ``ei`` [N m^2] in both planes, axial
    stiffness ``ea`` [N], mass per length [kg/m], no rotary inertia of its sections), held in its floating frame at
    the origin where a revolute joint about ``axis`` hinges it to a fixed ground. ``probes`` attachments ``x1``,
    ``x2``, ... at equal spacing along it carry nothing: they give the mode shapes on the axis."""
    area = 1e-3
    e = ea / area
    i = ei / e
    section = Section.given(area, i, i, i, i, i, torsion_constant=2 * i)
    material = Material("beam", e, e / 2.6, mass_per_length / area)
    line = MemberLine("beam", np.zeros(3), np.array([length, 0.0, 0.0]), section, material)
    probe = {f"x{k}": np.array([length * k / probes, 0.0, 0.0]) for k in range(1, probes + 1)}
    frame = build_frame([line], elements=elements, points={"hub": np.zeros(3), **probe}, rotary_inertia=False)
    basis = craig_bampton(
        frame, "hub", {}, n_modes=n_modes, inertia_relief=inertia_relief, centrifugal=centrifugal
    )  # fmt: skip
    el = ElasticBody.from_basis(basis, {k: k for k in probe}, geometric=geometric)
    inv = el.invariants
    bodies = [
        Body("ground", 1.0, [1.0, 1.0, 1.0], [0.0, 0.0, 0.0]),
        Body("beam", inv.mass, inv.inertia, inv.origin, elastic=el),
    ]
    joints = [
        Joint("base", "fixed", "ground"),
        Joint("hub", "revolute", "beam", "ground", axis=list(axis), point=[0.0, 0.0, 0.0]),
    ]
    return Multibody(bodies, joints)


def floating_arm(base: str = "free") -> Multibody:
    """The flexible L arm itself on ``base`` (its floating frame held at A), carrying the float and the lug."""
    el = l_arm()
    inv = el.invariants
    bodies = [Body("arm", inv.mass, inv.inertia, inv.origin, elastic=el), *_ARM_CHILDREN[0]]
    joints = [Joint("base", base, "arm"), *_ARM_CHILDREN[1]]  # type: ignore[arg-type]
    return Multibody(bodies, joints)
