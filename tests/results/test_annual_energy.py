"""Annual energy from a power matrix and a scatter diagram, held to closed forms."""

from __future__ import annotations

import json

import numpy as np
import pytest
import xarray as xr

from wecss.results import annual_energy, plot_annual_energy, power_matrix

HS = np.array([0.5, 1.0, 2.0, 3.0])
TP = np.array([4.0, 6.0, 8.0, 10.0, 12.0])


def _grid(values, hs=HS, tp=TP, units=None) -> xr.DataArray:  # type: ignore[no-untyped-def]
    da = xr.DataArray(np.asarray(values, dtype=float), coords={"hs": hs, "tp": tp}, dims=("hs", "tp"))
    return da.assign_attrs(units=units) if units else da


def _probabilities(hs=HS, tp=TP) -> xr.DataArray:  # type: ignore[no-untyped-def]
    weights = np.outer(np.exp(-hs), np.exp(-((tp - 8.0) ** 2) / 8.0))
    return _grid(weights / weights.sum(), hs, tp, units="1")


def test_a_constant_power_matrix_gives_the_power_times_a_year():
    result = annual_energy(_grid(np.full((4, 5), 2.5e5), units="W"), _probabilities())
    assert float(result.annual_energy) == pytest.approx(2.5e5 * 8766 * 3600, rel=1e-12)
    assert float(result.annual_energy_mwh) == pytest.approx(0.25 * 8766, rel=1e-12)
    assert float(result.covered_share) == pytest.approx(1.0, rel=1e-12)
    assert result.attrs["occurrence"] == "probability"


def test_a_matrix_in_hs_squared_tp_gives_the_exact_sum_over_hours():
    # P = c Hs^2 Tp on the scatter's own grid; the scatter in hours per year, a closed form per bin
    c = 400.0
    hours = _grid(np.outer(HS, TP) * 10.0, units="h")  # h = 10 Hs Tp, 1,120 h in all
    exact = sum(c * h**2 * t * 10.0 * h * t * 3600.0 for h in HS for t in TP)
    result = annual_energy(_grid(c * np.outer(HS**2, TP), units="W"), hours)
    assert float(result.annual_energy) == pytest.approx(exact, rel=1e-12)
    assert float(result.covered_share) == pytest.approx(float(hours.sum()) / 8766, rel=1e-12)
    assert result.attrs["occurrence"] == "hours per year"


def test_interpolating_a_bilinear_matrix_is_exact():
    def bilinear(h, t):  # type: ignore[no-untyped-def]
        return 1e3 + 2e3 * h + 50.0 * t + 300.0 * h * t

    matrix = _grid(bilinear(HS[:, None], TP[None, :]), units="W")
    fine_hs, fine_tp = np.array([0.75, 1.25, 2.9]), np.array([4.5, 7.0, 11.5])
    scatter = _grid(np.full((3, 3), 100.0), fine_hs, fine_tp, units="h")
    result = annual_energy(matrix, scatter)
    np.testing.assert_allclose(result.power.values, bilinear(fine_hs[:, None], fine_tp[None, :]), rtol=1e-13)
    expected = float(np.sum(bilinear(fine_hs[:, None], fine_tp[None, :]))) * 100.0 * 3600.0
    assert float(result.annual_energy) == pytest.approx(expected, rel=1e-13)


def test_bins_outside_the_matrix_are_refused_or_counted_as_unknown():
    matrix = _grid(np.full((4, 5), 1e3), units="W")
    scatter = _grid(np.full((2, 2), 1000.0), np.array([1.0, 4.0]), np.array([6.0, 8.0]), units="h")
    with pytest.raises(ValueError, match=r"2 bins .*outside the power matrix's range hs 0.5..3, tp 4..12"):
        annual_energy(matrix, scatter)
    result = annual_energy(matrix, scatter, outside="unknown")
    assert float(result.annual_energy) == pytest.approx(1e3 * 2000.0 * 3600.0, rel=1e-12)
    assert float(result.unknown_share) == pytest.approx(2000.0 / 8766, rel=1e-12)
    assert float(result.covered_share) == pytest.approx(2000.0 / 8766, rel=1e-12)
    assert result.known.values.tolist() == [[True, True], [False, False]]


def test_a_nan_of_the_matrix_makes_its_bins_unknown():
    values = np.full((4, 5), 1e3)
    values[1, 2] = np.nan  # a failed case
    with pytest.raises(ValueError, match="next to its NaN"):
        annual_energy(_grid(values, units="W"), _probabilities())
    result = annual_energy(_grid(values, units="W"), _probabilities(), outside="unknown")
    assert float(result.unknown_share) == pytest.approx(float(_probabilities()[1, 2]), rel=1e-12)


