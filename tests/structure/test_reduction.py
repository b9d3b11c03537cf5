"""Craig-Bampton reduction with inertia-relief vectors, on a frame of two members (an L, one body) with a lumped
mass off the members: with every interior mode it reproduces the full model's eigenvalues; with few modes the
statics under interface loads, the body's weight and a rigid-body acceleration stay exact (and under a rotation
only with the centrifugal vectors); the basis is mass-orthonormal, stiffness-diagonal and zero at the clamp."""

from __future__ import annotations

import numpy as np
import pytest

from wecss.structure import (
    MATERIALS,
    LumpedMass,
    MemberLine,
    Section,
    build_frame,
    craig_bampton,
    natural_modes,
    static_response,
)

A, B, C = np.array([0.0, 0.0, 0.0]), np.array([1.5, 0.0, 0.0]), np.array([1.5, 0.8, 0.6])


def _frame(elements: int = 5):  # type: ignore[no-untyped-def]
    steel = MATERIALS["S355"]
    members = [
        MemberLine("a", A, B, Section.tube(0.12, 0.006), steel, 20.0),
        MemberLine("b", B, C, Section.box(0.08, 0.12, 0.005), steel),
    ]
    mass = LumpedMass("lug", np.array([0.9, 0.05, -0.04]), 30.0, np.diag([0.2, 0.3, 0.4]))
    points = {"root": A, "pto": np.array([0.9, 0.0, 0.0]), "tip": C}
    return build_frame(members, elements=elements, points=points, masses=[mass])


INTERFACES = {"pto": "force", "tip": "joint"}


def test_all_interior_modes_reproduce_the_full_eigenvalues():
    frame = _frame()
    clamp = frame.node_dofs(frame.point("root")[0])
    full, _ = natural_modes(frame.stiffness, frame.mass, fixed=clamp)
    basis = craig_bampton(frame, "root", INTERFACES, n_modes=10_000)
    assert basis.n == len(full) and basis.counts["dropped"] == 6  # the six inertia-relief vectors repeat the span
    np.testing.assert_allclose(basis.omega**2, full**2, rtol=1e-10)


def test_the_basis_is_mass_orthonormal_stiffness_diagonal_and_held_at_the_clamp():
    frame = _frame()
    basis = craig_bampton(frame, "root", INTERFACES, n_modes=4, damping_ratio=0.02)
    phi = basis.basis
    assert basis.counts == {"constraint": 9, "normal": 4, "inertia_relief": 6, "centrifugal": 0, "dropped": 0}
    np.testing.assert_allclose(phi.T @ frame.mass @ phi, np.eye(basis.n), atol=1e-12)
    kr = phi.T @ frame.stiffness @ phi
    np.testing.assert_allclose(kr, np.diag(basis.omega**2), atol=1e-9 * basis.omega.max() ** 2)
    assert np.all(phi[basis.clamped] == 0.0)
    np.testing.assert_allclose(np.diag(basis.damping), 0.04 * basis.omega)
    full, _ = natural_modes(frame.stiffness, frame.mass, fixed=basis.clamped, n_modes=6)
    assert np.all(basis.omega[:6] >= full * (1 - 1e-12))  # Rayleigh-Ritz: from above


def _reduced_static(basis, loads):  # type: ignore[no-untyped-def]
    phi = basis.basis
    return phi @ np.linalg.solve(phi.T @ basis.frame.stiffness @ phi, phi.T @ loads)


@pytest.mark.parametrize("n_modes", [0, 3])
def test_interface_loads_weight_and_rigid_acceleration_are_exact(n_modes):
    frame = _frame()
    rng = np.random.default_rng(27)
    basis = craig_bampton(frame, "root", INTERFACES, n_modes=n_modes, centrifugal=True)
    rigid = rng.normal(size=12)  # g - a, alpha and the products of w (centrifugal and gyroscopic loads)
    loads = (
        frame.point_load("pto", rng.normal(size=3) * 1e3)
        + frame.point_load("tip", rng.normal(size=3) * 1e3, rng.normal(size=3) * 1e2)
        + frame.rigid_motion_loads(frame.nodes[3]) @ rigid
    )
    full = static_response(frame.stiffness, loads, basis.clamped)
    np.testing.assert_allclose(_reduced_static(basis, loads), full, rtol=0, atol=1e-10 * np.abs(full).max())


def test_without_centrifugal_vectors_a_rotation_is_not_exact():
    """The check above can fail: drop the centrifugal vectors and load by an angular velocity."""
    frame = _frame()
    basis = craig_bampton(frame, "root", INTERFACES, n_modes=3)
    loads = frame.rigid_motion_loads(frame.nodes[0]) @ np.r_[np.zeros(6), 1.0, 0.5, 0.2, 0.3, 0.1, 0.4]
    full = static_response(frame.stiffness, loads, basis.clamped)
    error = np.abs(_reduced_static(basis, loads) - full).max() / np.abs(full).max()
    assert error > 1e-4


def test_bad_reductions_are_refused():
    frame = _frame()
    with pytest.raises(ValueError, match="kind 'spring'; accepted"):
        craig_bampton(frame, "root", {"tip": "spring"})
    with pytest.raises(KeyError, match="no point 'nowhere'"):
        craig_bampton(frame, "nowhere")
    with pytest.raises(ValueError, match="rides on the clamp's node"):
        craig_bampton(frame, "root", {"root": "joint"})
    with pytest.raises(ValueError, match="damping_ratio must be a number in"):
        craig_bampton(frame, "root", damping_ratio=1.5)


def test_supports_name_components_and_refuse_a_partial_hold_off_a_node():
    frame = _frame()
    root = frame.node_dofs(frame.point("root")[0])
    np.testing.assert_array_equal(frame.support("root", ("ux", "rz")), root[[0, 5]])
    np.testing.assert_array_equal(frame.support("root"), root)
    with pytest.raises(ValueError, match=r"unknown components \['spin'\]"):
        frame.support("root", ("spin",))
    tube = MemberLine("a", A, B, Section.tube(0.12, 0.006), MATERIALS["S355"])
    off = build_frame([tube], points={"lug": [0.7, 0.2, 0.0]})  # 0.2 m beside the member: a rigid offset
    assert len(off.support("lug")) == 6
    with pytest.raises(ValueError, match="off its node"):
        off.support("lug", ("uz",))
