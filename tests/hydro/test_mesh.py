"""Surface meshes (wecss.hydro.mesh): STL files, the checks, revolved floats, the displaced volume, and meshes
against hydrodynamic databases.

References: closed forms of the profiles (``AxisymmetricProfile``, integrated on the true curves), of a box and of
the sphere; the shipped M4 database and the OES sphere's BEMIO file in ../shared/data (skipped when absent).
"""

from __future__ import annotations

import math
import re
import warnings
from pathlib import Path

import numpy as np
import pytest

from tests.hydro.meshes import box_mesh, sphere_mesh
from wecss.hydro import HydroData
from wecss.hydro.bem import AxisymmetricProfile, read_geometry
from wecss.hydro.mesh import (
    MeshError,
    SurfaceMesh,
    read_stl,
    revolve_profile,
    write_stl,
)

ROOT = Path(__file__).parents[2]
SHARED = ROOT.parent / "shared" / "data"
OES_STL = SHARED / "oes-sphere" / "oes_task10_sphere.stl"
OES_H5 = SHARED / "oes-sphere" / "sphere.h5"
M4_DATABASE = ROOT / "wecss" / "data" / "hydro" / "m4-111.nc"
M4_GEOMETRY = ROOT / "wecss" / "data" / "hydro" / "m4-111.toml"
RHO, G = 1000.0, 9.81

# Tolerances of issue 26 (not to be loosened).
EXACT = 1e-12
VOLUME_RTOL = 1e-4
STIFFNESS_RTOL = 1e-3

PROFILES = [
    AxisymmetricProfile(0.1, 0.0746, "flat"),
    AxisymmetricProfile(0.125, 0.1499, "hemispherical"),
    AxisymmetricProfile(0.175, 0.2143, "rounded", fillet_radius=0.125),
    AxisymmetricProfile(2.0, 3.0, "conical", cone_height=1.2),
    AxisymmetricProfile(3.0, 3.0, "hemispherical"),
    AxisymmetricProfile(1.0, 0.8, "rounded", fillet_radius=0.3),
]


# --- STL ---------------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("binary", [True, False])
def test_stl_round_trip(tmp_path: Path, binary: bool) -> None:
    mesh = box_mesh([-1.0, -0.6, -0.8], [1.4, 0.7, 0.5])
    path = tmp_path / ("box_b.stl" if binary else "box_a.stl")
    write_stl(path, mesh.triangles, binary=binary)
    triangles = read_stl(path)
    # binary STL stores float32; ASCII writes 17 significant digits
    expected = mesh.triangles.astype(np.float32).astype(float) if binary else mesh.triangles
    np.testing.assert_array_equal(triangles, expected)
    back = SurfaceMesh.from_stl(path, origin=(0.1, 0.0, -0.2))
    assert back.n_faces == mesh.n_faces
    assert back.vertices.shape == mesh.vertices.shape
    assert back.name == str(path)
    assert back.enclosed_volume == pytest.approx(2.4 * 1.3 * 1.3, rel=1e-6 if binary else EXACT)
    # the origin shifts the body frame
    np.testing.assert_allclose(back.vertices.min(axis=0), [-1.1, -0.6, -0.6], atol=1e-6)


def test_stl_errors(tmp_path: Path) -> None:
    with pytest.raises(FileNotFoundError, match="no STL file"):
        read_stl(tmp_path / "absent.stl")
    junk = tmp_path / "junk.stl"
    junk.write_text("not an stl at all\n")
    with pytest.raises(MeshError, match=re.escape(str(junk)) + ".*neither a binary STL"):
        read_stl(junk)
    quad = tmp_path / "quad.stl"
    quad.write_text(
        "solid q\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nvertex 0 1 0\n"
        "endloop\nendfacet\nendsolid q\n"
    )
    with pytest.raises(MeshError, match="1 facets hold 4 vertices"):
        read_stl(quad)


# --- checks ------------------------------------------------------------------------------------------------------


def _box() -> SurfaceMesh:
    return box_mesh([-1.0, -0.6, -0.8], [1.4, 0.7, 0.5], divisions=(2, 2, 2))


