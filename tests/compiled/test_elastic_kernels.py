"""Flexible bodies (``Body.elastic``) in the compiled plant and kernels against the Python multibody core (the
floating-frame oracle of ``wecss.multibody._elastic``): kinematics, centres of mass, B, Bdot and the generalised
accelerations with gravity, the structural stiffness and damping and the geometric stiffening, at random states of
a hull carrying a flexible arm (free, planar and fixed base; a float on an elastic attachment and a welded lug) and
of a hinged beam."""

from __future__ import annotations

import numpy as np
import pytest

from tests.multibody.elastic_models import arm_device, hinged_beam
from wecss.compiled import _kernels as K
from wecss.compiled import build_plant
from wecss.compiled._plant import elastic_arrays
from wecss.multibody import Dynamics, Multibody, gravity_force, integrate, kinematics, structural_force

G = 9.81


def _models() -> dict[str, Multibody]:
    return {
        "arm-free": arm_device("free"),
        "arm-planar": arm_device("planar"),
        "arm-fixed": arm_device("fixed"),
        "hinged-beam": hinged_beam(10.0, 1.4e4, 1.2, 2.8e7, axis=(0.0, 0.6, 0.8), elements=8, n_modes=4, probes=2),
    }


MODELS = _models()


def _relative(a: np.ndarray, ref: np.ndarray) -> float:
    return float(np.max(np.abs(a - ref)) / max(np.max(np.abs(ref)), 1e-300))


def _states(model: Multibody, count: int = 3):
    rng = np.random.default_rng(11)
    for _ in range(count):
        q = integrate(model, model.neutral_configuration(), 0.3 * rng.standard_normal(model.nv))
        yield q, rng.standard_normal(model.nv)


@pytest.mark.parametrize("name", list(MODELS))
def test_kinematics_match_the_multibody_core(name: str) -> None:
    model = MODELS[name]
    plant = build_plant(model, None, (), G)
    worst = {}
    for q, v in _states(model):
        rot, pos, b, bdot, omega = K.kinematics(plant, q, v)
        st = kinematics(model, q, v)
        for key, got, ref in (
            ("rotation", rot, st.rotation),
            ("position", pos, st.position),
            ("B", b, st.B),
            ("Bdot", bdot, st.Bdot),
            ("omega", omega, st.angular_velocity),
        ):
            worst[key] = max(worst.get(key, 0.0), _relative(got, ref))
        positions, _ = K.poses(plant, q[None, :])
        worst["poses"] = max(worst.get("poses", 0.0), _relative(positions[0], st.position))
    print(name, {k: f"{x:.1e}" for k, x in worst.items()})
    assert max(worst.values()) <= 1e-12


@pytest.mark.parametrize("name", list(MODELS))
def test_accelerations_match_the_multibody_core(name: str) -> None:
    """v_dot with gravity, the modes' structural stiffness and damping and the geometric stiffening; M* too, and
    the residual of the kernels' accelerations in the core's equations (their backward error: M* is conditioned
    at 1e5-1e6 here, so the accelerations' forward error is that much above it)."""
    model = MODELS[name]
    plant = build_plant(model, None, (), G)
    dyn = Dynamics(model)
    worst_a = worst_m = worst_r = 0.0
    for q, v in _states(model):
        a, _u, _x, _xd, _f, mass = K.accelerations(plant, q, v, np.zeros(0), np.zeros((0, 0)), np.zeros(0))
        terms = dyn.terms(q, v)
        force = terms.state.B.T @ (gravity_force(model, G) + structural_force(model, q, v)) - terms.nonlinear @ v
        ref = np.linalg.solve(terms.mass, force)
        worst_a = max(worst_a, _relative(a, ref))
        worst_m = max(worst_m, _relative(mass, terms.mass))
        worst_r = max(worst_r, float(np.max(np.abs(terms.mass @ a - force)) / np.max(np.abs(force))))
    print(f"{name}: accelerations {worst_a:.1e}, M* {worst_m:.1e}, residual {worst_r:.1e}")
    assert worst_a <= 1e-12
    assert worst_m <= 1e-12
    assert worst_r <= 1e-12


def test_geometric_stiffening_is_in_the_static_force() -> None:
    """The hinged beam's geometric tensor acts: the structural force of the kernels is the core's at a deformed
    configuration, and differs from the one without the tensor."""
    model = MODELS["hinged-beam"]
    plant = build_plant(model, None, (), 0.0)
    q, _ = next(_states(model))
    rot, pos = K.kinematics(plant, q, np.zeros(model.nv))[:2]
    force = K.hydrostatic_force(plant, q, rot, pos)
    ref = structural_force(model, q)
    rows = model.mode_rows
    assert _relative(force[rows], ref[rows]) <= 1e-12
    linear = -model.mode_stiffness @ q[model.mode_coordinates]
    assert _relative(force[rows], linear) > 1e-6


def test_a_rigid_plant_has_empty_elastic_arrays() -> None:
    from tests.multibody.chains import mixed_chain

    model = mixed_chain("free")
    el = build_plant(model, None, (), G).elastic
    per_body = {"of_body", "of_child", "on_path"}
    assert all(getattr(el, name).shape[0] == 0 for name in el._fields if name not in per_body)
    assert (el.of_body == -1).all() and (el.of_child == -1).all() and el.on_path.shape == (len(model.bodies), 0)


@pytest.mark.parametrize("name", list(MODELS))
def test_the_packed_elastic_arrays_give_back_the_built_ones(name: str) -> None:
    """``Plant.elastic`` (views of the two packed arrays) equals ``elastic_arrays`` exactly, array by array, and
    the Workspace's elastic array is as long as its views need."""
    model = MODELS[name]
    plant = build_plant(model, None, (), G)
    built = elastic_arrays(model, plant.active)
    got = plant.elastic
    assert plant.n_elastic == built.body.shape[0] > 0
    for field in built._fields:
        ref, value = getattr(built, field), getattr(got, field)
        assert value.shape == ref.shape and value.dtype == ref.dtype, field
        np.testing.assert_array_equal(value, ref, err_msg=field)
    work = K.workspace(plant).elastic
    views = K.elastic_work(plant.elastic_index, work)
    assert sum(v.size for v in views) == work.size
