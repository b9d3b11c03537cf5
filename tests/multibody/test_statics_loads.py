"""Static equilibrium, generalised stiffness, PTO transmission and joint reaction recovery."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import brentq

from wecss.multibody import (
    ActuatorPTO,
    Body,
    Dynamics,
    Joint,
    JointPTO,
    Multibody,
    StaticModel,
    gravity_force,
    integrate,
    joint_reactions,
    kinematics,
)

from .chains import mixed_chain

G = 9.81


def arm_model(length: float = 2.0, mass: float = 3.0) -> Multibody:
    """A fixed base and an arm on a revolute joint about +y at the origin, centre of mass at (L, 0, 0)."""
    bodies = [Body("base", 1.0, [1.0, 1.0, 1.0], [0.0, 0.0, 0.0]), Body("arm", mass, [0.1, 0.5, 0.5], [length, 0, 0])]
    joints = [
        Joint("ground", "fixed", "base"),
        Joint("pivot", "revolute", "arm", "base", axis=[0, 1, 0], point=[0, 0, 0]),
    ]
    return Multibody(bodies, joints)


def test_torsion_spring_equilibrium_matches_closed_form() -> None:
    length, mass, k, rest = 2.0, 3.0, 200.0, 0.3
    model = arm_model(length, mass)
    statics = StaticModel(model, G, ptos=[JointPTO("spring", "pivot", stiffness=k, rest=rest)])
    q = statics.equilibrium()
    # rotation phi about +y moves the centre of mass to (L cos phi, 0, -L sin phi): gravity torque m g L cos phi
    expected = brentq(lambda phi: mass * G * length * np.cos(phi) - k * (phi - rest), -1.0, 2.0)
    assert q[0] == pytest.approx(expected, abs=1e-12)
    assert np.max(np.abs(statics.generalized_force(q))) < 1e-10 * statics.scale()
    # stiffness = k + m g L sin phi (spring plus the geometric stiffness of gravity)
    assert statics.stiffness(q)[0, 0] == pytest.approx(k + mass * G * length * np.sin(expected), rel=1e-8)


def test_actuator_length_and_transmission() -> None:
    """A cylinder from a ground point B above the pivot to a point C on the arm: c = |C - B|, c_dot = g' v."""
    model = arm_model()
    a, b1 = 1.0, 1.2
    pto = ActuatorPTO("cyl", None, [0.0, 0.0, a], "arm", [b1, 0.0, 0.0])
    phi = 0.25
    st = kinematics(model, np.array([phi]))
    length, g = pto.stroke(model, np.array([phi]), st)
    # C at (b1 cos phi, 0, -b1 sin phi): c^2 = a^2 + b1^2 + 2 a b1 sin phi
    assert length == pytest.approx(np.sqrt(a**2 + b1**2 + 2 * a * b1 * np.sin(phi)), rel=1e-14)
    assert g[0] == pytest.approx(a * b1 * np.cos(phi) / length, rel=1e-12)
    assert pto.rest == pytest.approx(np.hypot(a, b1))
    with pytest.raises(ValueError, match="coincide"):
        ActuatorPTO("bad", None, [0, 0, 0], "arm", [0, 0, 0])


def test_static_reaction_of_a_hanging_arm() -> None:
    model = arm_model(2.0, 3.0)
    dyn = Dynamics(model)
    q = np.array([0.4])
    zero = np.zeros(1)
    force, moment = joint_reactions(model, q, zero, zero, gravity_force(model, G), dyn.total_mass, dyn.rigid_mass)
    k = [j.name for j in model.ordered_joints].index("pivot")
    np.testing.assert_allclose(force[k], [0.0, 0.0, 3.0 * G], atol=1e-12)
    # the hinge holds the weight; its moment about y must balance gravity: -m g L cos(phi)
    assert moment[k][1] == pytest.approx(-3.0 * G * 2.0 * np.cos(0.4), rel=1e-12)


@pytest.mark.parametrize("base", ["planar", "free"])
def test_reactions_do_no_work_on_free_directions(base: str) -> None:
    """Newton-Euler reactions against the MFM accelerations: on each joint's own DOF the reaction supplies exactly
    the actuation (here a PTO torque on 'h' and nothing elsewhere)."""
    model = mixed_chain(base)
    dyn = Dynamics(model)
    rng = np.random.default_rng(4)
    q = integrate(model, model.neutral_configuration(), 0.3 * rng.normal(size=model.nv))
    v = rng.normal(size=model.nv)
    applied = gravity_force(model, G) + rng.normal(size=6 * len(model.bodies))
    torque = 2.5
    k_h = model.velocity_names.index("h__angle")
    st = kinematics(model, q, v)
    gen = st.B.T @ applied
    gen[k_h] += torque
    terms = dyn.terms(q, v)
    v_dot = np.linalg.solve(terms.mass, gen - terms.nonlinear @ v)
    force, moment = joint_reactions(model, q, v, v_dot, applied, dyn.total_mass, dyn.rigid_mass)
    names = model.velocity_names
    col = 0
    for k, i in enumerate(model.order):
        joint = model.joints[model.joint_of[i]]
        body = model.bodies[i]
        point = st.position[i] + (
            st.rotation[i] @ (joint.point - body.center_of_mass) if joint.kind == "revolute" else 0.0
        )
        for _ in range(joint.nv):
            x_dot = st.B[6 * i : 6 * i + 6, col]
            w_world = st.rotation[i] @ x_dot[3:]
            point_velocity = x_dot[:3] + np.cross(w_world, point - st.position[i])
            power = force[k] @ point_velocity + moment[k] @ w_world
            expected = torque if col == k_h else 0.0
            assert power == pytest.approx(expected, abs=1e-9 * max(1.0, np.abs(applied).max())), names[col]
            col += 1
