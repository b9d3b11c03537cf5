"""The section loads of the elastic motion in a rotating floating frame against its kinematics, derived apart.

The stress modes' d'Alembert loads of an element (``wecss.structure._stress``) are written in the floating frame: the
rigid-motion loads, the modal accelerations' and the terms bilinear in the frame's rotation and the elastic
coordinates (alpha x u, w x (w x u), 2 w x u_dot on the mass, and the rotary inertia's share). Here they are
checked against an oracle that knows nothing of that split: every mass point of the finite-element model is moved
in the world, x(t) = R(t) (X + u(t)) and its section turned by R(t) exp(theta(t)), and its d'Alembert force and
moment are the numerical time derivatives of its momentum and angular momentum (the section's inertia J rotated with
it). The part linear in the elastic motion is taken by central differences in its amplitude, and it must equal the
modal acceleration's loads plus the new bilinear ones; without the bilinear ones it is far off.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from wecss.structure import (
    MATERIALS,
    MemberLine,
    Section,
    build_frame,
    craig_bampton,
    rigid_load_coordinates,
    stress_modes,
)

START, END = np.array([0.3, -0.2, 0.1]), np.array([2.1, 0.9, 0.8])
W0 = np.array([0.7, -1.1, 0.9])  # the frame's angular velocity at t = 0 [rad/s], body axes
ALPHA0 = np.array([-0.8, 0.5, 1.3])  # and its angular acceleration [rad/s^2]
RNG = np.random.default_rng(28)


def _frame_and_basis():
    line = MemberLine("m", START, END, Section.box(0.3, 0.5, 0.02), MATERIALS["S355"], 0.0, ())
    frame = build_frame([line], elements=4, points={"root": START, "tip": END})
    basis = craig_bampton(frame, "root", {"tip": "joint"}, n_modes=3)
    return frame, basis.basis


def _rotation(t: float) -> np.ndarray:
    """R(t) = exp([W0 t + ALPHA0 t^2 / 2]): body angular velocity W0 and acceleration ALPHA0 at t = 0 (the body
    rate of exp([phi]) is phi_dot - phi x phi_dot / 2 + ..., whose rate at phi = 0 is phi_ddot)."""
    return Rotation.from_rotvec(W0 * t + 0.5 * ALPHA0 * t**2).as_matrix()


def _derivative(f, h: float) -> np.ndarray:
    """f'(0) by the sixth-order central difference."""
    weights = {1: 45.0, 2: -9.0, 3: 1.0}
    return sum(w * (f(k * h) - f(-k * h)) for k, w in weights.items()) / (60.0 * h)


def _second_derivative(f, h: float) -> np.ndarray:
    """f''(0) by the sixth-order central difference."""
    weights = {0: -490.0, 1: 270.0, 2: -27.0, 3: 2.0}
    return (weights[0] * f(0.0) + sum(w * (f(k * h) + f(-k * h)) for k, w in list(weights.items())[1:])) / (
        180.0 * h**2
    )


def _oracle_element_loads(group, phi, xi_of_t) -> np.ndarray:
    """(12,) d'Alembert loads on the element's DOFs at t = 0 (body axes = world axes there) from the world motion
    of its mass points and sections, less the mass points' loads of the rigid motion R(t) X (no elastic part)."""
    field = phi[group.dofs]
    out = np.zeros(len(group.dofs))
    for p in range(len(group.masses)):
        nu, nt = group.nu[p], group.ntheta[p]

        def moved(t, nu=nu):  # R(t) u(t): the point's position R(t) (X + u(t)) less R(t) X, which is even in the
            return _rotation(t) @ (nu @ field @ xi_of_t(t))  # amplitude (kept apart: no round-off of X in the odd part)

        def section(t, nt=nt):
            return _rotation(t) @ Rotation.from_rotvec(nt @ field @ xi_of_t(t)).as_matrix()

        def momentum(t, p=p):
            turn = section(t)
            spin = _derivative(section, 1e-4) if t == 0.0 else _derivative(lambda s: section(t + s), 1e-4)
            w = spin @ turn.T
            omega = np.array([w[2, 1], w[0, 2], w[1, 0]])
            return turn @ group.inertias[p] @ turn.T @ omega

        force = -group.masses[p] * _second_derivative(moved, 1e-2)
        moment = -_derivative(momentum, 1e-2)
        out += nu.T @ force + nt.T @ moment
    return out


