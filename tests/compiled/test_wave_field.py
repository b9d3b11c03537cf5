"""The incident wave field at points (wecss.compiled._wave_field): direct sums against an independent numpy
evaluation, Wheeler stretching on the free surface, the table against direct sums, the ramp."""

from __future__ import annotations

import math

import numpy as np
import pytest

from wecss.compiled._wave_field import (
    CALM,
    DIRECT,
    OUTSIDE_TABLE,
    TABLE,
    calm_field,
    field_arrays,
    field_refresh,
    field_update,
    field_values,
    table_size,
)
from wecss.waves import Jonswap, Ramp, WaveComponents, irregular, wavenumber

RHO, G = 1000.0, 9.81
REGION = np.array([[[-12.0, -6.0, -9.0], [8.0, 6.0, 3.0]]])
ROUND_OFF = 1e-13  # of rho g sigma


def _sea(direction: float = 0.0) -> WaveComponents:
    """About 100 components of a JONSWAP sea (Hs 2 m, Tp 8 s)."""
    sea = irregular(Jonswap(hs=2.0, tp=8.0), d_omega=0.02, omega_min=0.3, omega_max=2.3, seed=3, energy_threshold=0)
    return WaveComponents(sea.omega, sea.amplitude, direction)


def _points(n: int = 2000, seed: int = 1) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    lo, hi = REGION[0]
    return rng.uniform(lo[0], hi[0], n), rng.uniform(lo[1], hi[1], n), rng.uniform(lo[2], hi[2], n)


def _reference(sea: WaveComponents, depth: float, x, y, z, t: float, ramp: float = 0.0):
    """Elevation and Wheeler-stretched pressure, in numpy from the module docstring's formulas."""
    k = wavenumber(sea.omega, depth, G)
    xp = x * math.cos(sea.direction) + y * math.sin(sea.direction)
    r = float(Ramp(ramp)(np.array(t)))
    phase = r * sea.amplitude[None, :] * np.exp(1j * (sea.omega[None, :] * t - k[None, :] * xp[:, None]))
    eta = phase.real.sum(axis=1)
    zs = (z - eta) if math.isinf(depth) else (z - eta) * depth / (depth + eta)
    if math.isinf(depth):
        profile = np.exp(k[None, :] * zs[:, None])
    else:
        profile = np.cosh(k[None, :] * (zs[:, None] + depth)) / np.cosh(k[None, :] * depth)
    pressure = np.where(z <= eta, RHO * G * (phase.real * profile).sum(axis=1), 0.0)
    return eta, pressure


@pytest.mark.parametrize("depth", [math.inf, 30.0])
def test_direct_sums_against_numpy(depth: float) -> None:
    sea = WaveComponents([0.6, 0.9, 1.3], [0.5, 0.3j, -0.2 + 0.1j], 0.4)
    field = field_arrays(sea, depth=depth, rho=RHO, g=G)
    assert field.kind == DIRECT
    x, y, z = _points(500)
    sigma = math.sqrt(sea.variance)
    for t in (0.0, 3.3, 17.0):
        eta, pressure = _reference(sea, depth, x, y, z, t)
        values = field_values(field, x, y, z, t)
        np.testing.assert_allclose(values[0], eta, rtol=0, atol=ROUND_OFF * sigma * 10)
        np.testing.assert_allclose(values[1], pressure, rtol=0, atol=ROUND_OFF * RHO * G * sigma * 10)


@pytest.mark.parametrize("depth", [math.inf, 30.0])
@pytest.mark.parametrize("method", ["direct", "table"])
def test_wheeler_total_pressure_vanishes_on_the_free_surface(depth: float, method: str) -> None:
    """On z = eta(x, y, t) the incident pressure is rho g eta, so the total pressure -rho g z + p is zero (to
    round-off: 1e-13 of rho g sigma)."""
    sea = _sea(0.6)
    field = field_arrays(sea, depth=depth, rho=RHO, g=G, regions=REGION, method=method)
    x, y, _ = _points()
    sigma = math.sqrt(sea.variance)
    for t in (0.0, 13.7, 101.3):
        eta = field_values(field, x, y, np.zeros_like(x), t)[0]
        pressure = field_values(field, x, y, eta, t)[1]
        assert np.max(np.abs(pressure - RHO * G * eta)) <= ROUND_OFF * RHO * G * sigma
    assert field.status[0] == 0


