"""Beam members and stress recovery: a cantilever with a tip load against the beam formula sigma = M c / I,
torsion against tau = T r / J (tube) and Bredt (box), axial N / A, the signed von Mises stress, spec errors."""

from __future__ import annotations

import numpy as np
import pytest

from wecss.devices import Device, DeviceSpecError, HotSpot, Member, Section

D, T_WALL, L, P = 0.1, 0.005, 2.0, 1000.0
I_TUBE = np.pi / 64 * (D**4 - (D - 2 * T_WALL) ** 4)


@pytest.mark.parametrize("direction", [(1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.6, 0.0, 0.8)])
def test_cantilever_tip_load_gives_the_beam_formula(direction):
    axis = np.array(direction)
    start = np.array([0.3, -0.2, 0.1])
    member = Member("cantilever", "b", start, start + L * axis, Section.tube(D, T_WALL), ())
    # a load perpendicular to the member, in the plane of the member and world z ("downwards" for a horizontal one)
    down = -member.axes[2]
    for station in (0.0, 0.5, 1.7):
        wrench = member.internal_wrench(station, (start + L * axis)[None], (P * down)[None], np.zeros((1, 3)))
        top = member.stresses(HotSpot("top", station, 0.0, D / 2), wrench)
        bottom = member.stresses(HotSpot("bottom", station, 0.0, -D / 2, scf=2.0), wrench)
        sigma = P * (L - station) * (D / 2) / I_TUBE  # hogging: tension on top
        assert top["normal"] == pytest.approx(sigma, rel=1e-12)
        assert top["signed_von_mises"] == pytest.approx(sigma, rel=1e-12)
        assert bottom["signed_von_mises"] == pytest.approx(-2 * sigma, rel=1e-12)
        np.testing.assert_allclose(wrench[[0, 1, 3, 5]], 0.0, atol=1e-9)  # no axial, lateral, torque, Mz
        assert wrench[2] == pytest.approx(-P)


def test_axial_torsion_and_von_mises_on_tube_and_box():
    start, axis = np.zeros(3), np.array([1.0, 0.0, 0.0])
    tube = Member("t", "b", start, start + L * axis, Section.tube(D, T_WALL), ())
    n, torque = 5e3, 300.0
    # several loads, one of them before the cut (it must not count)
    points = np.array([[L, 0, 0], [L, 0, 0], [0.2, 0, 0]])
    forces = np.array([[n, 0, 0], [0, 0, 0], [0, 0, -1e6]])
    moments = np.array([[0, 0, 0], [torque, 0, 0], [0, 0, 0]])
    w = tube.internal_wrench(1.0, points, forces[None], moments[None])  # a time axis of length 1
    s = tube.stresses(HotSpot("side", 1.0, D / 2, 0.0), w)
    area = np.pi / 4 * (D**2 - (D - 2 * T_WALL) ** 2)
    tau = torque * (D / 2) / (2 * I_TUBE)
    assert s["normal"][0] == pytest.approx(n / area, rel=1e-12)
    assert s["shear"][0] == pytest.approx(tau, rel=1e-12)
    assert s["von_mises"][0] == pytest.approx(np.sqrt((n / area) ** 2 + 3 * tau**2), rel=1e-12)
    box = Section.box(0.2, 0.1, 0.01)
    assert box.iy == pytest.approx((0.2 * 0.1**3 - 0.18 * 0.08**3) / 12)
    assert box.wt == pytest.approx(2 * 0.19 * 0.09 * 0.01)
    # lateral load along +y on a box member: Mz, stress -Mz y / Iz (compression on the +y side)
    m = Member("bx", "b", start, start + L * axis, box, ())
    w = m.internal_wrench(0.0, np.array([[L, 0, 0]]), np.array([[0.0, P, 0.0]]), np.zeros((1, 3)))
    s = m.stresses(HotSpot("side", 0.0, 0.1, 0.0), w)
    iz = (0.1 * 0.2**3 - 0.08 * 0.18**3) / 12
    assert s["normal"] == pytest.approx(-P * L * 0.1 / iz, rel=1e-12)


def test_members_from_a_spec_and_clear_errors():
    spec = {
        "name": "beam",
        "bodies": [{"name": "b", "mass": 1.0, "inertia": [1.0, 1.0, 1.0], "center_of_mass": [0.0, 0.0, 0.0]}],
        "joints": [{"name": "ground", "kind": "fixed", "child": "b"}],
        "members": [
            {
                "name": "m",
                "body": "b",
                "start": [0, 0, 0],
                "end": [2, 0, 0],
                "section": {"kind": "given", "area": 1e-3, "iy": 2e-6, "iz": 3e-6, "wy": 4e-5, "wz": 5e-5, "wt": 6e-5},
                "hot_spots": [{"name": "root", "at": 0.0, "scf": 1.5}],
            }
        ],
    }
    device = Device.from_spec(spec)
    member = device.member("m")
    assert member.section.z_max == pytest.approx(2e-6 / 4e-5)
    assert member.hot_spots[0].z == pytest.approx(member.section.z_max)  # the top fibre by default
    bad_section = {**spec["members"][0], "section": {"kind": "pipe", "outer_diameter": 0.1}}
    with pytest.raises(DeviceSpecError, match="section kind 'pipe'"):
        Device.from_spec({**spec, "members": [bad_section]})
    off = {**spec["members"][0], "hot_spots": [{"name": "x", "at": 3.0}]}
    with pytest.raises(DeviceSpecError, match="off the member"):
        Device.from_spec({**spec, "members": [off]})
    assert member.body_mass == "centre"  # the default: the body's own loads at its centre of mass
    assert Device.from_spec({**spec, "members": [{**spec["members"][0], "body_mass": "along"}]}).members[0].body_mass
    with pytest.raises(DeviceSpecError, match=r"body_mass 'spread'; accepted: \['centre', 'along'\]"):
        Device.from_spec({**spec, "members": [{**spec["members"][0], "body_mass": "spread"}]})
    with pytest.raises(DeviceSpecError, match="body 'q'"):
        Device.from_spec({**spec, "members": [{**spec["members"][0], "body": "q"}]})
    with pytest.raises(ValueError, match="thickness"):
        Section.tube(0.1, 0.06)
    with pytest.raises(KeyError, match="no member"):
        device.member("n")
