"""Bodies with generalised modes in the multibody model: the spec forms and their errors, the Cartesian offsets and
names, the kinematics of a mode's row, and the mapping of a database's modes onto the model."""

from __future__ import annotations

import numpy as np
import pytest

from tests.hydro.synthetic import synthetic_dataset
from tests.hydro.test_generalised_modes import with_mode
from tests.multibody.chains import mixed_chain
from wecss.hydro import HydroData
from wecss.multibody import (
    Body,
    Dynamics,
    GeneralisedModes,
    HydroCoupling,
    Joint,
    Multibody,
    difference,
    integrate,
    kinematics,
    structural_force,
)


def flexible_pair(base: str = "planar") -> Multibody:
    """Body ``a`` (hydro body ``a``) with mode ``flex1``; its revolute child ``b`` with two coupled modes."""
    bodies = [
        Body(
            "a",
            2.0,
            [1.0, 2.0, 3.0],
            [0.0, 0.0, -0.03],
            "a",
            [{"name": "flex1", "mass": 0.4, "stiffness": 30.0, "damping": 0.2}],
        ),
        Body(
            "b",
            1.0,
            [0.5, 0.6, 0.7],
            [1.0, 0.0, -0.08],
            "b",
            {"names": ["bend", "twist"], "mass": [[0.3, 0.05], [0.05, 0.2]], "stiffness": [40.0, 90.0]},
        ),
    ]
    joints = [
        Joint("base", base, "a"),  # type: ignore[arg-type]
        Joint("h", "revolute", "b", "a", axis=[0.0, 1.0, 0.0], point=[0.5, 0.0, 0.2]),
    ]
    return Multibody(bodies, joints)


def test_modes_from_the_spec_forms() -> None:
    listed = GeneralisedModes.from_spec(
        "hull", [{"name": "f1", "mass": 2.0, "stiffness": 8.0}, {"name": "f2", "mass": 3.0}]
    )
    assert listed.names == ("f1", "f2") and listed.n == 2
    np.testing.assert_array_equal(listed.mass, np.diag([2.0, 3.0]))
    np.testing.assert_array_equal(listed.stiffness, np.diag([8.0, 0.0]))
    np.testing.assert_array_equal(listed.damping, np.zeros((2, 2)))
    table = GeneralisedModes.from_spec(
        "hull", {"names": ["f1", "f2"], "mass": [[2.0, 0.5], [0.5, 3.0]], "damping": [1, 2]}
    )
    np.testing.assert_array_equal(table.mass, [[2.0, 0.5], [0.5, 3.0]])
    np.testing.assert_array_equal(table.damping, np.diag([1.0, 2.0]))


