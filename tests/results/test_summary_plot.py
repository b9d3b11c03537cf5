"""The summary plot ``wecss run`` writes: sea state in the title, the statistics window marked, every PTO in the
legends with its mean power, the elevation spectrum against the target, units scaled to the values."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import pytest
import xarray as xr

from tests.sim.scenes import scene
from wecss.results import mean_power, plot_summary
from wecss.results._summary_plot import scaled_unit, welch_density
from wecss.sim import simulate


@pytest.fixture(scope="module")
def run() -> xr.Dataset:
    return simulate(
        scene("m4-132", sea={"duration": "12 Tp", "ramp": "2 Tp"}, outputs={"variables": ["pto", "elevation"]})
    )


def _legend_texts(ax) -> list[str]:  # type: ignore[no-untyped-def]
    legend = ax.get_legend()
    return [] if legend is None else [t.get_text() for t in legend.get_texts()]


def _everything_inside(fig) -> bool:  # type: ignore[no-untyped-def]
    """Whether every artist of a drawn figure lies inside it (the margins are fixed: nothing is cut off)."""
    drawn = fig.get_tightbbox(fig.canvas.get_renderer())  # [in]
    width, height = fig.get_size_inches()
    return bool(drawn.x0 >= 0 and drawn.y0 >= 0 and drawn.x1 <= width and drawn.y1 <= height)


def test_the_saved_summary_is_drawn_once_with_everything_inside(run, tmp_path, monkeypatch):
    """The PNG is the figure as it is (fixed margins, no tight bounding box measured by a second drawing)."""
    from matplotlib.figure import Figure

    draws = []
    real = Figure.draw
    monkeypatch.setattr(Figure, "draw", lambda self, renderer: draws.append(1) or real(self, renderer))
    fig = plot_summary(run, tmp_path / "summary.png")
    try:
        assert len(draws) == 1
        assert _everything_inside(fig)
    finally:
        plt.close(fig)


def test_summary_plot_has_what_a_user_keeps(run, tmp_path):
    path = tmp_path / "summary.png"
    fig = plot_summary(run, path)
    try:
        assert path.is_file() and path.stat().st_size > 10_000
        title = fig._suptitle.get_text()
        assert "m4-132" in title and "JONSWAP" in title and "Hs 40 mm" in title and "Tp 1.2 s" in title
        assert "gamma 3.3" in title and "beeman" in title
        axes = fig.axes
        assert len(axes) == 5
        elevation, strokes, power, spectrum, bars = axes
        assert elevation.get_ylabel() == "elevation [mm]"  # Hs 40 mm: millimetres
        assert strokes.get_ylabel() == "PTO angle [deg]"
        assert power.get_ylabel() == "absorbed power [mW]"  # about 0.1 W per PTO: milliwatts
        # the statistics window: a shaded span from the window's start to the end on every time panel
        start = float(run.time[-1] - run.attrs["statistics_window"] * (run.time[-1] - run.time[0]))
        for ax in (elevation, strokes, power):
            starts = [
                float(np.min(p.get_path().transformed(p.get_patch_transform()).vertices[:, 0])) for p in ax.patches
            ]
            assert any(np.isclose(x, start) for x in starts), (ax.get_ylabel(), starts, start)
        assert "statistics window" in _legend_texts(elevation)
        # every PTO in the stroke and power legends, with its mean power in mW
        means = mean_power(run)
        assert _legend_texts(strokes) == ["pto_3", "pto_6"]
        for name, text in zip(["pto_3", "pto_6"], _legend_texts(power), strict=True):
            assert text == f"{name}: mean {float(means.sel(pto=name)) * 1e3:.3g} mW"
        # the two PTOs are told apart by colour and by line style
        lines = strokes.get_lines()
        assert lines[0].get_color() != lines[1].get_color() and lines[0].get_linestyle() != lines[1].get_linestyle()
        assert _legend_texts(spectrum) == ["recorded (Welch, statistics window)", "target spectrum"]
        assert "total" in bars.get_title() and [t.get_text() for t in bars.get_xticklabels()] == ["pto_3", "pto_6"]
    finally:
        plt.close(fig)


def test_the_target_spectrum_is_the_scenes(run):
    """The dashed line carries the scene's JONSWAP: its area is Hs^2 / 16 (in mm^2)."""
    fig = plot_summary(run)
    try:
        target = fig.axes[3].get_lines()[1]
        omega, s = target.get_xdata(), target.get_ydata()
        assert np.trapezoid(s, omega) == pytest.approx(40.0**2 / 16, rel=0.02)
    finally:
        plt.close(fig)


