"""BEM generation with Capytaine (wecss.hydro.bem) and the Capytaine reader.

Tiers: verification of the heaving floating hemisphere against Hulme (1982); closed forms of the profile
geometry; unit tests of the reader on the RM3 Capytaine file and on small in-memory Capytaine runs; checks
of specifications and geometry files. Reference data live in ../shared/data (skipped when absent).
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from wecss.hydro import HydroData, HydroDataError, read_capytaine
from wecss.hydro.bem import (
    AxisymmetricProfile,
    BEMSpec,
    FloatBody,
    GeometryFileError,
    hull_mesh,
    lid_mesh,
    omega_grid,
    read_geometry,
    run_bem,
    sectors_for,
)
from wecss.hydro.bem._lazy import INSTALL_HINT, import_capytaine

SHARED = Path(__file__).parents[3] / "shared" / "data"
HULME = SHARED / "hulme" / "hemisphere_heave.csv"
RM3 = SHARED / "capytaine" / "rm3_hydrodynamics.nc"
RHO, G = 1000.0, 9.81

# Tolerances of the verification (not to be loosened).
HULME_ADDED_MASS_RTOL = 0.02
HULME_DAMPING_RTOL = 0.015
HULME_INFINITE_RTOL = 0.02


def _capytaine():
    return pytest.importorskip("capytaine")


# --- verification: heaving hemisphere (Hulme 1982) ---------------------------------------------------------
@pytest.fixture(scope="module")
def hemisphere() -> tuple[xr.Dataset, np.ndarray]:
    """Heave of a floating hemisphere of radius 1 m at Hulme's 0.1 <= ka <= 1.4, about 1700 panels."""
    _capytaine()
    if not HULME.is_file():
        pytest.skip(f"reference data {HULME} not present")
    table = np.loadtxt(HULME, delimiter=",", comments="#", skiprows=4)
    table = table[(table[:, 0] >= 0.1 - 1e-9) & (table[:, 0] <= 1.4 + 1e-9)]
    radius = 1.0
    body = FloatBody(
        "hemisphere",
        AxisymmetricProfile(radius, radius, "hemispherical"),
        center_of_mass_z=-3 * radius / 8,
        inertia=(1.0, 1.0, 1.0),
        dofs=("Heave",),
    )
    omega = np.sqrt(table[:, 0] * G / radius)
    spec = BEMSpec(bodies=(body,), omega=tuple(omega), panel_size=0.05 * radius, name="hulme")
    return run_bem(spec, progress=False), table


def test_hemisphere_heave_matches_hulme(hemisphere: tuple[xr.Dataset, np.ndarray]) -> None:
    ds, table = hemisphere
    volume = 2 / 3 * np.pi
    omega = ds.omega.values
    added = ds.added_mass.values[:, 0, 0] / (RHO * volume)
    damping = ds.radiation_damping.values[:, 0, 0] / (RHO * volume * omega)
    error_a = np.abs(added / table[:, 1] - 1)
    error_b = np.abs(damping / table[:, 2] - 1)
    assert ds.attrs["mesh_hull_panels"] + ds.attrs["mesh_lid_panels"] < 1800
    assert error_a.max() < HULME_ADDED_MASS_RTOL, f"added mass errors {np.round(error_a, 4)} at ka {table[:, 0]}"
    assert error_b.max() < HULME_DAMPING_RTOL, f"damping errors {np.round(error_b, 4)} at ka {table[:, 0]}"


def test_hemisphere_zero_and_infinite_frequency_limits(hemisphere: tuple[xr.Dataset, np.ndarray]) -> None:
    ds, _ = hemisphere
    a_inf = float(ds.added_mass_inf.values[0, 0]) / (RHO * 2 / 3 * np.pi)
    assert abs(a_inf / 0.5 - 1) < HULME_INFINITE_RTOL, f"A_inf / (rho V) = {a_inf}"
    zero = np.loadtxt(HULME, delimiter=",", comments="#", skiprows=4)[0]  # ka = 0
    a_zero = float(ds.added_mass_zero.values[0, 0]) / (RHO * 2 / 3 * np.pi)
    assert zero[0] == 0 and abs(a_zero / zero[1] - 1) < HULME_ADDED_MASS_RTOL, f"A_0 / (rho V) = {a_zero}"


