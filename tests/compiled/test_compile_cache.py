"""The per-process cache of compile_plant (device, equilibrium, stiffness, radiation memory): a compile served from
the cache gives the arrays of a fresh compile, and a changed device file is built again."""

from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import Any

import numpy as np

from wecss.compiled import clear_compile_cache
from wecss.devices import spec_files
from wecss.sim import Scene, compile_scene, default_scene_path

DEVICE_DIR = Path(__file__).resolve().parents[2] / "wecss" / "data" / "devices"


def _arrays(value: Any, path: str = "", depth: int = 0) -> dict[str, np.ndarray]:
    """Every array inside a compiled part (NamedTuples, dataclasses, tuples), by path."""
    if isinstance(value, np.ndarray):
        return {path: value}
    if depth > 3:
        return {}
    if hasattr(value, "_asdict"):
        items = value._asdict().items()
    elif dataclasses.is_dataclass(value) and not isinstance(value, type):
        items = ((f.name, getattr(value, f.name)) for f in dataclasses.fields(value))
    elif isinstance(value, (tuple, list)):
        items = ((str(k), v) for k, v in enumerate(value))
    else:
        return {}
    out: dict[str, np.ndarray] = {}
    for key, item in items:
        out.update(_arrays(item, f"{path}.{key}", depth + 1))
    return out


def _compiled_arrays(scene: Scene) -> dict[str, np.ndarray]:
    compiled = compile_scene(scene)
    parts = ("plant", "radiation", "waves", "excitation", "q0", "stiffness")
    out = {}
    for name in parts:
        out.update(_arrays(getattr(compiled, name), name))
    return out


def _scene(device: str = "m4-111", height: float = 0.04, seed: int = 1) -> Scene:
    base = Scene.from_toml(default_scene_path())
    return dataclasses.replace(
        base,
        device=dataclasses.replace(base.device, name=device),
        sea=dataclasses.replace(base.sea, duration="10 Tp", ramp="1 Tp", height=height, seed=seed),
        radiation=dataclasses.replace(base.radiation, method="convolution"),
    )


def test_a_second_sea_state_from_the_cache_gives_the_arrays_of_a_fresh_compile():
    clear_compile_cache()
    compile_scene(_scene(height=0.04, seed=1))  # fills the cache
    second = _scene(height=0.06, seed=5)
    cached = _compiled_arrays(second)
    clear_compile_cache()
    fresh = _compiled_arrays(second)
    assert cached.keys() == fresh.keys()
    assert {"plant.active_mass", "q0", "stiffness", "radiation.fine", "excitation.coefficients"} <= fresh.keys()
    for key in fresh:
        np.testing.assert_array_equal(cached[key], fresh[key], err_msg=key)


def test_a_changed_device_file_is_built_again(tmp_path: Path):
    spec = tmp_path / "device.toml"
    text = (DEVICE_DIR / "m4-111.toml").read_text()
    spec.write_text(text)
    clear_compile_cache()
    first = compile_scene(_scene(str(spec)))
    again = compile_scene(_scene(str(spec), seed=3))
    assert again.device is first.device  # unchanged file: from the cache
    heavier = text.replace("mass = 17.52", "mass = 19.0", 1)
    assert heavier != text
    spec.write_text(heavier)
    changed = compile_scene(_scene(str(spec)))
    assert changed.device is not first.device
    assert not np.array_equal(changed.q0, first.q0) or not np.array_equal(changed.stiffness, first.stiffness)
    clear_compile_cache()
    fresh = compile_scene(_scene(str(spec)))
    np.testing.assert_array_equal(changed.q0, fresh.q0)
    np.testing.assert_array_equal(changed.stiffness, fresh.stiffness)


def test_the_files_of_a_spec_include_the_database_it_names(tmp_path: Path):
    spec = tmp_path / "device.toml"
    spec.write_text((DEVICE_DIR / "m4-111.toml").read_text().replace('hydro = "m4-111"', 'hydro = "db.nc"', 1))
    assert spec_files(spec) == (spec.resolve(),)  # the database file does not exist: nothing to watch
    (tmp_path / "db.nc").write_bytes(b"")
    assert spec_files(spec) == (spec.resolve(), (tmp_path / "db.nc").resolve())
    catalogued = spec.with_name("catalogued.toml")
    catalogued.write_text((DEVICE_DIR / "m4-111.toml").read_text())
    assert spec_files(catalogued) == (catalogued.resolve(),)  # a catalogue database name: shipped with wecss


def test_a_new_step_discretises_the_cached_fit_and_gives_the_arrays_of_a_fresh_compile():
    """A sweep over periods changes dt = Tp/200 with each period: the state-space fit is made (or read from the disk
    cache) once per process and only discretised again for the new step."""
    base = _scene()
    state_space = dataclasses.replace(base.radiation, method="state_space")
    first = dataclasses.replace(base, radiation=state_space)
    second = dataclasses.replace(first, sea=dataclasses.replace(first.sea, period=1.4, seed=4))
    clear_compile_cache()
    a = compile_scene(first)
    cached = _compiled_arrays(second)
    b = compile_scene(second)
    assert b.dt != a.dt
    assert b.radiation_fit is a.radiation_fit  # the fit from memory, not made or read again
    clear_compile_cache()
    fresh = _compiled_arrays(second)
    assert cached.keys() == fresh.keys()
    assert {"radiation.decay", "radiation.hold_real", "plant.active_mass"} <= fresh.keys()
    for key in fresh:
        np.testing.assert_array_equal(cached[key], fresh[key], err_msg=key)
