"""Sums of wave components in blocks of samples (a chirp-z transform per block) against the direct sum of the
components, and the work per block against the record's length."""

from __future__ import annotations

import numpy as np
import pytest

from wecss.waves import BlockSum, Jonswap, Ramp, excitation_model, irregular
from wecss.waves._blocks import fast_length, harmonic_period

from ..hydro.synthetic import synthetic_dataset

TP: float = 1.2
"""Peak period of the default sea [s]."""

TAU: float = TP / 200
"""The default step [s]."""


def default_sea(periods: float, periodic: bool = True):  # type: ignore[no-untyped-def]
    """The default scene's JONSWAP (Hs 0.04 m, Tp 1.2 s, gamma 3.3) for ``periods`` Tp, as the scene makes it."""
    return irregular(
        Jonswap(0.04, TP, 3.3), d_omega=2 * np.pi / (periods * TP), omega_max=20.0, seed=1, periodic=periodic
    )


def direct_sum(coefficients: np.ndarray, omega: np.ndarray, n: np.ndarray) -> np.ndarray:
    """sum_k C[j, k] exp(i omega_k n tau), one complex exponential per component and time (the reference)."""
    return coefficients @ np.exp(1j * np.outer(omega, n * TAU))


@pytest.mark.parametrize("n", [0, 1, 2, 7, 100, 1000, 87480, 174761])
def test_fast_length_is_the_smallest_5_smooth_length(n) -> None:
    length = fast_length(max(1, n))
    assert length >= n
    smooth = [m for m in range(max(1, n), length + 1) if _is_5_smooth(m)]
    assert smooth[0] == length


def _is_5_smooth(m: int) -> bool:
    for p in (2, 3, 5):
        while m % p == 0:
            m //= p
    return m == 1


@pytest.mark.parametrize(("block", "tau"), [(700, TAU), (4096, TAU), (700, TAU / 2)])
def test_blocks_equal_the_direct_sum_of_the_components(block, tau) -> None:
    """The default JONSWAP for 100 Tp with three rows (as for several DOFs or bodies), on the steps or the half
    steps: at the start, across block boundaries, in the second period and far into a long run."""
    waves = default_sea(100)
    rng = np.random.default_rng(5)
    coefficients = waves.amplitude[None, :] * (rng.normal(size=(3, waves.omega.size)) + 1j)
    sums = BlockSum.on_grid(coefficients, waves.omega, tau, block)
    assert sums is not None and sums.period == round(100 * TP / tau)
    scale = np.abs(coefficients).sum(axis=1).max()
    for n0, m in [(0, 3 * sums.block + 17), (sums.block - 5, 10), (sums.period - 40, 80), (10**6 + 3, 50)]:
        n = n0 + np.arange(m)
        expected = coefficients @ np.exp(1j * np.outer(waves.omega, n * tau))
        tolerance = 1e-14 * scale * max(1.0, float(waves.omega.max() * n[-1] * tau))  # the reference's phases
        assert np.max(np.abs(sums(n0, m) - expected)) <= tolerance


def test_sampled_excitation_equals_the_excitation_model() -> None:
    """A two-body database with a wave direction (the incident phase at each body's position): the forces by
    blocks, ramp included, equal the model's forces."""
    from wecss.hydro import HydroData

    hydro = HydroData(synthetic_dataset())
    waves = irregular(Jonswap(0.05, 2.0, 3.3), d_omega=2 * np.pi / 400.0, omega_max=float(hydro.omega[-1]), seed=2)
    model = excitation_model(hydro, waves, ramp=Ramp(5.0))
    tau = 0.01
    sampled = model.sampled(tau, 1000)
    assert sampled is not None
    n0, m = 150, 2500  # the ramp and three blocks
    expected = model.force(tau * (n0 + np.arange(m)))
    np.testing.assert_allclose(sampled(n0, m), expected.T, rtol=0, atol=1e-12 * np.abs(expected).max())
    np.testing.assert_allclose(sampled.sums.real(n0, m), np.real(sampled.sums(n0, m)).T, rtol=0, atol=0)


def test_records_that_do_not_repeat_have_no_blocks() -> None:
    waves = default_sea(100, periodic=False)
    assert harmonic_period(waves.omega, TAU) is None
    assert BlockSum.on_grid(waves.amplitude, waves.omega, TAU) is None


def test_the_work_per_sample_does_not_grow_with_the_record(monkeypatch) -> None:
    """Flat cost (a count, not a timing): for the loop's block of samples, records of 100, 1000 and 10,000 Tp (320
    to 32,000 components) make the same FFTs per block, at most 1.25 times as long as the block, and a call for
    the same samples does the same work at the start of the run and 10^6 samples into it."""
    calls: list[tuple[int, ...]] = []
    fft = np.fft.fft

    def counted(a, *args, **kwargs):  # type: ignore[no-untyped-def]
        calls.append(np.shape(a))
        return fft(a, *args, **kwargs)

    block = 2**22 // 24  # the loop's blocks on the default scene (24 hydrodynamic DOFs)
    lengths = []

    for periods in (100, 1000, 10_000):
        waves = default_sea(periods)
        sums = BlockSum.on_grid(np.ones((2, waves.omega.size)) * waves.amplitude, waves.omega, TAU, block)
        assert sums is not None
        assert block <= sums.block and sums.length <= 1.25 * sums.block  # the block's FFT: its length
        monkeypatch.setattr(np.fft, "fft", counted)
        calls.clear()
        sums(0, sums.block)
        assert calls == [(sums.length,), (2, sums.length)]  # the chirp's transform (made on first use) and the rows'
        for n0 in (0, 10**6):
            calls.clear()
            sums(n0, sums.block)
            assert calls == [(2, sums.length)]  # one forward transform of the rows (and one inverse)
        monkeypatch.setattr(np.fft, "fft", fft)
        lengths.append(sums.length / sums.block)
    assert max(lengths) <= 1.25 * min(lengths)


def test_a_call_for_fewer_samples_than_a_block_transforms_a_length_fitted_to_them() -> None:
    """The default block (2^22 values over the rows) is far longer than a short record: a call for m samples
    transforms the smallest fast length holding m + W - 1 (a 40-period regular run's window: 4,961 samples, not
    some 700,000), and its values are the direct sum's; a call for more samples than a block keeps the block."""
    waves = default_sea(100)
    rng = np.random.default_rng(3)
    coefficients = waves.amplitude[None, :] * (rng.normal(size=(6, waves.omega.size)) + 1j)
    sums = BlockSum.on_grid(coefficients, waves.omega, TAU)
    assert sums is not None and sums.block > 100_000
    width = sums.band.size
    scale = np.abs(coefficients).sum(axis=1).max()
    for n0, m in [(0, 4961), (sums.period - 40, 80), (10**6 + 3, 1)]:
        assert sums.fft_length(m) == fast_length(m + width - 1) < sums.length
        n = n0 + np.arange(m)
        np.testing.assert_allclose(sums(n0, m), direct_sum(coefficients, waves.omega, n), rtol=0, atol=1e-12 * scale)
        np.testing.assert_allclose(sums.real(n0, m), direct_sum(coefficients, waves.omega, n).real.T, rtol=0,
                                   atol=1e-12 * scale)  # fmt: skip
    assert sums.fft_length(sums.block) == sums.fft_length(3 * sums.block) == sums.length