def test_hemisphere_dataset_is_a_valid_database(hemisphere: tuple[xr.Dataset, np.ndarray]) -> None:
    ds, _ = hemisphere
    hydro = HydroData(ds)
    assert hydro.dofs == ["hemisphere__Heave"]
    np.testing.assert_allclose(ds.reference_point.values, ds.center_of_mass.values)
    # mass defaults to rho * displaced volume; hydrostatics on the area-preserving copy of the hull
    np.testing.assert_allclose(ds.mass.values, RHO * ds.displaced_volume.values)
    np.testing.assert_allclose(ds.displaced_volume.values, 2 / 3 * np.pi, rtol=1e-4)
    np.testing.assert_allclose(ds.hydrostatic_stiffness.values[0, 0], RHO * G * np.pi, rtol=1e-6)
    assert ds.attrs["capytaine_version"]
    assert ds.attrs["bem_run_time_s"] >= 0
    assert "repairs" in ds.attrs


# --- profile geometry --------------------------------------------------------------------------------------
def _fillet_closed_form(r: float, t: float, rf: float) -> tuple[float, float]:
    """Volume and z of the centre of buoyancy of a cylinder with a bilge fillet, by Pappus' theorem."""
    a = r - rf
    square_area, square_r = rf**2, r - rf / 2
    quarter_area, quarter_r = np.pi * rf**2 / 4, a + 4 * rf / (3 * np.pi)
    removed = 2 * np.pi * (square_area * square_r - quarter_area * quarter_r)
    zc = -t + rf  # centre of the fillet arc
    # first moment in z of the removed ring (square minus quarter disc, both revolved)
    square_mz = 2 * np.pi * square_area * square_r * (-t + rf / 2)
    quarter_rz = a * zc * (np.pi / 2) * rf**2 / 2 - a * rf**3 / 3 + zc * rf**3 / 3 - rf**4 / 8
    removed_mz = square_mz - 2 * np.pi * quarter_rz
    volume = np.pi * r**2 * t - removed
    return volume, (-np.pi * r**2 * t**2 / 2 - removed_mz) / volume


@pytest.mark.parametrize(
    ("profile", "volume", "zb", "area"),
    [
        (AxisymmetricProfile(0.5, 0.3, "flat"), np.pi * 0.25 * 0.3, -0.15, 2 * np.pi * 0.5 * 0.3 + np.pi * 0.25),
        (AxisymmetricProfile(1.0, 1.0, "hemispherical"), 2 / 3 * np.pi, -3 / 8, 2 * np.pi),
        (
            AxisymmetricProfile(1.0, 1.5, "hemispherical"),
            np.pi * 0.5 + 2 / 3 * np.pi,
            (-np.pi * 0.5 * 0.25 + 2 / 3 * np.pi * (-0.5 - 3 / 8)) / (np.pi * 0.5 + 2 / 3 * np.pi),
            2 * np.pi * 0.5 + 2 * np.pi,
        ),
        (
            AxisymmetricProfile(0.76, 0.8, "conical", cone_height=0.6),
            np.pi * 0.76**2 * (0.2 + 0.2),
            (-np.pi * 0.76**2 * 0.2 * 0.1 + np.pi * 0.76**2 * 0.2 * (-0.2 - 0.6 / 4)) / (np.pi * 0.76**2 * 0.4),
            2 * np.pi * 0.76 * 0.2 + np.pi * 0.76 * math.hypot(0.76, 0.6),
        ),
    ],
)
def test_profile_volume_centre_and_area_match_closed_forms(
    profile: AxisymmetricProfile, volume: float, zb: float, area: float
) -> None:
    assert profile.volume == pytest.approx(volume, rel=1e-12)
    assert profile.center_of_buoyancy_z == pytest.approx(zb, rel=1e-12)
    assert profile.wetted_area == pytest.approx(area, rel=1e-12)
    assert profile.waterplane_area == pytest.approx(np.pi * profile.radius**2)
    assert profile.waterplane_second_moment == pytest.approx(np.pi * profile.radius**4 / 4)


