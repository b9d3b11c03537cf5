"""The plot of a sweep's combined dataset: the heat map holds the data, failed cases are marked, labels carry units."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from wecss.results import plot_sweep

HEIGHTS, PERIODS = [0.02, 0.04], [1.0, 1.2, 1.4]


def _combined() -> xr.Dataset:
    power = np.array([[0.25, 0.5, 0.75], [1.0, np.nan, 3.0]])
    status = np.array([["done"] * 3, ["done", "failed", "done"]])
    axes = ("sea.height", "sea.period")
    return xr.Dataset(
        {
            "total_power": (axes, power, {"units": "W", "long_name": "total mean absorbed power"}),
            "mean_pto_power": ((*axes, "pto"), np.stack([power, 2 * power], axis=-1), {"units": "W"}),
            "status": (axes, status),
        },
        coords={"sea.height": HEIGHTS, "sea.period": PERIODS, "pto": ["pto_1", "pto_2"]},
        attrs={"title": "wecss sweep tiny", "sweep_mode": "grid"},
    )


def test_a_two_axis_sweep_is_a_heat_map_of_the_data_with_the_failed_case_marked():
    import matplotlib.pyplot as plt

    ds = _combined()
    fig = plot_sweep(ds.expand_dims({"solver.method": ["frequency"]}))  # an axis of one value is no dimension
    ax = fig.axes[0]
    image = ax.get_images()[0].get_array()
    np.testing.assert_array_equal(np.ma.filled(image, np.nan), ds.total_power.values)
    texts = {(t.get_position(), t.get_text()) for t in ax.texts}
    assert ((1, 1), "failed") in texts and ((0, 0), "0.25") in texts and ((2, 1), "3") in texts
    assert ax.get_xlabel() == "sea.period [s]" and ax.get_ylabel() == "sea.height [m]"
    assert [t.get_text() for t in ax.get_xticklabels()] == ["1", "1.2", "1.4"]
    assert fig.axes[1].get_ylabel() == "total_power [W]"
    plt.close(fig)


def test_one_axis_is_a_line_and_more_axes_need_a_selection(tmp_path):  # type: ignore[no-untyped-def]
    import matplotlib.pyplot as plt

    ds = _combined()
    with pytest.raises(ValueError, match=r"3 dimensions .*give select=\{dim: value\}"):
        plot_sweep(ds, "mean_pto_power")
    fig = plot_sweep(ds, "mean_pto_power", select={"pto": "pto_2", "sea.height": 0.04}, path=tmp_path / "s.png")
    ax = fig.axes[0]
    line = ax.get_lines()[0]
    np.testing.assert_array_equal(line.get_ydata(), [2.0, np.nan, 6.0])
    assert [t.get_text() for t in ax.texts] == ["failed"] and ax.get_xlabel() == "sea.period [s]"
    assert (tmp_path / "s.png").is_file()
    plt.close(fig)
    with pytest.raises(ValueError, match="no 'power'; accepted: \\['total_power', 'mean_pto_power'\\]"):
        plot_sweep(ds, "power")
    with pytest.raises(ValueError, match="select names 'seed'"):
        plot_sweep(ds, select={"seed": 1})


def test_a_selected_value_is_found_within_rounding_and_a_missing_one_lists_the_axis():
    """An axis made by linspace holds 0.1 + 0.2 where the user types 0.3: it is found; a value the axis does not
    hold is refused with the axis's values (xarray's KeyError before)."""
    import matplotlib.pyplot as plt

    ds = _combined()
    ds = ds.assign_coords({"sea.height": ds["sea.height"].values + np.array([0.1 + 0.2 - 0.3, 0.0])})
    typed = float(np.round(ds["sea.height"].values[0], 12))
    assert typed not in ds["sea.height"].values.tolist()
    fig = plot_sweep(ds, "mean_pto_power", select={"pto": "pto_2", "sea.height": typed})
    np.testing.assert_array_equal(
        fig.axes[0].get_lines()[0].get_ydata(), ds["mean_pto_power"].isel({"sea.height": 0}).sel(pto="pto_2").values
    )
    plt.close(fig)
    with pytest.raises(ValueError, match=r"select sea.height=7.0: not a value of that axis; accepted: \["):
        plot_sweep(ds, "mean_pto_power", select={"pto": "pto_2", "sea.height": 7.0})


def test_a_list_sweep_is_a_line_over_its_cases():
    import matplotlib.pyplot as plt

    ds = _combined().stack(case=["sea.height", "sea.period"]).reset_index("case")
    ds = ds.assign_coords(case=[f"case_{k}" for k in range(6)])
    fig = plot_sweep(ds)
    ax = fig.axes[0]
    np.testing.assert_array_equal(ax.get_lines()[0].get_ydata(), [0.25, 0.5, 0.75, 1.0, np.nan, 3.0])
    assert [t.get_text() for t in ax.get_xticklabels()] == [f"case_{k}" for k in range(6)]
    assert [t.get_text() for t in ax.texts] == ["failed"] and ax.get_ylabel() == "total_power [W]"
    plt.close(fig)