def test_mesh_errors_name_the_mesh_and_the_problem() -> None:
    box = _box()
    v, f = box.vertices, box.faces
    with pytest.raises(MeshError, match=r"mesh 'hull A'.*not closed.*belong to one face only"):
        SurfaceMesh(v, f[1:], name="hull A")
    with pytest.raises(MeshError, match=r"mesh 'hull B'.*oriented inwards.*reverse the order"):
        SurfaceMesh(v, f[:, ::-1], name="hull B")
    flipped = f.copy()
    flipped[3] = flipped[3, ::-1]
    with pytest.raises(MeshError, match=r"mesh 'hull C'.*opposite orientation.*faces"):
        SurfaceMesh(v, flipped, name="hull C")
    repeated = f.copy()
    repeated[5, 2] = repeated[5, 0]
    with pytest.raises(MeshError, match=r"mesh 'hull D'.*degenerate faces repeat a vertex.*face 5"):
        SurfaceMesh(v, repeated, name="hull D")
    flat = v.copy()
    a, b, c = f[7]
    flat[c] = 0.5 * (flat[a] + flat[b])  # a face with no area (and its neighbours bent)
    with pytest.raises(MeshError, match=r"mesh 'hull E'.*degenerate faces have no area"):
        SurfaceMesh(flat, f, name="hull E")
    with pytest.raises(MeshError, match=r"mesh 'hull F'.*outside 0\.\."):
        SurfaceMesh(v, np.vstack([f, [[0, 1, 10_000]]]), name="hull F")
    with pytest.raises(MeshError, match=r"mesh 'hull G'.*non-manifold"):
        SurfaceMesh(v, np.vstack([f, f[:1]]), name="hull G")
    with pytest.raises(MeshError, match=r"mesh 'hull H'.*finite"):
        SurfaceMesh(np.where(np.arange(v.size).reshape(v.shape) == 4, np.nan, v), f, name="hull H")


def test_open_above_accepts_a_hull_open_at_its_top_only() -> None:
    box = _box()
    top = np.all(box.vertices[box.faces][:, :, 2] > 0.49, axis=1)
    open_top = box.faces[~top]
    with pytest.raises(MeshError, match="not closed"):
        SurfaceMesh(box.vertices, open_top)
    mesh = SurfaceMesh(box.vertices, open_top, open_above=0.5)
    assert mesh.enclosed_volume == pytest.approx(2.4 * 1.3 * 1.3, rel=EXACT)
    lower = SurfaceMesh(box.vertices, open_top, open_above=0.3)  # the volume below open_above
    assert lower.enclosed_volume == pytest.approx(2.4 * 1.3 * 1.1, rel=EXACT)
    with pytest.raises(MeshError, match=r"below open_above = 0.7 m"):  # the open rim (z = 0.5) is below 0.7
        SurfaceMesh(box.vertices, open_top, open_above=0.7)


# --- displaced volume --------------------------------------------------------------------------------------------


def test_box_displaced_volume_waterplane_and_stiffness_exact() -> None:
    """An upright box at a heave offset: closed forms of volume, centroid, waterplane and stiffness."""
    lo, hi = np.array([-1.0, -0.6, -0.8]), np.array([1.4, 0.7, 0.5])
    mesh = box_mesh(lo, hi)
    pos = np.array([0.3, -0.2, 0.17])
    d = mesh.displaced(pos)
    length, width = hi[:2] - lo[:2]
    draft = -(pos[2] + lo[2])
    assert d.volume == pytest.approx(length * width * draft, rel=EXACT)
    center = np.array([pos[0] + (lo[0] + hi[0]) / 2, pos[1] + (lo[1] + hi[1]) / 2, -draft / 2])
    np.testing.assert_allclose(d.center_of_buoyancy, center, rtol=0, atol=EXACT)
    assert d.waterplane_area == pytest.approx(length * width, rel=EXACT)
    np.testing.assert_allclose(d.waterplane_center, center[:2], rtol=0, atol=EXACT)
    np.testing.assert_allclose(
        d.waterplane_inertia, [length * width**3 / 12, width * length**3 / 12, 0.0], rtol=EXACT, atol=EXACT
    )
    assert d.wetted_area == pytest.approx(length * width + 2 * (length + width) * draft, rel=EXACT)
    k = d.stiffness(pos, rho=RHO, g=G)
    area, volume = length * width, length * width * draft
    xf, yf, zb = center - pos
    assert k[2, 2] == pytest.approx(RHO * G * area, rel=EXACT)
    assert k[2, 4] == pytest.approx(-RHO * G * area * xf, rel=EXACT)
    assert k[3, 3] == pytest.approx(RHO * G * (length * width**3 / 12 + area * yf**2 + volume * zb), rel=EXACT)
    assert k[4, 4] == pytest.approx(RHO * G * (width * length**3 / 12 + area * xf**2 + volume * zb), rel=EXACT)


