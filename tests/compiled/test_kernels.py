"""The array kernels of the simulator against the object-based MFM of wecss.multibody (an independent code path)."""

from __future__ import annotations

import numpy as np
import pytest

from tests.multibody.chains import mixed_chain
from wecss.compiled import _kernels as K
from wecss.compiled import build_plant
from wecss.devices import load
from wecss.multibody import ActuatorPTO, Dynamics, JointPTO, gravity_force, integrate, kinematics
from wecss.multibody._hydrostatics import to_body_moments


def _reference_accelerations(model, coupling, ptos, g, q, v, hydro_force, command, damping):
    st = kinematics(model, q, v)
    world = gravity_force(model, g)
    added = None
    if coupling is not None:
        world = world + coupling.buoyancy - coupling.stiffness @ coupling.displacement(model, st)
        world[coupling.index] += hydro_force
        added = coupling.added_mass_inf
    force = to_body_moments(world, st)
    extra = np.zeros(model.nv)
    for k, pto in enumerate(ptos):
        x, grad = pto.stroke(model, q, st)
        f = command[k] - pto.stiffness * (x - pto.rest) - damping[k] * (grad @ v)
        extra += grad * f
    terms = Dynamics(model, added).terms(q, v)
    return np.linalg.solve(terms.mass, st.B.T @ force - terms.nonlinear @ v + extra)


@pytest.mark.parametrize("name", ["m4-111", "m4-134", "notc-10kw"])
def test_accelerations_match_object_mfm_on_devices(name):
    device = load(name)
    model, coupling = device.model, device.coupling()
    rng = np.random.default_rng(3)
    damping = rng.uniform(0, 5, len(device.ptos))
    plant = build_plant(model, coupling, device.ptos, 9.81, damping=damping)
    for _ in range(3):
        q = integrate(model, model.neutral_configuration(), 0.2 * rng.standard_normal(model.nv))
        v = rng.standard_normal(model.nv)
        hydro_force = rng.standard_normal(coupling.index.size)
        command = rng.standard_normal(len(device.ptos))
        a = K.accelerations(plant, q, v, hydro_force, np.zeros((hydro_force.size,) * 2), command)[0]
        ref = _reference_accelerations(model, coupling, device.ptos, 9.81, q, v, hydro_force, command, damping)
        assert np.max(np.abs(a - ref)) <= 1e-12 * np.max(np.abs(ref))


@pytest.mark.parametrize("base", ["fixed", "planar", "free"])
def test_kinematics_and_accelerations_match_on_a_mixed_chain(base):
    model = mixed_chain(base)
    ptos = (
        JointPTO("p_hinge", "h", damping=0.0, stiffness=2.0, rest=0.1),
        ActuatorPTO("p_act", "a", [0.2, 0.0, 0.1], "c", [1.4, 0.3, 0.0], stiffness=5.0),
    )
    damping = np.array([0.7, 1.3])
    plant = build_plant(model, None, ptos, 9.81, damping=damping)
    rng = np.random.default_rng(5)
    for _ in range(3):
        q = integrate(model, model.neutral_configuration(), 0.4 * rng.standard_normal(model.nv))
        v = rng.standard_normal(model.nv)
        _rot, pos, b, bdot, omega = K.kinematics(plant, q, v)
        st = kinematics(model, q, v)
        np.testing.assert_allclose(b, st.B, atol=1e-13)
        np.testing.assert_allclose(bdot, st.Bdot, atol=1e-12)
        np.testing.assert_allclose(pos, st.position, atol=1e-13)
        np.testing.assert_allclose(omega, st.angular_velocity, atol=1e-13)
        command = rng.standard_normal(2)
        a = K.accelerations(plant, q, v, np.zeros(0), np.zeros((0, 0)), command)[0]
        ref = _reference_accelerations(model, None, ptos, 9.81, q, v, None, command, damping)
        np.testing.assert_allclose(a, ref, rtol=1e-11, atol=1e-11)


def test_configuration_update_matches_integrate_on_a_free_base():
    model = mixed_chain("free")
    plant = build_plant(model, None, (), 9.81)
    rng = np.random.default_rng(2)
    q = integrate(model, model.neutral_configuration(), rng.standard_normal(model.nv))
    dv = 0.3 * rng.standard_normal(model.nv)
    np.testing.assert_allclose(K.integrate_configuration(plant, q, dv), integrate(model, q, dv), atol=1e-14)


@pytest.mark.parametrize("angle", [1e-9, 1e-5, 3e-3, 0.0099, 0.0101, 0.5, 2.0])
def test_screw_exponential_matches_the_matrix_exponential(angle):
    """exp(xi * angle) of a unit-rotation twist (below 0.01 rad from the coefficients' Taylor series, above from
    sin and cos) against scipy's matrix exponential of the 4 x 4 twist matrix."""
    from scipy.linalg import expm

    rng = np.random.default_rng(3)
    w = rng.standard_normal(3)
    xi = np.concatenate([rng.standard_normal(3), w / np.linalg.norm(w)])
    rot, trans = np.empty((3, 3)), np.empty(3)
    K._screw(xi, angle, rot, trans)
    twist = np.zeros((4, 4))
    twist[:3, :3] = np.array([[0, -xi[5], xi[4]], [xi[5], 0, -xi[3]], [-xi[4], xi[3], 0]])
    twist[:3, 3] = xi[:3]
    reference = expm(twist * angle)
    np.testing.assert_allclose(rot, reference[:3, :3], rtol=0, atol=2e-15)
    np.testing.assert_allclose(trans, reference[:3, 3], rtol=0, atol=2e-15 * max(1.0, angle))