def test_elastic_motion_loads_equal_those_of_the_world_kinematics():
    frame, phi = _frame_and_basis()
    n = phi.shape[1]
    scale = 1.0 / np.abs(phi).max()  # modal coordinates moving the structure by up to about a metre per unit
    xi0, xi1, xi2 = (scale * RNG.standard_normal(n) for _ in range(3))
    modes = stress_modes(frame, phi)
    groups = frame.mass_points

    def linear_part(element_index):
        """The oracle's loads linear in the elastic amplitude, by central differences in it (Richardson: O(e^4))."""

        def loads(eps):
            return _oracle_element_loads(groups[element_index], phi, lambda t: eps * (xi0 + xi1 * t + 0.5 * xi2 * t**2))

        def central(eps):
            return (loads(eps) - loads(-eps)) / (2 * eps)

        return (4 * central(1e-3) - central(2e-3)) / 3

    rigid = rigid_load_coordinates(np.zeros(3), ALPHA0, W0)
    predicted = (
        np.einsum("sjn,n->sj", modes.section_acceleration, xi2)
        + np.einsum("sjcn,c,n->sj", modes.section_motion, rigid[3:], xi0)
        + np.einsum("sjcn,c,n->sj", modes.section_coriolis, W0, xi1)
    )
    without = np.einsum("sjn,n->sj", modes.section_acceleration, xi2)
    elements = frame.members()["m"]
    index = {id(e): k for k, e in enumerate(frame.elements)}
    expected = []
    for e in elements:  # the load of the part beyond a cut at each element's first node, local axes
        expected.append((e.transform @ linear_part(index[id(e)]))[:6])
    last = elements[-1]  # and at the member's end: what the last element carries into its end node, reversed
    expected.append(-(last.transform @ linear_part(index[id(last)]))[6:])
    expected = np.array(expected)
    assert [s for _, s in modes.stations] == pytest.approx(
        [e.station for e in elements] + [np.linalg.norm(END - START)]
    )
    scale_of = np.abs(expected).max()
    np.testing.assert_allclose(predicted, expected, rtol=0, atol=1e-8 * scale_of)
    assert np.abs(without - expected).max() > 0.1 * scale_of  # the bilinear terms matter here


def test_stresses_carry_the_section_loads_of_the_motion_and_need_both_rates_and_omega():
    frame, phi = _frame_and_basis()
    modes = stress_modes(frame, phi)
    n = phi.shape[1]
    # elastic coordinates small enough that the inertia loads are not lost beside the elastic forces
    q, q_dot, q_ddot = (1e-7 * RNG.standard_normal((5, n)) for _ in range(3))
    omega = RNG.standard_normal((5, 3))
    rigid = rigid_load_coordinates(RNG.standard_normal((5, 3)), RNG.standard_normal((5, 3)), omega)
    loads = modes.section_loads(q, q_ddot, rigid, q_dot, omega)  # (5, n_station, 6)
    section = frame.elements[0].section
    station = {key: k for k, key in enumerate(modes.stations)}
    normal, shear = [], []
    for p in modes.points:
        n_, _, _, t_, my, mz = np.moveaxis(loads[:, station[(p.member, p.station)]], -1, 0)
        normal.append(n_ / section.area + my * p.z / section.iy - mz * p.y / section.iz)
        shear.append(t_ / section.wt)
    stresses = modes.stresses(q, q_ddot, rigid, q_dot, omega)
    normal, shear = np.array(normal).T, np.array(shear).T
    np.testing.assert_allclose(stresses["normal"], normal, rtol=0, atol=1e-12 * np.abs(normal).max())
    np.testing.assert_allclose(stresses["shear"], shear, rtol=0, atol=1e-12 * np.abs(shear).max())
    coriolis = modes.stresses(q, q_ddot, rigid, q_dot, omega)["normal"] - modes.stresses(q, q_ddot, rigid)["normal"]
    inertia = modes.stresses(q, q_ddot, rigid)["normal"] - modes.stresses(q, None, rigid)["normal"]
    assert np.abs(coriolis).max() > 0.1 * np.abs(inertia).max()  # of the modal accelerations' order here
    still = modes.stresses(q, q_ddot, rigid, motion=False)["normal"]  # a frozen body's quasi-static response
    cut = modes.section_loads(q, q_ddot, rigid, motion=False)
    expected_still = np.array([
        cut[:, station[(p.member, p.station)], 0] / section.area
        + cut[:, station[(p.member, p.station)], 4] * p.z / section.iy
        - cut[:, station[(p.member, p.station)], 5] * p.y / section.iz
        for p in modes.points
    ]).T  # fmt: skip
    np.testing.assert_allclose(still, expected_still, rtol=0, atol=1e-12 * np.abs(expected_still).max())
    turning = modes.stresses(q, q_ddot, rigid)["normal"] - still
    assert np.abs(turning).max() > 0.1 * np.abs(inertia).max()
    with pytest.raises(
        ValueError, match="both the modal rates q_dot and the frame's angular velocity omega; got q_dot"
    ):
        modes.stresses(q, q_ddot, rigid, q_dot)
    with pytest.raises(ValueError, match="got omega alone"):
        modes.section_loads(q, omega=omega)
