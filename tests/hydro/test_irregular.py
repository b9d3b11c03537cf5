"""Irregular-frequency artefacts: detection, warning and removal."""

from __future__ import annotations

import numpy as np
import pytest

from wecss.hydro import HydroData, IrregularFrequencyWarning, find_irregular_frequencies, remove_irregular_frequencies

from .synthetic import synthetic_dataset


def _with_spike(index: int, height: float):
    ds = synthetic_dataset(n_omega=80)
    clean = ds.radiation_damping.values.copy()
    values = clean.copy()
    values[index] += height * np.abs(clean).max() * np.eye(values.shape[1])
    return ds.assign(radiation_damping=ds.radiation_damping.copy(data=values)), clean


def test_clean_data_has_no_bands() -> None:
    assert find_irregular_frequencies(synthetic_dataset(n_omega=80)) == []


def test_spike_warns_and_is_interpolated_away() -> None:
    ds, clean = _with_spike(50, 0.3)
    with pytest.warns(IrregularFrequencyWarning, match="a__Heave"):
        HydroData(ds)
    bands = find_irregular_frequencies(ds)
    omega = float(ds.omega.values[50])
    assert {dof for dof, _, _ in bands} == set(ds.radiating_dof.values)
    assert all(lo == hi == omega for _, lo, hi in bands)  # one point flagged, not its neighbours
    cleaned, report = remove_irregular_frequencies(ds)
    assert report.omega == (omega,)
    assert str(report).startswith(f"replaced 1 frequencies by interpolation ({omega:.4g} rad/s: a__Surge, a__Heave")
    scale = np.abs(clean).max()
    assert np.max(np.abs(cleaned.radiation_damping.values - clean)) < 1e-2 * scale
    HydroData(cleaned)  # no warning (warnings are errors in this suite), validates


def test_negative_band_is_dropped_on_request() -> None:
    ds = synthetic_dataset(n_omega=80)
    values = ds.radiation_damping.values.copy()
    values[30:33, 4, 4] = -0.2 * np.abs(values[:, 4, 4]).max()
    ds = ds.assign(radiation_damping=ds.radiation_damping.copy(data=values))
    cleaned, report = remove_irregular_frequencies(ds, method="drop")
    assert cleaned.sizes["omega"] == 77
    assert set(report.omega) == set(ds.omega.values[30:33].tolist())
    HydroData(cleaned)


def test_unknown_method() -> None:
    with pytest.raises(ValueError, match="'interpolate' or 'drop'; got 'median'"):
        remove_irregular_frequencies(synthetic_dataset(), method="median")


def test_bad_frequencies_at_the_end_are_dropped_not_extrapolated() -> None:
    ds = synthetic_dataset(n_omega=80)
    values = ds.radiation_damping.values.copy()
    values[-4:, 1, 1] = -0.3 * np.abs(values[:, 1, 1]).max()
    ds = ds.assign(radiation_damping=ds.radiation_damping.copy(data=values))
    cleaned, report = remove_irregular_frequencies(ds)
    assert cleaned.sizes["omega"] == 76
    assert report.dropped_at_ends == tuple(ds.omega.values[-4:].tolist())
    assert "dropped 4 at the ends of the range" in str(report)
    HydroData(cleaned)
