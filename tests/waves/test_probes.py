"""Elevation probes (``outputs.probes``): the undisturbed elevation at points of the scene, against the dispersion
relation solved here (finite depth), the origin's channel, a directional sea's components, a measured record's
propagation, a streamed run, and the scene's refusals."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from scipy.optimize import brentq

from tests.waves import directional_float as fl
from wecss.control import ControlContext, Controller, Measurement
from wecss.scene import Scene, SceneError
from wecss.sim import compile_scene, simulate

PERIOD, HEIGHT, DT = 3.0, 0.2, 0.03


def finite_depth_wavelength(period: float, depth: float, g: float) -> float:
    """lambda from omega^2 = g k tanh(k h), solved by bracketing (independent of wecss's Newton iterations)."""
    omega = 2 * math.pi / period
    k = brentq(lambda k: g * k * math.tanh(k * depth) - omega**2, 1e-6, 100.0, xtol=1e-15, rtol=1e-15)
    return 2 * math.pi / k


@pytest.fixture(scope="module")
def spec(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return fl.write_device(tmp_path_factory.mktemp("float"))


def probe_scene(spec: Path, probes: list, **changes: dict) -> Scene:
    data: dict = {
        "device": {"name": str(spec)},
        "sea": {"kind": "regular", "height": HEIGHT, "period": PERIOD, "duration": 12.0, "ramp": 0},
        "solver": {"method": "beeman", "dt": DT},
        "radiation": {"method": "none"},
        "outputs": {"variables": ["motion", "elevation"], "probes": probes},
    }
    for key, value in changes.items():
        data[key] = {**data.get(key, {}), **value}
    return Scene.from_dict(data)


@pytest.mark.parametrize("direction_deg", [0.0, 30.0])
def test_a_quarter_wavelength_down_the_wave_lags_a_quarter_period(spec: Path, direction_deg: float) -> None:
    """A regular wave A cos(omega t) at the origin is A cos(omega t - pi / 2) a quarter wavelength further along its
    direction (the database's depth, 5 m: the finite-depth wavelength), and A cos(omega t) along its crest."""
    length = finite_depth_wavelength(PERIOD, fl.DEPTH, fl.G)
    assert abs(length - fl.G * PERIOD**2 / (2 * math.pi)) > 0.05  # depth matters here
    beta = math.radians(direction_deg)
    along = [length / 4 * math.cos(beta), length / 4 * math.sin(beta)]
    crest = [-3.0 * math.sin(beta), 3.0 * math.cos(beta)]
    sc = probe_scene(spec, [[0.0, 0.0], along, crest], sea={"direction": beta})
    result = simulate(sc)
    t = result.time.values
    omega = 2 * math.pi / PERIOD
    probe = result.wave_elevation_probe
    assert probe.dims == ("time", "probe")
    np.testing.assert_allclose(result.probe_x.values, [0.0, along[0], crest[0]])
    np.testing.assert_allclose(result.probe_y.values, [0.0, along[1], crest[1]])
    np.testing.assert_allclose(probe.values[:, 0], HEIGHT / 2 * np.cos(omega * t), atol=1e-12)
    np.testing.assert_allclose(probe.values[:, 1], HEIGHT / 2 * np.cos(omega * t - math.pi / 2), atol=1e-9)
    np.testing.assert_allclose(probe.values[:, 2], HEIGHT / 2 * np.cos(omega * t), atol=1e-12)
    shift = round(PERIOD / 4 / DT)  # the probe's record is the origin's a quarter period later
    np.testing.assert_allclose(probe.values[shift:, 1], result.wave_elevation.values[:-shift], atol=1e-9)


def test_a_probe_at_the_origin_is_the_elevation_channel(spec: Path) -> None:
    """Bit for bit, with the start ramp, in a long-crested and a directional irregular sea."""
    for spreading in (None, {"type": "cos-2s", "s": 4}):
        sea = {"kind": "jonswap", "height": 0.5, "ramp": 3.0, "direction": math.radians(30.0)}
        if spreading:
            sea["spreading"] = spreading
        result = simulate(probe_scene(spec, [[5.0, 2.0], [0.0, 0.0]], sea=sea))
        np.testing.assert_array_equal(result.wave_elevation_probe.values[:, 1], result.wave_elevation.values)
        assert np.abs(result.wave_elevation_probe.values[:, 0] - result.wave_elevation.values).max() > 0.01


def test_a_directional_sea_at_a_probe(spec: Path) -> None:
    """The probe is sum_k Re[A_k exp(i (omega_k t - k_k (x cos beta_k + y sin beta_k)))] r(t) over the run's
    components, with k_k solved here and the cosine ramp r written out."""
    sea = {"kind": "jonswap", "height": 0.5, "ramp": 3.0, "direction": 0.4, "spreading": {"type": "cos-2s", "s": 2}}
    sc = probe_scene(spec, [[7.0, -4.0]], sea=sea)
    waves = compile_scene(sc).waves
    result = simulate(sc)
    t = result.time.values
    k = np.array([2 * math.pi / finite_depth_wavelength(2 * math.pi / w, fl.DEPTH, fl.G) for w in waves.omega])
    phase = np.outer(t, waves.omega) - k * (7.0 * np.cos(waves.headings) - 4.0 * np.sin(waves.headings))
    ramp = np.where(t < 3.0, 0.5 * (1 - np.cos(np.pi * t / 3.0)), 1.0)
    expected = np.real(np.exp(1j * phase) @ waves.amplitude) * ramp
    np.testing.assert_allclose(result.wave_elevation_probe.values[:, 0], expected, atol=1e-10)


def test_a_measured_record_is_propagated_along_the_sea_direction(spec: Path, tmp_path: Path) -> None:
    """A measured elevation is at the origin; its components travel along ``sea.direction`` (long-crested)."""
    omega = 2 * math.pi / PERIOD
    t = np.arange(1000) * DT  # ten periods
    record = tmp_path / "eta.txt"
    np.savetxt(record, np.column_stack([t, HEIGHT / 2 * np.cos(omega * t)]))
    length = finite_depth_wavelength(PERIOD, fl.DEPTH, fl.G)
    beta = math.radians(90.0)
    sc = probe_scene(spec, [[0.0, length / 4]], sea={"kind": "elevation", "file": str(record), "direction": beta})
    result = simulate(sc)
    np.testing.assert_allclose(
        result.wave_elevation_probe.values[:, 0], HEIGHT / 2 * np.sin(omega * result.time.values), atol=1e-9
    )


def test_a_streamed_run_writes_the_probes(spec: Path, tmp_path: Path) -> None:
    sea = {"kind": "jonswap", "height": 0.5, "ramp": 3.0, "spreading": {"type": "cos-n", "n": 2}}
    sc = probe_scene(spec, [[0.0, 0.0], [4.0, 1.0]], sea=sea)
    whole = simulate(sc)
    simulate(sc, path=tmp_path / "run.nc").close()
    with xr.open_dataset(tmp_path / "run.nc", engine="netcdf4") as streamed:
        np.testing.assert_array_equal(streamed.wave_elevation_probe.values, whole.wave_elevation_probe.values)
        np.testing.assert_array_equal(streamed.probe_x.values, [0.0, 4.0])
        np.testing.assert_array_equal(streamed.wave_elevation_probe.values[:, 0], streamed.wave_elevation.values)


def test_probes_round_trip_through_the_scene(spec: Path) -> None:
    sc = probe_scene(spec, [[1, 2], [3.5, -4.0]])
    assert sc.outputs.probes == ((1.0, 2.0), (3.5, -4.0))
    assert Scene.from_json(sc.to_json()) == sc
    assert sc.to_dict()["outputs"]["probes"] == [[1.0, 2.0], [3.5, -4.0]]


@pytest.mark.parametrize(
    ("outputs", "match"),
    [
        ({"statistics_only": True, "variables": []}, r"outputs\.probes \(1 points\).*statistics_only = true keeps no"),
        ({"variables": ["motion"]}, r"outputs\.variables = \['motion'\] leaves it out: add 'elevation'"),
        ({"probes": [[1.0]]}, r"outputs\.probes\[0\] must be \[x, y\], two finite numbers \[m\]; got \[1\.0\]"),
        ({"probes": [[1.0, float("nan")]]}, r"outputs\.probes\[0\] must be \[x, y\]"),
        ({"probes": "origin"}, r"outputs\.probes must be a list of \[x, y\] points"),
    ],
)
def test_malformed_or_unkept_probes_are_refused(outputs: dict, match: str) -> None:
    with pytest.raises(SceneError, match=match):
        Scene.from_dict({"outputs": {"probes": [[0.0, 0.0]], **outputs}})


class ElevationRecorder(Controller):
    """Damping held over each step; keeps the elevation at its point it is given at each call."""

    needs_state = False
    preview_horizon = None

    def __init__(self, point: tuple[float, float]) -> None:
        self.elevation_at = point
        self.seen: list[tuple[float, float]] = []

    def setup(self, context: ControlContext) -> None:
        self.seen = []

    def compute(self, t: float, measurement: Measurement) -> np.ndarray:
        self.seen.append((t, float(measurement.elevation)))
        return -2000.0 * measurement.velocity


def test_a_controller_sees_the_probe_elevation_of_a_directional_sea(spec: Path) -> None:
    """The elevation a controller asks for at a point (``elevation_at``) is the probe's there (two code paths: one
    time at a call, the whole record after the run)."""
    sea = {"kind": "jonswap", "height": 0.5, "ramp": 3.0, "direction": 0.4, "spreading": {"type": "cos-2s", "s": 2}}
    sc = probe_scene(spec, [[4.0, -1.0]], sea=sea)
    controller = ElevationRecorder((4.0, -1.0))
    result = simulate(sc, controller=controller)
    times = np.array([t for t, _ in controller.seen])
    seen = np.array([value for _, value in controller.seen])
    index = np.round(times / DT).astype(int)
    probe = result.wave_elevation_probe.values[index, 0]
    assert np.abs(probe).max() > 0.05
    np.testing.assert_allclose(seen, probe, atol=1e-10)


def test_named_probes(spec: Path, tmp_path: Path) -> None:
    """A table of probes by name: the names are the probe coordinate; it round-trips and reads from TOML."""
    path = tmp_path / "scene.toml"
    path.write_text(
        f'[device]\nname = "{spec}"\n[sea]\nkind = "regular"\nheight = 0.2\nperiod = 3.0\nduration = 6.0\n'
        'ramp = 0\n[radiation]\nmethod = "none"\n[outputs]\nvariables = ["motion", "elevation"]\n'
        "[outputs.probes]\norigin = [0.0, 0.0]\nbuoy = [12.0, -3.5]\n"
    )
    sc = Scene.from_toml(path)
    assert sc.outputs.probe_names == ("origin", "buoy") and sc.outputs.probe_points == ((0.0, 0.0), (12.0, -3.5))
    assert Scene.from_json(sc.to_json()) == sc
    result = simulate(sc)
    assert list(result.probe.values) == ["origin", "buoy"]
    np.testing.assert_array_equal(result.probe_x.values, [0.0, 12.0])
    np.testing.assert_array_equal(result.wave_elevation_probe.sel(probe="origin").values, result.wave_elevation.values)
    simulate(sc, path=tmp_path / "named.nc").close()  # streamed: the names reach the file
    with xr.open_dataset(tmp_path / "named.nc", engine="netcdf4") as streamed:
        assert list(streamed.probe.values) == ["origin", "buoy"]
        np.testing.assert_array_equal(streamed.wave_elevation_probe.values, result.wave_elevation_probe.values)
    with pytest.raises(SceneError, match=r"outputs\.probes\.buoy must be \[x, y\], two finite numbers \[m\]"):
        Scene.from_dict({"outputs": {"probes": {"buoy": [1.0, 2.0, 3.0]}}})
