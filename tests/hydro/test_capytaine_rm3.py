"""WEC-Sim's Capytaine RM3 file by the default path: ``HydroData.from_capytaine`` with the missing body data ends
in valid data (the repair repeats until nothing more is flagged), warns loudly about the share of frequencies and
the change of A_inf, and a device spec carrying the reader's keywords runs with ``wecss run``."""

from __future__ import annotations

import re
import warnings
from pathlib import Path

import numpy as np
import pytest

import wecss
from wecss.cli import main
from wecss.devices import Device, DeviceSpecError
from wecss.hydro import HydroData, HydroDataWarning, read_capytaine

from .test_bem import RM3, RM3_BODIES

DEVICES = Path(wecss.__file__).parent / "data" / "devices"
pytestmark = pytest.mark.skipif(not RM3.is_file(), reason=f"reference data {RM3} not present")


def _read(**kwargs: object) -> tuple[HydroData, list[str]]:
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        hydro = HydroData.from_capytaine(RM3, added_mass_inf="highest_frequency", **RM3_BODIES, **kwargs)  # type: ignore[arg-type]
    messages = [str(w.message) for w in caught if issubclass(w.category, HydroDataWarning)]
    return hydro, messages


def test_the_default_path_ends_in_valid_data_with_loud_warnings():
    raw = read_capytaine(RM3, added_mass_inf="highest_frequency", **RM3_BODIES)  # type: ignore[arg-type]
    hydro, messages = _read()
    omega = hydro.omega
    # the spar's surge, pitch damping turns negative from 2.06 rad/s to the top of the range (5.2 rad/s), where
    # its largest |B| lies; once that band is gone, 2.04 rad/s is negative against the peak left: it goes too
    assert omega.size == 101 and omega[0] == pytest.approx(0.02) and omega[-1] == pytest.approx(2.02)
    # no negative diagonal damping beyond 1e-3 of its peak (yaw left out: zero to round-off, axisymmetric bodies)
    diag = np.diagonal(hydro.dataset.radiation_damping.values, axis1=1, axis2=2)
    not_yaw = [not d.endswith("__Yaw") for d in hydro.dofs]
    assert np.all(diag[:, not_yaw] >= -1e-3 * np.max(np.abs(diag[:, not_yaw]), axis=0))
    loud = next(m for m in messages if "check these data before use" in m)
    assert "replaced or dropped 160 of 260 frequencies (62%)" in loud
    assert "0.02-2.02 rad/s" in loud
    # A_inf is taken again at the highest frequency kept; the change is measured against the raw A(5.2 rad/s)
    a_before = np.abs(np.diagonal(raw.added_mass_inf.values))
    a_after = np.abs(np.diagonal(hydro.dataset.added_mass_inf.values))
    change = np.max(np.abs(a_after - a_before) / a_before)
    assert change > 0.3
    assert re.search(rf"A_inf changed by up to {change:.0%}", loud)
    np.testing.assert_array_equal(hydro.dataset.added_mass_inf.values, hydro.dataset.added_mass.values[-1])
    assert "kept by the repair, omega = 2.02 rad/s" in hydro.dataset.attrs["added_mass_inf_source"]


def test_repair_drop_also_ends_in_valid_data_and_bad_choices_are_refused():
    hydro, messages = _read(repair="drop")
    assert hydro.omega.size < 101 and any("check these data before use" in m for m in messages)
    with pytest.raises(ValueError, match="repair must be True, False, 'interpolate' or 'drop'; got 'yes'"):
        _read(repair="yes")


def _spec(tmp_path: Path, **options: object) -> Path:
    """WEC-Sim's RM3 device (the shipped spec) on the Capytaine file, with the reader's keywords in the spec."""
    text = (DEVICES / "rm3.toml").read_text().replace('"body_1"', '"rm3_float"').replace('"body_2"', '"rm3_spar"')
    name_line, rest = text.split("\n", 1)
    table = ["[hydro_options]", 'added_mass_inf = "highest_frequency"']
    for key, per_body in RM3_BODIES.items():
        entries = ", ".join(f"{b} = {list(v) if isinstance(v, tuple) else v}" for b, v in per_body.items())
        table.append(f"{key} = {{{entries}}}")
    table.extend(f'{key} = "{value}"' for key, value in options.items())
    path = tmp_path / "rm3-capytaine.toml"
    path.write_text(f'{name_line}\nhydro = "{RM3}"\n{rest}\n' + "\n".join(table) + "\n")
    return path


def test_a_device_spec_carries_the_reader_keywords_and_runs(tmp_path, capsys):
    path = _spec(tmp_path)
    device = Device.from_spec(path)
    assert device.hydro_options["added_mass_inf"] == "highest_frequency"
    with pytest.warns(HydroDataWarning):
        assert device.hydro().omega.size == 101
    scene = tmp_path / "scene.toml"
    scene.write_text(
        f'[device]\nname = "{path}"\n[sea]\nkind = "regular"\nheight = 1.0\nperiod = 8.0\nduration = "3 Tp"\n'
        'ramp = "1 Tp"\n[solver]\ndt = 0.05\n[outputs]\nvariables = ["pto"]\n'
    )
    out = tmp_path / "r.nc"
    with pytest.warns(HydroDataWarning) as record:
        assert main(["run", str(scene), "-o", str(out), "-q"]) == 0
    assert any("check these data before use" in str(w.message) for w in record)
    assert out.is_file() and "mean power [W]" in capsys.readouterr().out


def test_unknown_reader_keywords_in_a_spec_are_refused(tmp_path):
    device = Device.from_spec(_spec(tmp_path, center_of_gravity="x"))
    with pytest.raises(DeviceSpecError, match=r"hydro_options \['center_of_gravity'\] .* accepted: .*center_of_mass"):
        device.hydro()
