"""The "silent garbage" of issue 31: inputs that ran to the end with exit 0 and no note, each now refused (with the
field, the value and what is accepted) or noted in the result."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pytest

from tests.sim.scenes import scene
from wecss.control import ControlContext, Controller
from wecss.devices import DeviceSpecError, check_against_database
from wecss.devices import load as load_device
from wecss.hydro import HydroData
from wecss.multibody import Body
from wecss.results import plot_summary
from wecss.sim import SceneError, simulate

SPEC = Path(__file__).resolve().parents[2] / "wecss" / "data" / "devices"
SHORT = {"duration": 2.0, "ramp": 0.5}


def _spec(tmp_path: Path, layout: str, *edits: tuple[str, str]) -> str:
    """A copy of a catalogue spec with text ``edits`` (old, new), each found exactly once."""
    text = (SPEC / f"{layout}.toml").read_text()
    for old, new in edits:
        assert text.count(old) == 1, old
        text = text.replace(old, new)
    path = tmp_path / f"{layout}-edited.toml"
    path.write_text(text)
    return str(path)


def _compile(device: str) -> Any:
    from wecss.control import compile_scene

    return compile_scene(scene(device, sea=SHORT, radiation={"method": "none"}))


def test_a_hydro_body_naming_another_bodys_data_is_refused(tmp_path):
    """m4-111 with float_1 and float_3 swapping their data: float_1 (x = 0) reads float_3's (x = 2.12 m)."""
    device = _spec(
        tmp_path,
        "m4-111",
        ('hydro_body = "float_1"', 'hydro_body = "float_X"'),
        ('hydro_body = "float_3"', 'hydro_body = "float_1"'),
        ('hydro_body = "float_X"', 'hydro_body = "float_3"'),
    )
    with pytest.raises(SceneError) as info:
        _compile(device)
    message = str(info.value)
    assert "body 'float_1' (hydro_body 'float_3')" in message
    assert "its centre of mass [0.0, 0.0, -0.0634] m lies 2.12 m horizontally from the database body's" in message
    assert "accepted: within 0.5 x its size V^(1/3)" in message


def test_another_layouts_database_is_refused(tmp_path):
    """m4-132 read with m4-134's database: its stern float_3 at y = -0.5 m gets the data of 134's float_3 at
    y = -0.25 m (0.25 m away; the float's size is 0.26 m)."""
    device = _spec(tmp_path, "m4-132", ('hydro = "m4-132"', 'hydro = "m4-134"'))
    with pytest.raises(SceneError, match=r"body 'float_3' \(hydro_body 'float_3'\).* lies 0\.25 m horizontally"):
        _compile(device)


def test_a_float_10_m_above_the_water_is_refused(tmp_path):
    device = _spec(tmp_path, "m4-111", ("center_of_mass = [0.0, 0.0, -0.0634]", "center_of_mass = [0.0, 0.0, 10.0]"))
    with pytest.raises(SceneError, match=r"body 'float_1'.* lies 10\.04 m vertically .* within 3 x its size"):
        _compile(device)


def test_a_mass_typed_in_grams_is_refused(tmp_path):
    """float_1: 2.345 kg floats on its own displaced mass; 2345 (grams typed as kilograms) is 1000 times it."""
    device = _spec(tmp_path, "m4-111", ("mass = 2.345", "mass = 2345.0"))
    with pytest.raises(
        SceneError, match=r"body 'float_1'.*mass 2345 kg is 1000 times its displaced mass rho V = 2\.345"
    ):
        _compile(device)


def test_the_catalogue_devices_pass_the_database_checks():
    for name in ("m4-111", "m4-132", "m4-134", "notc-10kw"):
        device = load_device(name)
        check_against_database(name, list(device.model.bodies), device.hydro())


def _m4_111() -> tuple[Any, HydroData]:
    device = load_device("m4-111")
    return device, device.hydro()


def test_an_added_mass_1000_times_too_large_is_refused():
    device, hydro = _m4_111()
    ds = hydro.dataset.copy()
    ds["added_mass_inf"] = ds.added_mass_inf * 1000.0
    with pytest.raises(
        DeviceSpecError, match=r"float_1.*added mass in surge is .* 248\.5 times .* accepted: up to 100 times"
    ):
        check_against_database("m4-111", list(device.model.bodies), HydroData(ds))


def test_a_negative_heave_hydrostatic_stiffness_is_refused_before_the_run():
    """C33 = rho g A_wp >= 0: a sign error in the data made the float sink without end, seen late as a "drift"."""
    device, hydro = _m4_111()
    ds = hydro.dataset.copy(deep=True)
    heave = "float_1__Heave"
    c33 = float(ds.hydrostatic_stiffness.sel(influenced_dof=heave, radiating_dof=heave))
    assert c33 > 0
    ds["hydrostatic_stiffness"].loc[{"influenced_dof": heave, "radiating_dof": heave}] = -c33
    with pytest.raises(
        DeviceSpecError,
        match=rf"body 'float_1'.*hydrostatic stiffness in heave .* is {-c33:.6g} N/m; accepted: 0 or more",
    ):
        check_against_database("m4-111", list(device.model.bodies), HydroData(ds))


