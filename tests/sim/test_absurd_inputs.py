"""Issue 31's absurd inputs, refused before the run (they ended late as a "drift" with advice to raise
``solver.translation_bound`` or shrink the step): a sea steeper than waves can be (Hs 1e6 m, Hs 2.0 meant as 2 cm,
a measured elevation record in cm) and Beeman at a step beyond its stability limit (dt = T/5 on the M4). The
limits are checked against values derived here (the dispersion relation solved by scipy, the plant's eigenvalues)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

from wecss.control import compile_scene
from wecss.scene import SceneError
from wecss.sim import Scene, simulate

SHORT = {"duration": 6.0, "ramp": 1.2}


def _wavelength(period: float, depth: float, g: float) -> float:
    """lambda [m] from omega^2 = g k tanh(k d), solved by bisection (independent of wecss.waves)."""
    omega = 2 * np.pi / period
    k = brentq(lambda k: omega**2 - g * k * np.tanh(k * min(depth, 1e4)), 1e-9, 1e4)
    return 2 * np.pi / k


def _jonswap(height: float) -> Scene:
    return Scene.from_dict(
        {
            "device": {"name": "m4-134"},
            "sea": {"kind": "jonswap", "height": height, "period": 1.2, **SHORT},
            "radiation": {"method": "none"},
        }
    )


@pytest.mark.parametrize("height", [1e6, 2.0])
def test_an_absurd_significant_height_is_refused_before_the_run_with_the_breaking_limit(height):
    """Hs 1e6 m, and Hs 2.0 m meant as 2 cm: both far above 1/7 of the peak wavelength (2.25 m at Tp 1.2 s)."""
    compiled = compile_scene(_jonswap(0.02))
    wavelength = _wavelength(1.2, compiled.hydro.water_depth, compiled.hydro.g)
    with pytest.raises(SceneError) as info:
        simulate(_jonswap(height))
    message = str(info.value)
    assert message.startswith(f"sea.height = {height:.4g} m is {height / wavelength:.3g} times the wavelength ")
    assert f"{wavelength:.4g} m at the (peak) period 1.2 s" in message
    assert f"accepted: at most 1/7 of it, {wavelength / 7:.4g} m" in message


def test_a_height_below_the_breaking_limit_still_runs():
    compiled = compile_scene(_jonswap(0.02))
    wavelength = _wavelength(1.2, compiled.hydro.water_depth, compiled.hydro.g)
    ds = simulate(_jonswap(0.95 * wavelength / 7))  # steep (noted), not impossible
    assert "steep sea" in str(ds.attrs.get("notes"))


def test_an_elevation_record_in_cm_is_refused_naming_the_file(tmp_path: Path):
    """A record of 1 cm and 0.5 cm sinusoids (Hs = 4 sqrt(m0) = 3.16 cm; periods 1.25 and 0.8 s, whole numbers of
    them in the 20 s record) written in cm: Hs 3.16 "m" at 1.25 s."""
    t = np.arange(400) * 0.05
    eta = 0.01 * np.sin(2 * np.pi * t / 1.25) + 0.005 * np.sin(2 * np.pi * t / 0.8 + 1.0)

    def scene(scale: float, name: str) -> Scene:
        path = tmp_path / name
        np.savetxt(path, np.column_stack([t, scale * eta]))
        sea = {"kind": "elevation", "file": str(path), "period": 1.2, "duration": 20.0, "ramp": 2.0}
        return Scene.from_dict({"device": {"name": "m4-111"}, "sea": sea, "radiation": {"method": "none"}})

    simulate(scene(1.0, "metres.txt"))  # the record in metres runs
    hs = 100 * 4 * np.sqrt((0.01**2 + 0.005**2) / 2)
    with pytest.raises(SceneError) as info:
        simulate(scene(100.0, "centimetres.txt"))
    message = str(info.value)
    assert "the elevation sea's significant height 4 sqrt(m0) (sea.file '" in message and "centimetres.txt')" in message
    assert f" = {hs:.4g} m is " in message and "at the (peak) period 1.25 s" in message
    assert "a record in cm or mm instead of m?" in message


def test_beeman_at_a_fifth_of_the_period_is_refused_naming_dt_and_the_limit():
    """The M4 134 at dt = T/5 = 0.24 s: its fastest undamped mode (heave and pitch of the floats on their
    hydrostatic stiffness, with A_inf) has omega dt = 1.95, past Beeman's 2 / 1.1; the run used to diverge at
    t = 14 s blaming a stiff PTO. The frequency is checked against the eigenvalues of M^-1 K computed here."""
    sea = {"kind": "regular", "height": 0.04, "period": 1.2, "duration": "30 Tp", "ramp": "3 Tp"}
    compiled = compile_scene(Scene.from_dict({"device": {"name": "m4-134"}, "sea": sea, "solver": {"dt": "Tp/5"}}))
    from wecss.linear import linearize

    model = linearize(compiled)
    omega = float(np.sqrt(np.max(np.abs(np.linalg.eigvals(np.linalg.solve(model.mass, model.stiffness))))))
    limit = 2 / 1.1 / omega
    assert limit < 0.24 < 2 / omega * 1.03  # the step lies just past the limit
    with pytest.raises(SceneError) as info:
        simulate(compiled)
    message = str(info.value)
    assert message.startswith("solver.dt = 0.24 s is beyond the stability limit of Beeman's explicit position step")
    assert f"fastest undamped natural frequency is {omega:.4g} rad/s" in message
    assert f"dt <= 1.82 / omega = {limit:.4g} s" in message
    simulate(compile_scene(Scene.from_dict({"device": {"name": "m4-134"}, "sea": {**sea, "duration": "3 Tp",
                                            "ramp": "1 Tp"}, "solver": {"dt": "Tp/8"}})))  # fmt: skip
