"""Verification of generalised modes against closed forms.

1. A mode without hydrodynamics (generalised mass m, stiffness k) on a floating M4 body in waves oscillates freely at
   omega_n = sqrt(k / m) in the nonlinear runs (Beeman, RK4) and in the linear model's modal table: it is decoupled
   from the rigid motion (no inertial coupling, no hydro data). (The M4 111 layout's explicit added-mass iteration
   does not converge, modes or not: its split is checked directly.)
2. A body held fixed with one mode whose database entries are known in closed form: the steady amplitude in regular
   waves of amplitude A is |F A| / |k - omega^2 (m + a) + i omega b| (a 1-DOF oscillator), exactly in the
   frequency domain for constant a and b, and to the integrator's accuracy in the time domain for the added mass and
   damping of a first-order memory kernel K(t) = k0 exp(-alpha t) (a(omega) = a_inf - k0 / (alpha^2 + omega^2),
   b(omega) = k0 alpha / (alpha^2 + omega^2): data a radiation fit can represent); the modal table's period solves
   omega^2 (m + a(omega)) = k.
3. A rigid device given the data of a mode no body declares is refused.
"""

from __future__ import annotations

import dataclasses
from importlib.resources import files
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from scipy.optimize import brentq

from tests.hydro.test_generalised_modes import with_mode
from wecss.devices import load
from wecss.hydro import HydroData
from wecss.hydro import load as load_hydro
from wecss.hydro._build import build_dataset
from wecss.linear import modal_table, steady_state
from wecss.sim import Scene, compile_scene, simulate
from wecss.sim._explicit import split_added_mass

M_G, K_G = 0.5, 80.0  # the M4 mode: generalised mass [kg m^2], stiffness [N m]
M, K, F = 2.0, 80.0, 50.0 + 10.0j  # the fixed body's mode and its excitation per metre of wave amplitude [J/m]
A_INF, K0, ALPHA = 2.0, 20.0, 3.0  # the memory kernel's A_inf [kg m^2], K(0) [kg m^2/s^2], decay rate [1/s]
H, T = 0.1, 1.6  # regular wave height [m] and period [s]


def coordinate(ds: xr.Dataset, name: str) -> np.ndarray:
    """The time series of generalised coordinate ``name``: a mode is a coordinate of its own kind in a result
    (``dof_generalised``, units 1), never among the translations (``dof_linear``, m)."""
    if "__flex" in name:
        assert "dof_linear" not in ds.coords or name not in ds.dof_linear.values
        assert ds.generalised_coordinate.attrs["units"] == "1"
        return np.asarray(ds.generalised_coordinate.sel(dof_generalised=name).values)
    return np.asarray(ds.displacement.sel(dof_linear=name).values)