@pytest.mark.parametrize(
    ("value", "message"),
    [
        (
            [{"name": "f1", "mass": -1.0}],
            r"body 'hull': modes mass must be positive definite \[kg m\^2\]; got \[\[-1\.0\]\]",
        ),
        ([{"name": "f1"}], r"modes\[0\] has keys \['name'\]; accepted: \['name', 'mass', 'stiffness', 'damping'\]"),
        ([{"name": "f1", "mass": 1.0, "stiff": 2.0}], r"modes\[0\] has keys .*'stiff'"),
        ([{"name": "f1", "mass": [1.0, 2.0]}], r"modes\[0\]\.mass must be a number \[kg m\^2\]; got \[1\.0, 2\.0\]"),
        ([{"name": "Heave", "mass": 1.0}], r"generalised mode name 'Heave' spells the rigid-body DOF 'Heave'"),
        (
            [{"name": "f1", "mass": 1.0}, {"name": "f1", "mass": 1.0}],
            r"modes names must be distinct; got \['f1', 'f1'\]",
        ),
        ({"names": ["f1", "f2"], "mass": [1.0]}, r"modes mass must be 2 values \(the diagonal\) or a symmetric 2x2"),
        ({"names": ["f1"], "mass": [1.0], "stiffness": [-3.0]}, r"modes stiffness must be positive semi-definite"),
        ({"names": ["f1", "f2"], "mass": [[1.0, 0.2], [0.3, 1.0]]}, r"modes mass must be symmetric"),
        ({"mass": [1.0]}, r"modes table has keys \['mass'\]; accepted: \['names', 'mass', 'stiffness', 'damping'\]"),
        ("flex", r"modes must be a list of tables .* or a table .*; got 'flex'"),
    ],
)
def test_bad_modes_name_the_field_the_value_and_what_is_accepted(value: object, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        Body("hull", 1.0, [1.0, 1.0, 1.0], [0.0, 0.0, 0.0], modes=value)  # type: ignore[arg-type]


def test_a_rigid_name_is_not_a_mode_name() -> None:
    """A mode named like a rigid DOF would be ambiguous in the database (``hull__Heave``)."""
    with pytest.raises(ValueError, match="rigid"):
        GeneralisedModes.from_spec("hull", [{"name": "Heave", "mass": 1.0}])


def test_offsets_names_and_kinds() -> None:
    model = flexible_pair()
    assert model.cart_size == (7, 8) and model.cart_start == (0, 7) and model.n_cart == 15
    assert model.cart_body == (0,) * 7 + (1,) * 8
    assert model.cart_axis == (*range(7), *range(8))
    assert model.velocity_names == ("base__surge", "base__heave", "base__pitch", "h__pitch", "a__flex1", "b__bend",
                                    "b__twist")  # fmt: skip
    assert model.coordinate_names == model.velocity_names
    assert model.velocity_kinds == ("linear", "linear", "angular", "angular", "generalised", "generalised",
                                    "generalised")  # fmt: skip
    assert model.angular_velocities == (False, False, True, True, False, False, False)
    assert model.mode_rows.tolist() == [6, 13, 14]
    assert model.mode_velocities.tolist() == [4, 5, 6] and model.nv == 7 and model.nq == 7
    assert model.joint_damping.tolist() == [0.0] * 7
    np.testing.assert_array_equal(model.mode_mass, [[0.4, 0, 0], [0, 0.3, 0.05], [0, 0.05, 0.2]])
    assert model.cartesian_labels[6] == "a__flex1" and model.cartesian_labels[7] == "b__Surge"
    free = flexible_pair("free")
    assert free.nq == free.nv + 1 and free.mode_coordinates.tolist() == [8, 9, 10]


def test_a_mode_named_as_a_joint_coordinate_is_refused() -> None:
    bodies = [
        Body("a", 1.0, [1.0, 1.0, 1.0], [0.0, 0.0, 0.0]),
        Body("h", 1.0, [1.0, 1.0, 1.0], [1.0, 0.0, 0.0], modes=[{"name": "bend", "mass": 1.0}]),
    ]
    joints = [
        Joint("a", "planar", "a"),
        Joint("h", "revolute", "h", "a", axis=[0, 1, 0], point=[0.5, 0, 0], label="bend"),
    ]
    with pytest.raises(ValueError, match=r"generalised coordinates \['h__bend'\] are named twice"):
        Multibody(bodies, joints)


def test_kinematics_of_the_modes() -> None:
    """The rigid rows are the rigid model's; a mode's row is the identity on its column, with Bdot zero; modal
    coordinates add under integrate and difference."""
    model = flexible_pair()
    rigid = Multibody(
        [Body(b.name, b.mass, b.inertia, b.center_of_mass, b.hydro_body) for b in model.bodies], model.joints
    )
    rng = np.random.default_rng(7)
    q = integrate(model, model.neutral_configuration(), 0.3 * rng.standard_normal(model.nv))
    v = rng.standard_normal(model.nv)
    st, ref = kinematics(model, q, v), kinematics(rigid, q[:4], v[:4])
    assert st.Bdot is not None and ref.Bdot is not None
    rigid_rows = [k for k, a in enumerate(model.cart_axis) if a < 6]
    np.testing.assert_array_equal(st.B[np.ix_(rigid_rows, range(4))], ref.B)
    np.testing.assert_array_equal(st.B[np.ix_(rigid_rows, range(4, 7))], 0.0)
    np.testing.assert_array_equal(st.B[model.mode_rows], np.eye(7)[4:])
    np.testing.assert_array_equal(st.Bdot[model.mode_rows], 0.0)
    np.testing.assert_array_equal(st.modal, q[4:])
    np.testing.assert_array_equal(st.D()[model.mode_rows], 0.0)
    dv = rng.standard_normal(model.nv)
    np.testing.assert_allclose(difference(model, q, integrate(model, q, dv)), dv, atol=1e-12)
    assert integrate(model, q, dv)[4:] == pytest.approx(q[4:] + dv[4:])


def test_mass_matrix_and_structural_force() -> None:
    model = flexible_pair()
    mass = Dynamics(model).rigid_mass
    np.testing.assert_array_equal(mass[np.ix_(model.mode_rows, model.mode_rows)], model.mode_mass)
    np.testing.assert_array_equal(mass[np.ix_(model.mode_rows, [0, 1, 2, 3, 4, 5])], 0.0)  # no inertial coupling
    q, v = np.arange(7.0), np.arange(7.0) + 10
    force = structural_force(model, q, v)
    np.testing.assert_allclose(force[model.mode_rows], -model.mode_stiffness @ q[4:] - model.mode_damping @ v[4:])
    assert np.count_nonzero(force) == 3


def test_a_database_mode_maps_to_the_declared_mode_and_an_undeclared_one_is_refused() -> None:
    hydro = HydroData(with_mode(synthetic_dataset(), body="a"))
    coupling = HydroCoupling.from_hydro(flexible_pair(), hydro)
    assert coupling.index.tolist() == [0, 2, 4, 6, 7, 9, 11]  # a: Surge, Heave, Pitch, flex1; b: Surge, Heave, Pitch
    assert coupling.added_mass_inf.shape == (15, 15)
    np.testing.assert_array_equal(coupling.displacement(flexible_pair(), kinematics(flexible_pair(), np.arange(7.0)))[
        [6, 13, 14]], [4.0, 5.0, 6.0])  # fmt: skip
    rigid = mixed_chain("planar")
    bodies = [Body("a", 2.0, [1, 2, 3], [0, 0, -0.03], "a"), Body("b", 1.0, [1, 1, 1], [1, 0, -0.08], "b")]
    with pytest.raises(ValueError, match=r"generalised mode 'a__flex1', which body 'a' \(hydro body 'a'\) does not "
                       r"declare \(its modes: none\); declare it .* or drop it from the database"):  # fmt: skip
        HydroCoupling.from_hydro(Multibody(bodies, [Joint("base", "planar", "a"), Joint("w", "weld", "b", "a")]), hydro)
    assert rigid.n_modes == 0 and rigid.n_cart == 24
