"""BEMIO / WEC-Sim ``.h5`` reader.

The shared reference data hold no BEMIO file, so these tests write small ones in the published layout (WEC-Sim's
``writeBEMIOH5`` as h5py reads it, and the old Python bemio variant) from the RM3 WAMIT values, then check that
the reader recovers those values. They check the layout mapping (array orientation, normalisation by rho, rho
omega and rho g, degrees, string depth, body properties), not independent numbers.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import xarray as xr

from wecss.hydro import read_bemio, read_wamit
from wecss.hydro.readers.bemio import BemioFormatError

RM3 = Path(__file__).resolve().parents[3] / "shared" / "data" / "wamit" / "rm3" / "rm3.out"
COMPARED = (
    "added_mass",
    "radiation_damping",
    "added_mass_inf",
    "excitation",
    "hydrostatic_stiffness",
    "mass",
    "inertia",
    "center_of_mass",
    "center_of_buoyancy",
    "displaced_volume",
    "reference_point",
)


@pytest.fixture(scope="module")
def h5py() -> Any:
    return pytest.importorskip("h5py")


@pytest.fixture(scope="module")
def rm3() -> xr.Dataset:
    """Every 13th frequency of the RM3 WAMIT run (20 of 260), as the values to write."""
    if not RM3.is_file():
        pytest.skip(f"reference data not found: {RM3}")
    return read_wamit(RM3, body_names=["float", "spar"]).isel(omega=slice(None, None, 13))


def write_bemio(h5py: Any, path: Path, ds: xr.Dataset, *, scaled: bool = False, matlab: bool = True) -> Path:
    """Write ``ds`` as a BEMIO file: WEC-Sim MATLAB layout (``matlab``) or the old Python bemio one.

    Frequencies are written in WAMIT's order (increasing period), values normalised unless ``scaled``.
    """
    rho, g = ds.attrs["rho"], ds.attrs["g"]
    ds = ds.isel(omega=slice(None, None, -1))
    omega = ds.omega.values
    added = np.transpose(ds.added_mass.values, (1, 2, 0))  # (row, column, frequency)
    damping = np.transpose(ds.radiation_damping.values, (1, 2, 0))
    a_inf = ds.added_mass_inf.values
    stiffness = ds.hydrostatic_stiffness.values
    exc = np.transpose(ds.excitation.values, (2, 1, 0))  # (dof, heading, frequency)
    if not scaled:
        added, a_inf, damping = added / rho, a_inf / rho, damping / (rho * omega)
        stiffness, exc = stiffness / (rho * g), exc / (rho * g)

    def vector(x: Any) -> np.ndarray:  # MATLAB's h5write gives (n, 1)
        x = np.atleast_1d(np.asarray(x, dtype=float))
        return x[:, None] if matlab else x

    def scalar(x: float) -> Any:
        return np.array([[x]]) if matlab else x

    with h5py.File(path, "w") as f:
        f["simulation_parameters/rho"] = scalar(rho)
        f["simulation_parameters/g"] = scalar(g)
        f["simulation_parameters/w"] = vector(omega)
        f["simulation_parameters/T"] = vector(2 * np.pi / omega)
        f["simulation_parameters/wave_dir"] = vector(np.rad2deg(ds.wave_direction.values))
        f["simulation_parameters/water_depth"] = np.bytes_(b"infinite") if matlab else "infinite"
        f["simulation_parameters/scaled"] = scalar(float(scaled))
        f["bem_data/code"] = np.bytes_(b"WAMIT")
        for b, name in enumerate(ds.body.values):
            rows = slice(6 * b, 6 * b + 6)
            body = f"body{b + 1}"
            f[f"{body}/properties/name"] = np.bytes_(name.encode()) if matlab else name
            f[f"{body}/properties/body_number"] = scalar(b + 1)
            f[f"{body}/properties/cg"] = vector(ds.reference_point.values[b])
            f[f"{body}/properties/cb"] = vector(ds.center_of_buoyancy.values[b])
            f[f"{body}/properties/disp_vol"] = scalar(float(ds.displaced_volume.values[b]))
            if matlab:
                f[f"{body}/properties/dof"] = scalar(6)
                f[f"{body}/properties/dof_start"] = scalar(6 * b + 1)
                f[f"{body}/properties/dof_end"] = scalar(6 * b + 6)
            coeffs = f"{body}/hydro_coeffs"
            f[f"{coeffs}/linear_restoring_stiffness"] = stiffness[rows, rows]
            f[f"{coeffs}/added_mass/all"] = added[rows]
            f[f"{coeffs}/added_mass/inf_freq"] = a_inf[rows]
            f[f"{coeffs}/radiation_damping/all"] = damping[rows]
            f[f"{coeffs}/excitation/re"] = exc[rows].real
            f[f"{coeffs}/excitation/im"] = exc[rows].imag
            f[f"{coeffs}/excitation/scattering/re"] = np.full(exc[rows].shape, np.nan)  # WEC-Sim's "not read"
            f[f"{coeffs}/excitation/scattering/im"] = np.full(exc[rows].shape, np.nan)
    return path


def _assert_recovers(ds: xr.Dataset, ref: xr.Dataset) -> None:
    for name in COMPARED:
        xr.testing.assert_allclose(ds[name], ref[name], rtol=1e-12)
    for name in ("omega", "wave_direction"):
        np.testing.assert_allclose(ds[name].values, ref[name].values, rtol=1e-12)
    assert list(ds.radiating_dof.values) == list(ref.radiating_dof.values)
    assert (ds.attrs["rho"], ds.attrs["g"], ds.attrs["water_depth"]) == (1000.0, 9.81, np.inf)


def test_matlab_layout_is_recovered(h5py: Any, rm3: xr.Dataset, tmp_path: Path) -> None:
    ds = read_bemio(write_bemio(h5py, tmp_path / "rm3.h5", rm3))
    _assert_recovers(ds, rm3)
    assert "added_mass_zero" not in ds and "diffraction" not in ds  # NaN scattering placeholder dropped
    assert ds.attrs["bemio_scaled"] == 0 and ds.attrs["bemio_code"] == "WAMIT"
    assert ds.attrs["source"] == "BEMIO h5 rm3.h5 (WAMIT)"
    assert ds.attrs["inertia_unknown_bodies"] == "float, spar"


def test_python_bemio_layout_and_scaled_data(h5py: Any, rm3: xr.Dataset, tmp_path: Path) -> None:
    path = write_bemio(h5py, tmp_path / "rm3.h5", rm3, scaled=True, matlab=False)
    _assert_recovers(read_bemio(path), rm3)
    with pytest.raises(ValueError, match=r"holds dimensional data \(scaled = 1\) made with rho = 1000; got rho = 1025"):
        read_bemio(path, rho=1025.0)


def test_normalised_data_take_the_given_rho(h5py: Any, rm3: xr.Dataset, tmp_path: Path) -> None:
    ds = read_bemio(write_bemio(h5py, tmp_path / "rm3.h5", rm3), rho=1025.0, body_names=["a", "b"])
    assert ds.attrs["rho"] == 1025.0
    assert list(ds.body.values) == ["a", "b"]
    np.testing.assert_allclose(ds.added_mass.values, rm3.added_mass.values * 1.025, rtol=1e-12)
    np.testing.assert_allclose(ds.radiation_damping.values, rm3.radiation_damping.values * 1.025, rtol=1e-12)
    np.testing.assert_allclose(ds.excitation.values, rm3.excitation.values * 1.025, rtol=1e-12)


def test_scattering_and_froude_krylov_are_kept(h5py: Any, rm3: xr.Dataset, tmp_path: Path) -> None:
    path = write_bemio(h5py, tmp_path / "rm3.h5", rm3)
    with h5py.File(path, "a") as f:
        for body in ("body1", "body2"):
            group = f[f"{body}/hydro_coeffs/excitation"]
            for part, factor in (("scattering", 0.25), ("froude-krylov", 0.75)):
                for comp in ("re", "im"):
                    if f"{part}/{comp}" in group:
                        del group[f"{part}/{comp}"]
                    group[f"{part}/{comp}"] = factor * group[comp][()]
    ds = read_bemio(path)
    np.testing.assert_allclose(ds.diffraction.values, 0.25 * ds.excitation.values, rtol=1e-12)
    np.testing.assert_allclose(ds.froude_krylov.values, 0.75 * ds.excitation.values, rtol=1e-12)


def test_shape_errors_name_the_dataset(h5py: Any, rm3: xr.Dataset, tmp_path: Path) -> None:
    path = write_bemio(h5py, tmp_path / "rm3.h5", rm3)
    with h5py.File(path, "a") as f:
        key = "body2/hydro_coeffs/added_mass/all"
        values = f[key][()]
        del f[key]
        f[key] = np.transpose(values, (2, 1, 0))
    with pytest.raises(
        BemioFormatError, match=r"/body2/hydro_coeffs/added_mass/all has shape \(20, 12, 6\); expected \(6, 12, 20\)"
    ):
        read_bemio(path)


def test_wrong_dof_counts_and_missing_data_are_errors(h5py: Any, rm3: xr.Dataset, tmp_path: Path) -> None:
    path = write_bemio(h5py, tmp_path / "rm3.h5", rm3)
    with h5py.File(path, "a") as f:
        del f["body1/properties/dof"]
        f["body1/properties/dof"] = np.array([[8.0]])
    with pytest.raises(BemioFormatError, match=r"/body1/hydro_coeffs/linear_restoring_stiffness has shape \(6, 6\); "
                       r"expected \(8, 8\)"):  # fmt: skip
        read_bemio(path)
    path = write_bemio(h5py, tmp_path / "rm3.h5", rm3)
    with h5py.File(path, "a") as f:
        del f["body2/hydro_coeffs/radiation_damping/all"]
    with pytest.raises(BemioFormatError, match=r"missing dataset /body2/hydro_coeffs/radiation_damping/all"):
        read_bemio(path)


def test_file_and_argument_errors(h5py: Any, rm3: xr.Dataset, tmp_path: Path) -> None:
    with pytest.raises(FileNotFoundError, match=r"no BEMIO \.h5 file at .*absent\.h5"):
        read_bemio(tmp_path / "absent.h5")
    path = write_bemio(h5py, tmp_path / "rm3.h5", rm3)
    with pytest.raises(ValueError, match=r"body_names has 1 names \['x'\]; rm3\.h5 has 2 bodies \['float', 'spar'\]"):
        read_bemio(path, body_names=["x"])
    with pytest.raises(ValueError, match="body names must be distinct"):
        read_bemio(path, body_names=["x", "x"])


def test_missing_h5py_gives_the_install_hint(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    monkeypatch.setitem(sys.modules, "h5py", None)  # makes ``import h5py`` raise ImportError
    with pytest.raises(ImportError, match=r'pip install "wecss\[h5\]"'):
        read_bemio(tmp_path / "any.h5")


@pytest.mark.parametrize("kind", ["truncated", "empty", "random"])
def test_a_truncated_or_damaged_h5_file_is_named_with_what_is_wrong(h5py: Any, tmp_path: Path, kind: str) -> None:
    """HDF5's own OSError named no file; the reader's error names it and says what is wrong."""
    whole = tmp_path / "whole.h5"
    with h5py.File(whole, "w") as f:
        f["simulation_parameters/w"] = np.linspace(0.1, 3.0, 5000)
    data = whole.read_bytes()
    path = tmp_path / f"{kind}.h5"
    content = {"truncated": data[: len(data) // 2], "empty": b"", "random": np.random.default_rng(1).bytes(5000)}
    path.write_bytes(content[kind])
    what = {
        "truncated": rf"truncated or damaged: {len(data) // 2} bytes, the file's header says more",
        "empty": "the file is empty",
        "random": r"not an HDF5 file \(no HDF5 signature\)",
    }[kind]
    with pytest.raises(BemioFormatError, match=rf"cannot read the BEMIO \.h5 file '{path}': {what} \(HDF5: "):
        read_bemio(path)
