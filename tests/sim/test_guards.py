"""Validity guards (issue 18): the step against the fastest mode with the PTO gains (RK4 refused, a coarse step
noted, a divergence blamed on a stiff PTO), the sea and the motions against the bodies' size, drift (notes)."""

from __future__ import annotations

import numpy as np
import pytest

from tests.sim.scenes import scene
from wecss.control import compile_scene
from wecss.linear import exact_step, linearize
from wecss.sim import SceneError, SimulationDiverged, simulate
from wecss.sim._guards import (
    fastest_mode,
    motion_notes,
    stiff_pto_hint,
    wave_notes,
)
from wecss.sim._rk4_check import largest_stable_step, rk4_radius, rk4_step_limit

SHORT = {"duration": 4.0, "ramp": 1.0}


def _stiff(method: str, damping: float = 1e4):
    return compile_scene(
        scene(
            solver={"method": method},
            radiation={"method": "none"},
            controller={"name": "damping", "parameters": {"damping": damping}},
            sea=SHORT,
        )
    )


def test_fastest_mode_of_a_stiff_damper_is_its_decay_rate():
    """One PTO on a stiff damper: the fastest pole of M x'' + C x' + K x = 0 tends to c / m_eff for large c, with
    m_eff = 1 / (g M^-1 g^T) seen by the PTO; independent of the guard's eigenvalue route."""
    c = 1e5
    compiled = _stiff("beeman", c)
    model = linearize(compiled)
    g = model.pto_jacobian
    m_eff = 1.0 / (g @ np.linalg.solve(model.mass, g.T)).item()
    assert fastest_mode(compiled) == pytest.approx(c / m_eff, rel=1e-2)


def test_rk4_is_refused_for_a_stiff_pto_and_the_message_names_the_gain():
    compiled = _stiff("rk4")
    assert rk4_step_limit(compiled)[0] < compiled.dt
    with pytest.raises(SceneError, match=r"PTO gains \(pto_3: damping 1e\+04") as info:
        simulate(compiled)
    assert "reduce the PTO gain" in str(info.value)


def test_a_stiff_pto_under_beeman_is_noted_and_a_gentle_one_is_not():
    noted = simulate(_stiff("beeman")).attrs["notes"]
    assert "fastest mode of the plant with its PTO gains" in noted
    assert "fastest mode" not in simulate(_stiff("beeman", 6.0)).attrs["notes"]


def test_divergence_hint_names_the_pto_gain_when_it_sets_the_fastest_mode():
    assert "stiff PTO is the likely cause" in stiff_pto_hint(_stiff("beeman"))
    assert "stiff PTO" not in stiff_pto_hint(_stiff("beeman", 6.0))


def test_an_unstable_controller_divergence_message_keeps_a_hint():
    sc = scene(
        sea={"duration": 30.0}, controller={"name": "damping", "parameters": {"damping": 0.0, "stiffness": -500.0}}
    )
    with pytest.raises(SimulationDiverged) as info:
        simulate(sc)
    assert "solver.dt" in str(info.value) or "PTO gain" in str(info.value)


def test_steep_sea_and_large_motions_are_noted():
    """Hs 0.5 m, Tp 1.2 s on the model-scale M4: steepness Hs k_p / 2 pi = 0.5 * (2 pi / 1.2)^2 / g / 2 pi = 0.222
    (deep water), far above 1/25."""
    compiled = compile_scene(scene(sea={"height": 0.5, **SHORT}, radiation={"method": "none"}))
    notes = "; ".join(wave_notes(compiled))
    expected = 0.5 * (2 * np.pi / 1.2) ** 2 / compiled.hydro.g / (2 * np.pi)
    assert f"height / wavelength at the (peak) period = {expected:.3g}" in notes
    assert "exceeds 1 x the size" in notes
    assert wave_notes(compile_scene(scene(sea=SHORT, radiation={"method": "none"}))) == []


def test_motion_notes_from_given_configurations():
    """Configurations built by hand: a hinge turned by 30 degrees is noted, 10 degrees is not; a rigid shift of
    the whole device by 2 m in surge is a drift and a large translation."""
    compiled = compile_scene(scene(sea=SHORT, radiation={"method": "none"}))
    names = compiled.device.model.coordinate_names
    q0 = compiled.q0
    hinge = next(i for i, n in enumerate(names) if "__" in n and compiled.bounded.size and i in compiled.bounded)
    turned = np.repeat(q0[None], 20, axis=0)
    turned[10:, hinge] += np.deg2rad(30.0)
    assert any("large rotations" in n for n in motion_notes(compiled, turned))
    small = np.repeat(q0[None], 20, axis=0)
    small[10:, hinge] += np.deg2rad(10.0)
    assert not any("large rotations" in n for n in motion_notes(compiled, small))
    surge = next(i for i, n in enumerate(names) if n.lower().endswith("__surge"))
    moved = np.repeat(q0[None], 20, axis=0)
    moved[:, surge] += np.linspace(0.0, 2.0, 20)
    notes = "; ".join(motion_notes(compiled, moved))
    assert "drift" in notes and "large vertical motions" not in notes
    heave = next(i for i, n in enumerate(names) if n.lower().endswith("__heave"))
    lifted = np.repeat(q0[None], 20, axis=0)
    lifted[10:, heave] += 0.3  # the bow float's size V^(1/3) is 0.133 m
    notes = "; ".join(motion_notes(compiled, lifted))
    assert "large vertical motions" in notes and "drift" not in notes
    assert motion_notes(compiled, np.repeat(q0[None], 20, axis=0)) == []