def test_rounded_profile_matches_pappus() -> None:
    profile = AxisymmetricProfile(0.175, 0.25, "rounded", fillet_radius=0.125)
    volume, zb = _fillet_closed_form(0.175, 0.25, 0.125)
    assert profile.volume == pytest.approx(volume, rel=1e-12)
    assert profile.center_of_buoyancy_z == pytest.approx(zb, rel=1e-10)


@pytest.mark.parametrize(
    ("mass", "radius", "bottom", "extra", "draft"),
    [  # the M4 floats of Lande-Sudall et al., Table 1: drafts from mass = rho V
        (2.345, 0.10, "flat", {}, 0.0746437),
        (5.312, 0.125, "hemispherical", {}, 0.1498818),
        (17.520, 0.175, "rounded", {"fillet_radius": 0.125}, 0.2143068),
    ],
)
def test_draft_from_volume(mass: float, radius: float, bottom: str, extra: dict, draft: float) -> None:
    profile = AxisymmetricProfile.with_volume(mass / RHO, radius=radius, bottom=bottom, **extra)  # type: ignore[arg-type]
    assert profile.draft == pytest.approx(draft, abs=1e-7)
    assert profile.volume == pytest.approx(mass / RHO, rel=1e-12)


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"radius": 1.0, "draft": 1.0, "bottom": "round"}, "unknown bottom kind"),
        ({"radius": -1.0, "draft": 1.0}, "radius must be a positive"),
        ({"radius": 1.0, "draft": 0.5, "bottom": "hemispherical"}, "shorter than the hemispherical bottom"),
        ({"radius": 1.0, "draft": 1.0, "bottom": "rounded", "fillet_radius": 1.5}, "fillet_radius <= radius"),
        ({"radius": 1.0, "draft": 1.0, "fillet_radius": 0.2}, "only used by bottom='rounded'"),
        ({"radius": 1.0, "draft": 1.0, "bottom": "conical"}, "positive cone_height"),
    ],
)
def test_profile_rejects_bad_dimensions(kwargs: dict, match: str) -> None:
    with pytest.raises(ValueError, match=match):
        AxisymmetricProfile(**kwargs)


def test_with_volume_rejects_volume_smaller_than_bottom() -> None:
    with pytest.raises(ValueError, match="smaller than the hemispherical bottom's own volume"):
        AxisymmetricProfile.with_volume(1.0, radius=1.0, bottom="hemispherical")


def test_meridian_runs_from_waterline_to_axis_with_corners() -> None:
    profile = AxisymmetricProfile(0.175, 0.25, "rounded", fillet_radius=0.125)
    points = profile.meridian(0.01)
    np.testing.assert_allclose(points[0], [0.175, 0.0])
    np.testing.assert_allclose(points[-1], [0.0, -0.25])
    assert np.any(np.all(np.isclose(points, [0.175, -0.125]), axis=1))  # wall meets fillet
    assert np.any(np.all(np.isclose(points, [0.05, -0.25]), axis=1))  # fillet meets bottom
    steps = np.hypot(*np.diff(points, axis=0).T)
    assert steps.max() <= 0.0101


