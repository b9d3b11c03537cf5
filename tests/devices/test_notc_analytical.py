"""Cross-model check: the MFM model of ``notc-10kw`` against the paper's one-DOF analytical model (Eqs. 48-52),
both with the paper's simplifications: heave-only radiation with constant added mass and damping at the wave
frequency, heave excitation only, massless cylinder. Regular wave H = 0.28 m, T = 6.2 s (paper 003, Table 4)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import wecss.devices
import wecss.hydro
from wecss.devices.hinged_arm_analytical import HingedArmAnalytical
from wecss.multibody import Dynamics, configuration_rate, gravity_force, kinematics

H, T = 0.28, 6.2


@pytest.fixture(scope="module")
def setup():
    if "notc-10kw" not in wecss.hydro.available():
        pytest.skip("shipped database notc-10kw not generated yet")
    device = wecss.devices.load("notc-10kw")
    coupling = device.coupling()
    hydro = coupling.hydro.dataset
    omega = 2 * np.pi / T
    heave = {"influenced_dof": "floater__Heave", "radiating_dof": "floater__Heave"}
    added = float(hydro.added_mass.sel(**heave).interp(omega=omega))
    damping = float(hydro.radiation_damping.sel(**heave).interp(omega=omega))
    x3 = complex(hydro.excitation.sel(influenced_dof="floater__Heave").isel(wave_direction=0).interp(omega=omega))
    return device, coupling, added, damping, x3, omega


def _force(x3: complex, omega: float):
    ramp = 2 * T

    def f(t: float) -> float:
        r = 1.0 if t >= ramp else 0.5 * (1 - np.cos(np.pi * t / ramp))
        return r * H / 2 * float(np.real(x3 * np.exp(1j * omega * t)))

    return f


def test_mfm_agrees_with_the_analytical_arm_model(setup) -> None:
    device, coupling, added, damping, x3, omega = setup
    model = device.model
    arm, floater = model.body("arm"), model.body("floater")
    pto = device.ptos[0]
    force = _force(x3, omega)
    radius = 0.76
    reference = HingedArmAnalytical(
        arm_inertia=arm.inertia[1, 1] + arm.mass * 1.2**2,
        a=1.0,
        b1=1.2,
        b=2.4,
        h=0.2,
        float_mass=floater.mass,
        added_mass=added,
        damping=damping,
        waterplane_area=np.pi * radius**2,
        pto_stiffness=pto.stiffness,
        pto_damping=pto.damping,
        rho=coupling.hydro.rho,
        g=coupling.hydro.g,
    )
    times = np.linspace(0.0, 8 * T, 801)  # the steady state from 4 T on: four periods compared
    theta_ref = reference.simulate(times, force)

    # MFM with the same simplifications
    n6 = 6 * len(model.bodies)
    i_f = model.body_names.index("floater")
    heave = 6 * i_f + 2
    added_cartesian = np.zeros((n6, n6))
    added_cartesian[heave, heave] = added
    dyn = Dynamics(model, added_cartesian)
    gravity = gravity_force(model, coupling.hydro.g)
    q0 = device.statics().equilibrium()

    def rhs(t: float, y: np.ndarray) -> np.ndarray:
        q, v = y[:2], y[2:]
        st = kinematics(model, q)
        x_dot = st.B @ v
        f = gravity + coupling.hydrostatic_force(model, st)
        f[heave] += force(t) - damping * x_dot[heave]
        length, g = pto.stroke(model, q, st)
        gen = st.B.T @ f + g * (-pto.stiffness * (length - pto.rest) - pto.damping * (g @ v))
        terms = dyn.terms(q, v)
        return np.concatenate([configuration_rate(model, q, v), np.linalg.solve(terms.mass, gen - terms.nonlinear @ v)])

    sol = solve_ivp(rhs, (0, times[-1]), np.concatenate([q0, [0.0, 0.0]]), t_eval=times, method="DOP853", rtol=1e-10)
    theta_mfm = sol.y[0] - q0[0]
    steady = times >= 4 * T
    rms = np.sqrt(np.mean(theta_ref[steady] ** 2))
    difference = np.sqrt(np.mean((theta_mfm[steady] - theta_ref[steady]) ** 2)) / rms
    print(f"arm angle: RMS {np.degrees(rms):.3f} deg, relative RMS difference MFM vs analytical {difference:.2e}")
    assert rms > np.radians(0.5)  # the wave moves the arm
    assert difference < 0.01
