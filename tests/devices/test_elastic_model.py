"""A device's flexible body in the equations of motion (``flexible.dynamics = "elastic"``): the elastic model of the
NOTC arm (its mass from the structure, its children on its nodes), the refusals (a wetted elastic body, the
rigid model's methods until the device carries its modes, bad spec values), and the arm's static sag under its own
weight in the multibody equations against the finite-element solution of the same structure."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import wecss
from wecss.devices import Flexible
from wecss.devices._flexible import MASS_TOLERANCE
from wecss.multibody import Dynamics, gravity_force, structural_force
from wecss.scene import SceneError
from wecss.structure import static_response


def _elastic_notc(**changes: object) -> wecss.devices.Device:
    device = wecss.devices.load("notc-10kw")
    flexible = dataclasses.replace(device.flexible["arm"], dynamics="elastic", **changes)
    return dataclasses.replace(device, flexible={"arm": flexible})


def test_the_elastic_model_of_the_notc_arm() -> None:
    device = _elastic_notc()
    rigid, model = device.model, device.elastic_model()
    arm = model.body("arm")
    assert arm.elastic is not None
    n = arm.elastic.n
    assert model.nv == rigid.nv + n and model.velocity_names[: rigid.nv] == rigid.velocity_names
    assert model.velocity_names[rigid.nv :] == tuple(f"arm__flex{k + 1}" for k in range(n))
    assert arm.mass == pytest.approx(rigid.body("arm").mass, rel=MASS_TOLERANCE)
    assert sorted(arm.elastic.attachments) == ["pto:cylinder", "tip"]
    np.testing.assert_allclose(arm.elastic.attachments["tip"].point, rigid.joint("tip").point)
    assert arm.elastic.geometric is not None
    assert _elastic_notc(geometric_stiffness=False).elastic_model().body("arm").elastic.geometric is None  # type: ignore[union-attr]
    frozen = wecss.devices.load("notc-10kw")
    assert frozen.elastic_model() is frozen.model


def test_a_wetted_elastic_body_is_refused() -> None:
    device = wecss.devices.load("notc-10kw")
    float_body = device.model.body("floater")
    assert float_body.hydro_body is not None
    wet = dataclasses.replace(device, flexible={"floater": Flexible(dynamics="elastic")})
    with pytest.raises(ValueError, match=r"body .floater. has flexible.dynamics = 'elastic' and is wetted"):
        wet.elastic_model()


def test_spec_values_of_the_dynamics_are_checked() -> None:
    assert Flexible.from_spec("here", {"dynamics": "elastic"}).dynamics == "elastic"
    with pytest.raises(ValueError, match=r"flexible.dynamics 'soft'; accepted: \['frozen', 'elastic'\]"):
        Flexible.from_spec("here", {"dynamics": "soft"})
    with pytest.raises(ValueError, match=r"flexible\.geometric_stiffness must be true or false"):
        Flexible.from_spec("here", {"geometric_stiffness": 1})
    assert Flexible.from_spec("here", {"dynamics": "elastic", "quasi_static_above": 5}).quasi_static_above == 5.0
    with pytest.raises(ValueError, match=r"flexible\.quasi_static_above must be a frequency >= 0 \[Hz\]; got -1"):
        Flexible.from_spec("here", {"dynamics": "elastic", "quasi_static_above": -1})
    with pytest.raises(ValueError, match=r"quasi_static_above \(2 Hz\) .* flexible.dynamics is 'frozen'"):
        Flexible.from_spec("here", {"quasi_static_above": 2})


def test_the_coordinates_above_the_cut_off_are_held_quasi_static() -> None:
    """``quasi_static_above`` [Hz] holds the basis coordinates whose clamped natural frequency is above it; the
    model's mask puts them among the generalised velocities (after the joints')."""
    device = _elastic_notc()
    omega = device.flexible_body("arm").basis.omega
    cut = float(np.sqrt(omega[2] * omega[3])) / (2 * np.pi)  # between the third and the fourth
    for above, expected in ((None, np.zeros(omega.size, bool)), (0.0, np.ones(omega.size, bool)),
                            (cut, np.arange(omega.size) >= 3)):  # fmt: skip
        model = _elastic_notc(quasi_static_above=above).elastic_model()
        np.testing.assert_array_equal(model.body("arm").elastic.quasi_static, expected)  # type: ignore[union-attr]
        np.testing.assert_array_equal(model.quasi_static_velocities, np.concatenate([[False, False], expected]))


def test_a_run_of_a_wetted_elastic_device_is_refused_with_what_to_do(monkeypatch) -> None:  # type: ignore[no-untyped-def]
    from wecss.compiled import _compile

    device = wecss.devices.load("notc-10kw")
    wet = dataclasses.replace(device, flexible={"floater": Flexible(dynamics="elastic")})
    monkeypatch.setattr(_compile, "_device", lambda name: wet)
    with pytest.raises(SceneError, match=r"body .floater. has flexible.dynamics = 'elastic' and is wetted"):
        _compile._device_parts("wetted elastic notc, for this test", None, ())


def test_the_rigid_model_methods_refuse_an_elastic_device_until_it_carries_its_modes() -> None:
    device = _elastic_notc()
    with pytest.raises(ValueError, match=r"Device.statics would use the rigid model.*with_elastic_model\(\)"):
        device.statics()
    elastic = device.with_elastic_model()
    assert elastic.model.body("arm").elastic is not None and elastic.with_elastic_model() is elastic
    assert elastic.elastic_model() is elastic.model
    assert elastic.statics(with_hydro=False).model is elastic.model


def test_the_arm_sags_under_its_weight_as_the_finite_elements_say() -> None:
    """The pivot and the float's hinge held, the NOTC arm's elastic coordinates settle under the arm's own weight
    where the full finite-element model of the same structure, clamped at the pivot and held at the hinge, puts
    them (the basis holds the weight's static response; geometric stiffening off: a linear check)."""
    device = _elastic_notc(geometric_stiffness=False)
    model = device.elastic_model()
    arm = model.body("arm")
    assert arm.elastic is not None
    dyn, g = Dynamics(model), 9.81
    q, v = model.neutral_configuration(), np.zeros(model.nv)
    modes = slice(model.mode_velocity_start[1], model.mode_velocity_start[2])
    assert model.body_names[1] == "arm"
    terms = dyn.terms(q, v)
    load = terms.state.B.T @ (gravity_force(model, g) + structural_force(model, q))
    # the tip is held: the six coordinates of its constraint modes are the tip's displacement, zero; solve the rest
    tip = arm.elastic.attachments["tip"].shapes
    free = np.linalg.svd(tip)[2][6:].T  # modal directions that leave the tip in place
    stiffness = arm.elastic.invariants.modal_stiffness
    xi = free @ np.linalg.solve(free.T @ stiffness @ free, free.T @ load[modes])
    # the finite elements: weight of the arm, clamped at the pivot and held at the hinge
    flexible = device.flexible_body("arm")
    frame = flexible.frame
    held = np.concatenate([frame.support("clamp"), frame.support("joint:tip")])
    weight = frame.rigid_motion_loads(np.zeros(3))[:, 2] * -g
    u = static_response(frame.stiffness, weight, held)
    phi = flexible.basis.basis
    np.testing.assert_allclose(phi @ xi, u, rtol=0, atol=1e-9 * np.abs(u).max())


def test_the_linearised_elastic_model_has_the_modal_analysis_frequencies() -> None:
    """The NOTC device in air (no gravity), its arm elastic: the natural frequencies of the multibody equations
    linearised about the reference configuration by central differences (its mass matrix M*, the stiffness of the
    structure and of the cylinder, whose end rides on the arm's node) equal those of the device's modal analysis
    (``structural_modes``, a linear assembly of its own, issue 27) with the same reduced basis: two derivations."""
    from scipy.linalg import eigh

    from wecss.multibody import integrate, kinematics

    device = _elastic_notc(geometric_stiffness=False)
    model = device.elastic_model()
    q0, v0 = model.neutral_configuration(), np.zeros(model.nv)

    def force(q: np.ndarray) -> np.ndarray:
        state = kinematics(model, q)
        out = state.B.T @ structural_force(model, q)
        for pto in device.ptos:
            stroke, transmission = pto.stroke(model, q, state)
            out += transmission * (-pto.stiffness * (stroke - pto.rest))
        return out

    eps = 1e-7
    stiffness = -np.array(
        [(force(integrate(model, q0, eps * e)) - force(integrate(model, q0, -eps * e))) / (2 * eps)
         for e in np.eye(model.nv)]
    ).T  # fmt: skip
    squares = eigh(0.5 * (stiffness + stiffness.T), Dynamics(model).terms(q0, v0).mass, eigvals_only=True)
    ours = np.sqrt(np.clip(squares[:8], 0.0, None)) / (2 * np.pi)
    theirs = device.structural_modes(water=False, model="reduced", n_modes=8)["frequency"].values
    print(f"NOTC in air, elastic model against the modal analysis: {np.round(ours, 4).tolist()} Hz")
    # the mechanism: a zero frequency, to the eigensolvers' round-off (n eps of the largest eigenvalue omega^2; the
    # square root of that round-off is what either gives, 2.6e-5 Hz with scipy 1.17's LAPACK)
    largest = float(squares.max())
    print(f"largest omega^2 {largest:.3e} (rad/s)^2; mechanism {ours[0]:.2e}, {theirs[0]:.2e} Hz")
    for zero in (ours[0], theirs[0]):
        assert (2 * np.pi * zero) ** 2 <= model.nv * np.finfo(float).eps * largest
    np.testing.assert_allclose(ours[1:], theirs[1:], rtol=1e-8)
