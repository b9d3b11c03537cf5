"""Generalised modes in hydrodynamic databases: DOF names and kinds, validation, selection and transforms, and the
three readers on files the tests write (a rigid body plus an extra mode), and on a real Capytaine custom DOF."""

from __future__ import annotations

import time
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import xarray as xr

from wecss.hydro import (
    HydroData,
    HydroDataError,
    HydroDataWarning,
    dof_index,
    dof_kind,
    dof_kinds,
    dof_name,
    is_rigid_dof,
    move_reference_point,
    read_bemio,
    read_capytaine,
    read_wamit,
    split_dof,
)
from wecss.hydro._build import build_dataset
from wecss.hydro._peaks import negligible_dofs
from wecss.hydro.readers.wamit import WamitFormatError

from .synthetic import spd, synthetic_dataset

RHO, G = 1000.0, 9.81


# --- names and kinds ---------------------------------------------------------------------------------------------


def test_dof_names_and_kinds_with_generalised_modes() -> None:
    assert dof_name("barge", "flex1") == "barge__flex1"
    assert split_dof("barge__flex1") == ("barge", "flex1")
    assert [dof_kind(d) for d in ("Surge", "bow__Heave", "Roll", "bow__Yaw", "flex1", "bow__flex1")] == [
        "linear", "linear", "angular", "angular", "generalised", "generalised",
    ]  # fmt: skip
    assert dof_kinds(["a__Pitch", "a__twist"]) == ("angular", "generalised")
    assert is_rigid_dof("Heave") and not is_rigid_dof("a__twist")
    assert dof_index("Pitch") == 4
    with pytest.raises(ValueError, match="'flex1' is not a rigid-body DOF"):
        dof_index("flex1")


