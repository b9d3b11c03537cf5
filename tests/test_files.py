"""Nothing lost: atomic result files under interrupts and kills, and outputs checked before any run (issue 18)."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from wecss.cli import main
from wecss.netcdf import read_netcdf, remove_stale_temporaries, write_netcdf

WRITER = """
import sys, numpy as np, xarray as xr
from wecss.netcdf import write_netcdf
ds = xr.Dataset({"x": (("a", "b"), np.random.default_rng(0).standard_normal((4000, 6000)))})
print("writing", flush=True)
write_netcdf(ds, sys.argv[1])
print("done", flush=True)
"""


def _signal_a_whole_file_write(tmp_path, sig: int) -> int:  # type: ignore[no-untyped-def]
    """Start WRITER over a previous r.nc, send ``sig`` while it writes; check the previous file and that no
    temporary is left; the writer's return code."""
    target = tmp_path / "r.nc"
    write_netcdf(xr.Dataset({"y": ("t", np.arange(3.0))}), target)
    proc = subprocess.Popen([sys.executable, "-c", WRITER, str(target)], stdout=subprocess.PIPE, text=True)
    assert proc.stdout is not None and proc.stdout.readline().strip() == "writing"
    # the signal once the temporary is there, inside to_netcdf (190 MB: a fixed sleep raced the write on a quiet
    # machine, where it had ended before the signal came)
    deadline = time.monotonic() + 60
    while not list(tmp_path.glob(".r.nc.*")) and proc.poll() is None and time.monotonic() < deadline:
        time.sleep(0.001)
    assert proc.poll() is None, "the writer ended before the signal"
    proc.send_signal(sig)
    try:
        proc.wait(timeout=60)
    finally:
        proc.kill()
    np.testing.assert_array_equal(read_netcdf(target).y.values, np.arange(3.0))
    assert list(tmp_path.glob(".r.nc.*")) == []
    return proc.returncode


@pytest.mark.skipif(os.name != "posix", reason="signals")
def test_an_interrupt_during_a_write_leaves_the_previous_file_and_no_temporary(tmp_path):
    assert _signal_a_whole_file_write(tmp_path, signal.SIGINT) != 0  # KeyboardInterrupt, not "done"


def test_temporaries_of_killed_writers_are_removed_and_live_ones_kept(tmp_path):
    target = tmp_path / "r.nc"
    dead = tmp_path / ".r.nc.999999999.abc.tmp"  # no such process
    old = tmp_path / ".r.nc.x1y2.tmp"  # the former naming, without a process id
    live = tmp_path / f".r.nc.{os.getpid()}.abc.tmp"
    for p in (dead, old, live):
        p.write_text("partial")
    assert sorted(remove_stale_temporaries(target)) == sorted([dead, old])
    assert live.exists()


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["-o", "{scene}"], "the result file must end in .nc"),
        (["-o", "r.png"], "the result file must end in .nc"),
        (["-o", "r.nc", "--png", "r.nc"], "the picture file must end in .png"),
        (["-o", "{folder}"], "must end in .nc"),
        (["-o", "{folder_nc}"], "is a folder"),
        (["-o", "{missing}/r.nc"], "does not exist"),
    ],
)
def test_run_refuses_bad_outputs_before_simulating(tmp_path, capsys, args, message):
    scene = tmp_path / "s.toml"
    scene.write_text('[sea]\nduration = "2 Tp"\nramp = 0.0\n')
    (tmp_path / "out.nc").mkdir()
    names = {"scene": str(scene), "folder": str(tmp_path), "folder_nc": str(tmp_path / "out.nc")}
    names["missing"] = str(tmp_path / "nowhere")
    argv = ["run", str(scene), "-q", *[a.format(**names) for a in args]]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert message in err and "Traceback" not in err
    assert scene.read_text().startswith("[sea]")  # the scene file is untouched
    assert not list(tmp_path.glob("*.png"))


def test_plot_refuses_to_overwrite_its_input(tmp_path, capsys):
    scene = tmp_path / "s.toml"
    scene.write_text('[sea]\nduration = "2 Tp"\nramp = 0.0\n[outputs]\nvariables = ["pto"]\n')
    result = tmp_path / "r.nc"
    assert main(["run", str(scene), "-q", "-o", str(result), "--png", str(tmp_path / "r.png")]) == 0
    before = result.read_bytes()
    capsys.readouterr()
    assert main(["plot", str(result), "-o", str(result)]) == 2
    assert "must end in .png" in capsys.readouterr().err
    assert result.read_bytes() == before