@pytest.mark.parametrize("depth", [math.inf, 30.0])
@pytest.mark.parametrize("tolerance", [1e-3, 1e-4, 1e-6])
def test_table_against_direct_sums(depth: float, tolerance: float) -> None:
    """About 100 JONSWAP components, points spread over the region: elevation and pressure head of the table
    within its stated tolerance (a share of the sea's standard deviation) of the direct sums (measured: 0.16 to
    0.24 of it)."""
    sea = _sea(0.6)
    assert sea.omega.size >= 100
    table = field_arrays(sea, depth=depth, rho=RHO, g=G, regions=REGION, tolerance=tolerance)
    direct = field_arrays(sea, depth=depth, rho=RHO, g=G, method="direct")
    assert table.kind == TABLE
    x, y, z = _points()
    sigma = math.sqrt(sea.variance)
    for t in (0.0, 13.7, 55.5, 101.3):
        got, want = field_values(table, x, y, z, t), field_values(direct, x, y, z, t)
        assert np.max(np.abs(got[0] - want[0])) <= tolerance * sigma
        assert np.max(np.abs(got[1] - want[1])) <= tolerance * RHO * G * sigma
    assert table.status[0] == 0


def test_a_step_refreshes_the_nodes_under_its_points_only() -> None:
    """``field_refresh`` over an x' range brings the active nodes of the cells holding it to the new time (and no
    others), with the values of a whole refresh (to the rounding of the phasor at a run's first node); a second
    range at the same time refreshes only the nodes not yet at it."""
    sea = _sea()
    ranged = field_arrays(sea, rho=RHO, g=G, regions=REGION)
    whole = field_arrays(sea, rho=RHO, g=G, regions=REGION)
    t = 21.4
    field_update(whole, t)
    assert np.all(whole.node_time[whole.active == 1] == t)
    nodes = ranged.x_start + ranged.x_step * np.arange(ranged.active.size)
    field_refresh(ranged, t, -3.0, 2.0)
    fresh = ranged.node_time == t
    cells = (nodes >= -3.0 - ranged.x_step) & (nodes <= 2.0 + ranged.x_step) & (ranged.active == 1)
    np.testing.assert_array_equal(fresh, cells)  # the nodes of the cells [i, i + 1] that hold -3 <= x' <= 2
    assert np.all(np.isnan(ranged.node_time[~fresh]))
    sigma = math.sqrt(sea.variance)
    for name in ("elevation", "head"):
        got, want = getattr(ranged, name)[fresh], getattr(whole, name)[fresh]
        assert np.max(np.abs(got - want)) <= 1e-12 * sigma  # (the recurrence along x' over thousands of nodes)
    before = ranged.head.copy()
    field_refresh(ranged, t, 1.0, 4.0)
    again = ranged.node_time == t
    assert np.all(again[fresh]) and again.sum() > fresh.sum()
    np.testing.assert_array_equal(ranged.head[fresh], before[fresh])  # the nodes already at t are not redone
    field_refresh(ranged, t + 0.5, math.nan, math.nan)  # a NaN range refreshes nothing (a diverged body)
    assert not np.any(ranged.node_time == t + 0.5)


def test_the_table_reaches_far_beyond_the_regions_along_x() -> None:
    """A body that drifts out of the region it was given stays in the table: along x' the table holds about
    TABLE_NODE_BUDGET nodes, every one active (only those under the bodies are computed)."""
    from wecss.compiled._wave_field import TABLE_NODE_BUDGET

    table = field_arrays(_sea(), rho=RHO, g=G, regions=REGION)
    n_x, n_z = table_size(table)
    assert n_x == table.active.size and TABLE_NODE_BUDGET - 2 * n_z <= n_x * n_z <= TABLE_NODE_BUDGET
    width = REGION[0, 1, 0] - REGION[0, 0, 0]
    assert table.x_start < REGION[0, 0, 0] - 10 * width
    assert table.x_start + table.x_step * (n_x - 1) > REGION[0, 1, 0] + 10 * width


