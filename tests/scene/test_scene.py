"""Scenes: parsing, validation with clear errors, round trips through results."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from tests.sim.scenes import scene
from wecss.netcdf import global_attributes
from wecss.scene import resolve_time
from wecss.sim import Scene, SceneError, compile_scene, default_scene_path, simulate


def test_default_scene_is_the_issue_default():
    sc = Scene.from_toml(default_scene_path())
    assert sc.device.name == "m4-134"
    assert (sc.sea.kind, sc.sea.height, sc.sea.period, sc.sea.gamma) == ("jonswap", 0.04, 1.2, 3.3)
    assert sc.sea.duration_s == pytest.approx(120.0)
    assert sc.dt == pytest.approx(1.2 / 200)
    assert sc.n_steps == 20000
    assert sc.controller.name == "damping" and sc.controller.parameters == {"damping": 6.0}


@pytest.mark.parametrize(
    ("value", "seconds"), [(3.0, 3.0), ("100 Tp", 120.0), ("Tp/200", 0.006), ("2.5 T", 3.0), ("0.5*Tp", 0.6)]
)
def test_times_in_seconds_or_relative_to_the_period(value, seconds):
    assert resolve_time(value, 1.2, "x") == pytest.approx(seconds)


@pytest.mark.parametrize(
    ("sections", "message"),
    [
        ({"sea": {"kind": "choppy"}}, "accepted: regular, jonswap"),
        ({"sea": {"direction": 30.0}}, "looks like degrees"),
        ({"sea": {"duration": -5.0}}, "sea.duration must be positive"),
        ({"sea": {"duration": "ten Tp"}}, "cannot read 'ten Tp'"),
        ({"solver": {"dt": 30.0}}, "must be shorter than sea.duration"),
        (
            {"solver": {"method": "euler"}},
            "accepted: beeman, beeman-explicit, frequency, generalized-alpha, linear, reference, rk4",
        ),
        (
            {"solver": {"method": "rk4"}, "radiation": {"method": "convolution"}},
            "needs radiation.method 'state_space' or 'none'",
        ),
        ({"radiation": {"method": "magic"}}, "accepted: state_space, convolution, none"),
        ({"controller": {"name": "telepathy"}}, "unknown controller 'telepathy'; available: damping"),
        ({"controller": {"name": "damping", "parameters": {"damping": -1.0}}}, "damping must be >= 0"),
        ({"controller": {"name": "damping", "parameters": {"gain": 1.0}}}, "unexpected keyword argument 'gain'"),
        ({"sea": {"period": 0.1}}, "outside the hydrodynamic database"),
        ({"sea": {"kind": "tabulated"}}, "sea.file is required"),
        ({"sea": {"kind": "elevation", "file": "/no/such/file.txt"}}, "no file at '/no/such/file.txt'"),
        ({"outputs": {"variables": []}}, "outputs.variables is empty"),
        ({"outputs": {"variables": ["everything"]}}, "accepted: motion, pto"),
        ({"sea": {"heigth": 0.1}}, "unknown keys ['heigth']; accepted: kind, height"),
        ({"solver": {"dt": "Tp/0"}}, "divides by zero"),
        ({"solver": {"dt": "1e Tp"}}, "cannot read '1e Tp'"),
        ({"sea": {"periodic": "no"}}, "sea.periodic must be bool"),
        ({"sea": {"seed": 1.5}}, "sea.seed must be int"),
        ({"outputs": {"variables": "pto"}}, "outputs.variables must be a list"),
        ({"outputs": {"statistics_only": "false"}}, "outputs.statistics_only must be bool"),
        ({"controller": {"parameters": [1, 2]}}, "controller.parameters must be dict"),
        ({"outputs": {"every": 100000}}, "outputs.every = 100000 keeps 1 of the run's"),
        ({"solver": {"dt": "Tp/3"}}, "steps per period of the shortest wave component"),
        ({"sea": {"kind": "regular", "period": 1.2}, "solver": {"dt": "Tp"}}, "gives 1 steps per period"),
        ({"outputs": {"window": 1e-4}}, "leaves 0 steps for the statistics; it needs at least 2"),
        ({"sea": {"duration": "1e9 Tp"}}, "steps (at most 1e+09); at 50 us per step that is"),
        ({"sea": {"duration": "1e6 Tp"}, "outputs": {"every": 1}}, "2e+08 saved steps would take about 400 GB"),
    ],
)
def test_bad_scenes_fail_with_clear_messages(sections, message):
    with pytest.raises(SceneError, match=None) as info:
        compile_scene(scene(**sections))
    assert message in str(info.value)


def test_unknown_device_lists_the_known_ones():
    with pytest.raises(SceneError, match="unknown device 'm9'; known: m4-111"):
        compile_scene(scene("m9"))


def test_sections_must_be_tables_and_zero_ramps_are_allowed():
    with pytest.raises(SceneError, match=r"\[sea\] must be a table"):
        Scene.from_dict({"sea": 5})
    assert scene(sea={"ramp": "0 Tp"}).sea.ramp_s == 0.0


def test_scene_round_trips_through_json_and_result_attributes():
    sc = scene(sea={"duration": 2.0, "ramp": 0.5}, outputs={"variables": ["pto", "elevation"], "every": 2})
    assert Scene.from_json(sc.to_json()) == sc
    ds = simulate(sc)
    again = Scene.from_json(ds.attrs["scene"])
    assert again == sc
    rerun = simulate(again)
    np.testing.assert_array_equal(rerun.pto_angle.values, ds.pto_angle.values)
    assert ds.sizes["time"] == sc.n_steps // 2 + 1


def test_scene_from_toml_resolves_files_next_to_it(tmp_path):
    table = tmp_path / "spectrum.txt"
    omega = np.linspace(2.0, 12.0, 60)
    np.savetxt(table, np.column_stack([omega, 1e-4 * np.exp(-((omega - 5.0) ** 2))]))
    path = tmp_path / "scene.toml"
    path.write_text(
        '[device]\nname = "m4-111"\n[sea]\nkind = "tabulated"\nfile = "spectrum.txt"\nperiod = 1.2\n'
        'duration = "5 Tp"\nramp = "1 Tp"\n[outputs]\nvariables = ["pto"]\n'
    )
    sc = Scene.from_toml(path)
    assert sc.sea.file == str(table.resolve())
    ds = simulate(sc)
    assert json.loads(ds.attrs["scene"])["sea"]["kind"] == "tabulated"
    assert ds.attrs["wave_energy_flux_source"] == "theoretical spectrum"


def test_missing_scene_file_and_malformed_toml(tmp_path):
    with pytest.raises(FileNotFoundError, match="no scene file"):
        Scene.from_toml(tmp_path / "absent.toml")
    bad = tmp_path / "bad.toml"
    bad.write_text("[sea\nkind = 1")
    with pytest.raises(SceneError, match="not valid TOML"):
        Scene.from_toml(bad)


def test_scenes_are_hashable_and_equal_scenes_hash_equal():
    """Frozen scenes can be keys (sweeps and caches): controller parameters are frozen, lists to tuples."""
    import dataclasses
    import pickle

    a = scene(controller={"name": "damping", "parameters": {"damping": [6.0, 6.0]}})
    b = Scene.from_json(a.to_json())
    assert a == b and hash(a) == hash(b)
    assert {a: 1}[b] == 1
    assert a.controller.parameters["damping"] == (6.0, 6.0)
    assert json.loads(a.to_json())["controller"]["parameters"] == {"damping": [6.0, 6.0]}
    other = dataclasses.replace(a, controller=dataclasses.replace(a.controller, parameters={"damping": 5.0}))
    assert hash(other) != hash(a) and other != a
    assert pickle.loads(pickle.dumps(a)) == a  # sent to worker processes as it is
    with pytest.raises(TypeError, match="read-only"):
        a.controller.parameters["damping"] = 1.0  # type: ignore[index]


@pytest.mark.parametrize(
    ("sections", "message"),
    [
        (
            {"solver": {"method": "linear"}, "radiation": {"method": "convolution"}},
            "solver.method 'linear' needs radiation.method 'state_space'",
        ),
        ({"solver": {"hold": "zoh"}}, "solver.hold applies to solver.method 'linear' only"),
        (
            {"solver": {"method": "linear", "hold": "cubic"}, "radiation": {"method": "state_space"}},
            "solver.hold: unknown 'cubic'; accepted: foh, zoh",
        ),
    ],
)
def test_linear_and_frequency_solvers_refuse_what_they_cannot_use(sections, message):
    with pytest.raises(SceneError) as info:
        scene(**sections)
    assert message in str(info.value)


def test_a_coarse_step_is_noted_in_the_result():
    """A regular wave at 10 steps per period runs, and the result's notes say the step is coarse."""
    sc = scene(sea={"kind": "regular", "height": 0.01, "period": 1.2, "duration": "5 T", "ramp": 0.0},
               solver={"dt": "T/10"})  # fmt: skip
    assert "with 10 steps per period; 20 or more are recommended" in simulate(sc).attrs["notes"]