def test_revolved_sphere_halves_exactly() -> None:
    """The volume-preserving sphere (even number of chords) displaces half its volume, exactly, at its centre's
    immersion 0; its whole volume is the sphere's."""
    radius = 5.0
    mesh = sphere_mesh(radius)
    assert mesh.n_faces == 2016
    assert mesh.enclosed_volume == pytest.approx(4 / 3 * math.pi * radius**3, rel=EXACT)
    d = mesh.displaced()
    assert d.volume == pytest.approx(2 / 3 * math.pi * radius**3, rel=EXACT)
    # the waterplane is the equator's 48-gon (its vertices pushed out to keep the volume): its shoelace area
    ring = mesh.vertices[np.abs(mesh.vertices[:, 2]) < 1e-12]
    assert ring.shape[0] == 48
    order = np.argsort(np.arctan2(ring[:, 1], ring[:, 0]))
    x, y = ring[order, 0], ring[order, 1]
    assert d.waterplane_area == pytest.approx(0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y), rel=EXACT)


# --- revolved floats ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize("profile", PROFILES, ids=lambda p: f"{p.bottom}-R{p.radius:g}")
@pytest.mark.parametrize("resolution", [(None, None), (1 / 3, 16), (1 / 10, 64)], ids=["default", "coarse", "fine"])
def test_revolve_profile_volume_and_waterplane_exact(profile: AxisymmetricProfile, resolution) -> None:
    share, sectors = resolution
    panel = None if share is None else share * profile.radius
    z_g = -0.3 * profile.draft
    mesh = revolve_profile(profile, 0.4 * profile.radius, center_of_mass_z=z_g, panel_size=panel, sectors=sectors)
    top = np.isclose(mesh.vertices[:, 2], 0.4 * profile.radius - z_g)
    n = int(np.count_nonzero(top)) - 1  # the top ring (one vertex per sector) and the top's centre
    assert sectors is None or n == sectors
    area = math.pi * profile.radius**2
    d = mesh.displaced([0.0, 0.0, z_g])
    assert d.volume == pytest.approx(profile.volume, rel=EXACT)
    assert d.waterplane_area == pytest.approx(area, rel=EXACT)
    theta = 2 * math.pi / n
    factor = (theta / math.sin(theta)) * (2 + math.cos(theta)) / 3  # second moment of an area-scaled n-gon
    np.testing.assert_allclose(d.waterplane_inertia[:2], factor * math.pi * profile.radius**4 / 4, rtol=EXACT)
    # on the wall, the volume changes by the waterplane area times the heave
    dz = 0.25 * min(profile.wall_height, 0.4 * profile.radius) if profile.wall_height > 0 else 0.1 * profile.radius
    if profile.wall_height > 0:
        up = mesh.displaced([0.0, 0.0, z_g + dz])
        assert up.volume == pytest.approx(profile.volume - area * dz, rel=EXACT)
    down = mesh.displaced([0.0, 0.0, z_g - dz])
    assert down.volume == pytest.approx(profile.volume + area * dz, rel=EXACT)
    # the whole closed float: the profile's volume plus the freeboard's cylinder
    assert mesh.enclosed_volume == pytest.approx(profile.volume + area * 0.4 * profile.radius, rel=EXACT)


# --- meshes against databases ------------------------------------------------------------------------------------

needs_oes = pytest.mark.skipif(not (OES_STL.exists() and OES_H5.exists()), reason="../shared/data/oes-sphere absent")
OES_RADIUS = 5.0
OES_CENTER_OF_MASS = np.array([0.0, 0.0, -2.0])


def _oes_database() -> HydroData:
    pytest.importorskip("h5py")
    with warnings.catch_warnings():  # it drops a few frequencies at the end of its range, which is not used here
        warnings.simplefilter("ignore")
        return HydroData.from_bemio(OES_H5)


@needs_oes
def test_oes_stl_hydrostatics_exact_for_its_facets() -> None:
    """The shipped STL (vertices on the sphere, equator at z = 0): at the database's pose it displaces half its
    enclosed volume (it is symmetric about the equator) and its waterplane is its equator's polygon."""
    mesh = SurfaceMesh.from_stl(OES_STL, origin=OES_CENTER_OF_MASS)
    d = mesh.displaced(OES_CENTER_OF_MASS)
    assert d.volume == pytest.approx(mesh.enclosed_volume / 2, rel=EXACT)
    ring = mesh.vertices[np.abs(mesh.vertices[:, 2] - 2.0) < 1e-9]
    order = np.argsort(np.arctan2(ring[:, 1], ring[:, 0]))
    x, y = ring[order, 0], ring[order, 1]
    assert d.waterplane_area == pytest.approx(0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y), rel=EXACT)