@pytest.mark.parametrize("dt", [np.inf, np.nan, 0.0, -1.0])
def test_discretise_refuses_a_step_that_is_not_positive_and_finite(dt):
    compiled = compile_scene(scene(sea=SHORT, radiation={"method": "none"}))
    model = linearize(compiled)
    with pytest.raises(ValueError, match="positive finite step"):
        model.discretise(dt)
    with pytest.raises(ValueError, match="positive finite step"):
        exact_step(np.zeros((2, 2)), np.ones((2, 1)), dt)


def test_translation_bound_stops_a_run_and_names_the_setting():
    """The M4 moves by centimetres in 10 s of Hs 0.04 m: a 1 mm bound stops the run, the default bound does not."""
    sea = {"duration": 10.0, "ramp": 1.0}
    assert simulate(scene(sea=sea)).attrs["n_steps"] > 0
    with pytest.raises(
        SimulationDiverged, match=r"beyond solver.translation_bound \(0.001 m\): .* the integrator's error \(a run at"
    ):
        simulate(scene(sea=sea, solver={"translation_bound": 0.001}))


@pytest.mark.parametrize("bad", [0.0, -1.0, "far", True])
def test_translation_bound_must_be_a_positive_length(bad):
    with pytest.raises(SceneError, match=r"solver\.translation_bound must be (a positive length|a number)"):
        scene(solver={"translation_bound": bad})


@pytest.mark.parametrize(
    ("field", "bad"), [("corrector_tol", 2.0), ("max_corrector_iterations", 0), ("angle_bound", 10.0)]
)
def test_solver_settings_are_checked(field, bad):
    """These checks sat after a return (dead code) before issue 18: any value was accepted."""
    with pytest.raises(SceneError, match=rf"solver\.{field}"):
        scene(solver={field: bad})


def test_wave_elevation_is_recorded_as_applied_with_the_ramp():
    """The recorded elevation is the undisturbed one times the cosine ramp (1 - cos(pi t / T_r)) / 2 over the ramp
    T_r, which the excitation also carries."""
    compiled = compile_scene(
        scene(sea={"duration": 6.0, "ramp": 2.0}, radiation={"method": "none"}, outputs={"variables": ["elevation"]})
    )
    ds = simulate(compiled)
    t = ds.time.values
    undisturbed = compiled.waves.elevation(t)
    ramp = np.where(t >= 2.0, 1.0, 0.5 * (1 - np.cos(np.pi * t / 2.0)))
    np.testing.assert_allclose(ds.wave_elevation.values, undisturbed * ramp, rtol=0, atol=1e-12)
    assert ds.wave_elevation.values[0] == 0.0 and "with the start ramp" in ds.wave_elevation.attrs["long_name"]
    # CF attributes (issue 18)
    assert ds.attrs["Conventions"] == "CF-1.10" and "wecss" in ds.attrs["history"]
    assert ds.time.attrs["standard_name"] == "time"


def test_body_to_body_radiation_switch():
    """radiation.body_to_body = false: the compiled database has no added mass or damping between DOFs of
    different bodies (each body's own blocks unchanged), the notes say so, and the run differs from the default."""
    from wecss.hydro import split_dof

    sea = {"duration": 6.0, "ramp": 2.0}
    on = compile_scene(scene(sea=sea, radiation={"method": "none"}))
    off = compile_scene(scene(sea=sea, radiation={"method": "none", "body_to_body": False}))
    ds_on, ds_off = on.hydro.dataset, off.hydro.dataset
    bodies = np.array([split_dof(str(d))[0] for d in ds_off.influenced_dof.values])
    same = np.equal.outer(bodies, bodies)
    assert (~same).any()
    for name in ("added_mass", "radiation_damping"):
        assert np.all(ds_off[name].values[:, ~same] == 0.0)
        np.testing.assert_array_equal(ds_off[name].values[:, same], ds_on[name].values[:, same])
        assert np.any(ds_on[name].values[:, ~same] != 0.0)
    assert np.all(ds_off.added_mass_inf.values[~same] == 0.0)
    run_off = simulate(off)
    assert "radiation between bodies left out" in run_off.attrs["notes"]
    assert not np.allclose(run_off.pto_angle.values, simulate(on).pto_angle.values, rtol=1e-6, atol=0)
    with pytest.raises(SceneError, match=r"radiation\.body_to_body must be bool"):
        scene(radiation={"body_to_body": "no"})