def test_os_errors_reach_the_user_without_a_traceback(tmp_path, capsys, monkeypatch):
    def refuse(*args, **kwargs):
        raise PermissionError(13, "Permission denied", str(tmp_path / "r.nc"))

    monkeypatch.setattr("wecss.results._io.write_netcdf", refuse)
    monkeypatch.setattr("wecss.netcdf.AppendingWriter.append", refuse)  # wecss run streams its result
    scene = tmp_path / "s.toml"
    scene.write_text('[sea]\nduration = "2 Tp"\nramp = 0.0\n[outputs]\nvariables = ["pto"]\n')
    assert main(["run", str(scene), "-q", "-o", str(tmp_path / "r.nc")]) == 2
    err = capsys.readouterr().err
    assert "Permission denied" in err and "Traceback" not in err
    assert Path(tmp_path / "r.nc").exists() is False


def test_the_licence_file_states_the_licence_pyproject_declares():
    import tomllib

    root = Path(__file__).resolve().parents[1]
    declared = tomllib.loads((root / "pyproject.toml").read_text())["project"]["license"]["text"]
    assert (root / "LICENSE").read_text().startswith(f"{declared} License")


def test_the_tutorial_scene_and_spec_blocks_are_valid():
    """docs/byo-bem.md: its spec block builds a device, its scene block reads as a Scene and its
    ``[hydro_options]`` block holds keywords of the Capytaine reader (issue 18)."""
    import inspect
    import re
    import tomllib

    from wecss.devices import Device
    from wecss.hydro import read_capytaine
    from wecss.sim import Scene

    root = Path(__file__).resolve().parents[1]
    blocks = re.findall(r"```toml\n(.*?)```", (root / "docs" / "byo-bem.md").read_text(), flags=re.S)
    options, spec, scene = (tomllib.loads(b) for b in blocks)
    assert set(options["hydro_options"]) <= set(inspect.signature(read_capytaine).parameters)
    device = Device.from_spec(spec)  # refuses unknown or missing keys
    assert [p.name for p in device.ptos] == ["motor"]
    wamit = root.parent / "shared" / "data" / "wamit" / "wavestar" / "wavestar.out"
    scene["device"]["hydro"] = str(wamit)
    parsed = Scene.from_dict(scene)
    assert parsed.device.name == "wavestar" and parsed.radiation.body_to_body


@pytest.mark.skipif(os.name != "posix", reason="signals")
def test_sigterm_during_a_whole_file_write_leaves_the_previous_file_and_no_temporary(tmp_path):
    # the default action, after the clean-up
    assert _signal_a_whole_file_write(tmp_path, signal.SIGTERM) == -signal.SIGTERM


def test_a_stale_temporary_of_a_killed_whole_file_write_is_removed_by_the_next_streamed_run(tmp_path):
    from wecss.sim import simulate

    stale = tmp_path / ".r.nc.999999999.abc.tmp"  # a whole-file write of r.nc killed (SIGKILL): no such process
    stale.write_bytes(b"\x89HDF\r\n\x1a\n half a file")
    scene = tmp_path / "s.toml"
    scene.write_text('[sea]\nduration = "2 Tp"\nramp = 0.0\n[outputs]\nvariables = ["pto"]\n')
    with simulate(scene, path=tmp_path / "r.nc") as ds:  # streamed
        assert "pto_power" in ds
    assert not stale.exists()


@pytest.mark.skipif(os.name != "posix", reason="signals")
def test_sigterm_during_a_streamed_run_marks_its_partial_file_and_exits_143(tmp_path):
    scene = tmp_path / "long.toml"
    scene.write_text(  # far longer than the test waits; few wave components (d_omega)
        '[device]\nname = "m4-111"\n[sea]\nduration = "20000 Tp"\nramp = 0.0\nd_omega = 0.05\n'
        '[radiation]\nmethod = "none"\n[outputs]\nvariables = ["pto"]\nevery = 10\n'
    )
    env = {**os.environ, "OPENBLAS_NUM_THREADS": "1"}
    command = [sys.executable, "-m", "wecss.cli", "run", str(scene), "-q", "-o", str(tmp_path / "long.nc")]
    proc = subprocess.Popen(command, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    partial = tmp_path / "long.partial.nc"
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and proc.poll() is None and not partial.exists():
        time.sleep(0.05)
    assert proc.poll() is None, "the run must still be going"
    proc.send_signal(signal.SIGTERM)
    try:
        _, err = proc.communicate(timeout=120)
    finally:
        proc.kill()
    assert proc.returncode == 143, err
    assert "terminated (SIGTERM)" in err and "Traceback" not in err
    with xr.open_dataset(partial) as ds:
        status = ds.attrs["run_status"]
    assert status.startswith("stopped after") and status.endswith("terminated (SIGTERM)")
    assert not (tmp_path / "long.nc").exists() and not list(tmp_path.glob(".*.tmp"))
