"""Small multibody trees for the tests."""

from __future__ import annotations

from wecss.multibody import Body, Joint, Multibody


def mixed_chain(base: str = "planar") -> Multibody:
    """A base body with a revolute child on an oblique axis, a prismatic grandchild and a welded body."""
    bodies = [
        Body("a", 2.0, [1.0, 2.0, 3.0], [0.0, 0.0, -0.1]),
        Body("b", 1.0, [0.5, 0.6, 0.7], [1.0, 0.2, -0.2]),
        Body("c", 0.5, [0.1, 0.1, 0.1], [1.5, 0.3, -0.3]),
        Body("d", 0.3, [0.1, 0.2, 0.3], [0.5, 0.0, 0.0]),
    ]
    joints = [
        Joint("base", base, "a"),  # type: ignore[arg-type]
        Joint("h", "revolute", "b", "a", axis=[0.0, 1.0, 0.3], point=[0.8, 0.1, 0.2]),
        Joint("s", "prismatic", "c", "b", axis=[1.0, 0.0, 1.0]),
        Joint("w", "weld", "d", "a"),
    ]
    return Multibody(bodies, joints)


def m4_111_like() -> Multibody:
    """The 111 layout's tree (Table 1 masses and pitch inertias; hinge 0.25 m above the mid float)."""
    bodies = [
        Body("float_1", 2.345, [0.204, 0.204, 0.204], [0.0, 0.0, -0.0634]),
        Body("float_2", 5.312, [0.075, 0.075, 0.075], [1.06, 0.0, -0.0733]),
        Body("float_3", 17.52, [0.614, 0.614, 0.614], [2.12, 0.0, -0.1227]),
    ]
    joints = [
        Joint("bow", "planar", "float_1"),
        Joint("front_2", "weld", "float_2", "float_1"),
        Joint("hinge_3", "revolute", "float_3", "float_2", axis=[0.0, 1.0, 0.0], point=[1.06, 0.0, 0.25]),
    ]
    return Multibody(bodies, joints)
