"""Spectra, elevation records and excitation forces."""

from __future__ import annotations

import numpy as np
import pytest

from wecss.hydro import HydroData
from wecss.waves import (
    Jonswap,
    PiersonMoskowitz,
    Ramp,
    TabulatedSpectrum,
    deep_water_wavelength,
    energy_flux,
    energy_period,
    excitation_coefficients,
    excitation_model,
    from_elevation,
    hm0,
    irregular,
    mean_period,
    regular,
    wavenumber,
)

from ..hydro.synthetic import synthetic_dataset


@pytest.mark.parametrize("gamma", [1.0, 2.0, 3.3, 7.0])
def test_spectrum_integrates_to_hs_squared_over_16(gamma: float) -> None:
    s = Jonswap(0.04, 1.2, gamma)
    w = np.linspace(1e-3, 200.0, 2_000_001)
    assert np.trapezoid(s.density(w), w) == pytest.approx(0.04**2 / 16, rel=1e-6)
    assert hm0(s) == pytest.approx(0.04, rel=1e-12)


@pytest.mark.parametrize("n", [-2, -1, 0, 1, 2, 3])
def test_spectral_moments_of_the_shape(n: int) -> None:
    """Pierson-Moskowitz (gamma 1): int w^(n-5) exp(-1.25 w^-4) dw = Gamma((4 - n) / 4) 1.25^((n - 4) / 4) / 4 in
    closed form; JONSWAP: scipy's adaptive quadrature (to 1e-13) on the same pieces."""
    import math

    from scipy.integrate import quad

    from wecss.waves._spectra import _jonswap_shape, _shape_moment

    closed = math.gamma((4 - n) / 4) * 1.25 ** ((n - 4) / 4) / 4
    assert _shape_moment(n, 1.0) == pytest.approx(closed, rel=1e-13)
    for gamma in (1.5, 3.3, 7.0, 20.0):

        def integrand(w: float, gamma: float = gamma) -> float:
            return float(w**n * _jonswap_shape(np.array([w]), 1.0, gamma)[0])

        pieces = ((0.0, 0.5), (0.5, 1.0), (1.0, 1.5), (1.5, 3.0), (3.0, np.inf))
        reference = sum(quad(integrand, lo, hi, limit=200, epsabs=0.0, epsrel=1e-13)[0] for lo, hi in pieces)
        assert _shape_moment(n, gamma) == pytest.approx(reference, rel=1e-13)
    with pytest.raises(ValueError, match="infinite"):
        _shape_moment(4, 3.3)


def test_gamma_one_is_pierson_moskowitz_closed_form() -> None:
    hs, tp = 2.5, 9.0
    wp = 2 * np.pi / tp
    w = np.linspace(0.05, 5.0, 1000)
    closed = 5 / 16 * hs**2 * wp**4 * w**-5 * np.exp(-1.25 * (wp / w) ** 4)  # Bretschneider / PM
    np.testing.assert_allclose(PiersonMoskowitz(hs, tp).density(w), closed, rtol=1e-9)


@pytest.mark.parametrize(("gamma", "te", "t01"), [(3.3, 0.903, 0.834), (1.0, 0.857, 0.772)])
def test_period_ratios(gamma: float, te: float, t01: float) -> None:
    s = Jonswap(1.0, 1.2, gamma)
    assert energy_period(s) / 1.2 == pytest.approx(te, rel=5e-3)
    assert mean_period(s) / 1.2 == pytest.approx(t01, rel=5e-3)


def test_energy_flux_deep_and_finite_depth() -> None:
    s = Jonswap(0.04, 1.2, 3.3)
    rho, g = 1000.0, 9.81
    w = np.geomspace(1e-2, 1e4, 2_000_001)  # the omega^-6 tail of S / omega matters at 1e-6
    direct = rho * g * np.trapezoid(s.density(w) * g / (2 * w), w)
    assert energy_flux(s) == pytest.approx(direct, rel=1e-6)
    # in deep-enough water the finite-depth flux tends to the deep one; in shallow water it differs
    assert energy_flux(s, depth=50.0) == pytest.approx(energy_flux(s), rel=1e-6)
    assert energy_flux(s, depth=0.3) != pytest.approx(energy_flux(s), rel=1e-2)
    assert deep_water_wavelength(1.2) == pytest.approx(9.81 * 1.44 / (2 * np.pi))


