"""The optional linear mooring (``[[moorings]]`` in a device spec): it must act as the same spring and damper
applied by a linear PTO controller on a slider along the moored DOF in every simulator, give the surge natural
frequency sqrt(k / (m + A11(omega))) of an independent fixed-point solution, and switch off the drift note."""

from __future__ import annotations

import json
import tomllib
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

from wecss.devices import Device, DeviceSpecError
from wecss.hydro import load as load_hydro
from wecss.linear import linearize
from wecss.sim import Scene, compile_scene, simulate
from wecss.sim._guards import motion_notes, unrestrained_directions

FLOAT = Path(__file__).parents[1] / "control" / "heaving_float.toml"  # the M4 stern float on a slider
STIFFNESS = 300.0  # N/m: a surge period near 2 s, inside the database's band
DAMPING = 20.0  # N s/m
MASS = 17.52  # kg, the stern float's (heaving_float.toml)


def _surge_spec(stiffness: float, damping: float) -> dict:
    """The stern float on a surge slider (the PTO on the slider has no gains of its own), moored in surge."""
    spec = tomllib.loads(FLOAT.read_text())
    spec["name"] = "surging-float"
    spec["joints"][1]["axis"] = [1.0, 0.0, 0.0]
    if stiffness or damping:
        spec["moorings"] = [{"body": "float_3", "stiffness": {"Surge": stiffness}, "damping": {"surge": damping}}]
    return spec


def _scene(tmp_path: Path, moored: bool, method: str) -> Scene:
    spec = _surge_spec(STIFFNESS, DAMPING) if moored else _surge_spec(0.0, 0.0)
    path = tmp_path / f"float-{moored}.toml"
    _write_toml(path, spec)
    gains = {"damping": 0.0, "stiffness": 0.0} if moored else {"damping": DAMPING, "stiffness": STIFFNESS}
    return Scene.from_dict(
        {
            "device": {"name": str(path)},
            "sea": {"kind": "jonswap", "height": 0.03, "period": 2.0, "duration": 20.0, "ramp": 3.0},
            "controller": {"name": "damping", "parameters": gains},
            "solver": {"method": method},
            "radiation": {"method": "state_space"},
            "outputs": {"variables": ["motion", "pto"]},
        }
    )


def _write_toml(path: Path, spec: dict) -> None:
    """A small TOML writer for the specs of these tests (tables of numbers, strings and lists)."""

    def value(v: object) -> str:
        if isinstance(v, dict):
            return "{" + ", ".join(f"{k} = {value(x)}" for k, x in v.items()) + "}"
        return json.dumps(v)

    lines = [f"{k} = {value(v)}" for k, v in spec.items() if not isinstance(v, list)]
    for key, entries in spec.items():
        if isinstance(entries, list):
            for entry in entries:
                lines.append(f"[[{key}]]")
                lines.extend(f"{k} = {value(v)}" for k, v in entry.items())
    path.write_text("\n".join(lines) + "\n")


@pytest.mark.parametrize("method", ["beeman", "rk4", "linear", "frequency"])
def test_a_mooring_moves_the_float_as_the_same_spring_and_damper_on_a_slider(tmp_path, method):
    moored = simulate(_scene(tmp_path, True, method))
    as_pto = simulate(_scene(tmp_path, False, method))
    surge, same = (ds.pto_displacement.values for ds in (as_pto, moored))
    scale = np.max(np.abs(surge))
    assert scale > 1e-3  # the float moves
    assert np.max(np.abs(same - surge)) <= 1e-9 * scale
    assert float(moored.mean_pto_power.sum()) == 0.0  # the mooring absorbs, the PTO does not
    assert json.loads(moored.attrs["moorings"]) == [
        {"body": "float_3", "stiffness": {"Surge": STIFFNESS}, "damping": {"Surge": DAMPING}}
    ]
    assert as_pto.attrs["moorings"] == "none"