def test_a_regular_wave_marks_its_frequency_and_a_statistics_only_result_is_refused():
    ds = simulate(
        scene(
            "m4-111",
            sea={"kind": "regular", "height": 0.02, "period": 1.0, "duration": "12 T", "ramp": "2 T"},
            outputs={"variables": ["pto", "elevation"]},
        )
    )
    fig = plot_summary(ds)
    try:
        assert "regular, H 20 mm, T 1 s" in fig._suptitle.get_text()
        assert "wave frequency" in _legend_texts(fig.axes[3])
    finally:
        plt.close(fig)
    with pytest.raises(ValueError, match="nothing to plot"):
        plot_summary(ds.drop_dims("time"))


@pytest.mark.parametrize(
    ("values", "unit", "expected"),
    [(0.04, "m", "mm"), (2.0, "m", "m"), (0.3, "W", "mW"), (5.0, "W", "W"), (2e4, "W", "kW"), (0.1, "rad", "deg")],
)
def test_units_are_scaled_to_the_values(values, unit, expected):
    assert scaled_unit(np.array([values, -values / 2]), unit)[1] == expected


def test_rotary_and_linear_strokes_get_axes_of_their_own(tmp_path):
    """M4 111 with a vertical damper as well: the hinge angle in degrees on the left, the damper's stroke in mm on
    a right-hand axis, both PTOs in one legend."""
    from tests.sim.test_result_layout import DEVICES, STRUT

    spec = tmp_path / "m4-111-strut.toml"
    spec.write_text((DEVICES / "m4-111.toml").read_text().replace('"m4-111"', '"m4-111-strut"', 1) + STRUT)
    ds = simulate(scene(str(spec), sea={"duration": 8.0}, outputs={"variables": ["pto", "elevation"]}))
    fig = plot_summary(ds)
    try:
        labels = {ax.get_ylabel() for ax in fig.axes}
        assert {"PTO angle [deg]", "PTO stroke [mm]"} <= labels and len(fig.axes) == 6
        assert _legend_texts(fig.axes[1]) == ["pto_3", "strut"]
        fig.savefig(tmp_path / "summary.png")
        assert _everything_inside(fig)  # the right-hand axis's label too
    finally:
        plt.close(fig)


@pytest.mark.parametrize(("n", "nperseg"), [(10_000, 3333), (9_999, 3333), (101, 33), (64, 16), (17, 16)])
def test_the_recorded_spectrum_is_scipys_welch(n, nperseg):
    """The plot's Welch estimate (matplotlib's mlab) equals scipy.signal.welch with its defaults (periodic Hann,
    half overlap, mean removed per segment, one-sided density) to round-off, odd and even segment lengths."""
    from scipy.signal import welch

    rng = np.random.default_rng(n)
    values = 0.02 * np.sin(0.3 * np.arange(n)) + 1e-3 * rng.standard_normal(n).cumsum() + 0.5  # a mean, a drift
    expected_freq, expected = welch(values, fs=1 / 0.006, nperseg=nperseg)
    freq, density = welch_density(values, 0.006, nperseg)
    np.testing.assert_array_equal(freq, expected_freq)
    np.testing.assert_allclose(density, expected, rtol=1e-12, atol=1e-14 * expected.max())