@pytest.mark.parametrize(
    ("name", "message"),
    [
        ("heave", r"spells the rigid-body DOF 'Heave'"),
        ("", r"must be a non-empty string"),
        (" flex", r"without '__' or surrounding blanks"),
    ],
)
def test_bad_mode_names_are_refused(name: str, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        dof_name("barge", name)
    with pytest.raises(ValueError, match="is not of the form <body>__<Dof>"):
        split_dof(f"barge__{name}")


# --- a database with a mode --------------------------------------------------------------------------------------


def with_mode(ds: xr.Dataset, body: str = "a", mode: str = "flex1", seed: int = 1) -> xr.Dataset:
    """``ds`` with one generalised mode appended to ``body``'s DOFs: random symmetric couplings with every DOF."""
    rng = np.random.default_rng(seed)
    dofs = [str(d) for d in ds.radiating_dof.values]
    last = max(k for k, d in enumerate(dofs) if split_dof(d)[0] == body)
    new = [*dofs[: last + 1], f"{body}__{mode}", *dofs[last + 1 :]]
    n, at = len(new), last + 1
    keep = [k for k in range(n) if k != at]

    def grow(matrix: np.ndarray, extra: np.ndarray) -> np.ndarray:
        out = extra.copy()
        out[..., np.ix_(keep, keep)[0], np.ix_(keep, keep)[1]] = matrix
        return out

    omega = ds.omega.values
    full_a = spd(rng, n, 3.0)
    full_b = spd(rng, n, 2.0)
    bump = omega**2 / (1.0 + (omega - 2.0) ** 4)
    added = grow(ds.added_mass.values, np.broadcast_to(full_a, (omega.size, n, n)).copy())
    damping = grow(ds.radiation_damping.values, bump[:, None, None] * full_b)
    a_inf = grow(ds.added_mass_inf.values, full_a)
    a_zero = grow(ds.added_mass_zero.values, full_a)
    stiffness = grow(ds.hydrostatic_stiffness.values, np.zeros((n, n)))
    stiffness[at, at] = 50.0
    stiffness[at, at - 2] = stiffness[at - 2, at] = 5.0  # coupled with the body's heave
    exc = np.zeros((omega.size, ds.sizes["wave_direction"], n), dtype=complex)
    exc[..., keep] = ds.excitation.values
    exc[..., at] = 30.0 + 10.0j
    return build_dataset(
        omega=omega, dofs=new, wave_direction=ds.wave_direction.values, added_mass=added,
        radiation_damping=damping, added_mass_inf=a_inf, added_mass_zero=a_zero, excitation=exc,
        hydrostatic_stiffness=stiffness, bodies=list(ds.body.values), mass=ds.mass.values, inertia=ds.inertia.values,
        center_of_mass=ds.center_of_mass.values, center_of_buoyancy=ds.center_of_buoyancy.values,
        displaced_volume=ds.displaced_volume.values, reference_point=ds.reference_point.values, rho=RHO, g=G,
        water_depth=np.inf, source="synthetic test data with a generalised mode",
    )  # fmt: skip


def test_a_database_with_a_mode_is_valid_and_rigid_dofs_must_come_first() -> None:
    ds = with_mode(synthetic_dataset())
    hydro = HydroData(ds)
    assert hydro.dofs_of("a") == ["a__Surge", "a__Heave", "a__Pitch", "a__flex1"]
    assert "DOFs Surge, Heave, Pitch, flex1" in hydro.summary()
    order = [0, 3, 1, 2, 4, 5, 6]  # the mode before the body's Heave
    bad = ds.isel(radiating_dof=order, influenced_dof=order)
    with pytest.raises(HydroDataError, match=r"DOF 'a__Heave' comes after the generalised mode 'a__flex1'"):
        HydroData(bad)


def test_select_keeps_a_mode_by_its_name() -> None:
    hydro = HydroData(with_mode(synthetic_dataset()))
    assert hydro.select(dofs=["Heave", "flex1"]).dofs == ["a__Heave", "a__flex1", "b__Heave"]
    assert hydro.select(bodies=["b"]).dofs == ["b__Surge", "b__Heave", "b__Pitch"]
    with pytest.raises(ValueError, match=r"unknown DOFs \['twist'\]; accepted: .*, the generalised modes flex1"):
        hydro.select(dofs=["twist"])


def test_moving_the_reference_point_leaves_the_mode_alone() -> None:
    """T = blockdiag(T_rigid, I): the rigid block moves as without the mode, the mode's own entries stay, and its
    couplings with the rigid DOFs move with the rigid rows."""
    ds = with_mode(synthetic_dataset())
    moved = move_reference_point(ds, {"a": (0.3, 0.0, -0.2), "b": (1.2, 0.0, 0.1)})
    rigid = [d for d in ds.radiating_dof.values if not d.endswith("flex1")]
    alone = move_reference_point(ds.sel(radiating_dof=rigid, influenced_dof=rigid), {"a": (0.3, 0.0, -0.2),
                                 "b": (1.2, 0.0, 0.1)})  # fmt: skip
    for name in ("added_mass", "radiation_damping", "added_mass_inf", "hydrostatic_stiffness"):
        sub = moved[name].sel(radiating_dof=rigid, influenced_dof=rigid)
        np.testing.assert_allclose(sub.values, alone[name].values, rtol=1e-12, atol=1e-12)
        mode = {"radiating_dof": "a__flex1", "influenced_dof": "a__flex1"}
        assert float(moved[name].sel(mode).isel({"omega": 0} if "omega" in moved[name].dims else {})) == float(
            ds[name].sel(mode).isel({"omega": 0} if "omega" in ds[name].dims else {})
        )
    # its coupling with body a's pitch: row f of A_P = A_O T^-1 with T^-1 = [[I, hat(r)], [0, I]], r = P - O
    m = ds.added_mass_inf.sel(influenced_dof="a__flex1")
    r = np.array([0.3, 0.0, -0.2]) - ds.reference_point.values[0]
    surge, heave, pitch = (float(m.sel(radiating_dof=f"a__{d}")) for d in ("Surge", "Heave", "Pitch"))
    expected = pitch - r[2] * surge + r[0] * heave
    got = float(moved.added_mass_inf.sel(influenced_dof="a__flex1", radiating_dof="a__Pitch"))
    assert got == pytest.approx(expected, rel=1e-12)
    np.testing.assert_array_equal(
        moved.excitation.sel(influenced_dof="a__flex1").values, ds.excitation.sel(influenced_dof="a__flex1").values
    )


def test_negligible_damping_is_judged_among_the_modes() -> None:
    """A mode whose damping is tiny next to the translations' but not next to another mode's is kept."""
    ds = with_mode(with_mode(synthetic_dataset(), mode="flex1"), mode="flex2", seed=2)
    damping = ds.radiation_damping.values.copy()
    dofs = list(ds.radiating_dof.values)
    i, j = dofs.index("a__flex1"), dofs.index("a__flex2")
    for k in (i, j):
        damping[:, k, :] *= 1e-8
        damping[:, :, k] *= 1e-8
    damping[:, j, j] *= 1e-7
    flags = negligible_dofs(ds.assign(radiation_damping=(ds.radiation_damping.dims, damping)))
    assert not flags[i] and flags[j]


# --- WAMIT ------------------------------------------------------------------------------------------------------

PERIODS = (10.0, 5.0, 2.0)


def _a(i: int, j: int, period: float) -> float:
    return 100.0 * i + j + period / 10 if i == j else 0.5 * (i + j)


def _wamit_out(n_modes: int = 7) -> str:
    """A one-body WAMIT .out with ``n_modes`` modes (7: the six rigid ones and one generalised mode)."""
    lines = [
        "                        WAMIT  Version 7.2(x64)        ",
        " Input from Geometric Data File:         barge.gdf",
        " Gravity:     9.81000                Length scale:        1.00000",
        " Water depth:        infinite",
        " XBODY =    0.0000 YBODY =    0.0000 ZBODY =    0.0000 PHIBODY =   0.0",
        " Volumes (VOLX,VOLY,VOLZ):           2.00000      2.00000      2.00000",
        " Center of Buoyancy (Xb,Yb,Zb):     0.000000     0.000000    -0.250000",
        " Hydrostatic and gravitational restoring coefficients: ",
        " C(3,3),C(3,4),C(3,5):   3.0000      0.0000      0.0000    ",
        " C(4,4),C(4,5),C(4,6):               1.0000      0.0000     0.000000",
        "        C(5,5),C(5,6):                          1.0000      0.0000",
        " Center of Gravity  (Xg,Yg,Zg):     0.000000     0.000000     0.000000",
        "",
    ]
    modes = range(1, n_modes + 1)
    for header, value in (("Wave period = infinite", 1000.0), ("Wave period = zero", 1.0)):
        lines += [" " + "*" * 72, "", f" {header}                  Wavenumber = x", " " + "-" * 72, "", ""]
        lines += ["    ADDED-MASS COEFFICIENTS", "     I     J         A(I,J)", ""]
        lines += [f"{i:6d}{j:6d}   {_a(i, j, value):.6E}" for i in modes for j in modes]
        lines += ["", ""]
    for period in PERIODS:
        lines += [" " + "*" * 72, "", f" Wave period (sec) =  {period:.6E}        Wavenumber (kL) =  1.0E-01"]
        lines += [" " + "-" * 72, "", "", "    ADDED-MASS AND DAMPING COEFFICIENTS"]
        lines += ["     I     J         A(I,J)         B(I,J)", ""]
        lines += [
            f"{i:6d}{j:6d}   {_a(i, j, period):.6E}   {(period / 10 if i == j else 0.0):.6E}"
            for i in modes
            for j in modes
        ]
        lines += ["", "", "", "    DIFFRACTION EXCITING FORCES AND MOMENTS", ""]
        lines += ["  Wave Heading (deg) :     0", "", "     I     Mod[Xh(I)]     Pha[Xh(I)]", ""]
        lines += [f"{i:6d}   {i * period:.6E}    {10 * i:6.0f}" for i in modes]
        lines += ["", ""]
    lines += [" " + "*" * 72, ""]
    return "\n".join(lines)


def test_wamit_reads_a_generalised_mode_named_by_the_cfg(tmp_path: Path) -> None:
    out = tmp_path / "barge.out"
    out.write_text(_wamit_out())
    (tmp_path / "barge.cfg").write_text("IPERIN = 1\nNEWMDS(1) = 1   ! one bending mode\n")
    (tmp_path / "barge.hst").write_text(" 7 7  4.0E+00\n 3 7  0.5E+00\n 7 3  0.5E+00\n")
    ds = read_wamit(out, body_names=["barge"], mode_names={"barge": ["bend"]})
    assert list(ds.radiating_dof.values)[-2:] == ["barge__Yaw", "barge__bend"]
    mode = {"influenced_dof": "barge__bend", "radiating_dof": "barge__bend"}
    # normalised as a translation: A = Abar rho L^3, B = Bbar rho omega L^3, X = Xbar rho g L^2, C = Cbar rho g L^2
    np.testing.assert_allclose(ds.added_mass.sel(mode).values, [(707 + t / 10) * RHO for t in PERIODS])
    np.testing.assert_allclose(float(ds.added_mass_inf.sel(mode)), (707 + 0.1) * RHO)
    omega = 2 * np.pi / np.array(PERIODS)
    np.testing.assert_allclose(ds.radiation_damping.sel(mode).values, np.array(PERIODS) / 10 * RHO * omega)
    coupling = {"influenced_dof": "barge__bend", "radiating_dof": "barge__Pitch"}
    np.testing.assert_allclose(float(ds.added_mass_inf.sel(coupling)), 6.0 * RHO)  # 0.5 (7 + 5) rho L^(3+0+1)
    x = ds.excitation.sel(influenced_dof="barge__bend").values[:, 0]
    np.testing.assert_allclose(x, 7 * np.array(PERIODS) * RHO * G * np.exp(1j * np.deg2rad(70)), rtol=1e-6)
    np.testing.assert_allclose(float(ds.hydrostatic_stiffness.sel(mode)), 4.0 * RHO * G)
    assert float(ds.hydrostatic_stiffness.sel(influenced_dof="barge__Heave", radiating_dof="barge__bend")) == (
        pytest.approx(0.5 * RHO * G)
    )
    assert ds.attrs["wamit_files"] == "barge.out, barge.cfg, barge.hst"
    HydroData(ds)  # valid
    default = read_wamit(out)
    assert list(default.radiating_dof.values)[-1] == "body_1__mode7"


def test_wamit_needs_the_number_of_modes_per_body(tmp_path: Path) -> None:
    out = tmp_path / "barge.out"
    out.write_text(_wamit_out())
    with pytest.raises(WamitFormatError, match=r"mode index 7 .* keep the run's \.cfg beside the \.out or pass"):
        read_wamit(out)
    assert list(read_wamit(out, mode_names={"body_1": ["bend"]}).radiating_dof.values)[-1] == "body_1__bend"
    (tmp_path / "barge.cfg").write_text("NEWMDS = 2\n")
    with pytest.raises(WamitFormatError, match=r"NEWMDS\(1\) = 2, but mode_names gives body 'body_1' 1 modes"):
        read_wamit(out, mode_names={"body_1": ["bend"]})
    with pytest.raises(ValueError, match=r"mode_names names unknown body 'hull'; accepted: body_1, body_2"):
        read_wamit(out, mode_names={"hull": ["bend"]})


# --- BEMIO ----------------------------------------------------------------------------------------------------------


def test_bemio_reads_a_body_with_a_generalised_mode(tmp_path: Path) -> None:
    h5py = pytest.importorskip("h5py")
    ds = with_mode(synthetic_dataset(), body="a")
    full = ds.reindex(  # the rigid DOFs BEMIO always has (6 per body), zero where the synthetic data have none
        radiating_dof=_bemio_dofs(ds), influenced_dof=_bemio_dofs(ds), fill_value=0.0
    )
    sizes = [7, 6]
    starts = [0, 7]
    omega = full.omega.values
    with h5py.File(tmp_path / "flex.h5", "w") as f:
        f["simulation_parameters/rho"] = RHO
        f["simulation_parameters/g"] = G
        f["simulation_parameters/w"] = omega
        f["simulation_parameters/wave_dir"] = np.rad2deg(full.wave_direction.values)
        f["simulation_parameters/water_depth"] = "infinite"
        f["simulation_parameters/scaled"] = 1.0
        for b, name in enumerate(full.body.values):
            rows = slice(starts[b], starts[b] + sizes[b])
            body = f"body{b + 1}"
            f[f"{body}/properties/name"] = name
            f[f"{body}/properties/cg"] = full.reference_point.values[b]
            f[f"{body}/properties/cb"] = full.center_of_buoyancy.values[b]
            f[f"{body}/properties/disp_vol"] = float(full.displaced_volume.values[b])
            f[f"{body}/properties/dof"] = sizes[b]
            f[f"{body}/properties/dof_start"] = starts[b] + 1
            coeffs = f"{body}/hydro_coeffs"
            f[f"{coeffs}/linear_restoring_stiffness"] = full.hydrostatic_stiffness.values[rows, rows]
            f[f"{coeffs}/added_mass/all"] = np.moveaxis(full.added_mass.values, 0, -1)[rows]
            f[f"{coeffs}/added_mass/inf_freq"] = full.added_mass_inf.values[rows]
            f[f"{coeffs}/radiation_damping/all"] = np.moveaxis(full.radiation_damping.values, 0, -1)[rows]
            exc = np.transpose(full.excitation.values, (2, 1, 0))[rows]
            f[f"{coeffs}/excitation/re"], f[f"{coeffs}/excitation/im"] = exc.real, exc.imag
    read = read_bemio(tmp_path / "flex.h5", mode_names={"a": ["flex1"]})
    assert list(read.radiating_dof.values) == list(full.radiating_dof.values)
    for name in ("added_mass", "radiation_damping", "added_mass_inf", "hydrostatic_stiffness", "excitation"):
        np.testing.assert_allclose(read[name].values, full[name].values, rtol=1e-12, atol=1e-12)
    assert list(read_bemio(tmp_path / "flex.h5").radiating_dof.values)[6] == "a__mode7"
    with pytest.raises(ValueError, match=r"mode_names\['a'\] must give 1 distinct names \(the body's dof is 7\)"):
        read_bemio(tmp_path / "flex.h5", mode_names={"a": ["x", "y"]})


def _bemio_dofs(ds: xr.Dataset) -> list[str]:
    rigid = ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")
    out = []
    for body in ds.body.values:
        modes = [split_dof(d)[1] for d in ds.radiating_dof.values if split_dof(d)[0] == body]
        out += [f"{body}__{d}" for d in (*rigid, *(m for m in modes if m not in rigid))]
    return out


# --- Capytaine ---------------------------------------------------------------------------------------------------


def _capytaine_like(ds: xr.Dataset) -> xr.Dataset:
    """``ds`` laid out as Capytaine writes it (omega = inf in the frequencies, e^{-i omega t}, weight terms are
    absent here because the centres of mass are the rotation centres), custom DOF ``flex1`` included, its order
    shuffled (the mode first)."""
    order = [3, 0, 1, 2, 4, 5, 6]
    ds = ds.isel(radiating_dof=order, influenced_dof=order)
    omega = np.append(ds.omega.values, np.inf)
    added = np.concatenate([ds.added_mass.values, ds.added_mass_inf.values[None]])
    damping = np.concatenate([ds.radiation_damping.values, np.zeros((1, *ds.added_mass_inf.shape))])
    exc = np.concatenate([np.conj(ds.excitation.values), np.full((1, *ds.excitation.shape[1:]), np.nan)])
    dofs = list(ds.radiating_dof.values)
    return xr.Dataset(
        {
            "added_mass": (("omega", "influenced_dof", "radiating_dof"), added),
            "radiation_damping": (("omega", "influenced_dof", "radiating_dof"), damping),
            "excitation_force": (("omega", "wave_direction", "influenced_dof"), exc),
            "hydrostatic_stiffness": (("influenced_dof", "radiating_dof"), ds.hydrostatic_stiffness.values),
            "center_of_mass": (("body", "space_coordinate"), ds.center_of_mass.values),
            "center_of_buoyancy": (("body", "space_coordinate"), ds.center_of_buoyancy.values),
            "rotation_center": (("body", "space_coordinate"), ds.reference_point.values),
            "disp_mass": (("body",), RHO * ds.displaced_volume.values),
        },
        coords={
            "omega": omega, "influenced_dof": dofs, "radiating_dof": dofs, "wave_direction": ds.wave_direction.values,
            "body": list(ds.body.values), "g": G, "rho": RHO, "water_depth": np.inf,
        },
    )  # fmt: skip


def test_capytaine_reads_a_custom_dof_rigid_dofs_first() -> None:
    ds = with_mode(synthetic_dataset(), body="a")
    com = ds.reference_point.values
    ds = ds.assign(center_of_mass=(("body", "axis"), com))  # no weight terms to remove
    bodies = {"a": np.eye(3), "b": np.eye(3)}
    read = read_capytaine(_capytaine_like(ds), inertia=bodies)
    assert list(read.radiating_dof.values) == list(ds.radiating_dof.values)
    for name in ("added_mass", "radiation_damping", "added_mass_inf", "hydrostatic_stiffness"):
        np.testing.assert_allclose(read[name].values, ds[name].values, rtol=1e-14)
    np.testing.assert_allclose(read.excitation.values, ds.excitation.values, rtol=1e-14)
    HydroData(read)
    given = ds.hydrostatic_stiffness.copy(data=2 * ds.hydrostatic_stiffness.values)
    np.testing.assert_allclose(
        read_capytaine(_capytaine_like(ds), inertia=bodies, hydrostatic_stiffness=given).hydrostatic_stiffness,
        given.values,
    )


def _capytaine_flexible_sphere(cpt: Any) -> xr.Dataset:
    """A coarse floating hemisphere with a custom DOF (vertical displacement x^2 - 0.3 m per unit coordinate) solved
    at a few frequencies; Capytaine computes no hydrostatics for it."""
    mesh = cpt.mesh_sphere(radius=1.0, center=(0.0, 0.0, 0.0), resolution=(6, 10)).immersed_part()
    body = cpt.FloatingBody(mesh=mesh, dofs=cpt.rigid_body_dofs(rotation_center=(0, 0, 0)), name="ball")
    shape = np.zeros_like(body.mesh.faces_centers)
    shape[:, 2] = body.mesh.faces_centers[:, 0] ** 2 - 0.3
    body.dofs["flex1"] = shape
    test = xr.Dataset(
        coords={
            "omega": [0.5, 1.0, 1.5, 2.0, np.inf],
            "wave_direction": [0.0],
            "radiating_dof": list(body.dofs),
            "water_depth": [np.inf],
            "rho": [RHO],
        }
    )
    return cpt.BEMSolver().fill_dataset(test, body, hydrostatics=False)


def test_capytaine_custom_dof_from_a_real_solve() -> None:
    cpt = pytest.importorskip("capytaine")
    start = time.perf_counter()
    raw = _capytaine_flexible_sphere(cpt)
    stiffness = np.zeros((7, 7))
    stiffness[2, 2], stiffness[6, 6] = RHO * G * np.pi, 100.0
    read = read_capytaine(
        raw, mass={"ball": 2094.0}, inertia={"ball": [400.0, 400.0, 400.0]}, center_of_mass={"ball": [0, 0, -0.375]},
        center_of_buoyancy={"ball": [0, 0, -0.375]}, displaced_volume={"ball": 2.094},
        hydrostatic_stiffness=stiffness,
    )  # fmt: skip
    assert list(read.radiating_dof.values)[-1] == "ball__flex1"
    mode = {"influenced_dof": "ball__flex1", "radiating_dof": "ball__flex1"}
    assert float(read.added_mass_inf.sel(mode)) > 0 and np.all(read.radiation_damping.sel(mode).values > 0)
    # the exp(-i omega t) excitation is conjugated, on the mode as on the rigid DOFs
    capy = raw.excitation_force.sel(influenced_dof="flex1", omega=1.0).values
    np.testing.assert_allclose(read.excitation.sel(influenced_dof="ball__flex1", omega=1.0).values, np.conj(capy))
    # the coarse mesh's coupling of the mode with heave is symmetric to 0.5 %: the default repair symmetrises it
    with pytest.warns(HydroDataWarning, match=r"symmetrised added_mass .* ball__flex1"):
        hydro = HydroData.from_capytaine(
            raw, mass={"ball": 2094.0}, inertia={"ball": [400.0] * 3}, displaced_volume={"ball": 2.094},
            center_of_mass={"ball": [0, 0, -0.375]}, center_of_buoyancy={"ball": [0, 0, -0.375]},
            hydrostatic_stiffness=stiffness,
        )  # fmt: skip
    assert hydro.dofs_of("ball")[-1] == "ball__flex1"
    assert time.perf_counter() - start < 60