def test_dispersion_relation() -> None:
    omega = np.array([0.3, 1.0, 3.0, 10.0])
    k = wavenumber(omega, 2.0)
    np.testing.assert_allclose(9.81 * k * np.tanh(2.0 * k), omega**2, rtol=1e-12)


def test_periodic_record_has_exactly_the_discrete_variance_and_repeats() -> None:
    s = Jonswap(0.04, 1.2, 3.3)
    waves = irregular(s, d_omega=0.05, omega_max=30.0, seed=3, energy_threshold=0.0)
    period = waves.repeat_period
    assert period == pytest.approx(2 * np.pi / 0.05)
    t = np.linspace(0.0, period, 2**16, endpoint=False)
    eta = waves.elevation(t)
    k = np.arange(1, round(30.0 / 0.05) + 1)
    discrete = np.sum(s.density(k * 0.05) * 0.05)
    assert np.mean(eta**2) == pytest.approx(discrete, rel=1e-10)
    np.testing.assert_allclose(waves.elevation(t[:50] + period), eta[:50], atol=1e-12)


def test_same_seed_same_record_other_seed_other_record() -> None:
    s = Jonswap(0.04, 1.2, 3.3)
    a = irregular(s, d_omega=0.05, omega_max=30.0, seed=7)
    b = irregular(s, d_omega=0.05, omega_max=30.0, seed=7)
    c = irregular(s, d_omega=0.05, omega_max=30.0, seed=8)
    np.testing.assert_array_equal(a.amplitude, b.amplitude)
    assert not np.allclose(a.amplitude, c.amplitude)
    nonperiodic = irregular(s, d_omega=0.05, omega_max=30.0, seed=7, periodic=False)
    assert nonperiodic.repeat_period is None and not np.allclose(nonperiodic.omega % 0.05, 0)


def test_negligible_components_are_dropped_and_reported() -> None:
    waves = irregular(Jonswap(0.04, 1.2, 3.3), d_omega=0.05, omega_max=60.0, seed=1, energy_threshold=1e-4)
    report = waves.dropped
    assert report is not None and report.count > 100
    assert 0 < report.energy_share <= 1e-4
    assert "variance (threshold 1e-04)" in str(report)


def test_measured_record_round_trip() -> None:
    waves = irregular(Jonswap(0.04, 1.2, 3.3), d_omega=2 * np.pi / 100.0, omega_max=20.0, seed=2, energy_threshold=0)
    t = np.arange(0.0, 100.0, 0.02)
    eta = waves.elevation(t)
    back = from_elevation(t, eta, energy_threshold=0.0)
    np.testing.assert_allclose(back.elevation(t), eta, atol=1e-12)
    with pytest.raises(ValueError, match="uniformly"):
        from_elevation(np.array([0.0, 1.0, 3.0, 4.0]), np.zeros(4))


def test_regular_wave_and_ramp() -> None:
    wave = regular(0.04, 1.2, phase=0.3)
    t = np.linspace(0, 5, 101)
    np.testing.assert_allclose(wave.elevation(t), 0.02 * np.cos(2 * np.pi / 1.2 * t + 0.3), atol=1e-15)
    ramp = Ramp(2.0)
    np.testing.assert_allclose(ramp(np.array([0.0, 1.0, 2.0, 3.0])), [0.0, 0.5, 1.0, 1.0], atol=1e-15)
    with pytest.raises(ValueError, match="looks like degrees"):
        regular(0.04, 1.2, direction=90.0)


