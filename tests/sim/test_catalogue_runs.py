"""Every catalogue device runs with every radiation method and integrator (issue 18: the wavestar crashed with the
default convolution). Short irregular seas at each device's own scale; the runs must end with finite motions.
The full matrix (state-space fits of every database) is slow; the convolution with Beeman runs by default."""

from __future__ import annotations

import numpy as np
import pytest

import wecss.devices
from tests.devices.test_catalogue import EXTERNAL_HYDRO
from wecss.sim import Scene, simulate

# (Hs [m], Tp [s]) at each device's scale: model-scale M4 and Wavestar, full-scale RM3 and NOTC
SEAS = {"m4-111": (0.04, 1.2), "m4-132": (0.04, 1.2), "m4-134": (0.04, 1.2), "wavestar": (0.0208, 0.988)}
FULL_SCALE = (1.0, 8.0)
COMBINATIONS = [("convolution", "beeman"), ("none", "beeman"), ("none", "rk4"), ("state_space", "beeman"),
                ("state_space", "rk4"), ("state_space", "linear")]  # fmt: skip


def _scene(device: str, radiation: str, method: str) -> Scene:
    height, period = SEAS.get(device, FULL_SCALE)
    hydro = EXTERNAL_HYDRO.get(device)
    if hydro is not None and not hydro.is_file():
        pytest.skip(f"reference data not found: {hydro}")
    return Scene.from_dict(
        {
            "device": {"name": device, **({"hydro": str(hydro)} if hydro is not None else {})},
            "sea": {"height": height, "period": period, "duration": "12 Tp", "ramp": "3 Tp"},
            "solver": {"method": method, "dt": "Tp/100"},
            "radiation": {"method": radiation},
            "outputs": {"variables": ["motion", "pto"]},
        }
    )


def _params():
    for device in wecss.devices.available():
        for radiation, method in COMBINATIONS:
            marks: tuple = () if (radiation, method) == ("convolution", "beeman") else (pytest.mark.slow,)
            if device == "notc-10kw" and method == "rk4":
                # measured: diverges at t = 29 s (angle bound) though the up-front check passes it: its fastest mode
                # with the default PTO damping 3.2e5 is |s| = 26.8 rad/s, |s| dt = 2.15 < RK4_LIMIT 2.5 at Tp/100
                marks = (*marks, pytest.mark.xfail(reason="RK4 check not conservative enough here (issue 18)"))
            yield pytest.param(device, radiation, method, marks=marks, id=f"{device}-{radiation}-{method}")


@pytest.mark.filterwarnings("ignore::wecss.hydro.HydroDataWarning")
@pytest.mark.parametrize(("device", "radiation", "method"), list(_params()))
def test_every_device_runs_with_every_radiation_method_and_integrator(device, radiation, method):
    ds = simulate(_scene(device, radiation, method))
    for name in ("displacement", "angle"):
        if name in ds:
            assert np.all(np.isfinite(ds[name].values)), f"{device}: non-finite {name}"
    assert ds.attrs["n_steps"] == 1200
