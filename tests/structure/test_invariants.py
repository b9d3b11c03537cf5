"""Floating-frame inertia invariants against closed forms: a uniform tube's mass, centre and inertia (rotary inertia
of its section included); the couplings equal the rigid-body modes through the consistent mass; the inertia of a
body moved by a small rotation field is (I + hat(theta)) P0 (I + hat(theta))' exactly; a stretched rod's inertia;
the gyroscopic coupling of two translations."""

from __future__ import annotations

import numpy as np
import pytest

from wecss.structure import MATERIALS, LumpedMass, MemberLine, Section, build_frame, invariants, member_axes
from wecss.structure._frame import hat

STEEL = MATERIALS["S355"]
TUBE = Section.tube(0.1683, 0.008)
L = 2.4
START = np.array([0.3, -0.5, 1.0])
DIRECTION = np.array([1.0, 2.0, 2.0]) / 3


def _tube(elements: int = 5, **kw):  # type: ignore[no-untyped-def]
    return build_frame([MemberLine("t", START, START + L * DIRECTION, TUBE, STEEL, 12.0)], elements=elements, **kw)


def test_a_uniform_tube_has_its_rigid_mass_centre_and_inertia():
    frame = _tube()
    inv = invariants(frame, np.zeros((frame.n_dof, 0)))
    mu = STEEL.density * TUBE.area + 12.0
    m = mu * L
    assert inv.mass == pytest.approx(m, rel=1e-12)
    np.testing.assert_allclose(inv.center_of_mass, START + L * DIRECTION / 2, rtol=0, atol=1e-12 * L)
    axes = member_axes(START, START + L * DIRECTION)
    rho = STEEL.density
    local = np.diag([rho * TUBE.polar * L, m * L**2 / 12 + rho * TUBE.iy * L, m * L**2 / 12 + rho * TUBE.iz * L])
    np.testing.assert_allclose(inv.inertia, axes.T @ local @ axes, rtol=0, atol=1e-12 * np.abs(local).max())


def test_couplings_are_the_rigid_modes_through_the_mass_matrix():
    masses = [LumpedMass("m", START + np.array([0.4, 0.1, 0.2]), 40.0, np.diag([1.0, 2.0, 3.0]))]
    frame = _tube(masses=masses)
    phi = np.random.default_rng(3).normal(size=(frame.n_dof, 4))
    origin = np.array([0.7, 0.2, 1.4])
    inv = invariants(frame, phi, origin)
    rigid = frame.rigid_modes(origin)
    np.testing.assert_allclose(inv.translational_coupling, rigid[:, :3].T @ frame.mass @ phi, atol=1e-9)
    np.testing.assert_allclose(inv.rotational_coupling, rigid[:, 3:].T @ frame.mass @ phi, atol=1e-9)
    np.testing.assert_allclose(inv.inertia, rigid[:, 3:].T @ frame.mass @ rigid[:, 3:], atol=1e-10)
    np.testing.assert_allclose(inv.modal_mass, phi.T @ frame.mass @ phi, atol=1e-9)


def test_a_small_rotation_field_moves_the_second_moment_exactly():
    """The fields of three small rotations about the origin: P(q) = (I + hat(theta)) P0 (I + hat(theta))' with
    theta = q, so J(q) = tr(P) I - P to second order in q, section terms included."""
    frame = _tube(masses=[LumpedMass("m", START + np.array([0.4, 0.1, 0.2]), 40.0, np.diag([1.0, 2.0, 3.0]))])
    origin = np.array([0.7, 0.2, 1.4])
    inv = invariants(frame, frame.rigid_modes(origin)[:, 3:], origin)
    theta = np.array([0.03, -0.02, 0.05])
    moved = (np.eye(3) + hat(theta)) @ inv.second_moment @ (np.eye(3) + hat(theta)).T
    expected = np.trace(moved) * np.eye(3) - moved
    np.testing.assert_allclose(inv.inertia_at(theta), expected, rtol=0, atol=1e-12 * np.abs(expected).max())
    # a rotation leaves the inertia's eigenvalues, to first order
    assert np.linalg.eigvalsh(inv.inertia_at(1e-6 * theta)) == pytest.approx(np.linalg.eigvalsh(inv.inertia), rel=1e-10)


def test_a_stretched_rod_has_the_closed_form_inertia():
    """Along x, axial field u = s (s from the start, origin at the middle): the deformed rod's Iyy about the origin
    is mu ((1 + q)^2 L^3 / 12 + q^2 L^3 / 4) plus the sections' rho Iy L."""
    frame = build_frame([MemberLine("r", np.zeros(3), np.array([L, 0, 0]), TUBE, STEEL)], elements=3)
    field = np.zeros(frame.n_dof)
    for k in range(frame.n_nodes):
        field[frame.node_dofs(k)[0]] = frame.nodes[k, 0]
    inv = invariants(frame, field[:, None], np.array([L / 2, 0, 0]))
    mu = STEEL.density * TUBE.area
    for q in (0.0, 0.01, -0.3):
        iyy = mu * ((1 + q) ** 2 * L**3 / 12 + q**2 * L**3 / 4) + STEEL.density * TUBE.iy * L
        assert inv.inertia_at(np.array([q]))[1, 1] == pytest.approx(iyy, rel=1e-12)
        assert inv.first_moment_at(np.array([q]))[0] == pytest.approx(mu * L * q * L / 2, abs=1e-9)


def test_gyroscopic_coupling_of_two_translations():
    frame = _tube()
    rigid = frame.rigid_modes(np.zeros(3))
    inv = invariants(frame, rigid[:, :2])
    np.testing.assert_allclose(inv.gyroscopic[0, 1], [0, 0, inv.mass], atol=1e-9)
    np.testing.assert_allclose(inv.gyroscopic[1, 0], [0, 0, -inv.mass], atol=1e-9)
    np.testing.assert_allclose(inv.gyroscopic[0, 0], 0.0, atol=1e-12)
