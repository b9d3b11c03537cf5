"""The 3D frame element against closed forms: cantilever bending frequencies (beta_n L) in both planes of a box
section and along an oblique member, their h^4 convergence, pinned-pinned bending, axial and torsional rods
((2n - 1) pi / (2 L) sqrt(...)), static tip load, tip slope and self weight, the Timoshenko tip deflection."""

from __future__ import annotations

import numpy as np
import pytest

from wecss.structure import (
    Material,
    MemberLine,
    Section,
    build_frame,
    member_axes,
    natural_modes,
    shape_functions,
    static_response,
)

E, RHO, L = 2.1e11, 7850.0, 2.0
STEEL = Material("steel", E, E / 2.6, RHO)
BOX = Section.box(0.12, 0.2, 0.006)  # Iz (bending in y) about 0.44 Iy (bending in z): the planes do not mix
TUBE = Section.tube(0.1, 0.005)
BETA_L = np.array([1.87510407, 4.69409113, 7.85475744, 10.99554073])  # cantilever: cos(bL) cosh(bL) = -1
TOLERANCES = np.array([1e-7, 1e-6, 1e-5, 3e-5])


def _beam(n: int, section: Section = BOX, direction=(1.0, 0.0, 0.0), start=(0.0, 0.0, 0.0), **kw):  # type: ignore[no-untyped-def]
    d = np.asarray(direction, dtype=float) / np.linalg.norm(direction)
    s0 = np.asarray(start, dtype=float)
    kw.setdefault("rotary_inertia", False)  # the Euler-Bernoulli closed forms have no rotary inertia
    return build_frame([MemberLine("b", s0, s0 + L * d, section, STEEL)], elements=n, **kw)


def _along(shapes: np.ndarray, omega: np.ndarray, vector: np.ndarray) -> np.ndarray:
    """Frequencies of the modes whose nodal translations are along ``vector`` (bending in one plane)."""
    out = []
    for k in range(shapes.shape[1]):
        u = shapes[:, k].reshape(-1, 6)
        translation = np.sum(u[:, :3] ** 2)
        if translation > 1e-6 * np.sum(u**2) and np.sum((u[:, :3] @ vector) ** 2) > 0.99 * translation:
            out.append(omega[k])
    return np.array(out)


def _cantilever_errors(n: int, direction=(1.0, 0.0, 0.0), start=(0.0, 0.0, 0.0)) -> dict[str, np.ndarray]:  # type: ignore[no-untyped-def]
    frame = _beam(n, direction=direction, start=start)
    omega, shapes = natural_modes(frame.stiffness, frame.mass, fixed=frame.node_dofs(0), n_modes=14)
    axes = member_axes(frame.nodes[0], frame.nodes[-1])
    out = {}
    for plane, vector, inertia in (("z", axes[2], BOX.iy), ("y", axes[1], BOX.iz)):
        exact = BETA_L**2 * np.sqrt(E * inertia / (RHO * BOX.area * L**4))
        out[plane] = _along(shapes, omega, vector)[:4] / exact - 1
    return out


@pytest.mark.parametrize(
    ("direction", "start"), [((1.0, 0.0, 0.0), (0.0, 0.0, 0.0)), ((1.0, 2.0, 2.0), (0.3, -0.2, 0.5))]
)
def test_cantilever_frequencies_in_both_planes_with_32_elements(direction, start):
    errors = _cantilever_errors(32, direction, start)
    for plane in ("y", "z"):
        assert errors[plane].shape == (4,)
        assert np.all(np.abs(errors[plane]) < TOLERANCES), (plane, errors[plane])
        assert np.all(errors[plane][:3] > 0)  # the consistent mass bounds from above (the 1st: to 7e-9)


def test_cantilever_frequencies_converge_at_h4():
    """Observed order of the error of the first two bending frequencies from 4 to 8 to 16 elements."""
    errs = np.array([_cantilever_errors(n)["z"][:2] for n in (4, 8, 16)])
    order = np.log2(errs[:-1] / errs[1:])
    assert np.all((order > 3.8) & (order < 4.2)), order


def _planar(frame, keep: tuple[int, ...]) -> list[int]:  # type: ignore[no-untyped-def]
    """All DOFs but the ``keep`` components of every node."""
    return [int(d) for k in range(frame.n_nodes) for j, d in enumerate(frame.node_dofs(k)) if j not in keep]


def _pinned_pinned_errors(n: int) -> np.ndarray:
    frame = _beam(n)
    last = frame.n_nodes - 1
    fixed = [*_planar(frame, (2, 4)), int(frame.node_dofs(0)[2]), int(frame.node_dofs(last)[2])]
    omega, _ = natural_modes(frame.stiffness, frame.mass, fixed=fixed, n_modes=3)
    exact = (np.arange(1, 4) * np.pi) ** 2 * np.sqrt(E * BOX.iy / (RHO * BOX.area * L**4))
    return omega / exact - 1


def test_pinned_pinned_bending():
    """(n pi)^2 sqrt(EI / (rho A L^4)), modes 1-3 within 1e-6: 32 elements give 6.4e-8, 1.0e-6, 5.2e-6, so 64
    (4.1e-9, 6.4e-8, 3.3e-7); from 32 to 64 the errors fall 16 times (h^4)."""
    coarse, fine = _pinned_pinned_errors(32), _pinned_pinned_errors(64)
    assert 0 < coarse[0] < 1e-6
    assert np.all((fine > 0) & (fine < 1e-6)), fine
    order = np.log2(coarse / fine)
    assert np.all(np.abs(order - 4) < 0.05), order