def test_surge_natural_frequency_is_the_fixed_point_of_k_over_m_plus_a11(tmp_path):
    """omega_n solves omega^2 (m + A11(omega)) = k, with A11 the database's surge added mass (linear between its
    frequencies, as the model interpolates). The linear model's impedance Re[1 / H(omega)] vanishes there."""
    spec = _surge_spec(STIFFNESS, 0.0)
    path = tmp_path / "float.toml"
    _write_toml(path, spec)
    ds = load_hydro("m4-111").dataset
    a11 = ds.added_mass.sel(radiating_dof="float_3__Surge", influenced_dof="float_3__Surge").values
    omega = ds.omega.values

    def reactance(w: float) -> float:
        return STIFFNESS - w**2 * (MASS + np.interp(w, omega, a11))

    expected = brentq(reactance, 1.0, 6.0, xtol=1e-12)
    scene = Scene.from_dict(
        {
            "device": {"name": str(path)},
            "sea": {"kind": "calm", "duration": 10.0},
            "controller": {"name": "damping", "parameters": {"damping": 0.0}},
            "solver": {"method": "frequency"},
        }
    )
    model = linearize(compile_scene(scene))
    surge = list(compile_scene(scene).hydro.dofs).index("float_3__Surge")

    def impedance(w: float) -> float:
        return float(np.real(1.0 / model.frequency_response(np.array([w]))[0, 0, surge]))

    found = brentq(impedance, 1.0, 6.0, xtol=1e-12)
    print(f"surge natural frequency: {found:.8f} rad/s, fixed point {expected:.8f} rad/s")
    assert abs(found - expected) <= 1e-8 * expected
    assert abs(expected - np.sqrt(STIFFNESS / (MASS + a11[0]))) > 0.01  # the frequency dependence matters


def _planar_float(moorings: list[dict] | None) -> dict:
    """The M4 bow float alone on a planar base (surge, heave, pitch)."""
    spec = {
        "name": "planar-float",
        "hydro": "m4-111",
        "bodies": [
            {"name": "float_1", "mass": 2.345, "inertia": [0.204, 0.204, 0.204], "center_of_mass": [0, 0, -0.0634]}
        ],
        "joints": [{"name": "base", "kind": "planar", "child": "float_1"}],
    }
    spec["bodies"][0]["hydro_body"] = "float_1"
    if moorings is not None:
        spec["moorings"] = moorings
    return spec


@pytest.mark.parametrize("moored", [False, True])
def test_the_drift_note_fires_only_for_an_unmoored_float(tmp_path, moored):
    path = tmp_path / "planar.toml"
    _write_toml(path, _planar_float([{"body": "float_1", "stiffness": {"Surge": 50.0}}] if moored else None))
    compiled = compile_scene(
        Scene.from_dict({"device": {"name": str(path)}, "sea": {"kind": "calm", "duration": 10.0}})
    )
    assert unrestrained_directions(compiled)[0, 0] == (0.0 if moored else 1.0)
    names = compiled.device.model.coordinate_names
    surge = next(i for i, n in enumerate(names) if n.lower().endswith("__surge"))
    moved = np.repeat(compiled.q0[None], 20, axis=0)
    moved[:, surge] += np.linspace(0.0, 2.0, 20)
    notes = "; ".join(motion_notes(compiled, moved))
    if moored:
        assert "drift" not in notes
    else:
        assert "drift" in notes and "[[moorings]]" in notes
    k = compiled.stiffness[surge, surge]
    assert k == pytest.approx(50.0 if moored else 0.0, abs=1e-6)


@pytest.mark.parametrize(
    ("entry", "message"),
    [
        ({"body": "float_1", "stiffness": {"Surgee": 1.0}}, "unknown DOF 'Surgee'"),
        ({"body": "float_1", "stiffness": {"Surge": -1.0}}, "must be a finite number >= 0"),
        ({"body": "float_1", "stiffness": {"Surge": "1e3"}}, "must be a finite number >= 0"),
        ({"body": "float_9", "stiffness": {"Surge": 1.0}}, "unknown body 'float_9'"),
        ({"body": "float_1", "stiffness": {"Surge": 0.0}}, "give a positive stiffness or damping"),
        ({"body": "float_1", "spring": {"Surge": 1.0}}, "unknown keys \\['spring'\\]"),
        ({"stiffness": {"Surge": 1.0}}, "missing key 'body'"),
    ],
)
def test_bad_moorings_are_refused_with_the_entry(entry, message):
    with pytest.raises(DeviceSpecError, match=rf"moorings\[0\]: .*{message}"):
        Device.from_spec(_planar_float([entry]))


def test_a_mooring_on_a_dof_the_database_lacks_is_refused():
    device = Device.from_spec(_planar_float([{"body": "float_1", "stiffness": {"Sway": 10.0}}]))
    with pytest.raises(ValueError, match="float_1 Sway: the hydrodynamic database has no such DOF"):
        device.coupling()


def test_the_loads_of_a_moored_float_close_with_its_dampers(tmp_path):
    """The loads recovery counts the moorings' dampers: the closure residual (reactions, gravity, hydro, PTO and
    mooring forces against mass times acceleration) stays at round-off for a moored, damped float in waves."""
    scene = _scene(tmp_path, True, "beeman").to_dict()
    scene["outputs"]["variables"] = ["motion", "pto", "loads"]
    ds = simulate(Scene.from_dict(scene))
    assert float(np.max(np.abs(ds.velocity.values))) > 1e-3  # the float moves, so the dampers act
    assert ds.attrs["loads_closure_residual"] < 1e-10