@pytest.fixture(scope="module")
def flexible_m4(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The m4-111 spec with a mode on the mid float and no hydrodynamic data for it."""
    text = (files("wecss") / "data" / "devices" / "m4-111.toml").read_text()
    text = text.replace('name = "m4-111"', 'name = "m4-111-flexible"', 1)
    text = text.replace(
        'hydro_body = "float_2"\n',
        f'hydro_body = "float_2"\nmodes = [{{name = "flex1", mass = {M_G}, stiffness = {K_G}}}]\n',
    )
    path = tmp_path_factory.mktemp("flexible") / "m4-111-flexible.toml"
    path.write_text(text)
    return path


def _flexible_scene(path: Path, method: str, outputs: dict) -> Scene:
    return Scene.from_dict(
        {
            "device": {"name": str(path)},
            "sea": {"kind": "regular", "height": 0.04, "period": 1.2, "duration": "8 Tp", "ramp": "2 Tp"},
            "solver": {"method": method, "dt": "Tp/200"},
            "outputs": outputs,
        }
    )


@pytest.mark.parametrize("method", ["beeman", "rk4"])
def test_a_mode_without_hydrodynamics_oscillates_at_its_natural_frequency(flexible_m4: Path, method: str) -> None:
    compiled = compile_scene(_flexible_scene(flexible_m4, method, {"variables": ["motion"]}))
    names = compiled.device.model.velocity_names
    assert names[-1] == "float_2__flex1" and compiled.device.model.velocity_kinds[-1] == "generalised"
    q0 = compiled.q0.copy()
    q0[-1] = 0.01  # released from a displaced mode, in waves
    ds = simulate(dataclasses.replace(compiled, q0=q0))
    x, t = coordinate(ds, "float_2__flex1"), ds.time.values
    crossing = np.flatnonzero(np.sign(x[:-1]) * np.sign(x[1:]) < 0)
    zeros = t[crossing] - x[crossing] * (t[crossing + 1] - t[crossing]) / (x[crossing + 1] - x[crossing])
    period = 2 * float(np.mean(np.diff(zeros)))
    exact = 2 * np.pi * np.sqrt(M_G / K_G)
    step = 2 * np.pi / exact * compiled.dt  # omega_n dt = 0.076: Beeman's period error is (omega dt)^2 / 24 = 2.4e-4
    assert abs(period / exact - 1) < step**2 / 12  # measured: Beeman -2.4e-4, RK4 2.8e-7
    assert np.max(np.abs(x)) == pytest.approx(0.01, rel=1e-3)  # undamped, unforced
    assert np.ptp(coordinate(ds, "bow__heave")) > 1e-3  # while the float moves in the waves
    if method == "beeman":
        table = modal_table(compiled)
        mode = int(np.argmax(np.abs(table.shape.sel(dof="float_2__flex1").values)))
        assert float(table.period[mode]) == pytest.approx(exact, rel=1e-10)


def test_loads_close_and_the_explicit_split_keeps_the_modal_mass(flexible_m4: Path) -> None:
    """The loads recovery balances the modes' rows too (the structural stiffness in the configuration's loads);
    the explicit added-mass split keeps the generalised mass on the left (the mode has no added mass here)."""
    scene = _flexible_scene(flexible_m4, "beeman", {"variables": ["motion", "loads"], "every": 10})
    compiled = compile_scene(
        dataclasses.replace(scene, sea=dataclasses.replace(scene.sea, duration="2 Tp", ramp="1 Tp"))
    )
    q0 = compiled.q0.copy()
    q0[-1] = 0.01
    ds = simulate(dataclasses.replace(compiled, q0=q0))
    assert ds.attrs["loads_closure_residual"] < 1e-9
    p = compiled.plant
    rigid, added = split_added_mass(p)
    row = int(np.flatnonzero(p.active == p.mode_row[0])[0])
    assert rigid.active_mass[row, row] == M_G and not np.any(added[row])


def _one_mode_database(constant: bool) -> HydroData:
    omega = np.linspace(0.05, 30.0, 600)
    if constant:
        a, b, a_inf = np.full(omega.size, 1.2), np.full(omega.size, 3.0), 1.2
    else:
        a, b, a_inf = A_INF - K0 / (ALPHA**2 + omega**2), K0 * ALPHA / (ALPHA**2 + omega**2), A_INF
    return HydroData(
        build_dataset(
            omega=omega, dofs=["barge__flex1"], wave_direction=np.array([0.0]), added_mass=a[:, None, None],
            radiation_damping=b[:, None, None], added_mass_inf=np.array([[a_inf]]),
            excitation=np.full((omega.size, 1, 1), F), hydrostatic_stiffness=np.zeros((1, 1)), bodies=["barge"],
            mass=[100.0], inertia=[np.eye(3)], center_of_mass=[[0.0, 0.0, 0.0]], center_of_buoyancy=[[0.0, 0.0, 0.0]],
            displaced_volume=[0.1], reference_point=[[0.0, 0.0, 0.0]], rho=1000.0, g=9.81, water_depth=np.inf,
            source="one generalised mode in closed form",
        )
    )  # fmt: skip


def _one_mode_scene(tmp_path: Path, constant: bool, solver: str) -> Scene:
    kind = "constant" if constant else "kernel"
    _one_mode_database(constant).to_netcdf(tmp_path / f"{kind}.nc")
    (tmp_path / f"{kind}.toml").write_text(
        f'name = "barge-{kind}"\nhydro = "{kind}.nc"\n[[bodies]]\nname = "barge"\nmass = 100.0\n'
        'inertia = [1.0, 1.0, 1.0]\ncenter_of_mass = [0.0, 0.0, 0.0]\nhydro_body = "barge"\n'
        f'modes = [{{name = "flex1", mass = {M}, stiffness = {K}}}]\n[[joints]]\nname = "base"\nkind = "fixed"\n'
        'child = "barge"\n'
    )
    return Scene.from_dict(
        {
            "device": {"name": str(tmp_path / f"{kind}.toml")},
            "sea": {"kind": "regular", "height": H, "period": T, "duration": "40 Tp", "ramp": "5 Tp"},
            "solver": {"method": solver, "dt": "Tp/100"},
            "outputs": {"variables": ["motion", "excitation"]},
        }
    )


def _closed_form(a: float, b: float) -> float:
    omega = 2 * np.pi / T
    return abs(F * H / 2) / abs(K - omega**2 * (M + a) + 1j * omega * b)


def test_frequency_domain_amplitude_of_a_mode_with_constant_coefficients(tmp_path: Path) -> None:
    compiled = compile_scene(_one_mode_scene(tmp_path, constant=True, solver="frequency"))
    amplitude = steady_state(compiled).generalised_coordinate_amplitude.sel(dof_generalised="barge__flex1")
    assert float(np.abs(amplitude).max()) == pytest.approx(_closed_form(1.2, 3.0), rel=1e-12)


def test_time_domain_amplitude_and_modal_period_of_a_mode_with_a_memory_kernel(tmp_path: Path) -> None:
    compiled = compile_scene(_one_mode_scene(tmp_path, constant=False, solver="beeman"))
    ds = simulate(compiled)
    x, t = coordinate(ds, "barge__flex1"), ds.time.values
    assert ds.excitation_generalised_force.attrs["units"] == "J"  # the mode's excitation: a generalised force
    assert list(ds.hydro_dof_generalised.values) == ["barge__flex1"]
    omega = 2 * np.pi / T
    last = t > t[-1] - 10 * T
    basis = np.column_stack([np.cos(omega * t[last]), np.sin(omega * t[last]), np.ones(np.count_nonzero(last))])
    cos, sin, _ = np.linalg.lstsq(basis, x[last], rcond=None)[0]
    a, b = A_INF - K0 / (ALPHA**2 + omega**2), K0 * ALPHA / (ALPHA**2 + omega**2)
    assert np.hypot(cos, sin) == pytest.approx(_closed_form(a, b), rel=3e-3)  # measured -7e-4
    exact = steady_state(compiled).generalised_coordinate_amplitude.sel(dof_generalised="barge__flex1")
    assert float(np.abs(exact).max()) == pytest.approx(_closed_form(a, b), rel=1e-3)  # linear interpolation in omega
    natural = brentq(lambda w: w**2 * (M + A_INF - K0 / (ALPHA**2 + w**2)) - K, 0.1, 20.0)
    table = modal_table(compiled)
    assert float(table.period[0]) == pytest.approx(2 * np.pi / natural, rel=1e-4)
    ratio = K0 * ALPHA / (ALPHA**2 + natural**2) / (2 * (M + A_INF - K0 / (ALPHA**2 + natural**2)) * natural)
    assert float(table.damping_ratio[0]) == pytest.approx(ratio, rel=1e-3)


def test_a_database_mode_no_body_declares_is_refused() -> None:
    hydro = HydroData(with_mode(load_hydro("m4-111").dataset, body="float_1", mode="bend"))
    with pytest.raises(ValueError, match=r"generalised mode 'float_1__bend', which body 'float_1' .* does not declare"):
        load("m4-111").coupling(hydro)
    kept = hydro.select(dofs=[d for d in hydro.dofs if not d.endswith("__bend")])
    assert load("m4-111").coupling(kept).index.size == 9
