"""A full disk while a result is written (issue 31): the netCDF library's bare ``RuntimeError: NetCDF: HDF error``
(exit 3, the code of a diverged run) becomes a ``WriteFailed`` naming the file, saying the disk is full and what
became of the file, and ``wecss`` exits with its own status 4. The disk is not filled: the writer is made to fail."""

from __future__ import annotations

import errno
from collections import namedtuple
from pathlib import Path
from typing import Any

import pytest
import xarray as xr

from wecss import netcdf
from wecss.cli import EXIT_WRITE_FAILED, build_parser, main
from wecss.files import WriteFailed
from wecss.netcdf import AppendingWriter, write_netcdf

Usage = namedtuple("Usage", "total used free")


def _scene_file(tmp_path: Path) -> Path:
    path = tmp_path / "scene.toml"
    path.write_text(
        '[device]\nname = "m4-111"\n[sea]\nkind = "regular"\nheight = 0.02\nperiod = 1.2\nduration = 3.0\n'
        'ramp = 0.5\n[solver]\ndt = 0.006\n[radiation]\nmethod = "none"\n[outputs]\nvariables = ["motion"]\n'
    )
    return path


class _FailingSync:
    """The netCDF file of an AppendingWriter whose ``sync`` raises ``error`` the ``fail_at``-th time (the other
    calls go to the file)."""

    def __init__(self, nc: Any, error: BaseException, fail_at: int) -> None:
        self._nc, self._error, self._left = nc, error, fail_at

    def sync(self) -> None:
        self._left -= 1
        if self._left == 0:
            raise self._error
        self._nc.sync()

    def __getattr__(self, name: str) -> Any:
        return getattr(self._nc, name)


def _fail_second_part(monkeypatch: pytest.MonkeyPatch, error: BaseException) -> None:
    """Parts every 100 steps; the second part's write raises ``error``."""
    monkeypatch.setattr("wecss.sim._fixed_step.STREAM_STEPS", 100)
    monkeypatch.setattr("wecss.sim._fixed_step.CHUNK_STEPS", 100)
    create = AppendingWriter._create

    def failing(self: AppendingWriter, part: xr.Dataset, status: str) -> None:
        create(self, part, status)
        self._nc = _FailingSync(self._nc, error, 1)  # type: ignore[assignment]

    monkeypatch.setattr(AppendingWriter, "_create", failing)


def test_a_full_disk_while_streaming_exits_4_naming_the_file_and_the_partial_file_says_it_stopped(
    tmp_path, monkeypatch, capsys
):
    _fail_second_part(monkeypatch, RuntimeError("NetCDF: HDF error"))  # what netCDF-C raises on a full disk
    monkeypatch.setattr(netcdf.shutil, "disk_usage", lambda path: Usage(10**9, 10**9, 4096))
    out = tmp_path / "run.nc"
    assert main(["run", str(_scene_file(tmp_path)), "-o", str(out), "-q"]) == EXIT_WRITE_FAILED == 4
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err
    partial = tmp_path / "run.partial.nc"
    assert err.startswith(f"wecss: write failed: writing '{partial}' failed: the disk is full (4096 bytes free in ")
    assert "(RuntimeError: NetCDF: HDF error); the partial file keeps the first 101 of 501 rows whole" in err
    assert not out.exists()
    with xr.open_dataset(partial) as ds:
        assert ds.attrs["run_status"].startswith("stopped after 101 of 501 saved steps: WriteFailed: writing")
        assert ds.sizes["time"] >= 101


def test_enospc_is_a_full_disk_whatever_the_free_space_says(tmp_path, monkeypatch):
    from wecss.sim import Scene, simulate

    _fail_second_part(monkeypatch, OSError(errno.ENOSPC, "No space left on device"))
    with pytest.raises(WriteFailed, match=r"run.partial.nc' failed: the disk is full \(.* bytes free in") as info:
        simulate(Scene.from_toml(_scene_file(tmp_path)), path=tmp_path / "run.nc")
    assert info.value.errno == errno.ENOSPC
    assert isinstance(info.value.__cause__, OSError)  # the system's error kept


def test_another_write_error_is_not_called_a_full_disk(tmp_path, monkeypatch):
    from wecss.sim import Scene, simulate

    _fail_second_part(monkeypatch, OSError(errno.EIO, "Input/output error"))
    monkeypatch.setattr(netcdf.shutil, "disk_usage", lambda path: Usage(10**12, 0, 10**12))
    with pytest.raises(WriteFailed, match=r"failed: the write failed \(OSError: \[Errno 5\] Input/output error\)"):
        simulate(Scene.from_toml(_scene_file(tmp_path)), path=tmp_path / "run.nc")


def test_a_full_disk_at_the_first_part_leaves_no_half_made_file(tmp_path, monkeypatch):
    def full(*args: Any, **kwargs: Any) -> None:
        Path(args[1] if len(args) > 1 else kwargs["path"]).write_bytes(b"\x89HDF")  # a half-made file
        raise RuntimeError("NetCDF: HDF error")

    monkeypatch.setattr(xr.Dataset, "to_netcdf", lambda self, *a, **k: full(self, *a, **k))
    monkeypatch.setattr(netcdf.shutil, "disk_usage", lambda path: Usage(10**9, 10**9, 0))
    writer = AppendingWriter(tmp_path / "run.nc", 10)
    part = xr.Dataset({"x": ("time", [1.0, 2.0])}, coords={"time": [0.0, 1.0]})
    with pytest.raises(WriteFailed, match=r"the disk is full .*; nothing of the run was kept \(the half-made partial"):
        writer.append(part, "partial")
    assert not (tmp_path / "run.partial.nc").exists()
    assert writer.stop("stopped") is None


def test_a_full_disk_in_a_whole_file_write_keeps_the_previous_file(tmp_path, monkeypatch):
    target = tmp_path / "r.nc"
    target.write_bytes(b"previous")

    def full(self: xr.Dataset, *args: Any, **kwargs: Any) -> None:
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(xr.Dataset, "to_netcdf", full)
    with pytest.raises(WriteFailed, match=rf"writing '{target}' failed: the disk is full .*previous file there is"):
        write_netcdf(xr.Dataset({"x": ("t", [1.0])}), target)
    assert target.read_bytes() == b"previous"
    assert [p.name for p in tmp_path.iterdir()] == ["r.nc"]  # no temporary left


def test_the_exit_statuses_are_in_the_commands_help():
    for parser in (build_parser(), build_parser()._subparsers._group_actions[0].choices["run"]):  # type: ignore[union-attr]
        text = " ".join(parser.format_help().split())
        assert "3 a diverged run" in text and "4 an output file could not be written (a full disk)" in text