@pytest.mark.parametrize(
    ("matrix_units", "scatter", "kwargs", "message"),
    [
        ("W", _grid(-np.ones((4, 5)), units="h"), {}, "negative occurrence"),
        ("W", _grid(np.full((4, 5), np.nan), units="h"), {}, "20 NaN"),
        ("kW", _probabilities(), {}, "units are 'kW'; accepted: 'W'"),
        ("W", _grid(np.ones((4, 5))), {}, "does not say whether it holds hours per year or probabilities"),
        ("W", _probabilities(), {"occurrence": "hours"}, "contradicts the scatter diagram's units"),
        ("W", _grid(np.ones((4, 5)) / 10, units="1"), {}, "probabilities sum to 2, not 1"),
        ("W", _grid(np.full((4, 5), 500.0), units="h"), {}, "hours sum to 10000 h, more than the year's 8766 h"),
        ("W", _probabilities().rename(tp="te"), {}, r"over \('hs', 'tp'\) and the scatter diagram over \('hs', 'te'\)"),
        ("W", _grid(np.ones((4, 5)), units="m"), {}, "units 'm' are not an occurrence"),
        ("W", _probabilities(), {"outside": "zero"}, "outside must be 'refuse' or 'unknown'"),
    ],
)
def test_bad_inputs_are_refused_with_clear_messages(matrix_units, scatter, kwargs, message):  # type: ignore[no-untyped-def]
    with pytest.raises(ValueError, match=message):
        annual_energy(_grid(np.ones((4, 5)), units=matrix_units), scatter, **kwargs)


def test_occurrence_given_as_a_keyword_for_a_scatter_without_units():
    result = annual_energy(_grid(np.full((4, 5), 10.0)), _grid(np.full((4, 5), 5.0)), occurrence="hours")
    assert float(result.annual_energy) == pytest.approx(10.0 * 100.0 * 3600.0, rel=1e-12)


def _combined(mode: str = "grid") -> xr.Dataset:
    heights, periods = [0.04, 0.02], [1.0, 1.2, 1.4]  # the height axis descending, as a sweep may list it
    power = np.array([[1.0, 2.0, np.nan], [0.25, 0.5, 0.75]])
    status = np.array([["done", "done", "failed"], ["done"] * 3])
    ds = xr.Dataset(
        {
            "total_power": (("sea.height", "sea.period"), power, {"units": "W"}),
            "status": (("sea.height", "sea.period"), status),
        },
        coords={"sea.height": heights, "sea.period": periods},
        attrs={"base_scene": json.dumps({"sea": {"kind": "jonswap"}}), "sweep_mode": "grid"},
    )
    if mode == "list":
        ds = ds.stack(case=["sea.height", "sea.period"]).reset_index("case")
    return ds


@pytest.mark.parametrize("mode", ["grid", "list"])
def test_the_power_matrix_of_a_sweep(mode):  # type: ignore[no-untyped-def]
    matrix = power_matrix(_combined(mode))
    assert matrix.dims == ("hs", "tp") and matrix.attrs["units"] == "W"
    assert matrix.hs.values.tolist() == [0.02, 0.04] and matrix.tp.values.tolist() == [1.0, 1.2, 1.4]
    np.testing.assert_array_equal(matrix.values, [[0.25, 0.5, 0.75], [1.0, 2.0, np.nan]])


def test_the_power_matrix_of_a_sweep_refuses_what_it_cannot_use():
    regular = _combined()
    regular.attrs["base_scene"] = json.dumps({"sea": {"kind": "regular"}})
    with pytest.raises(ValueError, match="regular"):
        power_matrix(regular)
    with pytest.raises(ValueError, match="no 'cwr'"):
        power_matrix(_combined(), variable="cwr")
    seeds = _combined().expand_dims({"sea.seed": [1, 2]})
    with pytest.raises(ValueError, match=r"more dimensions than sea.height and sea.period: \['sea.seed'\]"):
        power_matrix(seeds)


def test_the_plot_writes_the_energy_in_each_bin(tmp_path):  # type: ignore[no-untyped-def]
    import matplotlib.pyplot as plt

    matrix = _grid(np.full((4, 5), 2e3), units="W")
    scatter = _grid(np.full((2, 2), 1000.0), np.array([1.0, 4.0]), np.array([6.0, 8.0]), units="h")
    result = annual_energy(matrix, scatter, outside="unknown")
    fig = plot_annual_energy(result, tmp_path / "aep.png")
    texts = sorted(t.get_text() for t in fig.axes[1].texts)
    assert texts == ["2", "2", "?", "?"]  # 2 kW for 1000 h: 2 MWh
    assert fig.axes[3].get_ylabel() == "energy per bin [MWh/year]" and fig.axes[2].get_ylabel() == "power matrix [W]"
    assert "annual energy 4 MWh/year" in fig._suptitle.get_text() and "% unknown" in fig._suptitle.get_text()
    assert fig.axes[0].get_xlabel() == "tp [s]" and fig.axes[0].get_ylabel() == "hs [m]"
    assert (tmp_path / "aep.png").is_file()
    plt.close(fig)


def test_only_the_bins_leaning_on_a_nan_node_are_unknown():
    values = np.full((4, 5), 1e3)
    values[1, 2] = np.nan  # node hs 1, tp 8
    scatter = _grid(np.full((2, 3), 10.0), np.array([1.5, 2.5]), np.array([7.0, 9.0, 11.0]), units="h")
    result = annual_energy(_grid(values, units="W"), scatter, outside="unknown")
    assert result.known.values.tolist() == [[False, False, True], [True, True, True]]
    assert float(result.annual_energy) == pytest.approx(1e3 * 40.0 * 3600.0, rel=1e-12)
    assert float(result.unknown_share) == pytest.approx(20.0 / 8766, rel=1e-12)
