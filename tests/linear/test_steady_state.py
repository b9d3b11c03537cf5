"""The public frequency-domain solution ``wecss.linear.steady_state``: a Dataset of complex amplitudes per wave
component (no time argument needed), time series on request, and the same numbers as ``solver.method =
"frequency"`` and the nonlinear simulator in small waves."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from tests.sim.scenes import held, scene
from wecss.linear import linearize, steady_state
from wecss.netcdf import read_netcdf, write_netcdf
from wecss.results import response_amplitude
from wecss.sim import compile_scene, simulate

REPEAT = 24.0  # the record repeats exactly over the run: the window mean of a periodic run is the long-time mean
SEA = {"height": 0.004, "duration": REPEAT, "d_omega": 2 * np.pi / REPEAT, "ramp": 2.0}


@pytest.fixture(scope="module")
def periodic():
    return compile_scene(
        scene(
            "m4-111",
            sea=SEA,
            solver={"method": "frequency"},
            outputs={"variables": ["motion", "pto"], "window": 1.0},
        )
    )


def test_amplitudes_need_no_time(periodic):
    ds = steady_state(periodic)
    assert isinstance(ds, xr.Dataset) and "time" not in ds.dims
    n_w = periodic.excitation.omega.size
    assert ds.pto_angle_amplitude.dims == ("omega", "pto") and ds.sizes["omega"] == n_w
    assert ds.angle_amplitude.dims == ("omega", "dof_angular")
    assert ds.displacement_amplitude.dims == ("omega", "dof_linear")
    assert np.iscomplexobj(ds.pto_angle_amplitude.values)
    assert list(ds.pto_kind.values) == ["rotary"]
    assert ds.pto_angle_amplitude.attrs["units"] == "rad" and ds.omega.attrs["units"] == "rad/s"
    assert ds.excitation_force_amplitude.dims == ("omega", "hydro_dof_linear")
    assert (
        ds.excitation_force_amplitude.attrs["units"] == "N" and ds.excitation_moment_amplitude.attrs["units"] == "N m"
    )
    heave = list(periodic.excitation.dofs).index("float_1__Heave")
    np.testing.assert_array_equal(
        ds.excitation_force_amplitude.sel(hydro_dof_linear="float_1__Heave"), periodic.excitation.coefficients[heave]
    )
    # the PTO stroke is the hinge angle of m4-111: its amplitude is the hinge coordinate's
    np.testing.assert_allclose(
        ds.pto_angle_amplitude.sel(pto="pto_3"), ds.angle_amplitude.sel(dof_angular="hinge_3__pitch"), rtol=1e-12
    )


def test_time_series_and_power_match_the_frequency_run(periodic):
    """The frequency-method run sums -f v over the steps of one whole period; the Dataset's mean power comes from
    the amplitudes alone (c sum omega^2 |x|^2 / 2)."""
    run = simulate(periodic)
    ds = steady_state(periodic, periodic.time)
    np.testing.assert_allclose(ds.pto_angle.values, run.pto_angle.values, rtol=0, atol=1e-12)
    np.testing.assert_allclose(ds.angle.values, run.angle.values, rtol=0, atol=1e-12)
    np.testing.assert_allclose(ds.pto_angular_velocity.values, run.pto_angular_velocity.values, rtol=0, atol=1e-12)
    np.testing.assert_allclose(steady_state(periodic).mean_pto_power, run.mean_pto_power, rtol=1e-9)
    # the time series are the amplitudes' sum about the equilibrium
    t = periodic.time[:50]
    sum_ = np.real(np.exp(1j * np.outer(t, ds.omega.values)) @ ds.pto_angle_amplitude.sel(pto="pto_3").values)
    equilibrium = linearize(periodic).pto_stroke[0]
    series = steady_state(periodic, t).pto_angle.sel(pto="pto_3").values
    np.testing.assert_allclose(series - equilibrium, sum_, rtol=0, atol=1e-14)


def test_amplitude_per_wave_amplitude_is_the_nonlinear_rao_in_small_regular_waves():
    """Regular wave, H 4 mm: the nonlinear simulator's hinge amplitude over the wave amplitude against
    |pto_angle_amplitude / wave_amplitude|, independent of the frequency-domain code."""
    sc = scene(
        "m4-111",
        sea={"kind": "regular", "height": 0.004, "period": 1.1, "duration": "40 T", "ramp": "5 T"},
        outputs={"variables": ["pto"]},
    )
    compiled = compile_scene(sc)
    fd = steady_state(compiled)
    assert fd.sizes["omega"] == 1
    rao = float(np.abs(fd.pto_angle_amplitude / fd.wave_amplitude).squeeze())
    assert float(np.abs(fd.wave_amplitude).squeeze()) == pytest.approx(0.002)
    run = simulate(compiled)
    measured = float(response_amplitude(run, "pto_angle", 2 * np.pi / 1.1, window=0.5).sel(pto="pto_3")) / 0.002
    assert measured == pytest.approx(rao, rel=0.01)


def test_steady_state_round_trips_through_netcdf(periodic, tmp_path):
    ds = steady_state(periodic, periodic.time[:10])
    xr.testing.assert_identical(read_netcdf(write_netcdf(ds, tmp_path / "fd.nc")), ds)


def test_steady_state_refuses_what_it_cannot_solve(periodic):
    with pytest.raises(TypeError, match="takes a CompiledScene"):
        steady_state(periodic.scene)
    calm = compile_scene(scene("m4-111", sea={"kind": "calm", "duration": 2.0, "ramp": 0.0}))
    with pytest.raises(ValueError, match="calm water"):
        steady_state(calm)
    with pytest.raises(ValueError, match="linear gains"):
        steady_state(held(periodic))