def test_a_scene_whose_device_names_a_scaled_or_thin_database_is_refused(tmp_path):
    """The same checks reached from a scene: the device spec names a database file with the added mass scaled by
    1000, then one of two frequencies."""
    _, hydro = _m4_111()
    scaled = hydro.dataset.copy()
    scaled["added_mass_inf"] = scaled.added_mass_inf * 1000.0
    HydroData(scaled).to_netcdf(tmp_path / "scaled.nc")
    HydroData(hydro.dataset.isel(omega=[50, 100])).to_netcdf(tmp_path / "two.nc")
    for database, match in (("scaled.nc", r"added mass in surge .* accepted: up to 100 times"),
                            ("two.nc", "has 2 frequencies; accepted: at least 10")):  # fmt: skip
        device = _spec(tmp_path, "m4-111", ('hydro = "m4-111"', f'hydro = "{tmp_path / database}"'))
        with pytest.raises(SceneError, match=match):
            _compile(device)


def test_a_database_of_two_frequencies_is_refused():
    device, hydro = _m4_111()
    two = HydroData(hydro.dataset.isel(omega=[50, 100]))
    with pytest.raises(DeviceSpecError, match="has 2 frequencies; accepted: at least 10"):
        check_against_database("m4-111", list(device.model.bodies), two)


@pytest.mark.parametrize("inertia", [[0.1, 0.1, 0.5], np.diag([1.0, 3.0, 1.0])], ids=["diagonal", "matrix"])
def test_an_inertia_that_breaks_the_triangle_inequality_is_refused(inertia):
    with pytest.raises(ValueError, match=r"break the triangle inequality .*accepted: each principal moment at most"):
        Body("b", 1.0, inertia, np.zeros(3))
    Body("flat", 1.0, [0.1, 0.2, 0.3], np.zeros(3))  # equality: a flat plate


def test_an_inertia_that_breaks_the_triangle_inequality_in_a_spec_is_refused(tmp_path):
    device = _spec(tmp_path, "m4-111", ("inertia = [0.204, 0.204, 0.204]", "inertia = [0.204, 0.204, 0.5]"))
    with pytest.raises(ValueError, match=r"bodies\[0\]: body 'float_1': the principal moments"):
        _compile(device)


def test_a_negative_pto_damping_in_the_spec_is_refused(tmp_path):
    device = _spec(tmp_path, "m4-111", ("damping = 6.0", "damping = -6.0"))
    with pytest.raises(ValueError, match=r"ptos\[0\]: PTO 'pto_3': damping must be >= 0 .*supplies energy.*got -6\.0"):
        _compile(device)


class NegativeGains(Controller):
    """A user controller offering linear gains with a negative damping."""

    needs_state = False

    def setup(self, context: ControlContext) -> None:
        self.n = context.n_pto

    def linear_gains(self) -> tuple[np.ndarray, np.ndarray]:
        return np.full(self.n, -2.0), np.zeros(self.n)

    def compute(self, t: float, measurement: Any) -> np.ndarray:
        return np.zeros(self.n)


def test_negative_linear_gains_of_a_user_controller_are_refused():
    with pytest.raises(SceneError, match=r"damping gains must be >= 0 \(a negative damping injects energy\)"):
        simulate(scene(sea=SHORT, radiation={"method": "none"}), controller=NegativeGains())


class Pushing(Controller):
    """A user controller that pushes with the velocity (force = +c v: a negative damper)."""

    needs_state = False

    def setup(self, context: ControlContext) -> None:
        self.n = context.n_pto

    def compute(self, t: float, measurement: Any) -> np.ndarray:
        return 2.0 * np.asarray(measurement.velocity, dtype=float)


def test_a_user_controller_that_injects_energy_is_noted_and_a_damper_is_not():
    sc = scene(sea={"duration": 8.0, "ramp": 1.0}, radiation={"method": "none"})
    ds = simulate(sc, controller=Pushing())
    assert float(ds.mean_pto_power.values[0]) < 0
    assert "energy injected" in ds.attrs["notes"] and "(Pushing)" in ds.attrs["notes"]
    assert "energy injected" not in simulate(sc).attrs["notes"]


def test_a_calm_sea_with_a_duration_in_tp_is_noted():
    ds = simulate(scene(sea={"kind": "calm", "duration": "10 Tp", "ramp": 0.0}, radiation={"method": "none"}))
    assert (
        "calm sea: sea.duration = '10 Tp' resolved with sea.period = 1.2 s though a calm sea has no period"
        in (ds.attrs["notes"])
    )
    ds = simulate(scene(sea={"kind": "calm", "duration": 2.0, "ramp": 0.0}, radiation={"method": "none"}))
    assert "calm sea" not in ds.attrs["notes"]


def test_statistics_only_with_variables_asked_for_is_refused():
    with pytest.raises(
        SceneError, match=r"statistics_only = true keeps no time series, yet outputs.variables = \['pto'\]"
    ):
        scene(outputs={"statistics_only": True, "variables": ["pto"]})
    assert scene(outputs={"statistics_only": True, "variables": []}).outputs.statistics_only


def test_a_plot_of_a_result_whose_power_is_all_nan_is_refused():
    pytest.importorskip("matplotlib")
    ds = simulate(scene(sea=SHORT, radiation={"method": "none"}, outputs={"variables": ["pto", "elevation"]}))
    ds["pto_power"] = ds.pto_power * np.nan
    with pytest.raises(ValueError, match=r"pto_power is NaN at all of its \d+ values"):
        plot_summary(ds)