# issue 18: wrong types and values name the field, the value and what is accepted, before any work
@pytest.mark.parametrize(
    ("section", "values", "message"),
    [
        ("sea", {"height": "big"}, r"sea\.height must be a number; got 'big' \(str\)"),
        ("sea", {"gamma": "x"}, r"sea\.gamma must be a number; got 'x'"),
        ("sea", {"direction": "north"}, r"sea\.direction must be a number; got 'north'"),
        ("sea", {"seed": -1}, r"sea\.seed must be an integer from 0 to 2\*\*64 - 1 .*; got -1"),
        ("sea", {"seed": 2**64}, r"sea\.seed must be an integer from 0 to 2\*\*64 - 1 .*; got 18446744073709551616"),
        ("sea", {"seed": True}, r"sea\.seed must be int; got True"),
        ("sea", {"d_omega": math.inf}, r"sea\.d_omega must be positive and finite \[rad/s\] \(or absent\); got inf"),
        ("sea", {"period": math.inf}, r"sea\.period must be positive and finite \[s\] for jonswap waves; got inf"),
        ("sea", {"height": math.inf}, r"sea\.height must be positive and finite \[m\]; got inf"),
        ("outputs", {"every": "2"}, r"outputs\.every must be int; got '2' \(str\)"),
        ("solver", {"angle_bound": "1"}, r"solver\.angle_bound must be a number; got '1'"),
    ],
)
def test_wrong_types_and_values_name_the_field(section, values, message):
    with pytest.raises(SceneError, match=message):
        Scene.from_dict({"device": {"name": "m4-111"}, section: values})


