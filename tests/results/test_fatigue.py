"""Fatigue on closed forms: rainflow counts of constant-amplitude and two-level records, Miner's sum and life by
hand from the S-N constants (paper 003, Table 5 and Eq. 55), bad inputs."""

from __future__ import annotations

import numpy as np
import pytest

from wecss.results import (
    SECONDS_PER_YEAR,
    SN_CURVES,
    Cycles,
    SNCurve,
    damage_equivalent_range,
    fatigue_life,
    life_years,
    long_term_life,
    miner_damage,
    rainflow_cycles,
    sn_curve,
)

pytest.importorskip("rainflow")

MPA = 1e6


def n_table5(range_mpa: float) -> float:
    """Cycles to failure by hand from the paper's Table 5 (knee at 10^7 cycles, i.e. at 10^((12.592 - 7) / 3) MPa)."""
    if range_mpa >= 10 ** ((12.592 - 7.0) / 3.0):
        return 10 ** (12.592 - 3.0 * np.log10(range_mpa))
    return 10 ** (16.320 - 5.0 * np.log10(range_mpa))


def test_constant_amplitude_cosine_counts_n_cycles_and_gives_the_sn_life():
    n, period, amplitude = 50, 6.2, 60.0 * MPA  # range 120 MPa
    t = np.arange(0, n * 20 + 1) * period / 20
    stress = amplitude * np.cos(2 * np.pi * t / period)
    cycles = rainflow_cycles(stress)
    assert cycles.counts.sum() == pytest.approx(n, abs=1e-12)
    np.testing.assert_allclose(cycles.ranges, 2 * amplitude, rtol=1e-12)
    damage, years = fatigue_life(stress, duration=n * period)
    assert damage == pytest.approx(n / n_table5(120.0), rel=1e-12)
    # Eq. 55: N_year = N T / (365 * 24 * 3600)
    assert years == pytest.approx(n_table5(120.0) * period / (365 * 24 * 3600), rel=1e-12)


def test_two_level_block_gives_the_hand_damage():
    # reversals: A, then n2 small cycles (0, s) nested in the fall from A, then n1 big cycles of range 2 A
    big, small, n1, n2 = 100.0 * MPA, 40.0 * MPA, 7, 30
    record = np.array([big] + [0.0, small] * n2 + [-big, big] * n1)
    cycles = rainflow_cycles(record)
    assert cycles.counts[np.isclose(cycles.ranges, small)].sum() == n2
    assert cycles.counts[np.isclose(cycles.ranges, 2 * big)].sum() == n1
    assert cycles.counts.sum() == n1 + n2
    # 200 MPa is above the knee (m 3), 40 MPa below it (m 5)
    by_hand = n1 / 10 ** (12.592 - 3 * np.log10(200.0)) + n2 / 10 ** (16.320 - 5 * np.log10(40.0))
    assert miner_damage(cycles) == pytest.approx(by_hand, rel=1e-12)
    assert miner_damage(cycles, scf=1.5) == pytest.approx(n1 / n_table5(300.0) + n2 / n_table5(60.0), rel=1e-12)


def test_damage_equivalent_range_does_the_same_single_slope_damage():
    cycles = Cycles(np.array([10.0, 25.0, 3.0]), np.array([1.0, 0.5, 40.0]))
    eq = damage_equivalent_range(cycles, slope=4.0, n_equivalent=1e3)
    assert eq == pytest.approx(((10**4 + 0.5 * 25**4 + 40 * 3**4) / 1e3) ** 0.25, rel=1e-14)
    single = SNCurve("m4", (4.0,), (20.0,))
    same = miner_damage(Cycles(np.array([eq * MPA]), np.array([1e3])), single)
    assert same == pytest.approx(miner_damage(Cycles(cycles.ranges * MPA, cycles.counts), single), rel=1e-12)


def test_catalogue_curves_are_continuous_at_their_knees():
    for curve in SN_CURVES.values():
        (s_knee,) = curve.knee_ranges()
        upper = 10 ** (curve.log_a[0] - curve.slopes[0] * np.log10(s_knee / MPA))
        lower = 10 ** (curve.log_a[1] - curve.slopes[1] * np.log10(s_knee / MPA))
        # an independent check of the constants: the two segments meet at the knee (log a rounded to 3 decimals)
        assert lower == pytest.approx(upper, rel=2e-3), curve.name
    assert sn_curve("paper-003-table-5").log_a == (12.592, 16.320)


def test_long_term_life_weights_damage_rates_by_probability():
    rates = np.array([1e-9, 4e-9])
    assert long_term_life(rates, np.array([0.75, 0.25])) == pytest.approx(1 / (1.75e-9 * SECONDS_PER_YEAR))
    assert life_years(0.0, 10.0) == float("inf")


@pytest.mark.parametrize(
    ("call", "match"),
    [
        (lambda: rainflow_cycles(np.array([])), "at least two samples"),
        (lambda: rainflow_cycles(np.array([1.0, np.nan, 2.0])), "NaN"),
        (lambda: Cycles(np.array([-1.0]), np.array([1.0])), "not negative"),
        (lambda: miner_damage(Cycles(np.array([1.0]), np.array([1.0])), "dnv-z"), "unknown S-N curve"),
        (lambda: miner_damage(Cycles(np.array([1.0]), np.array([1.0])), scf=0.0), "concentration factor"),
        (lambda: sn_curve("paper-003-table-5").cycles_to_failure(np.array([0.0])), "positive"),
        (lambda: long_term_life(np.array([1.0, 1.0]), np.array([0.5, 0.4])), "sum to 1"),
        (lambda: life_years(1.0, 0.0), "duration"),
        (lambda: SNCurve("bad", (3.0, 5.0), (12.0,)), "one intercept per slope"),
        (lambda: damage_equivalent_range(Cycles(np.ones(1), np.ones(1)), 0.0, 1.0), "slope"),
    ],
)
def test_bad_inputs_are_refused_with_clear_errors(call, match):
    with pytest.raises(ValueError, match=match):
        call()
