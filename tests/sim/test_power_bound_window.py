"""The share of the power bound on the run's own record and window (issue 31): ``power_bound`` is the
complex-conjugate bound of the excitation over the statistics window taken as a periodic record,
``power_bound_spectral`` the spectral expectation over the scene's wave components; a note only when the share
exceeds 1 beyond its stated tolerance."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from wecss.sim import Scene, simulate
from wecss.sim._attrs import bound_notes

FLOAT = Path(__file__).parents[1] / "control" / "heaving_float.toml"


def _run(sea: dict, window: float, dt: float | str = 0.03):
    return simulate(
        Scene.from_dict(
            {
                "device": {"name": str(FLOAT)},
                "sea": sea,
                "controller": {"name": "damping", "parameters": {"damping": 40.0}},
                "solver": {"dt": dt},
                "radiation": {"method": "none"},
                "outputs": {"variables": ["pto"], "window": window},
            }
        )
    )


def test_a_window_of_whole_periods_of_a_regular_wave_has_the_spectral_bound():
    # 12 s at dt 0.03: the last half is 200 steps, 6 s, five periods of 1.2 s after the 2.4 s ramp; the window's
    # excitation is one component at the wave's frequency, whose bound is the spectral one
    ds = _run({"kind": "regular", "height": 0.02, "period": 1.2, "duration": 12.0, "ramp": 2.4}, 0.5)
    np.testing.assert_allclose(ds.power_bound.values, ds.power_bound_spectral.values, rtol=1e-9)
    assert ds.attrs["share_of_power_bound"] == pytest.approx(ds.attrs["share_of_power_bound_spectral"], rel=1e-9)


@pytest.mark.parametrize("period", [0.7, 0.9, 1.4, 1.8])
def test_whole_periods_on_the_windows_grid_to_rounding_have_the_spectral_bound(period):
    # 10 periods at T/50, the last half: 5 whole periods, whose frequency lies on the window's grid only to rounding
    sea = {"kind": "regular", "height": 0.02, "period": period, "duration": "10 Tp", "ramp": "2 Tp"}
    ds = _run(sea, 0.5, "Tp/50")
    np.testing.assert_allclose(ds.power_bound.values, ds.power_bound_spectral.values, rtol=1e-9)


def test_a_window_without_components_in_the_band_keeps_the_spectral_share():
    # 2.5 periods of a regular wave in the window: its grid misses the wave's frequency, so no bound over the
    # window (a note says why); the spectral share is still there
    ds = _run({"kind": "regular", "height": 0.02, "period": 1.2, "duration": 6.0, "ramp": 1.2}, 0.5, 0.006)
    assert "power_bound" not in ds
    assert "no complex-conjugate power bound over the statistics window" in ds.attrs["notes"]
    assert "share_of_power_bound" not in ds.attrs and "share_of_power_bound_tolerance" not in ds.attrs
    total = float(ds.mean_pto_power.sum())
    assert ds.attrs["share_of_power_bound_spectral"] == pytest.approx(
        total / float(ds.power_bound_spectral.sum()), rel=1e-12
    )


def test_over_the_whole_record_an_irregular_sea_has_the_spectral_bound_and_over_its_last_half_its_own():
    sea = {"kind": "jonswap", "height": 0.04, "period": 1.2, "duration": 24.0, "ramp": 0.0, "seed": 3}
    whole = _run(sea, 1.0)  # the components are orthogonal over the record: the window's bound is the spectral one
    np.testing.assert_allclose(whole.power_bound.values, whole.power_bound_spectral.values, rtol=1e-6)
    half = _run(sea, 0.5)
    np.testing.assert_array_equal(half.power_bound_spectral.values, whole.power_bound_spectral.values)
    assert abs(float(half.power_bound[0] / half.power_bound_spectral[0]) - 1) > 0.01  # a half window has its own
    total = float(half.mean_pto_power.sum())
    assert half.attrs["share_of_power_bound"] == pytest.approx(total / float(half.power_bound.sum()), rel=1e-12)
    assert half.attrs["share_of_power_bound_spectral"] == pytest.approx(
        total / float(half.power_bound_spectral.sum()), rel=1e-12
    )
    assert "times the complex-conjugate bound" not in half.attrs["notes"]  # passive damping: well below it


def test_a_note_only_when_the_share_exceeds_one_beyond_its_tolerance():
    assert bound_notes({"share_of_power_bound": 1.019, "share_of_power_bound_tolerance": 0.02}) == []
    (note,) = bound_notes({"share_of_power_bound": 1.021, "share_of_power_bound_tolerance": 0.02})
    assert "1.021 times the complex-conjugate bound on the same record and window" in note
    assert "1 + 0.02" in note
    assert bound_notes({"share_of_power_bound_spectral": 1.5}) == []  # no bound over the window: no share of it
