"""Loads of multibody trees with flexible bodies: the Cartesian inertial load (``inertial_terms``) against the
equations of motion, and the joint reactions (``joint_reactions``) of the Newton-Euler sweep: a free base passes
nothing, a free hinge no moment about its axis, whatever the arm's deformation and motion."""

from __future__ import annotations

import numpy as np
import pytest

from wecss.multibody import (
    Dynamics,
    Multibody,
    body_mass_matrix,
    gravity_force,
    inertial_terms,
    integrate,
    joint_reactions,
    kinematics,
    structural_force,
)

from .elastic_models import arm_device, floating_arm

MODELS = {
    "hull on a free base": lambda: arm_device("free"),
    "hull on a planar base": lambda: arm_device("planar"),
    "hull fixed": lambda: arm_device("fixed"),
    "flexible arm on a free base": lambda: floating_arm("free"),
}


def _state(model: Multibody, seed: int) -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    q = integrate(model, model.neutral_configuration(), 0.3 * rng.normal(size=model.nv))
    return q, rng.normal(size=model.nv)


@pytest.mark.parametrize("base", list(MODELS))
def test_the_inertial_load_is_the_equations_of_motion(base: str) -> None:
    """B' (M(q) (B v_dot + Bdot v) + H X) = M* v_dot + N* v at random states and accelerations: the vector form the
    loads' recovery uses against the equations' matrices (whose energy identity and Lagrange derivation are tested
    in test_elastic_dynamics.py and test_flexible_lagrange.py)."""
    model = MODELS[base]()
    rigid = body_mass_matrix(model)
    dyn = Dynamics(model)
    worst = 0.0
    for seed in range(3):
        q, v = _state(model, seed)
        v_dot = np.random.default_rng(10 + seed).normal(size=model.nv)
        st = kinematics(model, q, v)
        assert st.Bdot is not None and st.angular_velocity is not None
        mass, quadratic = inertial_terms(model, q, v, st.angular_velocity, rigid, rigid)
        got = st.B.T @ (mass @ (st.B @ v_dot + st.Bdot @ v) + quadratic)
        terms = dyn.terms(q, v)
        want = terms.mass @ v_dot + terms.nonlinear @ v
        worst = max(worst, float(np.abs(got - want).max() / np.abs(want).max()))
    print(f"inertial load against M* v_dot + N* v ({base}): {worst:.1e}")
    assert worst < 1e-12


@pytest.mark.parametrize("base", ["free", "fixed"])
def test_the_reactions_of_a_flexible_tree_balance(base: str) -> None:
    """The hull carrying the flexible L arm (a float on an oblique hinge at its tip, a welded lug), moving under
    gravity and the arm's structural forces with the accelerations of the equations of motion, at random
    deformed states: a free base passes no load from the ground (the whole tree's momentum rate is its applied
    load), and the hinges, free, pass no moment about their axes (their joints' balance: the arm's Euler equation
    of a deformable body and its children riding on its nodes)."""
    model = arm_device(base)
    rigid = body_mass_matrix(model)
    dyn = Dynamics(model)
    for seed in range(3):
        q, v = _state(model, seed)
        applied = gravity_force(model, 9.81) + structural_force(model, q, v)
        v_dot = dyn.accelerations(q, v, applied)
        force, moment = joint_reactions(model, q, v, v_dot, applied, rigid, rigid)
        st = kinematics(model, q)
        scale = max(9.81 * sum(b.mass for b in model.bodies), float(np.abs(applied).max()))
        arm_scale = scale * 1.0  # moments about the hinge points: lengths of order 1 m
        for k, i in enumerate(model.order):
            joint = model.joints[model.joint_of[i]]
            if joint.kind == "free":
                assert np.abs(force[k]).max() < 1e-10 * scale
                assert np.abs(moment[k]).max() < 1e-10 * arm_scale
            elif joint.kind == "revolute":
                assert joint.axis is not None
                along = float(moment[k] @ (st.rotation[i] @ joint.axis))
                assert abs(along) < 1e-10 * arm_scale, (joint.name, along)
