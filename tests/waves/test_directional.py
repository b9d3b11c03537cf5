"""Directional seas: the spreading functions' weights on a database's headings (against closed forms), the
variance kept, the scene's field and its refusals, and runs on a float whose synthetic database has 24 headings
(``directional_float``) checked against an independent frequency-domain computation and the long-crested run."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from tests.waves import directional_float as fl
from wecss import waves as wv
from wecss.scene import Scene, SceneError
from wecss.sim import compile_scene, simulate


def binomial_cos2s_integral(s: int, lo: float, hi: float) -> float:
    """int_lo^hi cos^(2 s)(theta / 2) d theta / int_-pi^pi (same), by the binomial expansion (integer s):
    cos^(2 s)(u) = 2^(-2 s) [C(2s, s) + 2 sum_j C(2s, s - j) cos(2 j u)]."""

    def primitive(theta: float) -> float:
        total = math.comb(2 * s, s) * theta
        total += 2 * sum(math.comb(2 * s, s - j) * math.sin(j * theta) / j for j in range(1, s + 1))
        return total / 4**s

    return (primitive(hi) - primitive(lo)) / (primitive(math.pi) - primitive(-math.pi))


def test_cos2s_weights_match_the_closed_form_and_sum_to_one() -> None:
    headings = np.deg2rad(np.arange(0.0, 360.0, 30.0))
    mean = math.radians(20.0)
    spreading = wv.Spreading("cos-2s", 4, mean)
    weights = wv.heading_weights(spreading, headings)
    assert weights.weights.sum() == pytest.approx(1.0, abs=1e-14)
    assert weights.uncovered == pytest.approx(0.0, abs=1e-14)
    for h, w in zip(weights.headings, weights.weights, strict=True):
        lo, hi = h - math.radians(15) - mean, h + math.radians(15) - mean  # the bin, from the mean
        shift = 2 * math.pi * math.floor((lo + hi) / 2 / (2 * math.pi) + 0.5)  # its centre into [-pi, pi)
        expected = binomial_cos2s_integral(4, lo - shift, hi - shift)
        assert w == pytest.approx(expected, abs=1e-13)


def test_cos_n_weights_match_the_closed_form() -> None:
    """cos^2: int cos^2 = phi / 2 + sin(2 phi) / 4, normalised by pi / 2, zero behind the mean."""
    headings = np.deg2rad(np.arange(-90.0, 91.0, 15.0))
    weights = wv.heading_weights(wv.Spreading("cos-n", 2), headings)

    def primitive(phi: float) -> float:
        phi = max(-math.pi / 2, min(math.pi / 2, phi))
        return (phi / 2 + math.sin(2 * phi) / 4) / (math.pi / 2)

    half = math.radians(7.5)
    for h, w in zip(weights.headings, weights.weights, strict=True):
        h = (h + math.pi) % (2 * math.pi) - math.pi
        assert w == pytest.approx(primitive(h + half) - primitive(h - half), abs=1e-13)
    assert weights.weights.sum() == pytest.approx(1.0, abs=1e-14)


def test_density_integrates_to_one() -> None:
    theta = np.linspace(-math.pi, math.pi, 400001)
    for spreading in (wv.Spreading("cos-2s", 2.5, 1.0), wv.Spreading("cos-n", 3.0, -2.0)):
        assert np.trapezoid(spreading.density(theta), theta) == pytest.approx(1.0, rel=1e-9)
        # the cumulative integral is the density's integral
        arc = np.linspace(-0.3, 1.7, 200001)
        assert spreading.integral(np.array(arc[0]), np.array(arc[-1])) == pytest.approx(
            np.trapezoid(spreading.density(arc), arc), abs=1e-9
        )


def test_a_database_on_part_of_the_circle() -> None:
    """Headings 0-180 degrees: a spreading about 90 degrees is covered (the end bins reach 7.5 degrees beyond);
    one about 270 degrees is refused, naming the headings."""
    headings = np.deg2rad(np.arange(0.0, 181.0, 15.0))
    weights = wv.heading_weights(wv.Spreading("cos-2s", 10, math.pi / 2), headings)
    assert weights.uncovered < 1e-3
    assert np.rad2deg(weights.upper - weights.lower).round(9).tolist() == [15.0] * 13
    with pytest.raises(
        ValueError, match=r"99\.9% of the spreading.s energy .*\[0\.0, 15\.0, .*180\.0\] degrees do not cover"
    ):
        wv.heading_weights(wv.Spreading("cos-2s", 10, 3 * math.pi / 2), headings)


def test_the_variance_is_kept_and_each_heading_has_its_phases() -> None:
    spectrum = wv.Jonswap(2.0, 8.0)
    uni = wv.irregular(spectrum, d_omega=0.005, omega_max=4.0, seed=3, energy_threshold=0.0)
    assert uni.variance == pytest.approx(2.0**2 / 16, rel=2e-3)  # the discretised spectrum
    weights = wv.heading_weights(wv.Spreading("cos-2s", 6, 0.2), np.deg2rad(np.arange(0.0, 360.0, 20.0)))
    sea = wv.spread(uni, weights, seed=3, energy_threshold=0.0)
    assert sea.directional and sea.direction == uni.direction
    assert sea.variance == pytest.approx(uni.variance, rel=1e-12)
    for omega, a in zip(uni.omega[::50], uni.amplitude[::50], strict=True):  # each frequency's energy split
        same = sea.omega == omega
        assert np.sum(np.abs(sea.amplitude[same]) ** 2) == pytest.approx(abs(a) ** 2, rel=1e-12)
        assert np.unique(np.round(np.angle(sea.amplitude[same]), 12)).size == same.sum()
    again = wv.spread(uni, weights, seed=3, energy_threshold=0.0)
    np.testing.assert_array_equal(again.amplitude, sea.amplitude)
    other = wv.spread(uni, weights, seed=4, energy_threshold=0.0)
    assert not np.allclose(other.amplitude, sea.amplitude)


def test_elevation_at_a_point_follows_each_component_heading() -> None:
    """eta(x, y, t) = sum Re[A_k exp(i (omega_k t - k_k (x cos beta_k + y sin beta_k)))] (deep water)."""
    waves = wv.WaveComponents(np.array([0.8, 1.1]), np.array([0.5, 0.2j]), 0.0, headings=np.array([0.0, math.pi / 2]))
    t = np.linspace(0.0, 20.0, 7)
    x, y = 3.0, -2.0
    k = np.array([0.8, 1.1]) ** 2 / 9.81
    expected = 0.5 * np.cos(0.8 * t - k[0] * x) + np.real(0.2j * np.exp(1j * (1.1 * t - k[1] * y)))
    np.testing.assert_allclose(waves.elevation_at(t, x, y, g=9.81), expected, atol=1e-14)


@pytest.fixture(scope="module")
def spec(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return fl.write_device(tmp_path_factory.mktemp("float"))


def float_scene(spec: Path, spreading: dict | None = None, **changes: dict) -> Scene:
    sea = {"kind": "jonswap", "height": 0.5, "period": 3.0, "duration": 30.0, "ramp": 6.0, "direction": 0.5}
    if spreading is not None:
        sea["spreading"] = spreading
    data = {
        "device": {"name": str(spec)},
        "sea": sea,
        "solver": {"method": "beeman", "dt": 0.03},
        "radiation": {"method": "none"},
        "outputs": {"variables": ["motion", "excitation", "elevation"]},
    }
    for key, value in changes.items():
        data[key] = {**data.get(key, {}), **value}
    return Scene.from_dict(data)


def test_a_narrow_spreading_gives_the_long_crested_run(spec: Path) -> None:
    """With s large every heading but the mean's carries a negligible share (dropped), the mean heading keeps the
    long-crested phases: the run is the long-crested one (mean direction 30 degrees, a database heading)."""
    heading = math.radians(30.0)
    uni = simulate(float_scene(spec, sea={"direction": heading}))
    narrow = simulate(float_scene(spec, {"type": "cos-2s", "s": 1e5}, sea={"direction": heading}))
    scale = float(np.abs(uni.displacement).max())
    np.testing.assert_allclose(narrow.displacement, uni.displacement, atol=1e-9 * scale)
    wide = simulate(float_scene(spec, {"type": "cos-2s", "s": 2}, sea={"direction": heading}))
    assert float(np.abs(wide.displacement - uni.displacement).max()) > 0.05 * scale


def test_frequency_domain_response_is_the_sum_over_headings(spec: Path) -> None:
    """The steady heave of the frequency-domain run equals, at every time, sum_k Re[xi_k exp(i omega_k t)] with
    xi_k = sum_j X(omega_k, beta_j) A_kj / Z(omega_k), Z = -omega^2 (m + A) + i omega (B + c) + C, computed here
    from the test device's own formulas (not the database the run reads), on the run's components A_kj."""
    sc = float_scene(spec, {"type": "cos-2s", "s": 3}, solver={"method": "frequency", "dt": 0.05})
    compiled = compile_scene(sc)
    waves = compiled.waves
    assert waves.directional and np.unique(waves.headings).size > 5
    result = simulate(sc)
    t = result.time.values
    omega = waves.omega
    x = np.array([fl.excitation(np.array([w]), b)[0] for w, b in zip(omega, waves.headings, strict=True)])
    z = -(omega**2) * (fl.MASS + fl.ADDED_MASS) + 1j * omega * (fl.damping(omega) + 2000.0) + fl.STIFFNESS
    phasor = np.exp(1j * np.outer(t, omega))
    expected_force = np.real(phasor @ (x * waves.amplitude))
    expected_heave = np.real(phasor @ (x * waves.amplitude / z))
    force = result.excitation_force.values[:, 0]
    heave = result.displacement.values[:, 0] - float(compiled.q0[0])
    # the run interpolates X and B linearly between the database's 80 frequencies (1e-4 here)
    np.testing.assert_allclose(force, expected_force, atol=5e-4 * np.abs(expected_force).max())
    np.testing.assert_allclose(heave, expected_heave, atol=5e-4 * np.abs(expected_heave).max())


def test_scene_field_round_trips_and_is_recorded(spec: Path) -> None:
    sc = float_scene(spec, {"type": "cos-n", "n": 4}, sea={"duration": 10.0})
    assert dict(sc.sea.spreading) == {"type": "cos-n", "n": 4.0}
    again = Scene.from_json(sc.to_json())
    assert again == sc and hash(again) == hash(sc)
    result = simulate(sc)
    assert json.loads(result.attrs["scene"])["sea"]["spreading"] == {"type": "cos-n", "n": 4.0}


def test_toml_spreading(tmp_path: Path, spec: Path) -> None:
    path = tmp_path / "scene.toml"
    path.write_text(
        f'[device]\nname = "{spec}"\n[sea]\nkind = "jonswap"\nheight = 0.5\nperiod = 3.0\nduration = 9.0\n'
        'ramp = 3.0\nspreading = {type = "cos-2s", s = 10}\n[radiation]\nmethod = "none"\n'
    )
    assert dict(Scene.from_toml(path).sea.spreading) == {"type": "cos-2s", "s": 10.0}


@pytest.mark.parametrize(
    ("spreading", "sea", "match"),
    [
        ({"type": "cos2s", "s": 3}, {}, r"sea\.spreading\.type must be one of cos-2s, cos-n; got 'cos2s'"),
        ({"type": "cos-2s", "s": -1}, {}, r"sea\.spreading\.s must be a positive finite number.*-1"),
        ({"type": "cos-2s", "n": 3}, {}, r"unknown keys \['n'\].*accepted: type, s"),
        ({"type": "cos-n"}, {}, r"sea\.spreading\.n must be a positive finite number.*None"),
        ("cos-2s", {}, r"sea\.spreading must be a table"),
        ({"type": "cos-2s", "s": 3}, {"kind": "calm"}, r"sea\.kind = 'calm' has no waves"),
    ],
)
def test_malformed_spreading_is_refused(spreading: object, sea: dict, match: str) -> None:
    with pytest.raises(SceneError, match=match):
        Scene.from_dict({"sea": {"kind": "jonswap", **sea, "spreading": spreading}})


def test_a_measured_elevation_takes_no_spreading(tmp_path: Path) -> None:
    record = tmp_path / "eta.txt"
    t = np.arange(0, 200) * 0.05
    np.savetxt(record, np.column_stack([t, 0.01 * np.sin(2 * t)]))
    with pytest.raises(SceneError, match=r"sea\.kind = 'elevation' has a measured elevation at one point"):
        Scene.from_dict({"sea": {"kind": "elevation", "file": str(record), "spreading": {"type": "cos-2s", "s": 3}}})


def test_a_database_with_one_heading_is_refused() -> None:
    sc = Scene.from_dict(
        {
            "device": {"name": "m4-111"},
            "sea": {"duration": 12.0, "ramp": 2.0, "spreading": {"type": "cos-2s", "s": 10}},
            "radiation": {"method": "none"},
        }
    )
    with pytest.raises(
        SceneError, match=r"sea\.spreading .*the database of device 'm4-111' has one \(\[0\.0\] degrees\)"
    ):
        compile_scene(sc)


def test_terms_with_one_wave_direction_are_refused(spec: Path) -> None:
    for hydrodynamics, name in (
        ({"froude_krylov": "body-exact"}, 'hydrodynamics.froude_krylov = "body-exact"'),
        ({"drag": True}, "hydrodynamics.drag = true"),
    ):
        sc = float_scene(spec, {"type": "cos-2s", "s": 5}, hydrodynamics=hydrodynamics, sea={"duration": 9.0})
        with pytest.raises(SceneError, match=f"sea.spreading with {name}: these terms take the incident wave of one"):
            compile_scene(sc)


def test_response_per_unit_wave_is_refused_for_a_directional_sea(spec: Path) -> None:
    from wecss.linear._frequency import _wave_amplitudes

    compiled = compile_scene(float_scene(spec, {"type": "cos-2s", "s": 5}, sea={"duration": 9.0}))
    with pytest.raises(ValueError, match="several components per frequency"):
        _wave_amplitudes(compiled, compiled.excitation.omega)


def test_a_direction_the_database_lacks_is_refused_naming_the_field(spec: Path) -> None:
    with pytest.raises(SceneError, match=r"sea \(kind 'jonswap', direction 0\.4 rad\) on the database .*not in the"):
        compile_scene(float_scene(spec, sea={"direction": 0.4, "duration": 9.0}))


def test_a_spreading_beyond_the_database_headings_is_refused(tmp_path: Path) -> None:
    half = fl.write_device(tmp_path, headings_deg=np.arange(0.0, 181.0, 15.0))
    behind = float_scene(half, {"type": "cos-2s", "s": 10}, sea={"direction": math.radians(270.0), "duration": 9.0})
    with pytest.raises(SceneError, match=r"sea\.spreading .* on the database of device .*float\.toml.*do not cover"):
        compile_scene(behind)
    across = float_scene(half, {"type": "cos-2s", "s": 10}, sea={"direction": math.radians(90.0), "duration": 9.0})
    assert np.unique(compile_scene(across).waves.headings).size > 5


def test_a_regular_wave_spread_keeps_its_height_in_variance() -> None:
    """A regular wave of height H spread over headings: (H / 2)^2 / 2 of variance, split by the weights."""
    weights = wv.heading_weights(wv.Spreading("cos-n", 2, 0.0), np.deg2rad(np.arange(0.0, 360.0, 30.0)))
    sea = wv.spread(wv.regular(2.0, 8.0), weights, seed=5, energy_threshold=0.0)
    assert sea.variance == pytest.approx(0.5, rel=1e-14)
    np.testing.assert_allclose(np.abs(sea.amplitude) ** 2 / 2, 0.5 * weights.weights[weights.weights > 0], rtol=1e-14)
    assert sea.repeat_period == 8.0


def test_a_sweep_over_the_spreading_exponent() -> None:
    from wecss.sweep import Sweep

    base = {"sea": {"duration": 12.0, "ramp": 2.0, "spreading": {"type": "cos-2s", "s": 10}}}
    cases = Sweep(base, (("sea.spreading.s", (2.0, 10.0)),)).cases
    assert [dict(c.scene.sea.spreading) for c in cases] == [{"type": "cos-2s", "s": s} for s in (2.0, 10.0)]