# --- meshes ------------------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    "profile",
    [
        AxisymmetricProfile(0.1, 0.0746, "flat"),
        AxisymmetricProfile(0.125, 0.15, "hemispherical"),
        AxisymmetricProfile(0.175, 0.2143, "rounded", fillet_radius=0.125),
        AxisymmetricProfile(0.76, 0.8, "conical", cone_height=0.6),
    ],
)
def test_meshes_keep_volume_and_face_the_right_way(profile: AxisymmetricProfile) -> None:
    _capytaine()
    size = profile.draft / 10
    exact = hull_mesh(profile, size, preserve_area=True).merged()
    assert exact.volume == pytest.approx(profile.volume, rel=5e-4)
    assert exact.waterplane_area == pytest.approx(profile.waterplane_area, rel=1e-9)
    inscribed = hull_mesh(profile, size)
    assert inscribed.merged().volume < exact.volume  # vertices on the true surface
    assert inscribed.n % 4 == 0 and inscribed.n >= 24
    centres, normals = inscribed.merged().faces_centers, inscribed.merged().faces_normals
    outward = normals[:, 0] * centres[:, 0] + normals[:, 1] * centres[:, 1] - normals[:, 2] * 1e-3
    assert np.all(outward > -1e-12)
    lid = lid_mesh(profile, size)
    assert lid.n == inscribed.n
    assert np.all(lid.merged().faces_normals[:, 2] < 0)
    assert np.allclose(lid.merged().faces_centers[:, 2], 0.0)


def test_sectors_for_is_a_multiple_of_four_with_a_floor() -> None:
    assert sectors_for(0.1, 1.0) == 24
    assert sectors_for(1.0, 0.05) == 128
    with pytest.raises(ValueError, match="panel_size"):
        sectors_for(1.0, 0.0)


def test_missing_capytaine_gives_install_hint(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "capytaine", None)
    with pytest.raises(ImportError, match=r'pip install "wecss\[bem\]"'):
        import_capytaine()
    assert "wecss[bem]" in INSTALL_HINT


# --- reader on the RM3 Capytaine file (Capytaine 2.3.1) --------------------------------------------------------
RM3_BODIES = {
    # centres of mass = rotation centres of WEC-Sim's examples/BEMIO/CAPYTAINE/rm3/main.py, which made the file;
    # volumes and centres of buoyancy from WEC-Sim's WAMIT run of the same bodies (rm3.out)
    "center_of_mass": {"rm3_float": (0.0, 0.0, -0.72), "rm3_spar": (0.0, 0.0, -21.29)},
    "reference_point": {"rm3_float": (0.0, 0.0, -0.72), "rm3_spar": (0.0, 0.0, -21.29)},
    "center_of_buoyancy": {"rm3_float": (0.0, 0.0, -1.2927), "rm3_spar": (0.0, 0.0, -15.604)},
    "displaced_volume": {"rm3_float": 725.83, "rm3_spar": 886.69},
}


@pytest.fixture(scope="module")
def rm3_raw() -> xr.Dataset:
    if not RM3.is_file():
        pytest.skip(f"reference data {RM3} not present")
    with xr.open_dataset(RM3) as ds:
        return ds.load()


@pytest.fixture(scope="module")
def rm3(rm3_raw: xr.Dataset) -> xr.Dataset:
    return read_capytaine(RM3, added_mass_inf="highest_frequency", **RM3_BODIES)  # type: ignore[arg-type]


def test_rm3_reports_everything_missing(rm3_raw: xr.Dataset) -> None:
    with pytest.raises(HydroDataError) as info:
        read_capytaine(RM3)
    message = str(info.value)
    for what in ("infinite-frequency added mass", "center of mass of body 'rm3_spar'", "rotation centre",
                 "center of buoyancy", "displaced volume", "added_mass_inf='highest_frequency'"):  # fmt: skip
        assert what in message


def test_rm3_dimensions_and_names(rm3: xr.Dataset) -> None:
    assert rm3.added_mass.dims == ("omega", "influenced_dof", "radiating_dof")
    assert rm3.excitation.dims == ("omega", "wave_direction", "influenced_dof")
    assert list(rm3.body.values) == ["rm3_float", "rm3_spar"]
    assert rm3.influenced_dof.values[2] == "rm3_float__Heave"
    assert rm3.sizes["omega"] == 260 and np.all(np.isfinite(rm3.omega.values))
    assert rm3.attrs["capytaine_version"] == "2.3.1"
    np.testing.assert_allclose(rm3.mass.values, [7.2583e5, 8.8669e5], rtol=1e-4)  # from inertia_matrix


