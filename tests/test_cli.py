"""The ``wecss`` command."""

from __future__ import annotations

import pytest

from wecss.cli import main


def test_info_of_a_device_prints_its_natural_periods(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["info", "m4-134"]) == 0
    out = capsys.readouterr().out
    assert "generalised coordinates (7 DOF): bow__surge, bow__heave, bow__pitch" in out
    assert "float_8" in out and "mass      17.52 kg" in out
    assert "undamped natural periods with infinite-frequency added mass" in out
    assert "inf (no stiffness)  bow__surge" in out  # no mooring: surge is free


def test_info_lists_the_shipped_databases(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["info"]) == 0
    out = capsys.readouterr().out
    for name in ("m4-111", "m4-132", "m4-134", "notc-10kw"):
        assert f"[{name}]" in out


def test_unknown_target_is_an_error(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["info", "m4-999"]) == 2
    assert "known: m4-111" in capsys.readouterr().err