@needs_oes
def test_oes_database_stiffness_against_an_exact_sphere_mesh() -> None:
    """A sphere mesh whose displaced volume and waterplane are the sphere's (tests.hydro.meshes.sphere_mesh)
    against sphere.h5: heave and pitch stiffness within 1e-3 (measured: +1.1e-4 and -1.9e-4)."""
    hydro = _oes_database()
    mesh = sphere_mesh(OES_RADIUS, center=-OES_CENTER_OF_MASS)
    comparison = mesh.compare_with(hydro, "sphere")
    for dof in ("Heave", "Pitch"):
        assert abs(comparison.stiffness_difference[dof]) <= STIFFNESS_RTOL, str(comparison)
    # the mesh against the closed forms: K33 = rho g pi R^2, K55 = rho g (pi R^4 / 4 + V0 (z_B - z_G))
    volume = 2 / 3 * math.pi * OES_RADIUS**3
    heave = RHO * G * math.pi * OES_RADIUS**2
    pitch = RHO * G * (math.pi * OES_RADIUS**4 / 4 + volume * (-3 * OES_RADIUS / 8 + 2.0))
    assert comparison.stiffness["Heave"][0] == pytest.approx(heave, rel=EXACT)
    assert comparison.stiffness["Pitch"][0] == pytest.approx(pitch, rel=STIFFNESS_RTOL)
    assert comparison.volume[0] == pytest.approx(volume, rel=EXACT)


@needs_oes
@pytest.mark.xfail(
    strict=True,
    reason="sphere.h5's displaced volume (261.724 m^3) is itself 2.9e-4 below the sphere's (261.799 m^3): the "
    "database misses the 1e-4 target against the exact geometry",
)
def test_oes_database_volume_against_an_exact_sphere_mesh() -> None:
    comparison = sphere_mesh(OES_RADIUS, center=-OES_CENTER_OF_MASS).compare_with(_oes_database(), "sphere")
    assert abs(comparison.volume_difference) <= VOLUME_RTOL, str(comparison)


@needs_oes
@pytest.mark.xfail(
    strict=True,
    reason="the shipped STL (8,064 triangles, vertices on the sphere) is coarse for hydrostatics: displaced volume "
    "-1.9e-3, heave stiffness -1.5e-3, pitch -2.7e-3 against sphere.h5 (targets 1e-4 and 1e-3)",
)
def test_oes_stl_against_database() -> None:
    mesh = SurfaceMesh.from_stl(OES_STL, origin=OES_CENTER_OF_MASS)
    comparison = mesh.compare_with(_oes_database(), "sphere")
    assert comparison.agrees(), comparison.disagreements()


def _m4() -> tuple[HydroData, list]:
    spec = read_geometry(M4_GEOMETRY)
    return HydroData.from_netcdf(M4_DATABASE), list(spec.bodies)


def test_m4_floats_against_database() -> None:
    """The revolved M4 floats (freeboard 5 cm) against m4-111.nc: displaced volume within 1e-4, heave stiffness
    within 1e-3; pitch stiffness against the closed form of the profile within 1e-3."""
    hydro, bodies = _m4()
    for body in bodies:
        profile = body.profile
        mesh = revolve_profile(profile, 0.05, center_of_mass_z=body.center_of_mass_z)
        comparison = mesh.compare_with(hydro, body.name)
        assert abs(comparison.volume_difference) <= VOLUME_RTOL, str(comparison)
        assert abs(comparison.stiffness_difference["Heave"]) <= STIFFNESS_RTOL, str(comparison)
        exact_pitch = (
            RHO
            * G
            * (
                math.pi * profile.radius**4 / 4
                + profile.volume * (profile.center_of_buoyancy_z - body.center_of_mass_z)
            )
        )
        assert comparison.stiffness["Pitch"][0] == pytest.approx(exact_pitch, rel=STIFFNESS_RTOL)


@pytest.mark.xfail(
    strict=True,
    reason="m4-111.nc's pitch stiffness is Capytaine's (panel-centroid quadrature of the waterplane moments on the "
    "BEM hull): 5.8e-3, 4.3e-3 and 3.6e-3 below the exact value of the floats' profiles, which the revolved "
    "meshes reproduce within 4e-4",
)
def test_m4_pitch_stiffness_against_database() -> None:
    hydro, bodies = _m4()
    for body in bodies:
        mesh = revolve_profile(body.profile, 0.05, center_of_mass_z=body.center_of_mass_z)
        comparison = mesh.compare_with(hydro, body.name)
        assert abs(comparison.stiffness_difference["Pitch"]) <= STIFFNESS_RTOL, str(comparison)


def test_compare_with_names_an_unknown_body() -> None:
    hydro, bodies = _m4()
    mesh = revolve_profile(bodies[0].profile, 0.05, center_of_mass_z=bodies[0].center_of_mass_z)
    with pytest.raises(ValueError, match=r"no body 'float_9'.*float_1"):
        mesh.compare_with(hydro, "float_9")