def test_rm3_matrices_are_influenced_first(rm3: xr.Dataset, rm3_raw: xr.Dataset) -> None:
    i, j = "rm3_float__Surge", "rm3_spar__Pitch"
    raw = rm3_raw.added_mass.sel(influenced_dof=i, radiating_dof=j).values
    np.testing.assert_array_equal(rm3.added_mass.sel(influenced_dof=i, radiating_dof=j).values, raw)


def test_rm3_excitation_is_conjugated(rm3: xr.Dataset, rm3_raw: xr.Dataset) -> None:
    raw = rm3_raw.excitation_force.sel(complex="re") + 1j * rm3_raw.excitation_force.sel(complex="im")
    np.testing.assert_allclose(rm3.excitation.values, np.conj(raw.values))
    # Re[X exp(+i omega t)], waves along +x: the surge force of a small body leads the elevation by 90 degrees
    surge = rm3.excitation.sel(influenced_dof="rm3_float__Surge", wave_direction=0.0).sel(omega=slice(0.1, 1.0))
    assert np.all(surge.values.imag > 0)


def test_rm3_added_mass_inf_from_highest_frequency(rm3: xr.Dataset) -> None:
    np.testing.assert_array_equal(rm3.added_mass_inf.values, rm3.added_mass.values[-1])
    assert "highest frequency" in rm3.attrs["added_mass_inf_source"]
    assert "added_mass_zero" not in rm3


def test_rm3_explicit_added_mass_inf_and_checks(rm3: xr.Dataset) -> None:
    matrix = rm3.added_mass.values[-1] * 1.01
    ds = read_capytaine(RM3, added_mass_inf=matrix, **RM3_BODIES)  # type: ignore[arg-type]
    np.testing.assert_array_equal(ds.added_mass_inf.values, matrix)
    with pytest.raises(ValueError, match=r"finite \(12, 12\) matrix"):
        read_capytaine(RM3, added_mass_inf=np.eye(3), **RM3_BODIES)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="disagrees"):
        read_capytaine(RM3, rho=1025.0, added_mass_inf="highest_frequency", **RM3_BODIES)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="unknown bodies"):
        read_capytaine(RM3, added_mass_inf="highest_frequency", mass={"buoy": 1.0})


def test_reader_rejects_bad_sources(tmp_path: Path) -> None:
    with pytest.raises(FileNotFoundError, match="no Capytaine netCDF file"):
        read_capytaine(tmp_path / "missing.nc")
    with pytest.raises(TypeError, match=r"path or an xarray\.Dataset"):
        read_capytaine(42)  # type: ignore[arg-type]


# --- reader on small in-memory Capytaine runs ------------------------------------------------------------------
def test_reader_removes_capytaine_gravity_terms(tmp_path: Path) -> None:
    """Rotation centre at the waterline, centre of mass below: Capytaine's stiffness holds -m g z_G."""
    cpt = _capytaine()
    profile = AxisymmetricProfile(1.0, 1.0, "hemispherical")
    mesh = hull_mesh(profile, 0.1, aspect_ratio=2).merged()
    com = (0.0, 0.0, -0.2)
    body = cpt.FloatingBody(
        mesh=mesh,
        dofs=cpt.rigid_body_dofs(only=["Heave", "Pitch"], rotation_center=(0, 0, 0)),
        center_of_mass=com,
        name="h",
    )
    problems = [cpt.RadiationProblem(body=body, radiating_dof=d, omega=w) for w in (1.0, np.inf) for d in body.dofs]
    problems.append(cpt.DiffractionProblem(body=body, omega=1.0))
    raw = cpt.assemble_dataset(cpt.BEMSolver().solve_all(problems, progress_bar=False))
    ds = read_capytaine(raw, inertia={"h": (1.0, 2.0, 3.0)})
    volume, zb = mesh.disp_volume, mesh.center_of_buoyancy[2]
    wp_moment = mesh.waterplane_integral(mesh.quadrature_points[0][:, :, 0] ** 2)
    buoyancy_only = RHO * G * (wp_moment + volume * zb)  # about the origin
    k = ds.hydrostatic_stiffness.sel(influenced_dof="h__Pitch", radiating_dof="h__Pitch").item()
    k_capytaine = raw.hydrostatic_stiffness.sel(influenced_dof="Pitch", radiating_dof="Pitch").item()
    assert k == pytest.approx(buoyancy_only, rel=1e-9)
    assert k_capytaine == pytest.approx(buoyancy_only - RHO * volume * G * com[2], rel=1e-9)
    assert list(ds.radiating_dof.values) == ["h__Heave", "h__Pitch"]
    np.testing.assert_allclose(ds.reference_point.values[0], 0.0)
    np.testing.assert_allclose(ds.inertia.values[0], np.diag([1.0, 2.0, 3.0]))
    assert "added_mass_zero" not in ds and ds.attrs["added_mass_inf_source"] == "Capytaine, omega = inf"
    # the same through a netCDF file written by Capytaine (complex values split along a 'complex' dimension)
    cpt.export_dataset(tmp_path / "h.nc", raw)
    from_file = read_capytaine(tmp_path / "h.nc", inertia={"h": (1.0, 2.0, 3.0)})
    xr.testing.assert_allclose(from_file, ds)  # values and coordinates; attributes (source) differ


