"""Stress modes against the beam formulas: an oblique cantilever of a box and of a given section under a tip wrench
(axial force, both shears, torque, both moments) in a Craig-Bampton basis; the section loads at the cuts equal the
statics of the part beyond them, and the stresses at the default fibres sigma = N / A + My z / Iy - Mz y / Iz,
tau = T / W_t, as one matrix product with the modal coordinates."""

from __future__ import annotations

import numpy as np
import pytest

from wecss.structure import (
    MATERIALS,
    MemberLine,
    Section,
    StressPoint,
    build_frame,
    craig_bampton,
    member_axes,
    stress_modes,
)

START, END = np.array([0.2, -0.1, 0.4]), np.array([1.4, 0.7, 1.2])
STATIONS = (0.0, 0.36, 0.72, 1.08)
FORCE, MOMENT = np.array([3.1e3, -1.7e3, 2.3e3]), np.array([410.0, -230.0, 170.0])  # [N], [N m] at the tip
SECTIONS = {
    "box": Section.box(0.12, 0.2, 0.006),
    "given": Section.given(4e-3, 1.1e-5, 6e-6, 1.2e-4, 9e-5, 1.5e-4, torsion_constant=1.3e-5),
}


@pytest.mark.parametrize("kind", sorted(SECTIONS))
def test_stress_modes_of_a_tip_wrench_give_the_beam_formulas(kind):
    section = SECTIONS[kind]
    line = MemberLine("m", START, END, section, MATERIALS["S355"], 0.0, STATIONS)
    frame = build_frame([line], elements=6, points={"root": START, "tip": END})
    # 0 normal modes: the constraint modes of the tip and the inertia-relief vectors, where a tip load is exact
    basis = craig_bampton(frame, "root", {"tip": "joint"}, n_modes=0)
    phi = basis.basis
    loads = frame.point_load("tip", FORCE, MOMENT)
    q = np.linalg.solve(phi.T @ frame.stiffness @ phi, phi.T @ loads)
    points = [StressPoint("m", s, y, z, 1.0, f"s{s}") for s in STATIONS for y, z in section.fibres]
    modes = stress_modes(frame, phi, points)
    axes = member_axes(START, END)
    x = axes[0]
    expected_loads, normal, shear = [], [], []
    for s in STATIONS:
        moment = np.cross(END - (START + s * x), FORCE) + MOMENT  # the part beyond the cut, about its centre
        n, vy, vz = axes @ FORCE
        t, my, mz = axes @ moment
        expected_loads.append([n, vy, vz, t, my, mz])
        for y, z in section.fibres:
            normal.append(n / section.area + my * z / section.iy - mz * y / section.iz)
            shear.append(t / section.wt)
    expected = np.array(expected_loads)
    got = modes.section_loads(q)
    np.testing.assert_allclose(got, expected, rtol=0, atol=1e-10 * np.abs(expected).max())
    stresses = modes.stresses(q)
    normal, shear = np.array(normal), np.array(shear)
    np.testing.assert_allclose(stresses["normal"], normal, rtol=0, atol=1e-10 * np.abs(normal).max())
    np.testing.assert_allclose(stresses["shear"], shear, rtol=0, atol=1e-10 * np.abs(shear).max())
    np.testing.assert_allclose(modes.normal @ q, stresses["normal"], rtol=1e-14, atol=0)  # one matrix product
    vm = np.sqrt(normal**2 + 3 * shear**2)
    np.testing.assert_allclose(stresses["signed_von_mises"], np.where(normal < 0, -vm, vm), rtol=1e-10)


def test_a_stress_point_off_the_nodes_or_members_is_refused():
    line = MemberLine("m", START, END, SECTIONS["box"], MATERIALS["S355"])
    frame = build_frame([line], elements=4)
    phi = np.eye(frame.n_dof)
    with pytest.raises(ValueError, match=r"station 0.1 m of member 'm' is not a node"):
        stress_modes(frame, phi, [StressPoint("m", 0.1, 0.0, 0.0, name="x")])
    with pytest.raises(ValueError, match=r"member 'arm' is not in the frame: \['m'\]"):
        stress_modes(frame, phi, [StressPoint("arm", 0.0, 0.0, 0.0, name="x")])