def _travelling_excitation_hydro() -> HydroData:
    """Body 'b' at x = 1 m whose excitation is exactly X0 exp(-i k x_b): a pure incident-wave phase."""
    ds = synthetic_dataset(n_omega=40)
    omega = ds.omega.values
    k = omega**2 / 9.81
    x = np.zeros_like(ds.excitation.values)
    x[:, 0, :3] = 100.0 + 20j  # body a at x = 0
    x[:, 0, 3:] = (50.0 - 10j) * np.exp(-1j * k * 1.0)[:, None]  # body b at x = 1
    return HydroData(ds.assign(excitation=ds.excitation.copy(data=x)))


def test_excitation_interpolation_keeps_the_incident_phase() -> None:
    hydro = _travelling_excitation_hydro()
    omega = np.array([3.333, 6.789])  # between data frequencies, where the phase turns fast
    x = excitation_coefficients(hydro, omega)
    np.testing.assert_allclose(x[3, 0], (50.0 - 10j) * np.exp(-1j * omega[0] ** 2 / 9.81), rtol=1e-12)
    np.testing.assert_allclose(x[4, 1], (50.0 - 10j) * np.exp(-1j * omega[1] ** 2 / 9.81), rtol=1e-12)


def test_excitation_force_of_a_regular_wave() -> None:
    hydro = _travelling_excitation_hydro()
    wave = regular(0.1, 1.5, phase=0.2)
    model = excitation_model(hydro, wave)
    t = np.linspace(0, 3, 7)
    w = 2 * np.pi / 1.5
    expected = np.real((100.0 + 20j) * 0.05 * np.exp(1j * (w * t + 0.2)))
    np.testing.assert_allclose(model.force(t)[0], expected, rtol=1e-12)
    with pytest.raises(ValueError, match="outside the database"):
        excitation_model(hydro, regular(0.1, 0.2))


def test_tabulated_spectrum() -> None:
    s = TabulatedSpectrum(np.array([0.0, 1.0, 2.0]), np.array([0.0, 1.0, 0.0]))
    assert s.moment(0) == pytest.approx(1.0, rel=1e-8)
    assert s.density(np.array([0.5, 3.0])).tolist() == [0.5, 0.0]
    with pytest.raises(ValueError, match="strictly increasing"):
        TabulatedSpectrum(np.array([0.0, 2.0, 1.0]), np.ones(3))


@pytest.mark.parametrize(
    ("omega", "t0", "n_times", "fft"),
    [
        (np.delete(np.arange(3, 90), [7, 40]) * 2 * np.pi / 12.0, 0.35, 1201, True),  # periodic, 1200 steps per period
        (np.array([2 * np.pi / 1.2]), 0.0, 50, True),  # a regular wave sampled at T / 200 (period 200 steps)
        (np.arange(3, 90) * 2 * np.pi / 12.0 + 1e-4, 0.35, 1201, False),  # off the grid: the recurrence
    ],
)
def test_evaluate_equals_the_sum_of_exponentials(omega, t0, n_times, fft) -> None:
    """The FFT path (periodic components on a uniform grid) and the phasor recurrence both give the direct sum of
    complex exponentials, beyond one period of the record as well."""
    from wecss.waves._elevation import _fft_period, evaluate

    rng = np.random.default_rng(3)
    coefficients = rng.normal(size=(3, omega.size)) + 1j * rng.normal(size=(3, omega.size))
    dt = 0.006
    time = t0 + dt * np.arange(n_times)
    assert (_fft_period(omega, dt, n_times) is not None) == fft
    exact = coefficients @ np.exp(1j * np.outer(omega, time))
    assert np.max(np.abs(evaluate(coefficients, omega, time) - exact)) <= 1e-12 * np.max(np.abs(exact))
    if fft:  # past the period (the record repeats)
        later = time + dt * 2 * n_times
        exact = coefficients @ np.exp(1j * np.outer(omega, later))
        assert np.max(np.abs(evaluate(coefficients, omega, later) - exact)) <= 1e-12 * np.max(np.abs(exact))
