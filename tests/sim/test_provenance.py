"""Provenance (issue 31): a result records the controller that ran (its name, class, parameters and applied gains)
and its input files with their SHA-256 and the device spec's text, so that ``wecss run --from RESULT.nc`` makes
the run again, finds inputs moved with the result, refuses a changed input naming the file and both checksums,
and names the class a custom controller needs."""

from __future__ import annotations

import hashlib
import json
import shutil
from pathlib import Path

import numpy as np
import pytest

from wecss.cli import main
from wecss.compiled import clear_compile_cache
from wecss.netcdf import read_netcdf, write_netcdf
from wecss.results import open_result
from wecss.sim import Scene, simulate
from wecss_controllers import LinearDamping, OptimalDamping

from .scenes import HeldDamping

FLOAT = Path(__file__).parents[1] / "control" / "heaving_float.toml"


def _scene(spec: Path, damping: float = 40.0) -> Scene:
    """The heaving float (a spec file) in a short regular sea, its scene's controller a damping of ``damping``."""
    return Scene.from_dict(
        {
            "device": {"name": str(spec)},
            "sea": {"kind": "regular", "height": 0.02, "period": 1.2, "duration": 6.0, "ramp": 1.2},
            "controller": {"name": "damping", "parameters": {"damping": damping}},
            "radiation": {"method": "none"},
            "outputs": {"variables": ["pto"]},
        }
    )


@pytest.fixture
def spec(tmp_path: Path) -> Path:
    """A copy of the heaving float's spec in its own folder (its database is the shipped m4-111)."""
    folder = tmp_path / "project"
    folder.mkdir()
    return Path(shutil.copy(FLOAT, folder / "float.toml"))


def _records(ds) -> dict[str, dict]:
    return {r["field"]: r for r in json.loads(ds.attrs["input_files"])}


def test_the_controller_given_to_simulate_is_recorded_not_the_scenes(spec):
    ds = simulate(_scene(spec, damping=40.0), controller=LinearDamping(damping=90.0))
    assert ds.attrs["controller"] == "damping"
    assert ds.attrs["controller_class"] == "wecss_controllers._damping.LinearDamping"
    assert ds.attrs["controller_source"] == "given to simulate"
    assert json.loads(ds.attrs["controller_parameters"]) == {"damping": 90.0, "stiffness": 0.0}
    assert json.loads(ds.attrs["controller_gains"]) == {"damping": [90.0], "stiffness": [0.0]}
    assert "the scene's controller section ('damping', {'damping': 40.0}) was not used" in ds.attrs["notes"]
    own = simulate(_scene(spec, damping=40.0))
    assert own.attrs["controller_source"] == "scene"
    assert "was not used" not in own.attrs["notes"]
    assert not np.allclose(own.mean_pto_power, ds.mean_pto_power, rtol=1e-3)  # the two controllers differ


def test_tuned_gains_are_recorded(spec):
    tuned = OptimalDamping()
    ds = simulate(_scene(spec), controller=tuned)
    assert ds.attrs["controller"] == "optimal-damping"
    assert json.loads(ds.attrs["controller_parameters"]) == {}
    assert json.loads(ds.attrs["controller_gains"])["damping"] == tuned.damping.tolist()
    assert tuned.damping[0] > 0 and tuned.damping[0] != 40.0


def test_inputs_are_recorded_with_their_sha256_and_the_spec_embedded(spec, tmp_path):
    out = tmp_path / "results" / "r.nc"
    out.parent.mkdir()
    simulate(_scene(spec), path=out).close()
    ds = open_result(out)
    records = _records(ds)
    recorded = records["device spec of device.name"]
    assert recorded["sha256"] == hashlib.sha256(spec.read_bytes()).hexdigest()
    assert recorded["bytes"] == spec.stat().st_size
    assert recorded["relative_path"] == "../project/float.toml"
    database = records["hydrodynamic database named by the device spec (hydro) of device.name"]
    assert database["shipped_path"] == "hydro/m4-111.nc"  # the spec names a shipped database
    assert "relative_path" not in database
    assert ds.attrs["device_spec"] == spec.read_text()


def test_a_run_made_again_from_its_file_gives_the_same_result(spec, tmp_path, capsys):
    first = tmp_path / "first.nc"
    # the scene's controller (damping 40) is not the one that ran (damping 90)
    simulate(_scene(spec, damping=40.0), controller=LinearDamping(damping=90.0), path=first).close()
    again = tmp_path / "again.nc"
    assert main(["run", "--from", str(first), "-o", str(again), "-q"]) == 0
    a, b = open_result(first), open_result(again)
    np.testing.assert_array_equal(a.mean_pto_power.values, b.mean_pto_power.values)
    np.testing.assert_array_equal(a.pto_power.values, b.pto_power.values)
    assert json.loads(b.attrs["controller_parameters"]) == {"damping": 90.0, "stiffness": 0.0}
    assert b.attrs["input_files"] == a.attrs["input_files"]


