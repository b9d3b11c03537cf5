"""The ``loads`` output group: joint reactions and PTO loads recovered after the run (issue 17).

Checks: in calm water the hinges carry exactly weight minus buoyancy (from the database's displaced volume); in a
wave run the recovered loads close the equations of motion to round-off (reactions do no work on the joints'
free directions) and the PTO's end loads are its force along the cylinder; a linear run's loads agree with the
nonlinear run's to the size of the linearisation error."""

from __future__ import annotations

import numpy as np
import pytest

import wecss.devices
import wecss.hydro
from wecss.sim import simulate

from .scenes import scene

G = 9.81
REGULAR = {"kind": "regular", "height": 0.28, "period": 6.2, "duration": 18.6, "ramp": 6.2}


@pytest.fixture(scope="module", autouse=True)
def _database():
    if "notc-10kw" not in wecss.hydro.available():
        pytest.skip("shipped database notc-10kw not generated yet")


def _run(method: str = "beeman", sea: dict | None = None, **extra):
    sections = {"solver": {"method": method, "dt": 0.05}, "outputs": {"variables": ["motion", "pto", "loads"]}}
    sc = scene("notc-10kw", sea=sea or REGULAR, **{**sections, **extra})
    return simulate(sc)


def test_calm_water_joints_carry_weight_minus_buoyancy():
    ds = _run(sea={"kind": "calm", "duration": 2.0, "ramp": 0.0}, outputs={"variables": ["pto", "loads", "poses"]})
    model = wecss.devices.load("notc-10kw").model
    data = wecss.hydro.load("notc-10kw").dataset  # its reference point is the floater's centre of mass
    volume = float(data.displaced_volume.sum())
    c33 = float(data.hydrostatic_stiffness.sel(influenced_dof="floater__Heave", radiating_dof="floater__Heave"))
    m_arm, m_float = model.body("arm").mass, model.body("floater").mass
    # buoyancy where the device rests: rho g V less the restoring force of the tiny sink from the reference pose
    sink = ds.body_position.sel(body="floater", axis="z").values - model.body("floater").center_of_mass[2]
    buoyancy = 1000.0 * G * volume - c33 * sink
    force = ds.joint_reaction_force
    scale = m_float * G
    tip = force.sel(joint="tip").values
    pivot = force.sel(joint="pivot").values
    np.testing.assert_allclose(tip[:, 2], m_float * G - buoyancy, rtol=0, atol=1e-9 * scale)
    # the cylinder's spring holds a fraction of a newton: the rest pose is 3e-6 rad off the spec's reference pose
    cylinder = ds.pto_end_force.sel(pto="cylinder", pto_end="a").values
    assert np.abs(cylinder).max() < 1.0
    expected = (m_arm + m_float) * G - buoyancy - cylinder[:, 2]
    np.testing.assert_allclose(pivot[:, 2], expected, rtol=0, atol=1e-9 * scale)
    np.testing.assert_allclose(pivot[:, 0], -cylinder[:, 0], rtol=0, atol=1e-9 * scale)
    np.testing.assert_allclose(tip[:, :2], 0.0, atol=1e-9 * scale)
    # a hinge passes no moment about its own axis
    np.testing.assert_allclose(ds.joint_reaction_moment_local.sel(joint="tip", axis="y"), 0.0, atol=1e-9 * scale)


def test_reactions_close_in_a_wave_run_and_pto_loads_act_along_the_cylinder():
    ds = _run()
    assert ds.attrs["loads_closure_residual"] < 1e-10
    moments = ds.joint_reaction_moment_local
    peak = float(np.abs(moments).max())
    assert peak > 1e3  # loaded
    for hinge in ("pivot", "tip"):
        np.testing.assert_allclose(moments.sel(joint=hinge, axis="y"), 0.0, atol=1e-10 * peak)
    end_a = ds.pto_end_force.sel(pto="cylinder", pto_end="a").values
    np.testing.assert_allclose(np.linalg.norm(end_a, axis=1), np.abs(ds.pto_force.sel(pto="cylinder")), rtol=1e-12)
    np.testing.assert_allclose(ds.pto_end_force.sel(pto="cylinder", pto_end="b"), 0.0)  # that end is on the ground
    assert ds.joint_reaction_force.attrs["units"] == "N" and ds.joint_reaction_moment.attrs["units"] == "N m"


def test_linear_run_loads_agree_with_the_nonlinear_run():
    nonlinear = _run(radiation={"method": "state_space"}, solver={"method": "rk4", "dt": 0.05})
    linear = _run("linear", radiation={"method": "state_space"})
    a = nonlinear.joint_reaction_force.sel(joint="pivot").values
    b = linear.joint_reaction_force.sel(joint="pivot").values
    dynamic = np.abs(a - a[0]).max()
    print(f"pivot force: largest dynamic part {dynamic:.1f} N, linear - nonlinear {np.abs(a - b).max():.2f} N")
    assert np.abs(a - b).max() < 0.05 * dynamic