@pytest.mark.parametrize(("component", "speed"), [(0, np.sqrt(E / RHO)), (3, None)])
def test_axial_rod_and_torsion_shaft_fixed_free(component, speed):
    """Linear elements with consistent mass: (2n - 1) pi / (2 L) sqrt(E / rho) along, sqrt(G J / (rho Ip)) in
    torsion; 100 elements put the first two modes within 1e-4 (1.0e-5 and 9.3e-5)."""
    frame = _beam(100)
    if speed is None:
        speed = np.sqrt(STEEL.shear_modulus * BOX.torsion_constant / (RHO * BOX.polar))
    fixed = [int(d) for d in frame.node_dofs(0)] + _planar(frame, (component,))
    omega, _ = natural_modes(frame.stiffness, frame.mass, fixed=fixed, n_modes=2)
    exact = (2 * np.arange(1, 3) - 1) * np.pi / (2 * L) * speed
    assert np.all(np.abs(omega / exact - 1) < 1e-4)


@pytest.mark.parametrize("direction", [(1.0, 0.0, 0.0), (0.0, 0.0, 1.0), (1.0, -2.0, 2.0)])
def test_static_tip_load_slope_and_self_weight(direction):
    frame = _beam(4, TUBE, direction, points={"tip": L * np.asarray(direction) / np.linalg.norm(direction)})
    axes = member_axes(frame.nodes[0], frame.nodes[-1])
    ei, p = E * TUBE.iy, 1234.0
    u = static_response(frame.stiffness, frame.point_load("tip", p * axes[2]), frame.node_dofs(0))
    tip = frame.point_map("tip") @ u
    assert tip[:3] @ axes[2] == pytest.approx(p * L**3 / (3 * ei), rel=1e-12)
    assert tip[3:] @ axes[1] == pytest.approx(-p * L**2 / (2 * ei), rel=1e-12)  # w' > 0 is a rotation about -y
    g = 9.81
    weight = frame.rigid_motion_loads(np.zeros(3))[:, :3] @ (-g * axes[2])  # g along -z_local: q = rho A g
    u = static_response(frame.stiffness, weight, frame.node_dofs(0))
    q = RHO * TUBE.area * g
    assert (frame.point_map("tip") @ u)[:3] @ axes[2] == pytest.approx(-q * L**4 / (8 * ei), rel=1e-12)


def test_timoshenko_tip_deflection_adds_the_shear_term():
    frame = _beam(3, TUBE, points={"tip": [L, 0.0, 0.0]}, theory="timoshenko")
    p = 1000.0
    u = static_response(frame.stiffness, frame.point_load("tip", [0.0, 0.0, p]), frame.node_dofs(0))
    shear = p * L / (STEEL.shear_modulus * TUBE.shear_area_z)
    assert (frame.point_map("tip") @ u)[2] == pytest.approx(p * L**3 / (3 * E * TUBE.iy) + shear, rel=1e-12)


def test_timoshenko_functions_have_constant_shear_strain_and_reduce_to_hermite():
    """dv/ds - theta is constant along the element (no load inside); at Phi = 0 the rotation is dv/ds."""
    length, phi = 0.7, 0.3
    gamma = [
        shape_functions(xi, length, phi, phi)[2][1] - shape_functions(xi, length, phi, phi)[1][2]
        for xi in (0.1, 0.5, 0.9)
    ]
    np.testing.assert_allclose(gamma[0], gamma[1], atol=1e-14)
    np.testing.assert_allclose(gamma[0], gamma[2], atol=1e-14)
    _nu, nth, dnu, _ = shape_functions(0.37, length)
    np.testing.assert_allclose(nth[2], dnu[1], atol=1e-14)
    np.testing.assert_allclose(nth[1], -dnu[2], atol=1e-14)


def _timoshenko_pinned_pinned(n: int, section: Section) -> np.ndarray:
    frame = build_frame(
        [MemberLine("b", np.zeros(3), np.array([1.0, 0.0, 0.0]), section, STEEL)], elements=n, theory="timoshenko"
    )
    last = frame.n_nodes - 1
    fixed = [*_planar(frame, (2, 4)), int(frame.node_dofs(0)[2]), int(frame.node_dofs(last)[2])]
    omega, _ = natural_modes(frame.stiffness, frame.mass, fixed=fixed, n_modes=3)
    return omega


def test_timoshenko_pinned_pinned_frequencies_of_a_stocky_beam():
    """L / h = 5: the frequency equation of the simply supported Timoshenko beam (rotary inertia and shear,
    kappa A = the shear area), EI k^4 - rho A w^2 - rho I w^2 k^2 (1 + E / (kappa G)) + rho^2 I w^4 / (kappa G) = 0,
    k = n pi / L, its lower root; Euler-Bernoulli would be 12 % to 76 % high. The element's shear strain is constant,
    so the error falls as h^2: 1.7e-5, 1.7e-4, 5.3e-4 with 64 elements."""
    section = Section.box(0.12, 0.2, 0.01)
    g, kappa = STEEL.shear_modulus, section.shear_area_z / section.area
    exact = []
    for n in (1, 2, 3):
        k = n * np.pi / 1.0
        coefficients = [
            RHO**2 * section.iy / (kappa * g),
            -(RHO * section.area + RHO * section.iy * k**2 * (1 + E / (kappa * g))),
            E * section.iy * k**4,
        ]
        exact.append(np.sqrt(np.min(np.roots(coefficients))))
    errors = np.array([_timoshenko_pinned_pinned(n, section) / exact - 1 for n in (16, 32, 64)])
    assert np.all(errors > 0) and np.all(errors[-1] < [2e-5, 2e-4, 6e-4])
    order = np.log2(errors[:-1] / errors[1:])
    assert np.all(np.abs(order - 2) < 0.05), order
