"""The shipped hydrodynamic databases (wecss/data/hydro/<name>.nc): they load, validate and make physical sense.

A database whose .nc file is not there yet is skipped. Regenerate with ``python studies/generate_hydro.py``.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import wecss.hydro
from wecss.hydro import HydroData
from wecss.hydro._catalogue import DATA_DIR
from wecss.hydro.bem import BEMSpec, read_geometry

NAMES = ("m4-111", "m4-132", "m4-134", "notc-10kw")

# Lande-Sudall et al., Table 1: float masses [kg] by float number.
M4_MASS = {1: 2.345, 2: 5.312, 4: 5.312, 5: 5.312, 3: 17.520, 6: 17.520, 7: 17.520, 8: 17.520}
M4_FLOATS = {"m4-111": (1, 2, 3), "m4-132": (1, 2, 3, 4, 5, 6), "m4-134": (1, 2, 3, 4, 5, 6, 7, 8)}

MASS_RTOL = 1e-3
WATERPLANE_RTOL = 5e-3
DAMPING_TAIL = 0.01
"""Heave damping at the highest frequency must be below this fraction of its peak."""


@pytest.fixture(scope="module", params=NAMES)
def shipped(request: pytest.FixtureRequest) -> tuple[str, HydroData, BEMSpec]:
    name = request.param
    if not (DATA_DIR / f"{name}.nc").is_file():
        pytest.skip(f"{name}.nc not generated yet (python studies/generate_hydro.py {name})")
    return name, wecss.hydro.load(name), read_geometry(DATA_DIR / f"{name}.toml")


def test_loads_and_validates(shipped: tuple[str, HydroData, BEMSpec]) -> None:
    name, hydro, spec = shipped
    assert name in wecss.hydro.available()
    assert hydro.bodies == [b.name for b in spec.bodies]
    assert hydro.dofs == spec.dofs
    assert math.isinf(hydro.water_depth) and hydro.rho == 1000.0 and hydro.g == 9.81
    # validation ran in load(); warnings are errors in this suite, so no irregular-frequency artefacts either
    wecss.hydro.validate(hydro.dataset)


def test_made_from_the_current_geometry_file(shipped: tuple[str, HydroData, BEMSpec], tmp_path: Path) -> None:
    name, hydro, spec = shipped
    stored = tmp_path / f"{name}.toml"
    stored.write_text(hydro.dataset.attrs["geometry_file_text"], encoding="utf-8")
    assert read_geometry(stored) == spec, f"{name}.toml changed since {name}.nc was made: regenerate it"
    np.testing.assert_allclose(hydro.omega, spec.omega)


def test_damping_diagonal_is_not_negative(shipped: tuple[str, HydroData, BEMSpec]) -> None:
    _, hydro, _ = shipped
    diag = np.diagonal(hydro.dataset.radiation_damping.values, axis1=1, axis2=2)
    assert np.all(diag >= 0), f"negative damping at {hydro.dofs[int(np.argmin(diag.min(axis=0)))]}"


def test_infinite_frequency_added_mass_is_positive_definite(shipped: tuple[str, HydroData, BEMSpec]) -> None:
    _, hydro, _ = shipped
    a_inf = hydro.dataset.added_mass_inf.values
    np.testing.assert_array_equal(a_inf, a_inf.T)
    assert np.linalg.eigvalsh(a_inf).min() > 0


def test_heave_stiffness_is_rho_g_waterplane_area(shipped: tuple[str, HydroData, BEMSpec]) -> None:
    _, hydro, spec = shipped
    ds = hydro.dataset
    for body in spec.bodies:
        dof = f"{body.name}__Heave"
        k = ds.hydrostatic_stiffness.sel(influenced_dof=dof, radiating_dof=dof).item()
        assert k == pytest.approx(hydro.rho * hydro.g * np.pi * body.profile.radius**2, rel=WATERPLANE_RTOL)


def test_masses(shipped: tuple[str, HydroData, BEMSpec]) -> None:
    name, hydro, _ = shipped
    mass = dict(zip(hydro.bodies, hydro.dataset.mass.values, strict=True))
    if name in M4_FLOATS:
        expected = {f"float_{k}": M4_MASS[k] for k in M4_FLOATS[name]}
    else:  # NOTC floater: rho times a 1.52 m cylinder 0.2 m deep above a 0.6 m cone
        expected = {"floater": 1000.0 * np.pi * 0.76**2 * (0.2 + 0.6 / 3)}
    assert set(mass) == set(expected)
    for body, value in expected.items():
        assert mass[body] == pytest.approx(value, rel=MASS_RTOL), body
    # every float floats in its own equilibrium
    np.testing.assert_allclose(
        hydro.dataset.displaced_volume.values * hydro.rho, hydro.dataset.mass.values, rtol=MASS_RTOL
    )


def test_reference_points_at_centres_of_mass(shipped: tuple[str, HydroData, BEMSpec]) -> None:
    _, hydro, spec = shipped
    ds = hydro.dataset
    np.testing.assert_allclose(ds.reference_point.values, ds.center_of_mass.values, atol=1e-12)
    np.testing.assert_allclose(ds.center_of_mass.values, [b.center_of_mass for b in spec.bodies], atol=1e-12)


def test_frequencies_reach_the_heave_damping_tail(shipped: tuple[str, HydroData, BEMSpec]) -> None:
    """Heave damping at the highest frequency is below 1 % of its peak for every body.

    Surge and pitch damping of these wall-sided floats decay only as a power of omega (10-40 % of their peak at the
    M4 files' 22 rad/s, where the meshes run out of resolution); the radiation kernels need a fitted tail there.
    """
    _, hydro, spec = shipped
    ds = hydro.dataset
    for body in spec.bodies:
        dof = f"{body.name}__Heave"
        damping = ds.radiation_damping.sel(influenced_dof=dof, radiating_dof=dof).values
        assert damping[-1] < DAMPING_TAIL * damping.max(), f"{dof}: {damping[-1] / damping.max():.3%} of its peak"


def test_long_names_and_units_are_on_disk(shipped: tuple[str, HydroData, BEMSpec]) -> None:
    """Read with netCDF4 alone (no wecss): every variable the attribute table gives units has them in the file."""
    import netCDF4

    from wecss.attributes import VARIABLE_ATTRS

    name, _, _ = shipped
    missing = []
    with netCDF4.Dataset(DATA_DIR / f"{name}.nc") as nc:
        for variable in nc.variables.values():
            expected = VARIABLE_ATTRS.get(variable.name, {})
            for key, value in expected.items():
                if key in ("long_name", "units") and getattr(variable, key, None) != value:
                    missing.append(f"{variable.name}.{key}")
    assert missing == []


def test_files_are_small(shipped: tuple[str, HydroData, BEMSpec]) -> None:
    name, _, _ = shipped
    assert (DATA_DIR / f"{name}.nc").stat().st_size < 5e6


DOCS_RANGES = {"M4 (paper 000": ("m4-111", "m4-132", "m4-134"), "NOTC 10 kW floater": ("notc-10kw",)}


@pytest.mark.parametrize("heading", sorted(DOCS_RANGES))
def test_docs_state_the_frequency_ranges_the_shipped_files_have(heading):
    """docs/hydro.md's "a to b rad/s every c rad/s" for each shipped database is what the file holds (issue 18: the
    page said 0.1-25 and 0.05-20 rad/s for files of 0.1-22 and 0.05-12)."""
    import re

    text = (Path(__file__).resolve().parents[2] / "docs" / "hydro.md").read_text()
    bullet = text[text.index(f"- {heading}") :].split("\n- ")[0].replace("\n", " ")
    found = re.search(r"([0-9.]+) to ([0-9.]+) rad/s\s+every ([0-9.]+) rad/s", bullet)
    assert found, f"no frequency range stated for {heading}"
    low, high, step = (float(x) for x in found.groups())
    for name in DOCS_RANGES[heading]:
        path = DATA_DIR / f"{name}.nc"
        if not path.exists():
            pytest.skip(f"{path} not generated")
        omega = HydroData.from_netcdf(path).omega
        assert omega[0] == pytest.approx(low) and omega[-1] == pytest.approx(high)
        assert np.allclose(np.diff(omega), step)
