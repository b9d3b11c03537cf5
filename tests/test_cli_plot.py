"""``wecss plot``: a sweep's combined dataset or folder, ``--animate`` of a result's bodies, and the refusals."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from wecss.cli import main
from wecss.results import open_result, save


def _scene(tmp_path, variables: str) -> str:  # type: ignore[no-untyped-def]
    path = tmp_path / "s.toml"
    path.write_text(
        '[device]\nname = "m4-111"\n[sea]\nkind = "regular"\nheight = 0.04\nperiod = 1.2\nduration = "2 Tp"\n'
        f'ramp = "1 Tp"\n[outputs]\nvariables = {variables}\n'
    )
    return str(path)


def test_animate_a_run_and_refuse_what_cannot_be_animated(tmp_path, capsys: pytest.CaptureFixture[str]) -> None:
    from PIL import Image

    result = tmp_path / "r.nc"
    assert main(["run", _scene(tmp_path, '["pto", "elevation", "poses"]'), "-o", str(result), "-q"]) == 0
    steps = open_result(result).sizes["time"]
    movie = tmp_path / "bodies.gif"
    assert main(["plot", str(result), "--animate", "-o", str(movie), "--stride", "100", "--fps", "5"]) == 0
    with Image.open(movie) as gif:
        assert gif.n_frames == len(range(0, steps, 100))
    assert f"wrote {movie} ({len(range(0, steps, 100))} frames, every 100 saved steps)" in capsys.readouterr().out

    no_poses = tmp_path / "no_poses.nc"
    save(open_result(result).drop_vars(["body_position", "body_rotation"]), no_poses)
    cases = [
        (["plot", str(no_poses), "--animate"], "no body poses (body_position, body_rotation missing)"),
        (["plot", str(result), "--fps", "5"], "--fps set the animation: give --animate too"),
        (["plot", str(result), "--animate", "--stride", "0"], "stride must be a whole number of saved steps >= 1"),
        (["plot", str(result), "--animate", "-o", str(tmp_path / "b.avi")], "must end in .gif or .mp4"),
        (["plot", str(result), "--variable", "cwr"], "is no sweep"),
    ]
    for argv, message in cases:
        assert main(argv) == 2
        assert message in capsys.readouterr().err
    assert not (tmp_path / "no_poses.gif").exists()


def _combined_folder(tmp_path):  # type: ignore[no-untyped-def]
    folder = tmp_path / "sweep"
    folder.mkdir()
    axes = ("sea.height", "sea.period")
    power = np.array([[0.25, np.nan], [1.0, 2.0]])
    ds = xr.Dataset(
        {
            "total_power": (axes, power, {"units": "W"}),
            "mean_pto_power": ((*axes, "pto"), np.stack([power, power / 2], axis=-1), {"units": "W"}),
            "status": (axes, np.array([["done", "failed"], ["done", "done"]])),
        },
        coords={"sea.height": [0.02, 0.04], "sea.period": [1.0, 1.2], "pto": ["pto_1", "pto_2"]},
        attrs={"title": "wecss sweep tiny", "sweep_mode": "grid"},
    )
    save(ds, folder / "combined.nc")
    return folder


def test_plot_a_sweep_from_its_folder_or_combined_file(tmp_path, capsys: pytest.CaptureFixture[str]) -> None:
    folder = _combined_folder(tmp_path)
    assert main(["plot", str(folder)]) == 0
    assert (folder / "combined.png").is_file()
    picture = tmp_path / "pto.png"
    argv = ["plot", str(folder / "combined.nc"), "--variable", "mean_pto_power", "--select", "pto=pto_2"]
    assert main([*argv, "-o", str(picture)]) == 0
    assert picture.is_file()
    capsys.readouterr()
    cases = [
        (["plot", str(folder), "--variable", "mean_pto_power"], "give select={dim: value}"),
        (["plot", str(folder), "--select", "pto"], "--select takes DIM=VALUE"),
        (["plot", str(folder), "--animate"], "is a sweep's combined dataset: animate one of its case files"),
        (["plot", str(tmp_path)], "has no combined.nc"),
    ]
    for argv, message in cases:
        assert main(argv) == 2
        assert message in capsys.readouterr().err
