"""WAMIT reader: the RM3 and Wavestar WAMIT 7.2 runs of the shared reference data, and small synthetic files.

The reference files (``../shared/data/wamit``, from WEC-Sim) are parsed once per module; tests that need them
skip when the folder is absent. The synthetic ``.out`` files mimic WAMIT's layout with round numbers, to check
conventions (special periods, gravity terms, inertia, units) and error messages exactly.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from scipy.interpolate import CubicSpline

from wecss.attributes import apply_attrs
from wecss.hydro import HydroData, HydroDataError, HydroDataWarning, read_wamit
from wecss.hydro.readers.wamit import WamitFormatError
from wecss.netcdf import read_netcdf, write_netcdf

DATA = Path(__file__).resolve().parents[3] / "shared" / "data" / "wamit"
RM3 = DATA / "rm3" / "rm3.out"
WAVESTAR = DATA / "wavestar" / "wavestar.out"
RHO = 1000.0
G = 9.81


def _need(path: Path) -> None:
    if not path.is_file():
        pytest.skip(f"reference data not found: {path}")


@pytest.fixture(scope="module")
def rm3() -> xr.Dataset:
    _need(RM3)
    return read_wamit(RM3, body_names=["float", "spar"], rho=RHO)


@pytest.fixture(scope="module")
def rm3_out_only() -> xr.Dataset:
    _need(RM3)
    return read_wamit(RM3, body_names=["float", "spar"], rho=RHO, numeric_files=False)


@pytest.fixture(scope="module")
def wavestar() -> xr.Dataset:
    _need(WAVESTAR)
    return read_wamit(WAVESTAR)


# --- RM3 --------------------------------------------------------------------------------------------

OMEGA_8S = 2 * np.pi / 8.0
HEAVE = {"influenced_dof": "float__Heave", "radiating_dof": "float__Heave"}


def _at_8s(ds: xr.Dataset, values: np.ndarray) -> complex:
    return complex(CubicSpline(ds.omega.values, values)(OMEGA_8S))


@pytest.mark.parametrize(
    ("quantity", "expected"),
    [("added_mass", 1.4468e6), ("radiation_damping", 5.873e5), ("added_mass_inf", 1.2328e6), ("excitation", 1.5125e6)],
)
def test_rm3_float_heave_at_8_s(rm3: xr.Dataset, quantity: str, expected: float) -> None:
    """Float heave at T = 8 s (cubic spline in omega): A [kg], B [N s/m], A_inf [kg], |X| [N/m], within 0.1 %."""
    if quantity == "added_mass_inf":
        value = float(rm3.added_mass_inf.sel(HEAVE))
    elif quantity == "excitation":
        value = abs(_at_8s(rm3, rm3.excitation.sel(influenced_dof="float__Heave").isel(wave_direction=0).values))
    else:
        value = _at_8s(rm3, rm3[quantity].sel(HEAVE).values).real
    assert abs(value / expected - 1) < 1e-3


def test_rm3_coordinates_and_units(rm3: xr.Dataset) -> None:
    bodies = ["float", "spar"]
    dofs = [f"{b}__{d}" for b in bodies for d in ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")]
    assert list(rm3.radiating_dof.values) == dofs
    assert list(rm3.influenced_dof.values) == dofs
    omega = rm3.omega.values
    assert omega.size == 260
    assert np.all(np.diff(omega) > 0)
    np.testing.assert_allclose(omega[[0, -1]], [0.02, 5.2], rtol=1e-6)
    np.testing.assert_array_equal(rm3.wave_direction.values, [0.0])
    assert rm3.attrs["water_depth"] == np.inf
    assert (rm3.attrs["rho"], rm3.attrs["g"]) == (RHO, G)
    assert rm3.attrs["wamit_files"] == "rm3.out, rm3.1, rm3.3, rm3.hst, rm3.mmx"
    # Excitation phase (rm3.3): heave in phase with the crest at omega -> 0, surge leads by 90 deg.
    first = rm3.excitation.isel(omega=0, wave_direction=0)
    assert abs(np.angle(complex(first.sel(influenced_dof="float__Heave")), deg=True)) < 1.0
    assert abs(np.angle(complex(first.sel(influenced_dof="float__Surge")), deg=True) - 90) < 1.0


def test_rm3_special_periods_go_to_zero_and_infinite_frequency(rm3: xr.Dataset) -> None:
    """PER = -1 (infinite period) is omega = 0, PER = 0 (zero period) is omega = infinity."""
    surge = {"influenced_dof": "float__Surge", "radiating_dof": "float__Surge"}
    np.testing.assert_allclose(float(rm3.added_mass_zero.sel(surge)), 2.292294e2 * RHO)
    np.testing.assert_allclose(float(rm3.added_mass_inf.sel(surge)), 9.272929e1 * RHO)
    a = rm3.added_mass.sel(HEAVE).values
    assert abs(a[0] - float(rm3.added_mass_zero.sel(HEAVE))) < 0.01 * abs(a[0])
    assert abs(a[-1] - float(rm3.added_mass_inf.sel(HEAVE))) < abs(a[0] - float(rm3.added_mass_inf.sel(HEAVE)))


def test_rm3_bodies(rm3: xr.Dataset) -> None:
    np.testing.assert_allclose(rm3.reference_point.values, [[0, 0, -0.72], [0, 0, -21.29]])
    np.testing.assert_allclose(rm3.center_of_mass.values, rm3.reference_point.values)
    np.testing.assert_allclose(
        rm3.center_of_buoyancy.values, [[0, 3e-6, -0.72 - 0.572734], [0, -2e-6, -21.29 + 5.686012]]
    )
    np.testing.assert_allclose(rm3.displaced_volume.values, [725.833, 886.687])
    np.testing.assert_allclose(rm3.mass.values, RHO * rm3.displaced_volume.values)
    np.testing.assert_array_equal(rm3.inertia.values, 0.0)
    assert rm3.attrs["inertia_unknown_bodies"] == "float, spar"


def test_rm3_hydrostatics_are_buoyancy_about_xbody(rm3: xr.Dataset) -> None:
    k = rm3.hydrostatic_stiffness
    rho_g = RHO * G
    np.testing.assert_allclose(float(k.sel(HEAVE)), 2.855230e2 * rho_g)
    pitch = {"influenced_dof": "spar__Pitch", "radiating_dof": "spar__Pitch"}
    np.testing.assert_allclose(float(k.sel(pitch)), 5.104024e3 * rho_g)
    # VCG = 0 at XBODY; only WAMIT's m g Yg in C(5,6) goes, leaving -rho g V Yb (Yg = Yb = 3e-6 m).
    yaw = {"influenced_dof": "float__Pitch", "radiating_dof": "float__Yaw"}
    np.testing.assert_allclose(float(k.sel(yaw)), -rho_g * 725.833 * 3e-6, rtol=1e-5)
    np.testing.assert_array_equal(k.values[:6, 6:], 0.0)


def test_out_only_read_matches_numeric_files(rm3: xr.Dataset, rm3_out_only: xr.Dataset) -> None:
    """The .out prints A and B with the digits of .1; C has 5 digits (vs 7 in .hst), phases whole degrees."""
    for name in ("added_mass", "radiation_damping", "added_mass_inf", "added_mass_zero"):
        xr.testing.assert_allclose(rm3[name], rm3_out_only[name], rtol=1e-12)
    k, k_out = rm3.hydrostatic_stiffness.values, rm3_out_only.hydrostatic_stiffness.values
    assert np.max(np.abs(k - k_out)) < 1e-4 * np.max(np.abs(k))
    x, x_out = rm3.excitation.values, rm3_out_only.excitation.values
    peak = np.max(np.abs(x), axis=0, keepdims=True)
    assert np.max(np.abs(np.abs(x) - np.abs(x_out)) / peak) < 1e-5
    significant = np.abs(x) > 1e-6 * peak
    assert np.max(np.abs(np.angle(x[significant] / x_out[significant], deg=True))) <= 0.5 + 1e-3
    assert not np.array_equal(x, x_out)
    for name in ("mass", "center_of_mass", "center_of_buoyancy", "reference_point", "omega", "wave_direction"):
        np.testing.assert_array_equal(rm3[name].values, rm3_out_only[name].values)
    assert rm3_out_only.attrs["wamit_files"] == "rm3.out"


def test_raw_rm3_fails_validation_and_names_the_asymmetry(rm3: xr.Dataset) -> None:
    """The published RM3 run is not symmetric to 1e-3: body-to-body couplings and the float's sway-roll terms
    differ by up to 16 % of sqrt(A_ii A_jj) (Capytaine's run of the same bodies shows the same), so the raw data
    are refused with the DOFs named."""
    with pytest.raises(HydroDataError, match=r"'added_mass' is not symmetric .* float__Sway and float__Roll"):
        HydroData(rm3)


def test_from_wamit_repairs_and_says_so() -> None:
    _need(RM3)
    with pytest.warns(HydroDataWarning, match=r"symmetrised added_mass .* dropped 13 at the ends of the range"):
        hd = HydroData.from_wamit(RM3, body_names=["float", "spar"])
    ds = hd.dataset
    assert "symmetrised" in ds.attrs["repairs"]
    np.testing.assert_array_equal(ds.added_mass.values, np.swapaxes(ds.added_mass.values, 1, 2))
    assert ds.omega.values[-1] == pytest.approx(4.94, abs=0.01)  # negative damping above 4.9 rad/s dropped
    # the repair keeps the checked values: float heave at 8 s is unchanged by symmetrisation (a diagonal entry)
    heave = ds.added_mass.sel(influenced_dof="float__Heave", radiating_dof="float__Heave").values
    assert _at_8s(ds, heave).real == pytest.approx(1.4468e6, rel=1e-3)


def _symmetric_part(ds: xr.Dataset) -> xr.Dataset:
    out = ds.copy()
    for name in ("added_mass", "radiation_damping"):
        values = ds[name].values
        out[name] = (ds[name].dims, (values + np.swapaxes(values, 1, 2)) / 2)
    for name in ("added_mass_inf", "added_mass_zero"):
        out[name] = (ds[name].dims, (ds[name].values + ds[name].values.T) / 2)
    return out


@pytest.fixture(scope="module")
def rm3_clean(rm3: xr.Dataset) -> HydroData:
    """RM3 below 4.5 rad/s, coefficient matrices replaced by their symmetric part."""
    return HydroData(_symmetric_part(rm3.sel(omega=slice(None, 4.5))))


def test_hydrodata_accepts_everything_else_the_reader_makes(rm3_clean: HydroData) -> None:
    """With the data's own asymmetry set aside, the reader's dataset passes every check (yaw noise is ignored)."""
    assert rm3_clean.bodies == ["float", "spar"]
    assert len(rm3_clean.dofs) == 12


def test_netcdf_round_trip(rm3: xr.Dataset, rm3_clean: HydroData, tmp_path: Path) -> None:
    path = write_netcdf(rm3_clean.dataset, tmp_path / "rm3.nc")
    xr.testing.assert_identical(read_netcdf(path), rm3_clean.dataset)
    full = apply_attrs(rm3)  # what HydroData stores, for the complete dataset
    path = write_netcdf(full, tmp_path / "rm3_full.nc")
    xr.testing.assert_identical(read_netcdf(path), full)


# --- Wavestar ---------------------------------------------------------------------------------------------------


def test_wavestar(wavestar: xr.Dataset) -> None:
    assert wavestar.attrs["water_depth"] == 0.65
    assert wavestar.sizes["omega"] == 420
    assert np.all(np.diff(wavestar.omega.values) > 0)
    assert wavestar.attrs["g"] == 9.80665  # the run's gravity is kept unless g is given
    assert list(wavestar.body.values) == ["body_1"]
    assert wavestar.radiating_dof.values[4] == "body_1__Pitch"
    np.testing.assert_allclose(wavestar.reference_point.values, [[0.0511, 0.0, 0.0533]])
    np.testing.assert_allclose(wavestar.mass.values, [RHO * 0.344635e-2])
    # WAMIT's C(3,3) = 0.51648E-01 (non-dimensional, 5 digits in the .out)
    heave = {"influenced_dof": "body_1__Heave", "radiating_dof": "body_1__Heave"}
    np.testing.assert_allclose(float(wavestar.hydrostatic_stiffness.sel(heave)), 0.51648e-1 * RHO * 9.80665)


def test_wavestar_with_other_gravity(wavestar: xr.Dataset) -> None:
    other = read_wamit(WAVESTAR, g=9.81)
    assert other.attrs["g"] == 9.81 and other.attrs["wamit_gravity"] == 9.80665
    xr.testing.assert_allclose(other.excitation, wavestar.excitation * (9.81 / 9.80665))
    xr.testing.assert_identical(other.added_mass, wavestar.added_mass)


# --- synthetic files -----------------------------------------------------------------------------------------------

PERIODS = (10.0, 5.0, 2.0)
HEADINGS = (0.0, 90.0)


def _a(i: int, j: int, period: float) -> float:
    return 100.0 * i + j + period / 10 if i == j else 0.5 * (i + j)


def _b(i: int, j: int, period: float) -> float:
    return period / 10 if i == j else 0.0


def _out_text(*, vcg: float = 0.0, xb: float = 0.0, radius: float = 0.0, phibody: float = 0.0) -> str:
    """A one-body WAMIT .out in the layout of WAMIT 7 (ULEN = 1, infinite depth, g = 9.81)."""
    volume, zb, s22 = 2.0, -0.25, 1.5
    c44 = s22 + volume * zb - volume * vcg  # WAMIT includes -m g zg, with m = rho V
    c46 = -volume * xb + volume * xb  # -rho g V xb + m g xg, with xg = xb
    lines = [
        "                        WAMIT  Version 7.2(x64)        ",
        " Input from Geometric Data File:         cube.gdf",
        " Gravity:     9.81000                Length scale:        1.00000",
        " Water depth:        infinite",
        " XBODY =    1.0000 YBODY =    0.0000 ZBODY =   -0.5000 PHIBODY =   " + f"{phibody:.1f}",
        f" Volumes (VOLX,VOLY,VOLZ):           {volume:.5f}      {volume:.5f}      {volume:.5f}",
        f" Center of Buoyancy (Xb,Yb,Zb):     {xb:.6f}     0.000000    {zb:.6f}",
        " Hydrostatic and gravitational restoring coefficients: ",
        " C(3,3),C(3,4),C(3,5):   3.0000      0.0000      0.0000    ",
        f" C(4,4),C(4,5),C(4,6):               {c44:.6f}      0.0000     {c46:.6f}",
        f"        C(5,5),C(5,6):                          {c44:.6f}      0.0000",
        f" Center of Gravity  (Xg,Yg,Zg):     {xb:.6f}     0.000000     {vcg:.6f}",
        f" Radii of gyration:     {radius:.6f}     0.000000     0.000000",
        f"                        0.000000     {radius:.6f}     0.000000",
        f"                        0.000000     0.000000     {radius:.6f}",
        "",
    ]
    for header, value in (("Wave period = infinite", 1000.0), ("Wave period = zero", 1.0)):
        lines += [" " + "*" * 72, "", f" {header}                  Wavenumber = x", " " + "-" * 72, "", ""]
        lines += ["    ADDED-MASS COEFFICIENTS", "     I     J         A(I,J)", ""]
        lines += [f"{i:6d}{j:6d}   {_a(i, j, value):.6E}" for i in range(1, 7) for j in range(1, 7)]
        lines += ["", ""]
    for period in PERIODS:
        lines += [" " + "*" * 72, "", f" Wave period (sec) =  {period:.6E}        Wavenumber (kL) =  1.0E-01"]
        lines += [" " + "-" * 72, "", "", "    ADDED-MASS AND DAMPING COEFFICIENTS"]
        lines += ["     I     J         A(I,J)         B(I,J)", ""]
        lines += [
            f"{i:6d}{j:6d}   {_a(i, j, period):.6E}   {_b(i, j, period):.6E}" for i in range(1, 7) for j in range(1, 7)
        ]
        lines += ["", "", "", "    DIFFRACTION EXCITING FORCES AND MOMENTS", ""]
        for heading in HEADINGS:
            lines += [f"  Wave Heading (deg) :     {heading:g}", "", "     I     Mod[Xh(I)]     Pha[Xh(I)]", ""]
            lines += [f"{i:6d}   {i * period:.6E}    {10 * i + heading:6.0f}" for i in range(1, 7)]
            lines += ["", ""]
    lines += [" " + "*" * 72, ""]
    return "\n".join(lines)


def _write(tmp_path: Path, text: str, name: str = "cube.out") -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


def test_synthetic_conventions(tmp_path: Path) -> None:
    ds = read_wamit(_write(tmp_path, _out_text()))
    omega = 2 * np.pi / np.array(PERIODS)
    np.testing.assert_allclose(ds.omega.values, omega)
    np.testing.assert_allclose(ds.wave_direction.values, np.deg2rad(HEADINGS))
    sel = {"influenced_dof": "body_1__Roll", "radiating_dof": "body_1__Roll"}
    np.testing.assert_allclose(ds.added_mass.sel(sel).values, [(404 + t / 10) * RHO * 1.0**5 for t in PERIODS])
    np.testing.assert_allclose(ds.radiation_damping.sel(sel).values, [t / 10 * RHO for t in PERIODS] * omega)
    np.testing.assert_allclose(float(ds.added_mass_zero.sel(sel)), (404 + 100) * RHO)
    np.testing.assert_allclose(float(ds.added_mass_inf.sel(sel)), (404 + 0.1) * RHO)
    x = ds.excitation.sel(influenced_dof="body_1__Pitch", wave_direction=np.pi / 2).values
    np.testing.assert_allclose(x, 5 * np.array(PERIODS) * RHO * G * np.exp(1j * np.deg2rad(140)))
    assert ds.attrs["source"] == "WAMIT 7.2(x64) output cube.out"


def test_gravity_terms_removed_and_inertia_shifted(tmp_path: Path) -> None:
    """VCG = 0.1 m, Xb = Xg = 0.05 m: the stiffness is buoyancy alone, whatever WAMIT added for the weight."""
    ds = read_wamit(_write(tmp_path, _out_text(vcg=0.1, xb=0.05, radius=0.5)))
    k = ds.hydrostatic_stiffness.values * (1 / (RHO * G))
    volume, zb, s22 = 2.0, -0.25, 1.5
    np.testing.assert_allclose(k[3, 3], s22 + volume * zb, rtol=1e-6)
    np.testing.assert_allclose(k[4, 4], s22 + volume * zb, rtol=1e-6)
    np.testing.assert_allclose(k[3, 5], -volume * 0.05, rtol=1e-6)  # -rho g V xb
    np.testing.assert_allclose(ds.center_of_mass.values, [[1.0, 0.0, -0.4]])
    np.testing.assert_allclose(ds.reference_point.values, [[1.0, 0.0, -0.5]])
    np.testing.assert_allclose(ds.center_of_buoyancy.values, [[1.05, 0.0, -0.75]])
    mass = RHO * volume
    about_origin = mass * 0.25
    np.testing.assert_allclose(np.diag(ds.inertia.values[0]), [about_origin - mass * 0.01] * 2 + [about_origin])
    assert "inertia_unknown_bodies" not in ds.attrs


def test_numeric_files_are_preferred(tmp_path: Path) -> None:
    out = _write(tmp_path, _out_text())
    rows = ["WAMIT Numeric Output -- Filename  cube.1"]
    rows += [f" -1.000000E+00 {i:5d} {i:5d}  7.000000E+00" for i in range(1, 7)]
    rows += [f"  0.000000E+00 {i:5d} {i:5d}  3.000000E+00" for i in range(1, 7)]
    rows += [f"  {t:.6E} {i:5d} {i:5d}  {t + 0.125:.6E}  1.000000E+00" for t in PERIODS for i in range(1, 7)]
    (tmp_path / "cube.1").write_text("\n".join(rows) + "\n")
    rows = [
        f"  {t:.6E}  {h:.6E} {i:5d}  1.0E+00  0.0E+00  {i:.6E}  {-t:.6E}"
        for t in PERIODS
        for h in HEADINGS
        for i in range(1, 7)
    ]
    (tmp_path / "cube.3").write_text("\n".join(rows) + "\n")
    (tmp_path / "cube.hst").write_text("\n".join(f"{i:5d} {i:5d}  {2.5 * i:.6E}" for i in range(1, 7)) + "\n")
    ds = read_wamit(tmp_path / "cube.1")  # any file of the run stands for its .out
    heave = {"influenced_dof": "body_1__Heave", "radiating_dof": "body_1__Heave"}
    np.testing.assert_allclose(float(ds.added_mass_zero.sel(heave)), 7.0 * RHO)  # PER = -1: omega = 0
    np.testing.assert_allclose(float(ds.added_mass_inf.sel(heave)), 3.0 * RHO)  # PER = 0: omega = inf
    np.testing.assert_allclose(ds.added_mass.sel(heave).values, (np.array(PERIODS) + 0.125) * RHO)
    x = ds.excitation.sel(influenced_dof="body_1__Heave").values
    np.testing.assert_allclose(x, RHO * G * (3 - 1j * np.array(PERIODS))[:, None] * np.ones((1, 2)))
    np.testing.assert_allclose(float(ds.hydrostatic_stiffness.sel(heave)), 7.5 * RHO * G)
    assert ds.attrs["wamit_files"] == "cube.out, cube.1, cube.3, cube.hst"
    assert read_wamit(out, numeric_files=False).attrs["wamit_files"] == "cube.out"


def test_numeric_file_with_other_periods_is_an_error(tmp_path: Path) -> None:
    _write(tmp_path, _out_text())
    (tmp_path / "cube.1").write_text("  7.000000E+00     1     1  1.0E+00  1.0E+00\n")
    with pytest.raises(WamitFormatError, match=r"cube\.1, line 1: period 7 s is not among the 3 periods"):
        read_wamit(tmp_path / "cube.out")
    read_wamit(tmp_path / "cube.out", numeric_files=False)


def test_unreadable_row_names_file_and_line(tmp_path: Path) -> None:
    text = _out_text()
    lines = text.splitlines()
    n = next(k for k, line in enumerate(lines) if line.startswith("     2     3   ") and len(line.split()) == 4)
    lines[n] = lines[n][:30] + "  ******"
    with pytest.raises(
        WamitFormatError, match=rf"cube\.out, line {n + 1}: expected 4 numbers \(I J A\(I,J\) B\(I,J\)\)"
    ):
        read_wamit(_write(tmp_path, "\n".join(lines)))


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (lambda t: t.replace("PHIBODY =   0.0", "PHIBODY =   30.0"), r"line 5: body 1 is rotated \(PHIBODY = 30 deg\)"),
        (lambda t: t.replace("     6     6   6", "     7     6   6", 1), r"mode index 7 .* generalised modes"),
        (lambda t: t.replace("Gravity:", "Gravitas:"), r"no 'Gravity: \.\.\. Length scale: \.\.\.' line"),
        (lambda t: t.replace("DIFFRACTION", "HASKIND"), r"no diffraction exciting forces.*excitation='haskind'"),
    ],
)
def test_format_errors(tmp_path: Path, change: Callable[[str], str], message: str) -> None:
    path = _write(tmp_path, change(_out_text()))
    with pytest.raises(WamitFormatError, match=message):
        read_wamit(path)


def test_haskind_tables_are_read_on_request(tmp_path: Path) -> None:
    path = _write(tmp_path, _out_text().replace("DIFFRACTION", "HASKIND"))
    ds = read_wamit(path, excitation="haskind")
    assert ds.attrs["excitation_kind"] == "haskind"


def test_argument_errors(tmp_path: Path) -> None:
    missing = tmp_path / "nothing.out"
    with pytest.raises(FileNotFoundError, match=r"nothing\.out"):
        read_wamit(missing)
    path = _write(tmp_path, _out_text())
    with pytest.raises(ValueError, match=r"body_names has 2 names .* has 1 bodies \(geometry files: cube.gdf\)"):
        read_wamit(path, body_names=["a", "b"])
    with pytest.raises(ValueError, match="must not contain '__'"):
        read_wamit(path, body_names=["a__b"])
    with pytest.raises(ValueError, match="rho must be a positive number; got -1"):
        read_wamit(path, rho=-1.0)
    with pytest.raises(ValueError, match="excitation must be 'diffraction' or 'haskind'; got 'rao'"):
        read_wamit(path, excitation="rao")  # type: ignore[arg-type]
