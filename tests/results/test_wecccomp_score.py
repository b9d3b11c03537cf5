"""The WECCCOMP evaluation criterion against its closed form for a damped sinusoidal motion."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from wecss.results import wecccomp_score


def _run(c: float, amplitude: float, omega: float) -> xr.Dataset:
    t = np.linspace(0.0, 200 * 2 * np.pi / omega, 200_001)
    v = amplitude * np.cos(omega * t)
    f = -c * v
    return xr.Dataset(
        {
            "pto_power": (("time", "pto"), (-f * v)[:, None]),
            "pto_force": (("time", "pto"), f[:, None]),
            "pto_displacement": (("time", "pto"), (0.01 + amplitude / omega * np.sin(omega * t))[:, None]),
        },
        coords={"time": t, "pto": ["motor"], "pto_kind": ("pto", ["linear"])},
    )


def test_the_score_of_a_damped_sinusoid_matches_its_closed_form():
    """v = V cos(w t), f = -c v: P_elec = 0.7 c v^2, so mean 0.35 c V^2; the 98th percentile of |sin| is
    a = sin(0.98 pi / 2), giving |f|98 = c V a, |z|98 = V a / w and mean|P| / |P|98 = 0.5 / a^2."""
    c, amplitude, omega = 40.0, 0.05, 4.0
    a = np.sin(0.98 * np.pi / 2)
    expected = 0.35 * c * amplitude**2 / (2 + c * amplitude * a / 60 + amplitude * a / omega / 0.08 - 0.5 / a**2)
    score = wecccomp_score(_run(c, amplitude, omega), start=10.0)
    assert score["ec"] == pytest.approx(expected, rel=1e-3)
    assert score["mean_absorbed_power"] == pytest.approx(0.5 * c * amplitude**2, rel=1e-3)
    assert score["force_98"] == pytest.approx(c * amplitude * a, rel=1e-3)


def test_supplied_power_costs_more_than_absorbed_power_earns():
    run = _run(40.0, 0.05, 4.0)
    supplying = run.assign(pto_power=-run.pto_power)
    assert wecccomp_score(supplying)["mean_electrical_power"] == pytest.approx(
        -wecccomp_score(run)["mean_electrical_power"] / 0.49, rel=1e-9
    )


def test_bad_requests_say_what_is_accepted():
    with pytest.raises(ValueError, match="must lie within the run"):
        wecccomp_score(_run(40.0, 0.05, 4.0), start=1e4)
    with pytest.raises(ValueError, match="needs pto_power, pto_force, pto_displacement"):
        wecccomp_score(xr.Dataset())