def test_a_changed_input_is_refused_naming_the_file_and_both_checksums(spec, tmp_path, capsys):
    out = tmp_path / "r.nc"
    simulate(_scene(spec), path=out).close()
    before = hashlib.sha256(spec.read_bytes()).hexdigest()
    spec.write_text(spec.read_text().replace("mass = 17.52", "mass = 17.60"))
    after = hashlib.sha256(spec.read_bytes()).hexdigest()
    assert before != after
    assert main(["run", "--from", str(out), "-o", str(tmp_path / "again.nc"), "-q"]) == 2
    err = capsys.readouterr().err
    assert "device spec of device.name changed since the run" in err
    assert str(spec.resolve()) in err and before in err and after in err
    assert not (tmp_path / "again.nc").exists()


def test_inputs_moved_with_the_result_are_found_by_their_relative_path(spec, tmp_path, capsys):
    out = spec.parent / "r.nc"
    simulate(_scene(spec), path=out).close()
    moved = Path(shutil.move(spec.parent, tmp_path / "moved"))
    again = tmp_path / "again.nc"
    assert main(["run", "--from", str(moved / "r.nc"), "-o", str(again), "-q"]) == 0
    assert f"found at {str((moved / 'float.toml').resolve())!r}" in capsys.readouterr().err
    np.testing.assert_array_equal(open_result(moved / "r.nc").pto_power.values, open_result(again).pto_power.values)


def test_a_relative_path_in_the_scene_runs_the_checked_file_not_one_of_that_name_here(
    spec, tmp_path, capsys, monkeypatch
):
    monkeypatch.chdir(spec.parent)  # the scene names its spec relative to the folder the run is made in
    out = spec.parent / "r.nc"
    simulate(Scene.from_dict({**_scene(spec).to_dict(), "device": {"name": spec.name}}), path=out).close()
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    (elsewhere / spec.name).write_text(spec.read_text().replace("mass = 17.52", "mass = 30.0"))
    monkeypatch.chdir(elsewhere)  # another spec of that name here: the run must read the one it checked
    assert main(["run", "--from", str(out), "-o", "again.nc", "-q"]) == 0
    a, b = open_result(out), open_result(elsewhere / "again.nc")
    np.testing.assert_array_equal(a.pto_power.values, b.pto_power.values)
    assert _records(b)["device spec of device.name"]["path"] == str(spec.resolve())


def test_a_custom_controller_names_the_class_it_needs(spec, tmp_path, capsys):
    out = tmp_path / "r.nc"
    simulate(_scene(spec), controller=HeldDamping(damping=30.0), path=out).close()
    ds = open_result(out)
    assert ds.attrs["controller"] == "unregistered"
    assert ds.attrs["controller_class"] == "tests.sim.scenes.HeldDamping"
    assert json.loads(ds.attrs["controller_parameters"]) == {"damping": 30.0}
    assert "controller_gains" not in ds.attrs  # it applies no linear gains
    assert main(["run", "--from", str(out), "-o", str(tmp_path / "again.nc"), "-q"]) == 2
    err = capsys.readouterr().err
    assert "class tests.sim.scenes.HeldDamping" in err and "not registered" in err
    assert "{'damping': 30.0}" in err


def test_from_refuses_a_scene_file_beside_it_and_an_output_over_the_result(spec, tmp_path, capsys):
    out = tmp_path / "r.nc"
    simulate(_scene(spec), path=out).close()
    assert main(["run", str(spec), "--from", str(out), "-q"]) == 2
    assert "not both" in capsys.readouterr().err
    assert main(["run", "--from", str(out), "-o", str(out), "-q"]) == 2
    assert "result file read by --from" in capsys.readouterr().err


def test_a_changed_elevation_record_is_refused_naming_it(spec, tmp_path, capsys):
    t = np.arange(240) * 0.05
    record = spec.parent / "eta.txt"
    np.savetxt(record, np.column_stack([t, 0.01 * np.sin(2 * np.pi * t / 1.2)]))
    scene = Scene.from_dict(
        {
            "device": {"name": str(spec)},
            "sea": {"kind": "elevation", "file": str(record), "period": 1.2, "duration": 12.0, "ramp": 1.2},
            "radiation": {"method": "none"},
            "outputs": {"variables": ["pto"]},
        }
    )
    out = tmp_path / "r.nc"
    simulate(scene, path=out).close()
    recorded = _records(open_result(out))["measured elevation record (sea.file)"]
    before = hashlib.sha256(record.read_bytes()).hexdigest()
    assert recorded["sha256"] == before
    np.savetxt(record, np.column_stack([t, 0.02 * np.sin(2 * np.pi * t / 1.2)]))  # a record in other units
    assert main(["run", "--from", str(out), "-o", str(tmp_path / "again.nc"), "-q"]) == 2
    err = capsys.readouterr().err
    assert "measured elevation record (sea.file) changed since the run" in err
    assert before in err and hashlib.sha256(record.read_bytes()).hexdigest() in err


