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
    assert "natural periods with frequency-dependent added mass, damping ratios" in out  # the modal table
    assert "zeta" in out


def test_info_lists_the_devices_and_the_shipped_databases(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["info"]) == 0
    out = capsys.readouterr().out
    for name in ("m4-111", "m4-132", "m4-134", "notc-10kw"):
        assert f"[{name}]" in out
    for device in ("m4-134", "rm3", "wavestar"):
        assert f"\n  {device} " in out


def test_unknown_target_is_an_error(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["info", "m4-999"]) == 2
    assert "known: m4-111" in capsys.readouterr().err


def _small_scene(tmp_path) -> str:  # type: ignore[no-untyped-def]
    path = tmp_path / "small.toml"
    path.write_text(
        '[device]\nname = "m4-111"\n[sea]\nkind = "jonswap"\nheight = 0.04\nperiod = 1.2\nduration = "5 Tp"\n'
        'ramp = "1 Tp"\n[outputs]\nvariables = ["pto", "elevation"]\n'
    )
    return str(path)


def test_run_writes_result_and_picture_and_prints_the_summary(tmp_path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "r.nc"
    assert main(["run", _small_scene(tmp_path), "-o", str(out), "-q"]) == 0
    text = capsys.readouterr().out
    assert out.is_file() and out.with_suffix(".png").is_file()
    assert "mean power [W]" in text and "hinge_3" not in text and "pto_3" in text
    assert "capture width ratio" in text and "steps/s" in text
    assert main(["info", str(out)]) == 0
    assert "pto_power" in capsys.readouterr().out
    picture = tmp_path / "again.png"
    assert main(["plot", str(out), "-o", str(picture)]) == 0
    assert picture.is_file()


def test_run_reports_bad_scenes_without_a_traceback(tmp_path, capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / "bad.toml"
    path.write_text('[sea]\nkind = "choppy"\n')
    assert main(["run", str(path), "-q"]) == 2
    assert "accepted: regular, jonswap" in capsys.readouterr().err
    assert main(["run", str(tmp_path / "missing.toml"), "-q"]) == 2


def test_info_into_a_closed_pipe_ends_quietly():
    """``wecss info | head -1``: the reader stops early; no error and no traceback on standard error (issue 18)."""
    import os
    import subprocess
    import sys
    from pathlib import Path

    root = Path(__file__).resolve().parents[1]
    env = {**os.environ, "PYTHONPATH": str(root)}
    proc = subprocess.Popen(
        [sys.executable, "-m", "wecss.cli", "info"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env, cwd=root
    )
    assert proc.stdout is not None and proc.stderr is not None
    proc.stdout.close()  # as head does after its first line; here before the command writes (no race)
    err = proc.stderr.read()
    proc.wait(timeout=60)
    assert err == b""


def test_run_stores_compressed_and_single_precision_results(tmp_path) -> None:
    """--compress LEVEL (lossless zlib) and --float32 (data variables in single precision, coordinates kept):
    smaller files, float32 on disk, values within float32 rounding of the full-precision run."""
    import netCDF4
    import numpy as np
    import xarray as xr

    from wecss.results import open_result, save

    scene = _small_scene(tmp_path)
    plain, small = tmp_path / "plain.nc", tmp_path / "small.nc"
    longer = ["--set", 'sea.duration="12 Tp"']  # 2400 steps: every series is compressed (COMPRESS_MIN_SIZE)
    assert main(["run", scene, "-o", str(plain), "-q", *longer]) == 0
    assert main(["run", scene, "-o", str(small), "-q", *longer, "--compress", "4", "--float32"]) == 0
    assert small.stat().st_size < 0.75 * plain.stat().st_size
    with netCDF4.Dataset(small) as nc:
        assert nc["pto_power"].dtype == np.float32 and nc["wave_elevation"].dtype == np.float32
        assert nc["time"].dtype == np.float64
        assert nc["pto_power"].filters()["zlib"] and nc["pto_power"].filters()["complevel"] == 4
        assert not nc["mean_pto_power"].filters()["zlib"]  # one value: not worth an index
    full, single = open_result(plain), open_result(small)
    np.testing.assert_array_equal(single.time, full.time)
    for name in ("pto_power", "pto_angle", "wave_elevation", "mean_pto_power"):
        np.testing.assert_allclose(single[name], full[name], rtol=2.0**-24, atol=0, err_msg=name)
        assert not np.array_equal(single[name].values.astype(float), full[name].values), name  # really rounded
    # compression alone is lossless
    zipped = save(full, tmp_path / "zipped.nc", compress=9)
    assert zipped.stat().st_size < plain.stat().st_size
    xr.testing.assert_identical(open_result(zipped), full)


@pytest.mark.parametrize("level", ["10", "-1", "high"])
def test_run_refuses_a_bad_compression_level_before_the_run(tmp_path, level, capsys) -> None:  # type: ignore[no-untyped-def]
    with pytest.raises(SystemExit) as stop:
        main(["run", _small_scene(tmp_path), "-q", "--compress", level])
    assert stop.value.code == 2
    assert "--compress" in capsys.readouterr().err
    assert not (tmp_path / "small.nc").exists()


def test_save_refuses_a_bad_compression_level(tmp_path) -> None:
    import numpy as np
    import xarray as xr

    from wecss.results import save

    with pytest.raises(ValueError, match="compress must be a zlib level 0"):
        save(xr.Dataset({"a": ("x", [1.0])}), tmp_path / "a.nc", compress=12)
    from wecss.netcdf import storage_encoding

    big = xr.Dataset({"a": ("x", np.zeros(2000))})
    assert storage_encoding(big, compress=False) == {}  # the bools of earlier callers: off, and level 6
    assert storage_encoding(big, compress=True) == {"a": {"zlib": True, "complevel": 6}}


def test_modes_prints_the_table_and_plots_the_shapes(tmp_path, capsys: pytest.CaptureFixture[str]) -> None:
    png = tmp_path / "arm.png"
    assert main(["modes", "notc-10kw", "--air", "-n", "4", "--png", str(png)]) == 0
    out = capsys.readouterr().out
    assert "notc-10kw: structural modes in air (no gravity, no water); full model, 98 coordinates" in out
    assert "strain energy in / out of plane / torsion [%]" in out
    lines = [line.split() for line in out.splitlines() if line[:4].strip().isdigit()]
    assert [line[0] for line in lines] == ["1", "2", "3", "4"]
    assert float(lines[1][1]) == pytest.approx(0.6184, abs=1e-4)  # the arm on the PTO spring
    assert lines[3][3:6] == ["0.0", "5.5", "94.5"]  # the torsion mode's strain energy
    assert png.is_file() and f"wrote {png}" in out


def test_modes_of_a_device_without_flexible_bodies_and_bad_input(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["modes", "m4-111", "--water", "--model", "reduced", "-n", "3"]) == 0
    out = capsys.readouterr().out
    assert "flexible bodies: none" in out and out.count("\n   ") >= 3
    assert main(["modes", "m4-999"]) == 2
    assert "no catalogue device 'm4-999'" in capsys.readouterr().err
    assert main(["modes", "notc-10kw", "--air", "--png", "x.jpg"]) == 2
    assert "must end in .png" in capsys.readouterr().err


def test_ctrl_c_in_the_compiled_loop_of_a_statistics_only_run_exits_130_with_one_line(
    tmp_path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    from tests.sim.test_interrupts import numba_interrupt
    from wecss.sim._beeman import Beeman

    def interrupted(self, prepared, chunk):  # type: ignore[no-untyped-def]
        raise numba_interrupt()

    monkeypatch.setattr(Beeman, "advance", interrupted)
    scene = tmp_path / "s.toml"
    scene.write_text(
        '[device]\nname = "m4-111"\n[sea]\nduration = "2 Tp"\nramp = 0.0\n[radiation]\nmethod = "none"\n'
        "[outputs]\nstatistics_only = true\nvariables = []\n"
    )
    assert main(["run", str(scene), "-q", "-o", str(tmp_path / "r.nc")]) == 130
    err = capsys.readouterr().err.strip().splitlines()
    assert err[-1].startswith("wecss: interrupted") and not any("Traceback" in line for line in err)
    assert not (tmp_path / "r.nc").exists()


def test_info_of_a_partial_result_reports_how_far_it_got(
    tmp_path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    """Issue 31: ``wecss info`` on a ``.partial.nc`` ended in a TypeError (no solver attributes yet)."""
    import wecss.sim._fixed_step as fixed_step
    import wecss.sim._stream as stream_module
    from wecss.sim import simulate

    monkeypatch.setattr(fixed_step, "CHUNK_STEPS", 100)  # parts of about 100 steps: a short run is written in many
    monkeypatch.setattr(fixed_step, "STREAM_STEPS", 100)
    add = stream_module.ResultStream.add
    parts: list[int] = []

    def interrupt_second(self, part):  # type: ignore[no-untyped-def]
        parts.append(part.time.size)
        if len(parts) == 2:
            raise KeyboardInterrupt
        add(self, part)

    monkeypatch.setattr(stream_module.ResultStream, "add", interrupt_second)
    with pytest.raises(KeyboardInterrupt):
        simulate(_small_scene(tmp_path), path=tmp_path / "r.nc")
    assert main(["info", str(tmp_path / "r.partial.nc")]) == 0
    out = capsys.readouterr().out
    assert f"partial result: stopped after {parts[0]} of" in out and out.rstrip().endswith("when a run finishes")
    assert f"{parts[0]} saved steps, t = 0 to" in out


def test_run_with_a_tolerance_prints_the_choice(tmp_path, capsys: pytest.CaptureFixture[str]) -> None:
    """``--set solver.tolerance=1e-3``: the summary says which integrator and step were chosen, and why."""
    out = tmp_path / "r.nc"
    assert main(["run", _small_scene(tmp_path), "-o", str(out), "-q", "--set", "solver.tolerance=1e-3"]) == 0
    text = capsys.readouterr().out
    assert "solver.tolerance = 0.001: " in text and "estimated relative error of the statistics" in text
