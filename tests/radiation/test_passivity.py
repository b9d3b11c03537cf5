"""Passivity of state-space radiation models: the enforcement on a non-passive model, and the shipped fits, checked
independently of the code that made them (the damping matrix from direct solves on a dense grid, and the tail bound
from A, B, C by hand)."""

from __future__ import annotations

import numpy as np
import pytest

from wecss.radiation import RadiationStateSpace, enforce_passivity, tail_bound
from wecss.radiation._passivity import lift_response

from .analytic import known_system


def _lowest_damping_eigenvalue(model: RadiationStateSpace, omega: np.ndarray, scale: np.ndarray) -> np.ndarray:
    """lambda_min of S (K_hat + K_hat^H)/2 S at each omega, K_hat from a direct (sparse LU) solve of
    (i omega I - A) X = B."""
    from scipy.sparse import csc_matrix, identity
    from scipy.sparse.linalg import splu

    root = 1.0 / np.sqrt(scale)
    a = csc_matrix(model.A)
    eye = identity(model.n_states, format="csc")
    out = np.empty(omega.size)
    for k, w in enumerate(omega):
        h = model.C @ splu((1j * w * eye - a).tocsc()).solve(model.B.astype(complex))
        h = root[:, None] * h * root[None, :]
        out[k] = np.linalg.eigvalsh(0.5 * (h + h.conj().T))[0]
    return out


def _tail_by_hand(model: RadiationStateSpace, scale: np.ndarray) -> tuple[float, float, float]:
    """(skew of C B, lambda_min(-sym(C A B)), rho + 2 r / mu) of the scaled model, from A, B, C and eig(A)."""
    root = 1.0 / np.sqrt(scale)
    b, c = model.B * root[None, :], model.C * root[:, None]
    cb, cab = c @ b, c @ model.A @ b
    mu = np.linalg.eigvalsh(-(cab + cab.T) / 2)[0]
    lam, vec = np.linalg.eig(model.A)
    left, right = c @ vec, np.linalg.solve(vec, b)
    r = np.sum(np.linalg.norm(left, axis=0) * np.linalg.norm(right, axis=1) * np.abs(lam) ** 2)
    return float(np.abs(cb - cb.T).max()), float(mu), float(np.abs(lam.imag).max() + 2 * r / mu)


def test_lift_section_is_positive_real() -> None:
    """Re T(i omega) of T(s) = a2 s / ((s + a1)(s + a2)) from the closed form against complex arithmetic: >= 0,
    zero at 0, about 1 between the corners."""
    omega = np.geomspace(1e-3, 1e4, 500)
    a1, a2 = 0.3, 40.0
    s = 1j * omega
    direct = np.real(a2 * s / ((s + a1) * (s + a2)))
    np.testing.assert_allclose(lift_response(a1, a2, omega), direct, rtol=1e-12, atol=1e-300)
    assert np.all(direct >= 0) and lift_response(a1, a2, np.array([0.0]))[0] == 0
    assert np.all(lift_response(a1, a2, np.array([3.0, 4.0])) > 0.9)


def test_enforcement_makes_a_non_passive_model_passive() -> None:
    """A known passive 2-DOF model with one residue sign flipped (Re K_hat < 0 over a band): the enforced model is
    passive on a dense grid of direct solves up to its tail bound, whose conditions hold by hand; the damping
    changes little where the model was passive."""
    a, b, c = known_system()
    bad = c.copy()
    bad[1, 4] *= -3.0
    model = RadiationStateSpace(a, b, bad, ("p__Heave", "q__Heave"))
    scale = np.array([400.0, 300.0])
    omega_data = np.linspace(0.05, 20.0, 400)
    grid = np.linspace(0.01, 40.0, 4000)
    assert _lowest_damping_eigenvalue(model, grid, scale).min() < -1e-3
    passive, report = enforce_passivity(model, omega_data, scale)
    assert report.after is not None and report.after.passive and report.before is not None
    assert report.before.margin < -1e-3 and report.lift_states > 0
    skew, mu, omega_tail = _tail_by_hand(passive, scale)
    assert skew < 1e-9 and mu > 0
    assert omega_tail == pytest.approx(tail_bound(passive, scale).omega_tail, rel=1e-9)
    dense = np.concatenate([np.linspace(0.0, 60.0, 6001), np.geomspace(60.0, 1.2 * omega_tail, 3000)])
    lowest = _lowest_damping_eigenvalue(passive, dense, scale)
    assert lowest.min() >= -1e-10
    # K_hat(0) = 0: the damping vanishes at omega = 0
    np.testing.assert_allclose(passive.C @ np.linalg.solve(-passive.A, passive.B), 0.0, atol=1e-9)


def test_a_passive_model_is_left_alone() -> None:
    a, b, c = known_system()
    model = RadiationStateSpace(a, b, c, ("p__Heave", "q__Heave"))
    same, report = enforce_passivity(model, np.linspace(0.05, 20.0, 400), np.array([400.0, 300.0]))
    assert same is model and report.lift_states == 0


@pytest.mark.parametrize("name", ["m4-111", "m4-132", "m4-134"])
def test_shipped_fits_are_passive(name: str) -> None:
    """The shipped fit of each M4 layout (the one a default state-space scene loads): lambda_min of the scaled
    damping >= -1e-12 on a grid of direct solves (dense over the data, across every resonance, logarithmic to 1.2 x
    the tail bound), CB symmetric and -sym(CAB) > 0 by hand (so passive above the tail bound)."""
    from wecss.compiled import fit_request
    from wecss.devices import load as load_device
    from wecss.radiation import damping_scale, fit_cache_key, load_cached_fit
    from wecss.scene import Scene

    hydro = load_device(name).coupling().hydro
    settings, band = fit_request(Scene().radiation, hydro)
    cached = load_cached_fit(fit_cache_key(hydro, settings, band))
    assert cached is not None, "no shipped fit for the default settings"
    model = cached[0]
    scale = damping_scale(hydro.dataset.radiation_damping.values)
    skew, mu, omega_tail = _tail_by_hand(model, scale)
    assert skew < 1e-8 * np.abs(model.C @ model.B).max() and mu > 0
    lam = np.linalg.eigvals(model.A)
    upper = lam[lam.imag > 0]
    across = (upper.imag[:, None] + np.abs(upper.real)[:, None] * np.array([-2, -1, -0.5, 0, 0.5, 1, 2])).ravel()
    grid = np.unique(
        np.concatenate([np.linspace(0.0, 40.0, 801), across[across > 0], np.geomspace(40.0, 1.2 * omega_tail, 300)])
    )
    lowest = _lowest_damping_eigenvalue(model, grid, scale)
    assert lowest.min() >= -1e-12, (lowest.min(), grid[np.argmin(lowest)])


def test_a_model_the_enforcement_cannot_fix_is_kept_and_reported() -> None:
    """K_hat = -1 / (s + 1) on one DOF: negative damping at omega = 0, where no lift reaches, and K_hat(0) = 0 would
    take all of C. The fitted model comes back unchanged, and the report says it is not passive and why."""
    model = RadiationStateSpace(np.array([[-1.0]]), np.array([[1.0]]), np.array([[-1.0]]), ("p__Heave",))
    same, report = enforce_passivity(model, np.linspace(0.05, 10.0, 200), np.array([1.0]))
    assert same is model and report.after is not None and not report.after.passive
    assert str(report).startswith("NOT PASSIVE: enforcement failed") and "omega = 0" in str(report)