def test_two_floats_with_interactions() -> None:
    _capytaine()
    small = AxisymmetricProfile.with_volume(2e-3, radius=0.1, bottom="flat")
    large = AxisymmetricProfile.with_volume(8e-3, radius=0.15, bottom="rounded", fillet_radius=0.05)
    spec = BEMSpec(
        bodies=(
            FloatBody("a", small, -0.03, (0.01, 0.01, 0.01), position=(0.0, 0.0), mass=2.0),
            FloatBody("b", large, -0.05, (0.05, 0.05, 0.05), position=(0.5, 0.1), mass=8.0),
        ),
        omega=(3.0, 6.0, 9.0),
        panel_size=0.03,
    )
    ds = run_bem(spec, progress=False)
    HydroData(ds)
    assert ds.sizes["radiating_dof"] == 6
    coupling = ds.added_mass.sel(influenced_dof="a__Heave", radiating_dof="b__Heave").values
    assert np.all(np.abs(coupling) > 0)
    np.testing.assert_allclose(ds.reference_point.values, ds.center_of_mass.values)
    np.testing.assert_allclose(ds.mass.values, [2.0, 8.0])
    np.testing.assert_allclose(ds.displaced_volume.values, [2e-3, 8e-3], rtol=1e-3)
    heave = ds.hydrostatic_stiffness.sel(
        influenced_dof=["a__Heave", "b__Heave"], radiating_dof=["a__Heave", "b__Heave"]
    )
    np.testing.assert_allclose(np.diag(heave.values), RHO * G * np.pi * np.array([0.1, 0.15]) ** 2, rtol=1e-6)
    pitch = ds.hydrostatic_stiffness.sel(influenced_dof="b__Pitch", radiating_dof="b__Pitch").item()
    expected = RHO * G * (large.waterplane_second_moment + large.volume * (large.center_of_buoyancy_z + 0.05))
    # buoyancy alone about the centre of mass; 2 % covers this coarse mesh (the two terms nearly cancel)
    assert pitch == pytest.approx(expected, rel=2e-2)
    assert sum(ds.attrs["mesh_hull_panels_per_body"]) == ds.attrs["mesh_hull_panels"]
    assert len(ds.attrs["mesh_lid_panels_per_body"]) == 2


# --- specifications and geometry files -------------------------------------------------------------------------
def _float(name: str = "f", x: float = 0.0) -> FloatBody:
    return FloatBody(name, AxisymmetricProfile(0.1, 0.1), -0.05, (1.0, 1.0, 1.0), position=(x, 0.0))


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"bodies": (_float("a"), _float("b", 0.15))}, "overlap"),
        ({"bodies": (_float("a"), _float("a", 1.0))}, "distinct"),
        ({"omega": (2.0, 1.0)}, "strictly increasing"),
        ({"omega": (0.0, 1.0)}, "positive"),
        ({"water_depth": 2.0}, "only available in deep water"),
        ({"method": "fast"}, "'direct' or 'indirect'"),
        ({"panel_size": 0.0}, "panel_size must be positive"),
    ],
)
def test_spec_rejects_bad_input(kwargs: dict, match: str) -> None:
    base = {"bodies": (_float(),), "omega": (1.0, 2.0), "panel_size": 0.02}
    with pytest.raises(ValueError, match=match):
        BEMSpec(**{**base, **kwargs})