def test_points_outside_the_table_fall_back_to_direct_sums() -> None:
    sea = _sea()
    table = field_arrays(sea, rho=RHO, g=G, regions=REGION)
    direct = field_arrays(sea, rho=RHO, g=G, method="direct")
    inside = field_values(table, np.array([0.0]), np.array([0.0]), np.array([-1.0]), 3.0)
    assert table.status[0] == 0
    # off the x' nodes (after and before; the table reaches far beyond the region), and below its lowest z'
    x, y, z = np.array([1e5, -4e4, 0.0]), np.zeros(3), np.array([-1.0, -1.0, -30.0])
    got, want = field_values(table, x, y, z, 3.0), field_values(direct, x, y, z, 3.0)
    assert table.status[0] == OUTSIDE_TABLE
    np.testing.assert_array_equal(got[:, :2], want[:, :2])
    assert got[1, 2] == want[1, 2] or abs(got[1, 2] - want[1, 2]) <= 1e-4 * RHO * G * math.sqrt(sea.variance)
    assert inside.shape == (2, 1)


def test_method_choice_and_validation() -> None:
    assert field_arrays(None).kind == CALM
    assert calm_field().kind == CALM
    np.testing.assert_array_equal(field_values(calm_field(), np.zeros(2), np.zeros(2), np.array([-1.0, 1.0]), 1.0), 0)
    regular = WaveComponents([1.0], [0.5])
    assert field_arrays(regular).kind == DIRECT
    assert field_arrays(regular, regions=REGION, method="table").kind == TABLE
    assert table_size(field_arrays(regular)) == (0, 0)
    with pytest.raises(ValueError, match="needs the regions"):
        field_arrays(_sea())
    with pytest.raises(ValueError, match="method must be"):
        field_arrays(regular, method="fast")
    with pytest.raises(ValueError, match="depth must be positive"):
        field_arrays(regular, depth=0.0)
    with pytest.raises(ValueError, match="tolerance must be positive"):
        field_arrays(regular, tolerance=0.0)
    with pytest.raises(ValueError, match="lower corner"):
        field_arrays(_sea(), regions=REGION[:, ::-1])
    with pytest.raises(ValueError, match="shape"):
        field_arrays(_sea(), regions=np.zeros((1, 3, 3)))
    with pytest.raises(ValueError, match="more than"):
        field_arrays(_sea(), regions=np.array([[[-5e3, -1, -10], [5e3, 1, 1]]]), tolerance=1e-10)
    for ramp in (-1.0, math.inf, math.nan):
        with pytest.raises(ValueError, match="ramp must be finite and >= 0"):
            field_arrays(regular, ramp=ramp)


@pytest.mark.parametrize("method", ["direct", "table"])
def test_ramp(method: str) -> None:
    """With a ramp of T seconds the field is that of the sea scaled by r(t) = (1 - cos(pi t / T)) / 2 (0 before
    t = 0, 1 after T): elevation r eta exactly, pressure that of the scaled sea (Wheeler stretching follows the
    ramped surface)."""
    sea = _sea()
    duration = 30.0
    ramped = field_arrays(sea, rho=RHO, g=G, regions=REGION, method=method, ramp=duration)
    plain = field_arrays(sea, rho=RHO, g=G, regions=REGION, method=method)
    assert ramped.ramp == duration and plain.ramp == 0.0
    x, y, z = _points(300)
    sigma = math.sqrt(sea.variance)
    for t in (-1.0, 0.0, 7.0, 15.0, 29.9, 30.0, 45.0):
        r = float(Ramp(duration)(np.array(t)))
        got = field_values(ramped, x, y, z, t)
        np.testing.assert_allclose(got[0], r * field_values(plain, x, y, z, t)[0], rtol=0, atol=ROUND_OFF * sigma * 10)
        eta, pressure = _reference(sea, math.inf, x, y, z, t, ramp=duration)
        tolerance = ROUND_OFF * 10 if method == "direct" else 1e-4  # the table's stated tolerance
        np.testing.assert_allclose(got[0], eta, rtol=0, atol=tolerance * sigma)
        np.testing.assert_allclose(got[1], pressure, rtol=0, atol=tolerance * RHO * G * sigma)
        if t <= 0:
            np.testing.assert_array_equal(got, 0.0)
