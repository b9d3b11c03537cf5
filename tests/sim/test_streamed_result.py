"""``simulate(scene, path=...)``: the result streamed to its file chunk by chunk holds what ``save(simulate(scene))``
writes (every variable, coordinate, dimension and attribute), and a run that stops leaves a readable partial file
that says how far it got."""

from __future__ import annotations

import netCDF4
import numpy as np
import pytest
import xarray as xr

import wecss.sim._fixed_step as fixed_step
import wecss.sim._stream as stream_module
from tests.sim.scenes import held, scene
from wecss.results import open_result, save
from wecss.sim import SimulationDiverged, compile_scene, simulate
from wecss.sim._stream import streamable as streamed

#: Attributes that differ between two runs of the same scene (the clock).
CLOCK = ("history", "run_time_s", "steps_per_second")

GROUPS = ["motion", "pto", "excitation", "radiation", "elevation", "poses"]


def _read(path) -> xr.Dataset:
    with xr.open_dataset(path, engine="netcdf4") as ds:
        loaded = ds.load()
    for key in CLOCK:
        loaded.attrs.pop(key)
    return loaded


def _variable_attrs(path) -> dict[str, tuple[str, tuple[str, ...], dict]]:
    """Every variable's type, dimensions and netCDF attributes as stored (``_FillValue``, ``coordinates``...)."""
    with netCDF4.Dataset(path) as nc:
        return {
            name: (str(v.dtype), v.dimensions, {k: str(v.getncattr(k)) for k in v.ncattrs()})
            for name, v in nc.variables.items()
        }


def _assert_same_file(whole, streamed_file) -> None:
    a, b = _read(whole), _read(streamed_file)
    xr.testing.assert_identical(a, b)  # values, names, dims, coordinates, attributes
    assert list(a.attrs) == list(b.attrs)
    assert _variable_attrs(whole) == _variable_attrs(streamed_file)


@pytest.fixture
def small_parts(monkeypatch):
    """Kernel calls of 100 steps and parts of at least 230 (300), so that a short run is written in many (the
    defaults are 2,000 and 10,000)."""
    monkeypatch.setattr(fixed_step, "CHUNK_STEPS", 100)
    monkeypatch.setattr(fixed_step, "STREAM_STEPS", 230)


@pytest.mark.parametrize(
    ("method", "every", "radiation"),
    [("beeman", 1, "convolution"), ("beeman", 3, "state_space"), ("rk4", 2, "state_space")],
)
def test_streamed_file_equals_the_saved_dataset(tmp_path, small_parts, method, every, radiation):
    sc = scene(
        "m4-134",
        solver={"method": method},
        radiation={"method": radiation},
        outputs={"variables": GROUPS, "every": every},
    )
    compiled = compile_scene(sc)
    assert streamed(compiled)
    save(simulate(compiled), tmp_path / "whole.nc")
    ds = simulate(compiled, path=tmp_path / "streamed.nc")
    assert ds.sizes["time"] == compiled.n_steps // every + 1 > 10 * 300 // every  # many parts
    ds.close()
    _assert_same_file(tmp_path / "whole.nc", tmp_path / "streamed.nc")
    assert not (tmp_path / "streamed.partial.nc").exists()


def test_streamed_file_with_a_held_controller_and_storage_options(tmp_path, small_parts):
    # called every step: the loop's chunks are one step long, the parts still about 230 steps
    compiled = held(compile_scene(scene("m4-111", outputs={"variables": ["motion", "pto", "elevation"]})))
    save(simulate(compiled), tmp_path / "whole.nc", compress=4, float32=True)
    simulate(compiled, path=tmp_path / "streamed.nc", compress=4, float32=True).close()
    _assert_same_file(tmp_path / "whole.nc", tmp_path / "streamed.nc")
    with netCDF4.Dataset(tmp_path / "streamed.nc") as nc:
        assert nc.dimensions["time"].isunlimited()
        assert nc["pto_power"].dtype == np.float32 and nc["pto_power"].filters()["zlib"]
        assert nc["time"].dtype == np.float64
    # saved again, a streamed result is written as a whole one: fixed dimensions
    save(open_result(tmp_path / "streamed.nc"), tmp_path / "again.nc", compress=4)
    with netCDF4.Dataset(tmp_path / "again.nc") as nc:
        assert not nc.dimensions["time"].isunlimited()
    assert (tmp_path / "again.nc").stat().st_size <= 1.05 * (tmp_path / "streamed.nc").stat().st_size


@pytest.mark.parametrize("method", ["linear", "frequency"])
def test_runs_not_streamed_write_the_saved_dataset(tmp_path, method):
    compiled = compile_scene(
        scene(
            "m4-111",
            solver={"method": method},
            radiation={"method": "state_space"},
            outputs={"variables": ["motion", "pto"]},
        )
    )
    assert not streamed(compiled)
    save(simulate(compiled), tmp_path / "whole.nc")
    simulate(compiled, path=tmp_path / "direct.nc")
    _assert_same_file(tmp_path / "whole.nc", tmp_path / "direct.nc")


def test_a_diverging_run_leaves_a_partial_file_of_its_good_steps(tmp_path, monkeypatch):
    monkeypatch.setattr(fixed_step, "CHUNK_STEPS", 50)
    monkeypatch.setattr(fixed_step, "STREAM_STEPS", 100)
    # a hinge bound the waves pass after a few parts: the run stops with SimulationDiverged
    compiled = compile_scene(scene("m4-111", solver={"angle_bound": 0.02}))
    with pytest.raises(SimulationDiverged) as caught:
        simulate(compiled, path=tmp_path / "run.nc")
    assert not (tmp_path / "run.nc").exists()
    partial = tmp_path / "run.partial.nc"
    with xr.open_dataset(partial) as ds:
        status = ds.attrs["run_status"]
        assert status.startswith(f"stopped after {ds.sizes['time']} of {compiled.n_steps + 1} saved steps")
        assert "SimulationDiverged" in status
        assert 0 < ds.time.values[-1] <= caught.value.time
        assert np.all(np.isfinite(ds.angle.values))
        assert "scene" in ds.attrs


def test_an_interrupted_run_leaves_a_partial_file(tmp_path, small_parts, monkeypatch):
    compiled = compile_scene(scene("m4-111"))
    calls = []
    add = stream_module.ResultStream.add

    def interrupt_third(self, part):  # Ctrl-C after the second part
        calls.append(part.time.size)
        if len(calls) == 3:
            raise KeyboardInterrupt
        add(self, part)

    monkeypatch.setattr(stream_module.ResultStream, "add", interrupt_third)
    with pytest.raises(KeyboardInterrupt):
        simulate(compiled, path=tmp_path / "run.nc")
    with xr.open_dataset(tmp_path / "run.partial.nc") as ds:
        assert ds.attrs["run_status"].endswith("interrupted")
        assert ds.sizes["time"] == calls[0] + calls[1]
        whole = simulate(compiled)
        np.testing.assert_array_equal(ds.angle.values, whole.angle.values[: ds.sizes["time"]])


def test_storage_options_need_a_path_and_are_checked_before_the_run(tmp_path):
    with pytest.raises(ValueError, match="give path"):
        simulate(scene("m4-111"), compress=4)
    for method in ("beeman", "linear"):  # streamed or not
        sc = scene("m4-111", solver={"method": method}, radiation={"method": "state_space"})
        with pytest.raises(ValueError, match="zlib level"):
            simulate(sc, path=tmp_path / "r.nc", compress=12)
    assert not list(tmp_path.iterdir())
