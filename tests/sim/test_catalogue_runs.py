"""Every catalogue device runs with every radiation method and integrator (issue 18: the wavestar crashed with the
default convolution). Short irregular seas at each device's own scale; the runs must end with finite motions.
The full matrix (state-space fits of every database) is slow; the convolution with Beeman runs by default."""

from __future__ import annotations

import numpy as np
import pytest

import wecss.devices
from tests.devices.test_catalogue import EXTERNAL_HYDRO
from wecss.sim import Scene, SceneError, SimulationDiverged, simulate

# (Hs [m], Tp [s]) at each device's scale: model-scale M4 and Wavestar, full-scale RM3 and NOTC
SEAS = {"m4-111": (0.04, 1.2), "m4-132": (0.04, 1.2), "m4-134": (0.04, 1.2), "wavestar": (0.0208, 0.988)}
FULL_SCALE = (1.0, 8.0)
COMBINATIONS = [("convolution", "beeman"), ("none", "beeman"), ("none", "rk4"), ("state_space", "beeman"),
                ("state_space", "rk4"), ("state_space", "linear")]  # fmt: skip


def _scene(device: str, radiation: str, method: str, dt: str = "Tp/100") -> Scene:
    height, period = SEAS.get(device, FULL_SCALE)
    hydro = EXTERNAL_HYDRO.get(device)
    if hydro is not None and not hydro.is_file():
        pytest.skip(f"reference data not found: {hydro}")
    return Scene.from_dict(
        {
            "device": {"name": device, **({"hydro": str(hydro)} if hydro is not None else {})},
            "sea": {"height": height, "period": period, "duration": "12 Tp", "ramp": "3 Tp"},
            "solver": {"method": method, "dt": dt},
            "radiation": {"method": radiation},
            "outputs": {"variables": ["motion", "pto"]},
        }
    )


#: RK4 at Tp/100 is refused for these: measured, the NOTC run diverged at t = 29 s (angle bound) when the up-front
#: check looked at the equilibrium only (|s| dt = 2.15 there); its cylinder's transmission grows as the arm turns
#: and the floater pitches on the arm tip by up to 1.4 rad (Beeman run), which the check now takes into account;
#: at the step given here the runs finish.
RK4_REFUSED = {"notc-10kw": "Tp/200"}


def _params():
    for device in wecss.devices.available():
        for radiation, method in COMBINATIONS:
            marks: tuple = () if (radiation, method) == ("convolution", "beeman") else (pytest.mark.slow,)
            yield pytest.param(device, radiation, method, marks=marks, id=f"{device}-{radiation}-{method}")


@pytest.mark.filterwarnings("ignore::wecss.hydro.HydroDataWarning")
@pytest.mark.parametrize(("device", "radiation", "method"), list(_params()))
def test_every_device_runs_with_every_radiation_method_and_integrator(device, radiation, method):
    dt = "Tp/100"
    if method == "rk4" and device in RK4_REFUSED:
        with pytest.raises(SceneError, match="RK4 is unstable for this plant"):
            simulate(_scene(device, radiation, method))
        dt = RK4_REFUSED[device]
        if radiation == "none":
            # without radiation damping the NOTC floater pitches past the 1.5 rad angle bound at t = 56.4 s
            # (measured with Beeman at Tp/200 and RK4 at Tp/400): physics, not the integrator; RK4 must agree
            stops = []
            for integrator in ("beeman", "rk4"):
                with pytest.raises(SimulationDiverged, match="angle passed the bound") as info:
                    simulate(_scene(device, radiation, integrator, dt))
                stops.append(float(str(info.value).split("t = ")[1].split(" s")[0]))
            assert abs(stops[0] - stops[1]) < 0.5, stops
            return
    ds = simulate(_scene(device, radiation, method, dt))
    for name in ("displacement", "angle"):
        if name in ds:
            assert np.all(np.isfinite(ds[name].values)), f"{device}: non-finite {name}"
    assert ds.attrs["n_steps"] == 12 * int(dt.split("/")[1])  # 12 Tp
