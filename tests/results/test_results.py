"""Result datasets: contents, units, netCDF round trip, metrics against closed forms and the frequency domain."""

from __future__ import annotations

import dataclasses
import os
import subprocess
import sys

import numpy as np
import pytest
import xarray as xr

from tests.sim.scenes import held, scene
from wecss.linear import linearize
from wecss.results import (
    capture_width_ratio,
    mean_power,
    open_result,
    rao_irregular,
    rao_regular,
    rms_hinge_angle,
    save,
    spectral_moments,
)
from wecss.sim import JIT, compile_scene, simulate
from wecss.waves import Jonswap, deep_water_wavelength, energy_flux, energy_period, mean_period


@pytest.fixture(scope="module")
def run() -> xr.Dataset:
    return simulate(
        scene(
            sea={"duration": 24.0, "ramp": 3.0},
            outputs={"variables": ["motion", "pto", "excitation", "radiation", "elevation", "poses"]},
        )
    )


def test_every_variable_has_long_name_and_units(run):
    for name, da in run.variables.items():
        if name in (
            "dof_linear",
            "dof_angular",
            "pto",
            "pto_kind",
            "hydro_dof_linear",
            "hydro_dof_angular",
            "body",
            "axis",
        ):
            assert "long_name" in da.attrs, name
            continue
        assert "long_name" in da.attrs and "units" in da.attrs, name
        assert " or " not in da.attrs["units"], name
    assert set(run.dof_angular.values) == {"bow__pitch", "hinge_3__pitch"}
    assert set(run.dof_linear.values) == {"bow__surge", "bow__heave"}


def test_netcdf_round_trip_is_identical(run, tmp_path):
    path = save(run, tmp_path / "r.nc")
    xr.testing.assert_identical(open_result(path), run)