def test_a_binary_scene_file_and_bad_json_are_named(tmp_path):
    path = tmp_path / "scene.toml"
    path.write_bytes(b"\x00\x01binary\xff\xfe")
    with pytest.raises(SceneError, match=r"scene\.toml: not a text file"):
        Scene.from_toml(path)
    with pytest.raises(SceneError, match=r"a scene's JSON could not be read .*got '\{bad'"):
        Scene.from_json("{bad")
    with pytest.raises(SceneError, match="JSON could not be read"):
        Scene.from_json(None)  # type: ignore[arg-type]


def test_wrong_objects_passed_to_the_entry_points_name_what_is_accepted():
    from wecss.sim import compile_scene, linearize, simulate

    for bad in (3, {"device": {"name": "m4-111"}}):
        with pytest.raises(TypeError, match=r"simulate takes a Scene, a CompiledScene or a scene file; got"):
            simulate(bad)  # type: ignore[arg-type]
        with pytest.raises(TypeError, match=r"compile_scene takes a wecss\.scene\.Scene; got"):
            compile_scene(bad)  # type: ignore[arg-type]
        with pytest.raises(TypeError, match=r"linearize takes a CompiledScene .*; got"):
            linearize(bad)  # type: ignore[arg-type]


def test_a_seed_beyond_64_bits_is_refused_at_input_and_the_largest_is_stored(tmp_path):
    """Issue 31: a seed of 2**64 ran to the end, then writing the result failed and nothing was saved."""
    with pytest.raises(SceneError, match=r"sea\.seed must be an integer from 0 to 2\*\*64 - 1"):
        scene(sea={"seed": 2**64})
    largest = scene(
        sea={"seed": 2**64 - 1, "duration": 10.0, "ramp": 0.0},
        solver={"method": "frequency"},
        outputs={"statistics_only": True, "variables": []},
    )
    simulate(largest, path=tmp_path / "r.nc")
    assert global_attributes(tmp_path / "r.nc")["seed"] == 2**64 - 1


def test_a_scene_file_with_a_utf8_byte_order_mark_is_read(tmp_path):
    """Issue 31: a scene saved by an editor that writes a byte-order mark was refused as invalid TOML."""
    path = tmp_path / "bom.toml"
    path.write_bytes(b"\xef\xbb\xbf" + b'[device]\nname = "m4-111"\n[sea]\nheight = 0.05\n')
    sc = Scene.from_toml(path)
    assert sc.device.name == "m4-111" and sc.sea.height == 0.05
