"""Radiation memory: impulse responses against a closed form, fits that recover a known system, passivity repair,
and the 1-DOF agreement of convolution, state space and the exact frequency-domain solution."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from wecss.radiation import (
    FitSettings,
    RadiationConvolution,
    RadiationStateSpace,
    filon_cosine_weights,
    fit_radiation,
    impulse_response,
)
from wecss.waves import Jonswap, excitation_coefficients, irregular

from .analytic import analytic_hydro, analytic_kernel, known_system, response


@pytest.fixture(scope="module")
def hydro():
    return analytic_hydro(np.arange(0.05, 100.0001, 0.05))


@pytest.fixture(scope="module")
def irf(hydro):
    return impulse_response(hydro)


def test_filon_weights_are_exact_for_piecewise_linear_functions() -> None:
    omega = np.array([0.0, 0.3, 1.0, 1.1, 4.0])
    values = np.array([0.0, 2.0, -1.0, 0.5, 0.2])
    for t in (0.0, 0.7, 13.0):
        fine = np.linspace(0.0, 4.0, 400001)
        direct = np.trapezoid(np.interp(fine, omega, values) * np.cos(fine * t), fine)
        assert filon_cosine_weights(omega, np.array([t]))[0] @ values == pytest.approx(direct, abs=1e-9)


def test_impulse_response_matches_closed_form(irf) -> None:
    exact = analytic_kernel(irf.time)
    peak = np.max(np.abs(exact), axis=0)
    error = np.abs(irf.kernel - exact) / peak
    assert np.max(error[0]) < 1e-3  # K(0), with the fitted tail beyond 100 rad/s
    assert np.max(error[irf.time > 0.2]) < 5e-4
    np.testing.assert_allclose(irf.kernel[0], irf.k0_integral, rtol=1e-12)  # K(0) = (2/pi) int B
    assert irf.time[-1] <= np.pi / 0.05 + 1e-9
    assert np.all(irf.truncation_time > 1.0) and np.all(irf.truncation_time < irf.time[-1])
    with pytest.raises(ValueError, match="exceeds pi / d_omega"):
        impulse_response(analytic_hydro(np.arange(0.05, 20.0001, 0.05)), t_max=100.0)


@pytest.mark.parametrize("method", ["prony", "era", "era-mimo"])
def test_fits_recover_the_known_system(hydro, irf, method: str) -> None:
    fit = fit_radiation(hydro, FitSettings(method=method), irf=irf)
    report = fit.report
    assert report.attrs["targets_met"] == 1
    assert report.attrs["stable"] == 1 and report.attrs["passive"] == 1
    # the true system: 6 states (3 oscillatory modes); per-entry fits realise each coupling separately
    expected_states = 6 if method == "era-mimo" else 4 + 4 + 2 * 2
    assert fit.model.n_states == expected_states
    a, b, c = known_system()
    omega = np.linspace(0.1, 30, 300)
    exact = response(a, b, c, omega)
    exact = 0.5 * (exact + np.swapaxes(exact, 1, 2))
    np.testing.assert_allclose(fit.model.frequency_response(omega), exact, atol=2e-3 * np.abs(exact).max())


def _one_dof_case(name: str):
    """(one-DOF HydroData, mass [kg], stiffness [N/m], PTO damping [N s/m], JONSWAP) of a heaving float."""
    if name == "analytic":
        one = analytic_hydro(np.arange(0.05, 100.0001, 0.05)).select(bodies=["p"])
        return one, 100.0, 1000.0, 150.0, Jonswap(0.1, 2.0, 3.3), 2 * np.pi / 64.0
    import wecss.hydro

    one = wecss.hydro.load("m4-111").select(bodies=["float_1"], dofs=["Heave"])
    ds = one.dataset
    mass = float(ds.mass.values[0])
    stiffness = float(ds.hydrostatic_stiffness.values[0, 0])
    return one, mass, stiffness, 20.0, Jonswap(0.04, 1.0, 3.3), 2 * np.pi / 64.0


@pytest.mark.parametrize("case", ["analytic", "m4-111 bow float"])
def test_one_dof_convolution_state_space_and_frequency_domain_agree(case: str) -> None:
    """Heave of one float with a linear damper in a periodic irregular sea: three independent solutions."""
    one, mass, stiffness, pto, spectrum, d_omega = _one_dof_case(case.split()[0])
    irf1 = impulse_response(one)
    fit = fit_radiation(one, irf=irf1)
    ds = one.dataset
    a_inf = float(ds.added_mass_inf.values[0, 0])
    waves = irregular(spectrum, d_omega=d_omega, omega_max=min(12.0, one.omega[-1]), seed=4, energy_threshold=0.0)
    x = excitation_coefficients(one, waves.omega)[0] * waves.amplitude
    # exact steady state: (-w^2 (m + A) + i w (B + c) + K) X = F
    a_w = np.interp(waves.omega, one.omega, ds.added_mass.values[:, 0, 0])
    b_w = np.interp(waves.omega, one.omega, ds.radiation_damping.values[:, 0, 0])
    z = -(waves.omega**2) * (mass + a_w) + 1j * waves.omega * (b_w + pto) + stiffness
    period = 2 * np.pi / d_omega
    t = np.arange(0.0, 3 * period, 0.005)
    force = np.real(np.exp(1j * np.outer(t, waves.omega)) @ x)
    exact = np.real(np.exp(1j * np.outer(t, waves.omega)) @ (x / z))
    last = t >= 2 * period  # after the transient
    model = fit.model

    def rhs(tt: float, y: np.ndarray) -> np.ndarray:
        pos, vel, states = y[0], y[1], y[2:]
        f = np.real(np.exp(1j * tt * waves.omega) @ x)
        acc = (f - stiffness * pos - pto * vel - (model.C @ states)[0]) / (mass + a_inf)
        return np.concatenate([[vel, acc], model.A @ states + model.B[:, 0] * vel])

    sol = solve_ivp(rhs, (0, t[-1]), np.zeros(2 + model.n_states), t_eval=t, method="DOP853", rtol=1e-9, atol=1e-12)
    ss = sol.y[0]

    # convolution, with the implicit trapezoidal rule (Newmark average acceleration) on the same step
    dt = t[1] - t[0]
    conv = RadiationConvolution(irf1, dt)
    pos = np.zeros(t.size)
    vel, acc = 0.0, 0.0
    m_eff = mass + a_inf
    for n in range(1, t.size):
        # x_n = x + dt/2 (v + v_n), a_n = 2 (v_n - v)/dt - a, memory force = history + newest * v_n
        lhs = m_eff * 2 / dt + pto - conv.newest[0, 0] + stiffness * dt / 2
        rhs_ = force[n] + conv.history[0] - stiffness * (pos[n - 1] + dt / 2 * vel) + m_eff * (2 * vel / dt + acc)
        v_new = rhs_ / lhs
        acc = 2 * (v_new - vel) / dt - acc
        pos[n] = pos[n - 1] + dt / 2 * (vel + v_new)
        vel = v_new
        conv.push(np.array([vel]))
    rms = np.sqrt(np.mean(exact[last] ** 2))
    err_ss = np.sqrt(np.mean((ss[last] - exact[last]) ** 2)) / rms
    err_conv = np.sqrt(np.mean((pos[last] - exact[last]) ** 2)) / rms
    print(
        f"1-DOF heave ({case}): RMS error state space {err_ss:.2e} ({model.n_states} states), "
        f"convolution {err_conv:.2e}"
    )
    assert err_ss < 5e-3
    assert err_conv < 5e-3


def test_cache_returns_the_same_fit(tmp_path, monkeypatch) -> None:
    # the module's data to 40 rad/s every 0.1 rad/s (not to 100 every 0.05): the cache does not depend on the grid,
    # and each of the three impulse responses made here costs 0.06 s instead of 1.2 s
    hydro = analytic_hydro(np.arange(0.1, 40.0001, 0.1))
    monkeypatch.setenv("WECSS_CACHE_DIR", str(tmp_path))
    first = fit_radiation(hydro, cache=True)
    files = list((tmp_path / "radiation").glob("*.nc"))
    assert len(files) == 1
    second = fit_radiation(hydro, cache=True)
    np.testing.assert_array_equal(second.model.A, first.model.A)
    np.testing.assert_array_equal(second.model.C, first.model.C)
    assert second.report.attrs["n_states"] == first.report.attrs["n_states"]
    other = fit_radiation(hydro, FitSettings(rms_tol=0.02), cache=True)
    assert other.model.n_states > 0 and len(list((tmp_path / "radiation").glob("*.nc"))) == 2


def test_fit_plot(hydro, irf) -> None:
    import matplotlib

    matplotlib.use("Agg")
    from wecss.radiation import plot_fit

    fig = plot_fit(fit_radiation(hydro, irf=irf))
    assert len(fig.axes) == 2


def test_real_modal_form_keeps_the_kernel() -> None:
    a, b, c = known_system()
    model = RadiationStateSpace(a, b, c, ("p__Heave", "q__Heave"))
    modal = model.real_modal()
    assert np.count_nonzero(modal.A) <= 4 * modal.n_states  # 2x2 blocks
    omega = np.linspace(0.1, 20.0, 40)
    np.testing.assert_allclose(modal.frequency_response(omega), model.frequency_response(omega), atol=1e-10)


def test_shipped_fits_are_found_when_the_user_cache_is_empty(tmp_path, monkeypatch) -> None:
    """Band-limited fits of the shipped M4 databases ship with the package (studies/generate_fits.py)."""
    from wecss.devices import load as load_device
    from wecss.radiation import fit_cache_key, load_cached_fit

    monkeypatch.setenv("WECSS_CACHE_DIR", str(tmp_path))
    hydro = load_device("m4-111").coupling().hydro
    top = float(hydro.omega[-1])
    key = fit_cache_key(hydro, FitSettings(method="era-mimo"), (0.6 * top, top))
    hit = load_cached_fit(key)
    assert hit is not None
    model, report = hit
    assert model.n_states == int(report.attrs["n_states"]) and model.is_stable(0.0)
    assert not list(tmp_path.glob("**/*.nc"))


def test_balanced_truncation_error_is_within_its_bound() -> None:
    from wecss.radiation import balanced_truncation

    a, b, c = known_system()
    model = RadiationStateSpace(a, b, c, ("p__Heave", "q__Heave"))
    omega = np.linspace(0.0, 60.0, 6001)
    full = model.frequency_response(omega)
    for order in (2, 4):
        reduction = balanced_truncation(model, order=order)
        assert reduction.model.n_states == order
        error = np.linalg.norm(full - reduction.model.frequency_response(omega), ord=2, axis=(1, 2)).max()
        assert 0 < error <= reduction.error_bound
    exact = balanced_truncation(model, tol=1e-9)
    assert exact.model.n_states == 6 and exact.error_bound == 0.0
    np.testing.assert_allclose(exact.model.frequency_response(omega), full, atol=1e-9 * np.abs(full).max())
    with pytest.raises(ValueError, match="exactly one of order"):
        balanced_truncation(model)


def test_truncate_to_error_meets_its_target_on_a_finer_grid_and_within_the_a_priori_bound() -> None:
    """The order is chosen on a coarse grid; on a grid ten times finer the error stays near the target, never
    above the a-priori bound 2 sum of the discarded Hankel singular values, and one state fewer (balanced afresh by
    ``balanced_truncation``) misses the target."""
    from wecss.radiation import balanced_truncation, truncate_to_error

    a, b, c = known_system()
    model = RadiationStateSpace(a, b, c, ("p__Heave", "q__Heave"))
    coarse, fine = np.linspace(0.0, 60.0, 601), np.linspace(0.0, 60.0, 6001)
    full = model.frequency_response(fine)
    peak = np.linalg.norm(full, ord=2, axis=(1, 2)).max()
    for target in (0.3, 0.17, 0.065):  # orders 2, 3 and 5 of 6
        reduction, measured = truncate_to_error(model, target, coarse)
        assert measured <= target
        error = np.linalg.norm(full - reduction.model.frequency_response(fine), ord=2, axis=(1, 2)).max()
        assert error <= reduction.error_bound * (1 + 1e-9) + 1e-12 * peak
        assert error <= 1.05 * target * peak
        order = reduction.model.n_states
        assert 0 < order < 6
        fewer = balanced_truncation(model, order=order - 1).model.frequency_response(coarse)
        coarse_full = model.frequency_response(coarse)
        coarse_peak = np.linalg.norm(coarse_full, ord=2, axis=(1, 2)).max()
        assert np.linalg.norm(fewer - coarse_full, ord=2, axis=(1, 2)).max() > target * coarse_peak
    with pytest.raises(ValueError, match="relative_error"):
        truncate_to_error(model, 1.5, coarse)