def test_power_is_damping_times_rate_squared(run):
    rate = run.pto_angular_velocity.values
    np.testing.assert_allclose(run.pto_power.values, 6.0 * rate**2, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(run.pto_torque.values, -6.0 * rate, rtol=1e-12, atol=1e-15)


def test_statistics_only_matches_the_time_series():
    base = scene(sea={"duration": 24.0, "ramp": 3.0})
    full = simulate(base)
    stats = simulate(
        dataclasses.replace(base, outputs=dataclasses.replace(base.outputs, statistics_only=True, variables=()))
    )
    assert "time" not in stats.dims
    # running sums over steps vs the trapezoidal mean of the stored series: equal to O(dt / window)
    np.testing.assert_allclose(stats.mean_pto_power.values, mean_power(full).values, rtol=2e-3)
    np.testing.assert_allclose(stats.rms_pto_angle.values, rms_hinge_angle(full).values, rtol=2e-3)
    with pytest.raises(ValueError, match="no time series"):
        mean_power(stats, window=0.25)


def test_capture_width_ratio_conventions():
    sea = Jonswap(0.04, 1.2, 3.3)
    t = np.linspace(0.0, 10.0, 101)
    ds = xr.Dataset(
        {"pto_power": (("time", "pto"), np.full((t.size, 2), 0.25))},
        coords={"time": t, "pto": ["a", "b"]},
        attrs={
            "statistics_window": 0.5,
            "energy_period": energy_period(sea),
            "wave_energy_flux": energy_flux(sea),
            "g": 9.81,
            "scene": '{"sea": {"kind": "jonswap", "gamma": 3.3, "period": 1.2}}',
        },
    )
    cwr = capture_width_ratio(ds)
    expected = 0.5 / (energy_flux(sea) * deep_water_wavelength(energy_period(sea)))
    assert float(cwr) == pytest.approx(expected, rel=1e-12)
    paper = capture_width_ratio(ds, convention="paper")
    assert float(paper) == pytest.approx(0.5 / (energy_flux(sea) * deep_water_wavelength(0.84 * 1.2)), rel=1e-12)
    # the paper's 0.84 Tp is the mean period T01 of this spectrum, not its energy period
    assert mean_period(sea) / 1.2 == pytest.approx(0.84, abs=0.01)
    per_pto = capture_width_ratio(ds, power="per_pto")
    np.testing.assert_allclose(per_pto.values, expected / 2)
    with pytest.raises(ValueError, match="convention must be"):
        capture_width_ratio(ds, convention="other")


def test_rms_hinge_angle_of_a_sinusoid():
    t = np.linspace(0.0, 20.0, 4001)
    ds = xr.Dataset(
        {"pto_angle": (("time", "pto"), 0.03 * np.sin(2 * np.pi * t)[:, None] + 0.01)},
        coords={"time": t, "pto": ["h"]},
    )
    assert float(rms_hinge_angle(ds, 1.0).sel(pto="h")) == pytest.approx(0.03 / np.sqrt(2), rel=1e-4)


def test_regular_wave_rao_matches_the_frequency_domain():
    """Small regular waves: response amplitude / wave amplitude against |H(omega) X(omega)| of the linear model."""
    runs, expected = [], []
    for period in (0.9, 1.3):
        sc = scene(
            sea={"kind": "regular", "height": 0.004, "period": period, "duration": "40 T", "ramp": "5 T"},
            outputs={"variables": ["pto", "elevation"]},
        )
        compiled = compile_scene(sc)
        runs.append(simulate(compiled))
        omega = 2 * np.pi / period
        lin = linearize(compiled)
        h = lin.frequency_response(np.array([omega]))
        per_amplitude = compiled.excitation.coefficients[:, 0] / (0.004 / 2)
        expected.append(np.abs(lin.pto_jacobian @ h[0] @ per_amplitude))
    rao = rao_regular(runs)  # sorted by omega: the 1.3 s run first
    np.testing.assert_allclose(rao.values, np.array(expected[::-1]), rtol=0.01)


def test_irregular_rao_and_spectral_moments(run):
    rao = rao_irregular(run, window=1.0, segments=4)
    assert rao.dims == ("omega", "pto")
    peak = float(rao.omega[int(np.nanargmax(rao.values[:, 0]))])
    assert 2.0 < peak < 15.0
    moments = spectral_moments(run, window=1.0)
    variance = float(np.var(run.wave_elevation.values))
    assert moments[0] == pytest.approx(variance, rel=0.01)


def test_held_controller_force_approaches_the_continuous_damper():
    """A controller without linear gains is sampled once per step (zero-order hold): first order in dt."""
    sc = scene(sea={"duration": 8.0, "ramp": 2.0})
    compiled = compile_scene(sc)
    sampled = simulate(held(compiled))
    continuous = simulate(compiled)
    a, b = sampled.pto_angle.values, continuous.pto_angle.values
    assert np.sqrt(np.mean((a - b) ** 2)) <= 0.05 * np.sqrt(np.mean(b**2))
    assert "zero-order hold" in sampled.attrs["notes"]


@pytest.mark.skipif(not JIT, reason="numba is not installed: there is only the pure path")
def test_pure_python_path_gives_the_same_numbers(tmp_path):
    """The kernels without numba (WECSS_JIT=0) against the compiled ones, on a short run."""
    code = (
        "import sys; sys.path.insert(0, '.')\n"
        "from tests.sim.scenes import scene\n"
        "from wecss.sim import simulate, JIT\n"
        "from wecss.results import save\n"
        "ds = simulate(scene(sea={'duration': 0.3, 'ramp': 0.1}, solver={'dt': 0.006}))\n"
        f"save(ds, {str(tmp_path / 'r.nc')!r}); print(JIT)\n"
    )
    env = {**os.environ, "WECSS_JIT": "0"}
    out = subprocess.run(
        [sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True, cwd=os.getcwd()
    )
    assert out.stdout.strip() == "False"
    pure = open_result(tmp_path / "r.nc")
    compiled = simulate(scene(sea={"duration": 0.3, "ramp": 0.1}, solver={"dt": 0.006}))
    np.testing.assert_allclose(pure.pto_angle.values, compiled.pto_angle.values, rtol=1e-9, atol=1e-14)
    np.testing.assert_allclose(pure.angle.values, compiled.angle.values, rtol=1e-9, atol=1e-14)
