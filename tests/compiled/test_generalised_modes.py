"""The kernels on a plant with generalised modes against the object-based model of wecss.multibody: the Cartesian
offsets, kinematics, hydrostatics with the structural stiffness, and the accelerations with added-mass coupling
between the rigid rows and the modes, structural damping and an actuator PTO."""

from __future__ import annotations

import numpy as np

from tests.hydro.synthetic import synthetic_dataset
from tests.hydro.test_generalised_modes import with_mode
from tests.multibody.test_generalised_modes import flexible_pair
from wecss.compiled import _kernels as K
from wecss.compiled import build_plant, linear_damping
from wecss.hydro import HydroData
from wecss.multibody import (
    ActuatorPTO,
    Dynamics,
    HydroCoupling,
    configuration_rate,
    gravity_force,
    integrate,
    kinematics,
    structural_force,
)
from wecss.multibody._hydrostatics import to_body_moments

G = 9.81


def _plant():
    model = flexible_pair()
    coupling = HydroCoupling.from_hydro(model, HydroData(with_mode(synthetic_dataset(), body="a")))
    ptos = (ActuatorPTO("act", "a", [0.2, 0.0, 0.3], "b", [1.2, 0.0, 0.1], stiffness=50.0),)
    damping = np.array([3.0])
    return model, coupling, ptos, damping, build_plant(model, coupling, ptos, G, damping=damping)


def test_the_plant_holds_the_offsets() -> None:
    model, coupling, _, _, p = _plant()
    assert p.cart_start.tolist() == [0, 7] and p.cart_size.tolist() == [7, 8]
    assert p.cart_body.tolist() == list(model.cart_body) and p.cart_axis.tolist() == list(model.cart_axis)
    assert p.mode_row.tolist() == [6, 13, 14]
    assert p.cart_column[p.mode_row].tolist() == [4, 5, 6] and p.cart_coordinate[p.mode_row].tolist() == [4, 5, 6]
    assert np.all(p.cart_column[p.cart_axis < 6] == -1)
    assert p.hydro_index.tolist() == coupling.index.tolist()
    assert set(p.mode_row.tolist()) <= set(p.active.tolist())
    np.testing.assert_array_equal(p.rigid_mass, Dynamics(model).rigid_mass)


def test_kernels_match_the_object_model_with_modes() -> None:
    model, coupling, ptos, damping, p = _plant()
    rng = np.random.default_rng(11)
    for _ in range(3):
        q = integrate(model, model.neutral_configuration(), 0.2 * rng.standard_normal(model.nv))
        v = rng.standard_normal(model.nv)
        rot, pos, b, bdot, _omega = K.kinematics(p, q, v)
        st = kinematics(model, q, v)
        assert st.Bdot is not None
        np.testing.assert_allclose(b, st.B, atol=1e-13)
        np.testing.assert_allclose(bdot, st.Bdot, atol=1e-12)
        np.testing.assert_allclose(K.configuration_rate(p, q, v), configuration_rate(model, q, v), atol=1e-14)
        dv = rng.standard_normal(model.nv)
        np.testing.assert_allclose(K.integrate_configuration(p, q, dv), integrate(model, q, dv), atol=1e-14)
        # configuration loads: gravity, buoyancy, hydrostatics (the mode's coordinate as its displacement), the
        # modes' structural stiffness
        world = gravity_force(model, G) + coupling.buoyancy - coupling.stiffness @ coupling.displacement(model, st)
        world += structural_force(model, q)
        np.testing.assert_allclose(K.hydrostatic_force(p, q, rot, pos), world, rtol=1e-13, atol=1e-12)
        # accelerations with the hydro force, the structural damping and the PTO
        hydro_force = rng.standard_normal(coupling.index.size)
        command = rng.standard_normal(1)
        world[coupling.index] += hydro_force
        force = to_body_moments(world, st) + structural_force(model, q, v) - structural_force(model, q)
        x, grad = ptos[0].stroke(model, q, st)
        extra = grad * (command[0] - ptos[0].stiffness * (x - ptos[0].rest) - damping[0] * (grad @ v))
        terms = Dynamics(model, coupling.added_mass_inf).terms(q, v)
        ref = np.linalg.solve(terms.mass, st.B.T @ force - terms.nonlinear @ v + extra)
        a = K.accelerations(p, q, v, hydro_force, np.zeros((hydro_force.size,) * 2), command)[0]
        np.testing.assert_allclose(a, ref, rtol=1e-11, atol=1e-11 * np.max(np.abs(ref)))
        # the hydro velocities: the modes' rates on their rows
        u = K.hydro_velocity(p, q, v)
        np.testing.assert_allclose(u[3], v[4])  # a__flex1


def test_linear_damping_holds_the_structural_damping() -> None:
    model, _, _, _, p = _plant()
    out = linear_damping(p, np.zeros((1, model.nv)), np.zeros((p.hydro_index.size, model.nv)))
    np.testing.assert_array_equal(out[np.ix_([4, 5, 6], [4, 5, 6])], model.mode_damping)
    np.testing.assert_array_equal(out[:4], 0.0)
