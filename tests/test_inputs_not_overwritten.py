"""No output of a run overwrites an input of it (issue 31, data safety): the result file (``wecss run -o``,
``simulate(..., path=...)``) or a sweep's files naming the device spec's database, the scene's database, the
measured elevation record or a file in the radiation-fit cache are refused before any work, naming the field and
the file; nothing is written."""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest

from wecss.cli import main
from wecss.files import OverwriteError, refuse_overwrite
from wecss.hydro import DATA_DIR
from wecss.scene import Scene
from wecss.sim import simulate
from wecss.sweep import Sweep, run_sweep

DEVICES = Path(__file__).resolve().parent.parent / "wecss" / "data" / "devices"
SHORT = {"kind": "jonswap", "height": 0.04, "period": 1.2, "duration": "2 Tp", "ramp": 0.0}


def _database(folder: Path, name: str = "db.nc") -> Path:
    path = folder / name
    shutil.copyfile(DATA_DIR / "m4-111.nc", path)
    return path


def _spec_naming(folder: Path, database: Path) -> Path:
    spec = folder / "device.toml"
    spec.write_text((DEVICES / "m4-111.toml").read_text().replace('hydro = "m4-111"', f'hydro = "{database.name}"', 1))
    return spec


def _record(folder: Path, name: str = "eta.nc") -> Path:
    t = np.arange(2000) * 0.01
    path = folder / name  # a text record with a misleading suffix, as a user may name it
    np.savetxt(path, np.column_stack([t, 0.01 * np.sin(2 * np.pi * t / 1.2)]))
    return path


def _scene_file(folder: Path, device: str, sea: str) -> Path:
    path = folder / "scene.toml"
    path.write_text(f'[device]\n{device}\n[sea]\n{sea}\n[radiation]\nmethod = "none"\n')
    return path


def _bytes(path: Path) -> bytes:
    return path.read_bytes()


SEA = 'kind = "jonswap"\nheight = 0.04\nperiod = 1.2\nduration = "2 Tp"\nramp = 0.0'


def test_run_refuses_a_result_named_as_the_database_of_the_device_spec(tmp_path, capsys):
    database = _database(tmp_path)
    spec = _spec_naming(tmp_path, database)
    before = _bytes(database)
    scene = _scene_file(tmp_path, f'name = "{spec.name}"', SEA)
    assert main(["run", str(scene), "-q", "-o", str(database)]) == 2
    err = capsys.readouterr().err
    assert "hydrodynamic database named by the device spec (hydro) of device.name" in err
    assert str(database) in err and "nothing was written" in err and "Traceback" not in err
    assert _bytes(database) == before
    assert not list(tmp_path.glob("*.png")) and not list(tmp_path.glob("*.partial.nc"))


def test_run_refuses_a_result_named_as_the_scenes_database(tmp_path, capsys):
    database = _database(tmp_path)
    before = _bytes(database)
    scene = _scene_file(tmp_path, f'name = "m4-111"\nhydro = "{database.name}"', SEA)
    assert main(["run", str(scene), "-q", "-o", str(database)]) == 2
    err = capsys.readouterr().err
    assert "hydrodynamic database (device.hydro)" in err and str(database) in err
    assert _bytes(database) == before


def test_run_refuses_a_result_named_as_the_measured_elevation_record(tmp_path, capsys):
    record = _record(tmp_path)
    before = _bytes(record)
    sea = f'kind = "elevation"\nfile = "{record.name}"\nperiod = 1.2\nduration = 5.0\nramp = 0.0'
    scene = _scene_file(tmp_path, 'name = "m4-111"', sea)
    assert main(["run", str(scene), "-q", "-o", str(record)]) == 2
    err = capsys.readouterr().err
    assert "measured elevation record (sea.file)" in err and str(record) in err
    assert _bytes(record) == before