def test_a_state_space_run_reports_its_fits_passivity():
    """The result of a run with the scene's state-space fit carries the fit's passivity (the flag, and the margin:
    the smallest eigenvalue of the scaled damping over the check grid, zero to rounding for a passive fit),
    stability and repair, as the fit report has them; a passive, stable fit gets no note."""
    compiled = compile_scene(scene(sea={"duration": 6.0, "ramp": 2.0}, radiation={"method": "state_space"}))
    ds = simulate(compiled)
    report = compiled.radiation_fit.report.attrs
    assert ds.attrs["radiation_fit_passivity_margin"] == float(report["passivity_margin"])
    assert ds.attrs["radiation_fit_stable"] == int(report["stable"])
    assert ds.attrs["radiation_fit_repair"] == str(report["repair"])
    assert ds.attrs["radiation_fit_passive"] == int(report["passive"]) == 1 and report["stable"] == 1
    assert "radiation state-space fit" not in ds.attrs["notes"]


def test_rk4_region_boundary_on_the_axes():
    """|R(z)| = 1 at z = -2.7853 (root of x^3/24 - x^2/6 + x/2 - 1 = 0) and z = +-2 sqrt(2) i (|R(iy)|^2 =
    1 - y^6/72 + y^8/576): independent closed forms of RK4's region."""
    real_root = float(next(r.real for r in np.roots([1 / 24, -1 / 6, 1 / 2, -1]) if abs(r.imag) < 1e-12))
    radius = rk4_radius(np.array([np.pi, np.pi / 2]))
    assert radius[0] == pytest.approx(real_root, abs=1e-3)
    assert radius[1] == pytest.approx(2 * np.sqrt(2), abs=1e-3)
    assert largest_stable_step(np.array([-10.0, -1.0 + 0j, 0.5])) == pytest.approx(real_root / 10, abs=1e-4)


@pytest.mark.filterwarnings("ignore::wecss.hydro.HydroDataWarning")
def test_rk4_check_takes_the_configurations_the_run_reaches():
    """NOTC 10 kW in Hs 1 m, Tp 8 s at Tp/100: the equilibrium alone allows the step (|s| dt = 2.15, measured: the
    run then diverged at t = 29 s); its cylinder's transmission grows as the arm turns, and the check refuses it."""
    from tests.sim.test_catalogue_runs import _scene
    from wecss.sim._rk4_check import RK4_MARGIN, _mechanical_eigenvalues

    compiled = compile_scene(_scene("notc-10kw", "none", "rk4"))
    at_rest = largest_stable_step(_mechanical_eigenvalues(compiled, compiled.q0)) / RK4_MARGIN
    assert at_rest > compiled.dt  # the old check's view
    limit, cause = rk4_step_limit(compiled)
    assert limit < compiled.dt and "mechanical modes" in cause
    with pytest.raises(SceneError, match=r"RK4 is unstable for this plant.*cylinder: damping 3.2e\+05"):
        simulate(compiled)


def test_a_fit_that_is_not_passive_or_not_stable_gets_a_note():
    """The note reads the fit report's flags: none for a passive, stable fit; one naming what is wrong otherwise
    (and for reports stored before the passive flag existed, the sign of the margin)."""
    from types import SimpleNamespace

    import xarray as xr

    from wecss.sim._guards import fit_notes

    def notes(**attrs):
        report = xr.Dataset(attrs={"passivity_margin": 0.0, "stable": 1, "repair": "r", **attrs})
        return fit_notes(SimpleNamespace(radiation_fit=SimpleNamespace(report=report)))  # type: ignore[arg-type]

    assert notes(passive=1) == []
    assert "NOT PASSIVE" in notes(passive=0, passivity_margin=-1e-3)[0]
    assert "not stable to the required damping" in notes(passive=1, stable=0)[0]
    assert "NOT PASSIVE" in notes(passivity_margin=-1e-3)[0] and notes(passivity_margin=0.0) == []


def test_a_fit_far_off_its_targets_gets_a_note():
    """A fit report whose largest error is more than 10 x its target: the note names it and the convolution."""
    from types import SimpleNamespace

    import xarray as xr

    from wecss.sim._guards import fit_notes

    def notes(k0_error: float):
        report = xr.Dataset(
            {"k0_error": ("entry", [0.001, k0_error]), "rms_error": ("entry", [0.001, 0.002])},
            attrs={"passivity_margin": 0.0, "passive": 1, "stable": 1, "repair": "r", "k0_tol": 0.01, "rms_tol": 0.01},
        )
        return fit_notes(SimpleNamespace(radiation_fit=SimpleNamespace(report=report)))  # type: ignore[arg-type]

    assert notes(0.05) == []
    (note,) = notes(0.5)
    assert "k0 error is 50 times its target" in note and "convolution" in note
