"""The tuned controllers in the linear simulator on one body in heave, against closed forms from the database
itself (issue 13): optimal damping reaches |F|^2 / (4 (B + |Z|)) and reactive control the complex-conjugate bound
|F|^2 / (8 B) within 1 %, and each beats its neighbours on a grid of gains in the time domain too."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from wecss.control import compile_scene
from wecss.sim import Scene, simulate

DEVICE = Path(__file__).with_name("heaving_float.toml")  # the M4 stern float on a vertical slider
PERIOD = 1.0


def _scene(name: str, parameters: dict | None = None) -> Scene:
    return Scene.from_dict(
        {
            "device": {"name": str(DEVICE)},
            "sea": {"kind": "regular", "height": 0.01, "period": PERIOD, "duration": "60 T", "ramp": "5 T"},
            "controller": {"name": name, "parameters": parameters or {}},
            "solver": {"method": "linear"},
            "radiation": {"method": "state_space"},
            "outputs": {"variables": ["pto"], "window": 0.5},
        }
    )


@pytest.fixture(scope="module")
def closed_forms():
    """F, B and the intrinsic impedance Z = B + i (omega (m + A) - C / omega) of the float's heave at the wave
    frequency, read from the database and the statics (not from the control code)."""
    compiled = compile_scene(_scene("damping", {"damping": 0.0}))
    hydro, omega = compiled.hydro, 2 * np.pi / PERIOD
    k = list(hydro.dofs).index("float_3__Heave")
    b = np.interp(omega, hydro.omega, hydro.dataset.radiation_damping.values[:, k, k])
    a = np.interp(omega, hydro.omega, hydro.dataset.added_mass.values[:, k, k])
    force = compiled.excitation.coefficients[k, 0]
    z = b + 1j * (omega * (17.52 + a) - compiled.stiffness[0, 0] / omega)
    return abs(force), b, z


def _power(name: str, parameters: dict | None = None) -> float:
    return float(simulate(_scene(name, parameters)).mean_pto_power.values[0])


def test_optimal_damping_reaches_its_closed_form(closed_forms):
    force, b, z = closed_forms
    compiled = compile_scene(_scene("optimal-damping"))
    assert compiled.controller.damping[0] == pytest.approx(abs(z), rel=1e-3)
    assert _power("optimal-damping") == pytest.approx(force**2 / (4 * (b + abs(z))), rel=0.01)


def test_reactive_control_reaches_the_complex_conjugate_bound(closed_forms):
    force, b, _ = closed_forms
    assert _power("reactive") == pytest.approx(force**2 / (8 * b), rel=0.01)


@pytest.mark.parametrize("name", ["optimal-damping", "reactive"])
def test_the_tuned_gains_beat_their_neighbours_in_the_time_domain(name):
    controller = compile_scene(_scene(name)).controller
    c, k = float(controller.damping[0]), float(controller.stiffness[0])
    best = _power("spring-damper", {"damping": c, "stiffness": k})
    for dc, dk in ((0.8, 1.0), (1.25, 1.0), (1.0, 0.8), (1.0, 1.25)):
        if name == "optimal-damping" and dk != 1.0:
            continue  # passive: stiffness stays zero
        assert _power("spring-damper", {"damping": c * dc, "stiffness": k * dk}) < best