def test_spec_warns_on_degrees() -> None:
    with pytest.warns(UserWarning, match="look like degrees"):
        BEMSpec(bodies=(_float(),), omega=(1.0,), panel_size=0.02, wave_directions=(180.0,))


def test_float_body_checks_and_orders_dofs() -> None:
    body = FloatBody("f", AxisymmetricProfile(0.1, 0.1), -0.05, (1.0, 1.0, 1.0), dofs=("Pitch", "Surge"))
    assert body.dofs == ("Surge", "Pitch")
    with pytest.raises(ValueError, match="distinct names among"):
        FloatBody("f", AxisymmetricProfile(0.1, 0.1), -0.05, (1.0, 1.0, 1.0), dofs=("Heave", "heave"))
    with pytest.raises(ValueError, match="without"):
        FloatBody("a__b", AxisymmetricProfile(0.1, 0.1), -0.05, (1.0, 1.0, 1.0))


def test_omega_grid() -> None:
    grid = omega_grid(0.1, 25.0, 0.1)
    assert len(grid) == 250 and grid[0] == 0.1 and grid[-1] == 25.0


GEOMETRY = """
name = "test"
[frequencies]
start = 1.0
stop = 3.0
step = 1.0
[mesh]
panel_size = 0.02
[float_types.small]
diameter = 0.2
mass = 2.0
center_of_mass_z = -0.03
inertia = [0.01, 0.01, 0.01]
[[bodies]]
name = "a"
type = "small"
[[bodies]]
name = "b"
type = "small"
x = 1.0
draft = 0.05
"""


def test_read_geometry(tmp_path: Path) -> None:
    path = tmp_path / "test.toml"
    path.write_text(GEOMETRY)
    spec = read_geometry(path)
    assert spec.name == "test" and spec.omega == (1.0, 2.0, 3.0) and spec.zero_frequency
    a, b = spec.bodies
    assert a.profile.draft == pytest.approx(2.0 / RHO / (np.pi * 0.01))
    assert b.profile.draft == 0.05 and b.position == (1.0, 0.0) and b.mass == 2.0
    assert a.dofs == ("Surge", "Heave", "Pitch") and spec.method == "direct"


@pytest.mark.parametrize(
    ("edit", "match"),
    [
        (("[mesh]", "[mesh]\ncolour = 1"), r"\[mesh\]: unknown keys \['colour'\]"),
        (('type = "small"\n[[bodies]]', 'type = "large"\n[[bodies]]'), "unknown float type 'large'"),
        (("mass = 2.0\n", ""), "give 'draft' or 'mass'"),
        (("diameter = 0.2", "diameter = -0.2"), "radius must be a positive"),
        (("panel_size = 0.02", ""), "missing key 'panel_size'"),
    ],
)
def test_read_geometry_errors(tmp_path: Path, edit: tuple[str, str], match: str) -> None:
    path = tmp_path / "bad.toml"
    path.write_text(GEOMETRY.replace(*edit, 1))
    with pytest.raises(GeometryFileError, match=match):
        read_geometry(path)


def test_shipped_geometry_files_read() -> None:
    from wecss.hydro._catalogue import DATA_DIR

    files = sorted(DATA_DIR.glob("*.toml"))
    if not files:
        pytest.skip("no geometry files")
    for path in files:
        spec = read_geometry(path)
        assert spec.rho == RHO and spec.g == G and math.isinf(spec.water_depth)
        assert all(b.dofs == ("Surge", "Heave", "Pitch") for b in spec.bodies)