def test_a_radiation_fit_that_changed_in_the_cache_is_named_before_the_run(spec, tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("WECSS_CACHE_DIR", str(tmp_path / "cache"))
    scene = Scene.from_dict({**_scene(spec).to_dict(), "radiation": {"method": "state_space"}})
    out = tmp_path / "r.nc"
    simulate(scene, path=out).close()
    recorded = open_result(out).attrs["radiation_fit_sha256"]
    assert len(recorded) == 64
    assert main(["run", "--from", str(out), "-o", str(tmp_path / "same.nc"), "-q"]) == 0
    assert "radiation fit differs" not in capsys.readouterr().err  # the same fit, from the cache
    (entry,) = (tmp_path / "cache" / "radiation").glob("*.nc")
    fit = read_netcdf(entry)
    fit["C"] = fit["C"] * 1.001  # another fit in the cache entry (still stable and passive)
    write_netcdf(fit, entry)
    clear_compile_cache()  # a new process reads the cache again
    assert main(["run", "--from", str(out), "-o", str(tmp_path / "again.nc"), "-q"]) == 0
    err = capsys.readouterr().err
    assert "warning: the radiation fit differs from the run's" in err and recorded in err
    assert open_result(tmp_path / "again.nc").attrs["radiation_fit_sha256"] != recorded


def test_gains_that_differ_from_the_recorded_ones_are_named_before_the_run(spec, tmp_path, capsys):
    damping = [90.0]
    controller = LinearDamping(damping=damping)
    damping[0] = 10.0  # changed after the controller was made: it runs 90, its arguments now say 10
    out = tmp_path / "r.nc"
    simulate(_scene(spec), controller=controller, path=out).close()
    assert json.loads(open_result(out).attrs["controller_gains"])["damping"] == [90.0]
    assert main(["run", "--from", str(out), "-o", str(tmp_path / "again.nc"), "-q"]) == 0
    err = capsys.readouterr().err
    assert "warning: the controller's linear gains differ from the run's" in err
    assert "[10.0]" in err and "[90.0]" in err
    assert main(["run", "--from", str(tmp_path / "again.nc"), "-o", str(tmp_path / "same.nc"), "-q"]) == 0
    assert "gains differ" not in capsys.readouterr().err  # the same gains: no warning


def test_a_controller_name_that_now_makes_another_class_is_refused(spec, tmp_path, capsys):
    out = tmp_path / "r.nc"
    simulate(_scene(spec), path=out).close()
    ds = read_netcdf(out)
    ds.attrs["controller_class"] = "theirpackage.Damping"  # a result made where another package registered 'damping'
    write_netcdf(ds, out)
    assert main(["run", "--from", str(out), "-o", str(tmp_path / "again.nc"), "-q"]) == 2
    err = capsys.readouterr().err
    assert "was class theirpackage.Damping" in err and "wecss_controllers:LinearDamping" not in err
    assert "now makes wecss_controllers.LinearDamping" in err


@pytest.mark.parametrize("given", [False, True], ids=["scene's controller", "given to simulate"])
def test_a_result_made_before_the_controllers_package_was_renamed_runs_again(spec, tmp_path, capsys, given):
    """Results written before issue 31 record the built-in classes under the package's former name,
    ``controllers``; --from reads them under ``wecss_controllers`` and says so."""
    out = tmp_path / "old.nc"
    simulate(_scene(spec), controller=LinearDamping(damping=90.0) if given else None, path=out).close()
    ds = read_netcdf(out)
    assert ds.attrs["controller_class"] == "wecss_controllers._damping.LinearDamping"
    ds.attrs["controller_class"] = "controllers._damping.LinearDamping"  # as written before the rename
    write_netcdf(ds, out)
    again = tmp_path / "again.nc"
    assert main(["run", "--from", str(out), "-o", str(again), "-q"]) == 0
    err = capsys.readouterr().err
    assert "controller class controllers._damping.LinearDamping is read as wecss_controllers._damping." in err
    np.testing.assert_array_equal(open_result(again).pto_power.values, open_result(out).pto_power.values)


def test_a_former_package_name_of_another_class_is_still_refused(spec, tmp_path, capsys):
    """The renaming maps the module name only: a class the name does not make now is refused as before."""
    out = tmp_path / "old.nc"
    simulate(_scene(spec), path=out).close()
    ds = read_netcdf(out)
    ds.attrs["controller_class"] = "controllers._theirs.Damping"
    write_netcdf(ds, out)
    assert main(["run", "--from", str(out), "-o", str(tmp_path / "again.nc"), "-q"]) == 2
    assert "was class controllers._theirs.Damping" in capsys.readouterr().err
