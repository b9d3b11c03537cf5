"""Truncated or corrupt netCDF files (databases and results) in ``wecss info``, ``wecss plot`` and
``Device.hydro``: an error naming the file and saying what is wrong, no traceback at the command line; a wecss
database that fails validation reports its own validation error."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from wecss.cli import main
from wecss.devices import Device
from wecss.hydro import DATA_DIR, HydroData, HydroDataError
from wecss.netcdf import NetCDFFileError, read_netcdf, write_netcdf
from wecss.sim import Scene, simulate

DATABASE = Path(DATA_DIR) / "m4-111.nc"
FLOAT = Path(__file__).parent / "control" / "heaving_float.toml"


def _damaged(folder: Path, source: Path, kind: str) -> tuple[Path, str]:
    """A damaged copy of ``source`` and the phrase its error must hold."""
    path = folder / f"{kind}.nc"
    data = source.read_bytes()
    if kind == "truncated":
        path.write_bytes(data[: len(data) // 2])
        return path, "truncated or damaged"
    if kind == "header-only":
        path.write_bytes(data[:2000])
        return path, "truncated or damaged"
    if kind == "random":
        path.write_bytes(np.random.default_rng(1).bytes(5000))
        return path, "not a netCDF file"
    path.write_bytes(b"")
    return path, "the file is empty"


KINDS = ["truncated", "header-only", "random", "empty"]


@pytest.fixture(scope="module")
def result_file(tmp_path_factory: pytest.TempPathFactory) -> Path:
    scene = Scene.from_dict(
        {
            "device": {"name": "m4-111"},
            "sea": {"kind": "regular", "height": 0.02, "period": 1.2, "duration": 3.0, "ramp": 1.0},
            "outputs": {"variables": ["pto"]},
        }
    )
    path = tmp_path_factory.mktemp("result") / "r.nc"
    write_netcdf(simulate(scene), path)
    return path


@pytest.mark.parametrize("kind", KINDS)
def test_a_damaged_database_is_named_with_what_is_wrong(tmp_path, kind, capsys):
    path, phrase = _damaged(tmp_path, DATABASE, kind)
    with pytest.raises(NetCDFFileError, match=rf"cannot read '{path}': .*{phrase}"):
        read_netcdf(path)
    with pytest.raises(NetCDFFileError, match=phrase):
        HydroData.from_netcdf(path)
    spec = FLOAT.read_text().replace('hydro = "m4-111"', f'hydro = "{path}"')
    (tmp_path / "float.toml").write_text(spec)
    with pytest.raises(NetCDFFileError, match=rf"'{path}': .*{phrase}"):
        Device.from_spec(tmp_path / "float.toml").hydro()
    assert main(["info", str(path)]) == 2
    err = capsys.readouterr().err
    assert str(path) in err and phrase in err and "Traceback" not in err


@pytest.mark.parametrize("kind", KINDS)
def test_a_damaged_result_is_named_in_info_and_plot(tmp_path, kind, result_file, capsys):
    path, phrase = _damaged(tmp_path, result_file, kind)
    for argv in (["info", str(path)], ["plot", str(path), "-o", str(tmp_path / "p.png")]):
        assert main(argv) == 2
        err = capsys.readouterr().err
        assert err.startswith("wecss: error: ") and str(path) in err and phrase in err
    assert not (tmp_path / "p.png").exists()


def test_plot_of_a_database_says_it_is_no_result(tmp_path, capsys):
    assert main(["plot", str(DATABASE), "-o", str(tmp_path / "p.png")]) == 2
    assert "is not a wecss result" in capsys.readouterr().err


def test_an_invalid_wecss_database_reports_its_own_validation_error(tmp_path):
    """A wecss database with negative volumes fails its schema's validation; the device must not fall back to the
    Capytaine reader (whose complaint would be a missing 'rho' variable)."""
    ds = read_netcdf(DATABASE)
    ds["displaced_volume"] = -ds.displaced_volume
    path = tmp_path / "bad.nc"
    write_netcdf(ds, path)
    spec = FLOAT.read_text().replace('hydro = "m4-111"', f'hydro = "{path}"')
    (tmp_path / "float.toml").write_text(spec)
    with pytest.raises(HydroDataError, match=r"not a valid wecss hydrodynamic database: .*displaced_volume") as info:
        Device.from_spec(tmp_path / "float.toml").hydro()
    assert "rho" not in str(info.value)
