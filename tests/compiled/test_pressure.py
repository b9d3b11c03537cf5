"""The per-step pressure force on a mesh (wecss.compiled._pressure) and the linear Froude-Krylov force
(wecss.compiled._froude_krylov), against closed forms.

References: a wall-sided box (its wet part is a prism cut by a plane: volume and centroid by exact polynomial
integrals), a sphere (spherical caps), a vertical cylinder in deep water (Bessel functions), and the linear force
for the per-step kernel in small waves.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.spatial.transform import Rotation
from scipy.special import j1

from tests.hydro.meshes import box_mesh, sphere_mesh
from wecss.compiled._froude_krylov import linear_froude_krylov
from wecss.compiled._pressure import DRY, SUBMERGED, mesh_arrays, mesh_pressure_force
from wecss.compiled._wave_field import calm_field, field_arrays
from wecss.hydro.bem import AxisymmetricProfile
from wecss.hydro.mesh import revolve_profile
from wecss.waves import WaveComponents, wavenumber

RHO, G = 1025.0, 9.80665

# Tolerances of issue 26 (not to be loosened).
BOX_RTOL = 1e-12
SPHERE_RTOL = 1e-3  # of rho g V0, and of rho g V0 times the lever for the moment
FK_RTOL = 3e-3

BOX_LOWER, BOX_UPPER = np.array([-1.0, -0.6, -0.8]), np.array([1.4, 0.7, 0.5])


def _box_closed_form(pos: np.ndarray, rot: np.ndarray) -> tuple[float, np.ndarray]:
    """Volume and world centroid of the box's part below z = 0 while the plane cuts only its walls.

    In the body frame the wet part is {z_b < z < h(x, y)} over the box's rectangle, with the plane
    h = h0 + hx x + hy y from e . r + p_z = 0 (e the third row of the rotation): polynomial integrals over the
    rectangle, written out from the moments int x^p y^q dx dy."""
    e = rot[2]
    assert e[2] > 0
    h0, hx, hy = -pos[2] / e[2], -e[0] / e[2], -e[1] / e[2]
    (x0, y0, zb), (x1, y1, zt) = BOX_LOWER, BOX_UPPER
    corners = [h0 + hx * x + hy * y for x in (x0, x1) for y in (y0, y1)]
    assert zb < min(corners) and max(corners) < zt, "pose outside the wall-sided range"

    def m(p: int, q: int) -> float:
        return (x1 ** (p + 1) - x0 ** (p + 1)) / (p + 1) * (y1 ** (q + 1) - y0 ** (q + 1)) / (q + 1)

    c0 = h0 - zb
    volume = c0 * m(0, 0) + hx * m(1, 0) + hy * m(0, 1)
    first_x = c0 * m(1, 0) + hx * m(2, 0) + hy * m(1, 1)
    first_y = c0 * m(0, 1) + hx * m(1, 1) + hy * m(0, 2)
    first_z = 0.5 * (
        (h0**2 - zb**2) * m(0, 0)
        + hx**2 * m(2, 0)
        + hy**2 * m(0, 2)
        + 2 * h0 * hx * m(1, 0)
        + 2 * h0 * hy * m(0, 1)
        + 2 * hx * hy * m(1, 1)
    )
    return volume, pos + rot @ (np.array([first_x, first_y, first_z]) / volume)


BOX_POSES = [  # (position of the centre of mass, Euler angles xyz [deg])
    ((0.3, -0.2, 0.0), (0, 0, 0)),
    ((0.3, -0.2, 0.2), (0, 0, 0)),
    ((0.3, -0.2, -0.3), (0, 0, 0)),
    ((0.3, -0.2, 0.0), (10, 0, 0)),
    ((0.3, -0.2, 0.0), (0, 12, 0)),
    ((0.0, 0.0, 0.1), (0, -9, 0)),
    ((-0.4, 1.0, 0.1), (8, -9, 30)),
    ((2.0, 0.5, -0.15), (-12, 7, -70)),
    ((0.3, -0.2, 0.05), (15, 0, 180)),
]


@pytest.mark.parametrize("surface_mode", [0, 1])
def test_wall_sided_box_exact(surface_mode: int) -> None:
    """Force rho g V e_z, moment (c_B - p) x F and the displaced volume's centroid to 1e-12 at heave offsets,
    heel and pitch angles and combined poses, in calm water (either surface mode)."""
    mesh = box_mesh(BOX_LOWER, BOX_UPPER)
    arrays = mesh_arrays(mesh)
    field = calm_field(rho=RHO, g=G)
    out = np.zeros(6)
    size = float(np.linalg.norm(BOX_UPPER - BOX_LOWER))
    for position, angles in BOX_POSES:
        pos = np.array(position, dtype=float)
        rot = Rotation.from_euler("xyz", angles, degrees=True).as_matrix()
        volume, centroid = _box_closed_form(pos, rot)
        force = np.array([0.0, 0.0, RHO * G * volume])
        moment = np.cross(centroid - pos, force)
        flags = mesh_pressure_force(arrays, rot, pos, field, 0.0, surface_mode, False, RHO, G, out, 0)
        assert flags == 0
        scale = RHO * G * volume
        np.testing.assert_allclose(out[:3], force, rtol=0, atol=BOX_RTOL * scale)
        np.testing.assert_allclose(out[3:], moment, rtol=0, atol=BOX_RTOL * scale * size)
        d = mesh.displaced(pos, rot)
        assert d.volume == pytest.approx(volume, rel=BOX_RTOL)
        np.testing.assert_allclose(d.center_of_buoyancy, centroid, rtol=0, atol=BOX_RTOL * size)


def test_box_flags_dry_and_submerged() -> None:
    arrays = mesh_arrays(box_mesh(BOX_LOWER, BOX_UPPER))
    field = calm_field()
    out = np.full(6, np.nan)
    assert (
        mesh_pressure_force(arrays, np.eye(3), np.array([0.0, 0.0, 0.9]), field, 0.0, 0, False, RHO, G, out, 0) == DRY
    )
    np.testing.assert_array_equal(out, 0.0)
    pos = np.array([0.0, 0.0, -0.6])
    assert mesh_pressure_force(arrays, np.eye(3), pos, field, 0.0, 0, False, RHO, G, out, 0) == SUBMERGED
    volume = float(np.prod(BOX_UPPER - BOX_LOWER))
    centroid = pos + (BOX_LOWER + BOX_UPPER) / 2
    np.testing.assert_allclose(out[:3], [0, 0, RHO * G * volume], rtol=0, atol=BOX_RTOL * RHO * G * volume)
    np.testing.assert_allclose(out[3:], np.cross(centroid - pos, out[:3]), rtol=0, atol=BOX_RTOL * RHO * G * volume * 2)


def test_sphere_heave_force_and_pitch_moment() -> None:
    """A sphere of radius R (2,016 triangles) with its centre of gravity a below the centre, at centre depths s
    over the whole range [-R, R] and pitch angles theta: the wet volume below z = 0 is the cap
    V(s) = pi (R^2 s - s^3 / 3) + V0 (V0 = 2 pi R^3 / 3, the half sphere; equivalently pi d^2 (3R - d) / 3 for
    the immersion d = R + s of the lowest point), the force is rho g V(s) e_z through the sphere's centre, and
    the pitch moment about the centre of gravity is -a sin(theta) rho g V(s). Errors within 1e-3 of rho g V0
    (and of rho g V0 a for the moment); measured 7.3e-5 and 5.8e-5."""
    radius, lever = 5.0, 2.0
    arrays = mesh_arrays(sphere_mesh(radius, center=(0.0, 0.0, lever)))
    field = calm_field()
    v0 = 2 / 3 * math.pi * radius**3
    out = np.zeros(6)
    worst_force = worst_moment = 0.0
    for theta in (0.0, 0.3, -0.7, 1.2):
        rot = Rotation.from_euler("y", theta).as_matrix()
        for s in np.linspace(-radius, radius, 81):
            pos = np.array([0.0, 0.0, -s]) - rot @ np.array([0.0, 0.0, lever])
            mesh_pressure_force(arrays, rot, pos, field, 0.0, 0, False, RHO, G, out, 0)
            buoyancy = RHO * G * (math.pi * (radius**2 * s - s**3 / 3) + v0)
            worst_force = max(worst_force, abs(out[2] - buoyancy) / (RHO * G * v0))
            worst_moment = max(worst_moment, abs(out[4] + lever * math.sin(theta) * buoyancy) / (RHO * G * v0 * lever))
            assert max(abs(out[0]), abs(out[1]), abs(out[3]), abs(out[5])) <= 1e-12 * RHO * G * v0 * radius
    assert worst_force <= SPHERE_RTOL
    assert worst_moment <= SPHERE_RTOL


# --- Froude-Krylov -----------------------------------------------------------------------------------------------

CYLINDER = AxisymmetricProfile(5.0, 6.0, "flat")


def _cylinder():
    return revolve_profile(CYLINDER, 2.0, center_of_mass_z=-2.0, sectors=48)


def test_linear_froude_krylov_of_a_vertical_cylinder() -> None:
    """Deep water, a wave Re[A exp(i (omega t - k x))] on a vertical cylinder of radius a and draft T (48
    sectors): the incident pressure rho g A e^{kz} e^{-ikx} gives

    heave  F3 = rho g A e^{-kT} int_disc e^{-ikx} dA = rho g A e^{-kT} 2 pi a J1(ka) / k,
    surge  F1 = -rho g A int_{-T}^0 e^{kz} dz int_0^{2 pi} e^{-ika cos phi} cos phi a dphi
              = rho g A 2 pi i a J1(ka) (1 - e^{-kT}) / k,

    within 3e-3 (measured below 1e-6 up to ka = 4.6)."""
    omega = np.linspace(0.3, 3.0, 12)
    amplitude = 0.5 * np.exp(1j * np.linspace(0.0, 3.0, omega.size))
    sea = WaveComponents(omega, amplitude)
    k = wavenumber(omega, math.inf, G)
    a, draft = CYLINDER.radius, CYLINDER.draft
    force = linear_froude_krylov(_cylinder(), [0.0, 0.0, -2.0], np.eye(3), sea, rho=RHO, g=G)
    heave = RHO * G * amplitude * np.exp(-k * draft) * 2 * math.pi * a * j1(k * a) / k
    surge = RHO * G * amplitude * 2j * math.pi * a * j1(k * a) * (1 - np.exp(-k * draft)) / k
    assert np.max(np.abs(force[:, 2] / heave - 1)) <= FK_RTOL
    assert np.max(np.abs(force[:, 0] / surge - 1)) <= FK_RTOL
    assert np.max(np.abs(force[:, [1, 3, 5]])) <= 1e-6 * np.max(np.abs(surge))  # symmetry, to rounding


def test_per_step_froude_krylov_tends_to_the_linear_force() -> None:
    """The per-step kernel's Froude-Krylov force (surface mode 0: the wet surface is the mesh below z = 0) minus
    its hydrostatic force, in a regular wave of small amplitude A, against Re[F exp(i omega t)] of
    ``linear_froude_krylov``: the difference is of second order (it falls tenfold with A) and below 3e-3 of |F|
    at kA = 4e-4."""
    mesh = _cylinder()
    arrays = mesh_arrays(mesh)
    pos, rot = np.array([0.0, 0.0, -2.0]), np.eye(3)
    still, wavy = np.zeros(6), np.zeros(6)
    omega = 1.0
    errors = []
    for amp in (1e-2, 1e-3):
        sea = WaveComponents([omega], [amp * np.exp(0.4j)])
        linear = linear_froude_krylov(mesh, pos, rot, sea, rho=RHO, g=G)[0]
        field = field_arrays(sea, rho=RHO, g=G)
        error = np.zeros(6)
        for t in np.linspace(0.0, 2 * math.pi / omega, 9)[:-1]:
            mesh_pressure_force(arrays, rot, pos, field, t, 0, False, RHO, G, still, 0)
            mesh_pressure_force(arrays, rot, pos, field, t, 0, True, RHO, G, wavy, 0)
            error = np.maximum(error, np.abs(wavy - still - (linear * np.exp(1j * omega * t)).real))
        errors.append(error[[0, 2, 4]] / np.abs(linear[[0, 2, 4]]))
    assert np.all(errors[1] <= FK_RTOL)
    ratio = errors[1] / errors[0]
    assert np.all((ratio > 0.08) & (ratio < 0.12)), ratio
