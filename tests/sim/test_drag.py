"""Viscous forces (``hydrodynamics.drag``): the body drag's work per cycle against its closed form, a free decay's
amplitude law, the drag on the fluid's velocity relative to a fixed body, and the Morison inertia force on a fixed
vertical cylinder against the integral of the Airy acceleration."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

from wecss.compiled import compile_plant
from wecss.compiled._viscous import no_viscous
from wecss.compiled.kernels import configure, respond, workspace
from wecss.linear import linearize, response_amplitudes
from wecss.scene import Scene
from wecss.sim import compile_scene, simulate

FLOAT = Path(__file__).parents[1] / "control" / "heaving_float.toml"  # the M4 stern float on a vertical slider
C_HEAVE = 40.0  # quadratic heave drag [N s^2/m^2]


def _float_with_drag(tmp_path: Path) -> Path:
    text = FLOAT.read_text() + f'\n[[drag]]\nbody = "float_3"\ncoefficient = {{Heave = {C_HEAVE}}}\n'
    path = tmp_path / "float_drag.toml"
    path.write_text(text)
    return path


def _scene(device: Path, **sections) -> Scene:
    data = {
        "device": {"name": str(device)},
        "sea": {"kind": "calm", "period": None, "duration": 20.0, "ramp": 0.0},
        "solver": {"method": "beeman", "dt": 0.002},
        "radiation": {"method": "none"},
        "hydrodynamics": {"drag": True},
        "outputs": {"variables": ["motion", "hydrodynamics"]},
    }
    for key, value in sections.items():
        data[key] = {**data.get(key, {}), **value}
    return Scene.from_dict(data)


def _generalised_drag(compiled, q, v, t=0.0):
    """The generalised force of the viscous terms at (q, v): the plant with them less the plant without."""
    p = compiled.plant
    bare = p._replace(viscous=no_viscous())
    out = []
    for plant in (p, bare):
        w = workspace(plant)
        configure(plant, q, np.zeros(plant.hydro_index.size), t, w)
        respond(plant, v, np.zeros((plant.hydro_index.size,) * 2), np.zeros(plant.pto_kind.size), w)
        out.append(w.gen.copy())
    return out[0] - out[1]


def test_work_per_cycle_of_a_harmonic_motion_is_the_closed_form(tmp_path):
    compiled = compile_plant(_scene(_float_with_drag(tmp_path)))
    amplitude, omega, n = 0.03, 5.0, 4000
    times = np.arange(n) * (2 * np.pi / omega) / n
    work = 0.0
    for t in times:
        q = compiled.q0 + np.array([amplitude * np.sin(omega * t)])
        v = np.array([amplitude * omega * np.cos(omega * t)])
        force = _generalised_drag(compiled, q, v)[0]
        work -= force * v[0] * (2 * np.pi / omega) / n  # dissipated
    exact = 8.0 / 3.0 * C_HEAVE * omega**2 * amplitude**3
    assert work == pytest.approx(exact, rel=1e-6)


def test_a_free_decay_follows_the_quadratic_damping_law(tmp_path):
    """m x'' + c |x'| x' + k x = 0 loses (8/3) c omega^2 A^3 per cycle, so 1/A_n = 1/A_0 + (8/3) (c/m) n
    (slow decay); released from 4 cm, no radiation memory, the mass with its infinite-frequency added mass."""
    start = 0.04
    scene = _scene(
        _float_with_drag(tmp_path),
        initial={"displacement": {"slider__heave": start}},
        outputs={"variables": ["motion"]},
    )
    compiled = compile_plant(scene)
    ds = simulate(scene)
    x = ds.displacement.sel(dof_linear="slider__heave").values - compiled.q0[0]
    peaks = np.flatnonzero((x[1:-1] > x[:-2]) & (x[1:-1] >= x[2:])) + 1
    amplitudes = np.concatenate([[start], x[peaks]])
    mass = float(compiled.plant.active_mass.max())  # the heave row: 17.52 kg and its A_inf
    n = np.arange(amplitudes.size)
    law = 1.0 / start + 8.0 / 3.0 * C_HEAVE / mass * n
    assert amplitudes.size >= 8
    np.testing.assert_allclose(1.0 / amplitudes, law, rtol=0.02)


def test_the_drag_acts_on_the_fluid_velocity_relative_to_a_body_at_rest(tmp_path):
    """In a regular wave the drag on a body at rest at its equilibrium is c |u| u with u the Airy velocity at its
    centre of mass, Wheeler-stretched (deep water: u_z = -omega a e^{k (z - eta)} sin(omega t - k x), eta = a
    cos(omega t - k x))."""
    sea = {"kind": "regular", "height": 0.04, "period": 1.2, "duration": 12.0, "ramp": 0.0}
    compiled = compile_plant(_scene(_float_with_drag(tmp_path), sea=sea))
    a, omega = 0.02, 2 * np.pi / 1.2
    k = omega**2 / 9.81
    x0, z0 = compiled.plant.viscous.drag_point[0, 0], compiled.plant.viscous.drag_point[0, 2]
    for t in (0.1, 0.4, 0.77):
        eta = a * np.cos(omega * t - k * x0)
        w = -omega * a * np.exp(k * (z0 - eta)) * np.sin(omega * t - k * x0)
        force = _generalised_drag(compiled, compiled.q0, np.zeros(1), t)[0]
        assert force == pytest.approx(C_HEAVE * abs(w) * w, rel=1e-9, abs=1e-12)


def test_the_morison_inertia_on_a_vertical_cylinder_is_the_integral_of_the_airy_acceleration(tmp_path):
    """A vertical cylinder of diameter D from z1 to z2 below the surface, in a regular wave when the surface is at
    rest level over it (eta = 0, so the stretching is the identity): F_x = rho (1 + Ca) pi D^2/4 int du/dt dz =
    -rho (1 + Ca) pi D^2/4 omega^2 a sin(theta) (e^{k z2} - e^{k z1}) / k; midpoint rule on 400 segments."""
    diameter, ca, z1, z2 = 0.05, 1.0, -1.2, -0.2
    bare = compile_plant(_scene(_float_with_drag(tmp_path)))  # the float with body drag only
    path = _float_with_drag(tmp_path)
    path.write_text(
        path.read_text() + f'\n[[morison]]\nbody = "float_3"\nstart = [2.12, 0.0, {z2}]\nend = [2.12, 0.0, {z1}]\n'
        f"diameter = {diameter}\ncd = 0.0\nca = {ca}\nsegments = 400\n"
    )
    sea = {"kind": "regular", "height": 0.04, "period": 1.2, "duration": 12.0, "ramp": 0.0}
    compiled = compile_plant(_scene(path, sea=sea))
    a, omega, rho = 0.02, 2 * np.pi / 1.2, 1000.0
    k = omega**2 / 9.81
    x0 = 2.12
    p = compiled.plant
    w = workspace(p)
    t = (np.pi / 2 + k * x0) / omega  # theta = pi/2: eta = 0 over the cylinder, the acceleration at its largest
    configure(p, compiled.q0, np.zeros(p.hydro_index.size), t, w)
    area = np.pi * diameter**2 / 4
    shift = compiled.q0[0]  # the slider's equilibrium heave moves the cylinder with the float
    exact = -rho * (1 + ca) * area * omega**2 * a * (np.exp(k * (z2 + shift)) - np.exp(k * (z1 + shift))) / k
    body = list(compiled.device.model.body_names).index("float_3")
    assert w.terms.out[body, 4, 0] == pytest.approx(exact, rel=1e-4)
    # the added mass of the submerged cylinder, normal to its axis, in the Cartesian mass matrix
    rows = compiled.device.model.cart_start[body] + np.arange(2)
    added = p.total_mass[np.ix_(rows, rows)] - bare.plant.total_mass[np.ix_(rows, rows)]
    np.testing.assert_allclose(np.diag(added), rho * ca * area * (z2 - z1), rtol=1e-12)


def test_the_result_shows_the_viscous_force_it_applied(tmp_path):
    scene = _scene(_float_with_drag(tmp_path), initial={"displacement": {"slider__heave": 0.04}}, sea={"duration": 2.0})
    ds = simulate(scene)
    heave = ds.velocity.sel(dof_linear="slider__heave").values
    force = ds.viscous_force.sel(body="float_3", axis="z").values
    np.testing.assert_allclose(force, -C_HEAVE * np.abs(heave) * heave, rtol=1e-12, atol=1e-15)
    np.testing.assert_array_equal(ds.nonlinear_hydro_force.values, ds.viscous_force.values)
    assert ds.viscous_force.attrs["units"] == "N" and ds.viscous_moment.attrs["units"] == "N m"


def test_the_linearised_drag_is_the_describing_function_in_a_regular_wave(tmp_path):
    """One heaving float, drag on its velocity relative to the fluid, a regular wave: the frequency-domain amplitude
    X solves X = (F + c_eq U) / (Z + i omega c_eq) with c_eq = 8/(3 pi) c |i omega X - U| (the describing function),
    found here by a scalar root search on the model without drag and the closed-form Airy velocity U."""
    sea = {"kind": "regular", "height": 0.06, "period": 1.0, "duration": 20.0, "ramp": 0.0}
    solver = {"method": "frequency", "dt": 0.01}
    with_drag = compile_scene(
        _scene(_float_with_drag(tmp_path), sea=sea, solver=solver, outputs={"variables": ["motion"]})
    )
    without = compile_scene(
        _scene(
            _float_with_drag(tmp_path),
            sea=sea,
            solver=solver,
            hydrodynamics={"drag": False},
            outputs={"variables": ["motion"]},
        )
    )
    omega = float(with_drag.excitation.omega[0])
    bare = linearize(without)
    z = complex(bare.dynamic_stiffness(np.array([omega]))[0, 0, 0])
    force = complex((bare.hydro_jacobian.T @ with_drag.excitation.coefficients)[0, 0])
    a, k = 0.03, omega**2 / 9.81
    x0, z0 = with_drag.plant.viscous.drag_point[0, 0], with_drag.plant.viscous.drag_point[0, 2]
    u = 1j * omega * a * np.exp(k * z0) * np.exp(-1j * k * x0)  # heave velocity amplitude of the fluid (Airy)

    def amplitude(ceq: float) -> complex:
        return (force + ceq * u) / (z + 1j * omega * ceq)

    def mismatch(ceq: float) -> float:
        return ceq - 8.0 / (3.0 * np.pi) * C_HEAVE * abs(1j * omega * amplitude(ceq) - u)

    ceq = brentq(mismatch, 0.0, 1e4, xtol=1e-14)
    model = linearize(with_drag)
    xi = response_amplitudes(model, with_drag.excitation.omega, with_drag.excitation.coefficients)[0, 0]
    assert model.drag is not None and model.drag.coefficients[0, 2] == pytest.approx(ceq, rel=1e-8)
    assert xi == pytest.approx(amplitude(ceq), rel=1e-8)


def test_linear_frequency_and_nonlinear_runs_with_drag_agree_in_a_regular_wave(tmp_path):
    """The describing function keeps the first harmonic's energy balance: the nonlinear run's steady heave amplitude
    (Beeman, the drag exact) is the frequency domain's within 2 %, and the linear run's (the same linearised model
    stepped in time) within 0.5 %."""
    sea = {"kind": "regular", "height": 0.06, "period": 1.0, "duration": "40 T", "ramp": "5 T"}
    amplitudes = {}
    for method in ("frequency", "linear", "beeman"):
        solver = {"method": method, "dt": "T/100"}
        radiation = {"method": "state_space"}
        ds = simulate(
            _scene(
                _float_with_drag(tmp_path),
                sea=sea,
                solver=solver,
                radiation=radiation,
                outputs={"variables": ["motion"]},
            )
        )
        x = ds.displacement.sel(dof_linear="slider__heave").values
        last = x[-200:]
        amplitudes[method] = 0.5 * (last.max() - last.min())
    assert amplitudes["linear"] == pytest.approx(amplitudes["frequency"], rel=5e-3)
    assert amplitudes["beeman"] == pytest.approx(amplitudes["frequency"], rel=2e-2)