def test_run_refuses_a_picture_named_as_an_input(tmp_path, capsys):
    record = _record(tmp_path, "eta.png")
    sea = f'kind = "elevation"\nfile = "{record.name}"\nperiod = 1.2\nduration = 5.0\nramp = 0.0'
    scene = _scene_file(tmp_path, 'name = "m4-111"', sea)
    assert main(["run", str(scene), "-q", "-o", str(tmp_path / "r.nc"), "--png", str(record)]) == 2
    assert "the picture file" in capsys.readouterr().err
    assert not (tmp_path / "r.nc").exists()


def test_simulate_refuses_a_path_that_is_the_database_before_the_run(tmp_path, monkeypatch):
    database = _database(tmp_path)
    before = _bytes(database)
    scene = Scene.from_dict({"device": {"name": "m4-111", "hydro": str(database)}, "sea": SHORT})
    monkeypatch.setattr("wecss.sim._simulate.compile_scene", _never)  # refused before any work
    with pytest.raises(OverwriteError, match=r"hydrodynamic database \(device.hydro\)"):
        simulate(scene, path=database)
    assert _bytes(database) == before
    assert not (tmp_path / "db.partial.nc").exists()


def test_simulate_refuses_a_path_that_is_the_scene_file(tmp_path):
    scene = _scene_file(tmp_path, 'name = "m4-111"', SEA)
    with pytest.raises(OverwriteError, match="scene file"):
        simulate(scene, path=scene.with_suffix(".toml"))


def test_simulate_refuses_a_path_inside_the_radiation_fit_cache(tmp_path, monkeypatch):
    monkeypatch.setenv("WECSS_CACHE_DIR", str(tmp_path))
    cache = tmp_path / "radiation"
    cache.mkdir()
    entry = cache / "0123456789abcdef0123456789abcdef.nc"
    entry.write_bytes(b"a cached fit")
    scene = Scene.from_dict({"device": {"name": "m4-111"}, "sea": SHORT})
    with pytest.raises(OverwriteError, match="radiation-fit cache folder"):
        simulate(scene, path=entry)
    assert entry.read_bytes() == b"a cached fit"


def test_a_sweep_whose_files_would_overwrite_a_case_input_is_refused_before_any_file(tmp_path):
    folder = tmp_path / "out"
    folder.mkdir()
    database = _database(folder, "combined.nc")
    before = _bytes(database)
    base = {
        "device": {"name": "m4-111", "hydro": str(database)},
        "sea": {**SHORT, "duration": 30.0},
        "solver": {"method": "frequency", "dt": 0.01},
        "outputs": {"statistics_only": True, "variables": []},
    }
    sweep = Sweep(base, (("sea.period", (1.0, 1.4)),))
    with pytest.raises(OverwriteError, match=r"combined dataset .* hydrodynamic database \(device.hydro\) in case"):
        run_sweep(sweep, folder, progress=None)
    assert _bytes(database) == before
    assert sorted(p.name for p in folder.iterdir()) == ["combined.nc"]  # no sweep.json, no log


def test_the_guard_names_the_output_the_field_and_the_file(tmp_path):
    db = tmp_path / "db.nc"
    db.write_bytes(b"")
    with pytest.raises(OverwriteError) as info:
        refuse_overwrite({"result file": tmp_path / "." / "db.nc"}, {"hydrodynamic database (device.hydro)": db})
    message = str(info.value)
    assert "the result file" in message and "device.hydro" in message and str(db) in message
    refuse_overwrite({"result file": tmp_path / "other.nc"}, {"database": db, "cache": tmp_path / "cache"})


def _never(*args, **kwargs):  # type: ignore[no-untyped-def]
    raise AssertionError("the scene was compiled: the output must be refused before any work")


def test_simulate_refuses_a_path_among_the_data_shipped_with_wecss(tmp_path):
    shipped = DATA_DIR / "m4-111.nc"  # the catalogue device's own database
    before = _bytes(shipped)
    scene = Scene.from_dict({"device": {"name": "m4-111"}, "sea": SHORT})
    with pytest.raises(OverwriteError, match=r"data shipped with wecss"):
        simulate(scene, path=shipped)
    assert _bytes(shipped) == before
