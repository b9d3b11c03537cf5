"""Flexible bodies of a device: the NOTC arm's structural model against today's free-body cut and the beam closed
forms (pinned at A, held at C, 1 kN at the tip D), the inertia-relief quasi-static stress under a rigid-body motion
against the free-body cut with the arm's mass along it, the arm's invariants, and the spec's errors."""

from __future__ import annotations

import copy

import numpy as np
import pytest

import wecss.devices
import wecss.multibody
from wecss.devices import Device, DeviceSpecError
from wecss.sim._sections import BodyHistory, section_loads
from wecss.structure import (
    MemberLine,
    StressPoint,
    build_frame,
    craig_bampton,
    natural_modes,
    static_response,
    stress_modes,
)

A, C, D = np.array([-2.4, 0.0, 0.2]), np.array([-1.2, 0.0, 0.2]), np.array([0.0, 0.0, 0.2])
B1, OVERHANG = 1.2, 1.2  # A to C, C to D [m]


@pytest.fixture(scope="module")
def notc() -> Device:
    return wecss.devices.load("notc-10kw")


def test_the_arm_pinned_at_a_held_at_c_under_1_kn_at_the_tip(notc):
    """Section stress at C: today's 7.78 MPa (the free-body cut, M c / I) to 1e-9; tip deflection P a^2 (b1 + a) /
    (3 E I) to 1e-9."""
    frame = notc.structure("arm")
    member = notc.member("arm")
    a_node, c_node = frame.point("clamp")[0], frame.point("pto:cylinder")[0]
    assert np.allclose(frame.nodes[a_node], A) and np.allclose(frame.nodes[c_node], C)
    # pinned at A (a revolute about y: translations, torsion and the rotation about z held), held vertically at C
    fixed = [*frame.support("clamp", ("ux", "uy", "uz", "rx", "rz")), *frame.support("pto:cylinder", ("uz",))]
    p = 1000.0
    u = static_response(frame.stiffness, frame.point_load("joint:tip", [0.0, 0.0, p]), fixed)
    spots = [StressPoint("arm", s.at, s.y, s.z, s.scf, s.name) for s in member.hot_spots]
    fe = stress_modes(frame, np.eye(frame.n_dof), spots).stresses(u)
    today = [
        member.stresses(s, member.internal_wrench(s.at, D[None], np.array([[0.0, 0.0, p]]), np.zeros((1, 3))))
        for s in member.hot_spots
    ]
    for k, spot in enumerate(member.hot_spots):
        assert spot.at == B1
        assert fe["signed_von_mises"][k] == pytest.approx(float(today[k]["signed_von_mises"]), rel=1e-9)
    assert abs(fe["normal"][0]) == pytest.approx(7.78e6, rel=1e-3)  # docs/notc.md
    ei = member.material.youngs_modulus * member.section.iy
    tip = (frame.point_map("joint:tip") @ u)[2]
    assert tip == pytest.approx(p * OVERHANG**2 * (B1 + OVERHANG) / (3 * ei), rel=1e-9)


@pytest.mark.parametrize("centrifugal", [False, True])
def test_inertia_relief_stress_equals_the_free_body_cut_with_the_mass_along(notc, centrifugal):
    """The arm in a rigid-body motion with loads at C and D, held at A: the section loads of the reduced model's
    quasi-static response (6 modes, inertia-relief vectors) equal today's free-body cut with body_mass = "along" at
    three stations, to 1e-10. The beam's line mass alone, as the cut has it: no rotary inertia of the sections, and
    no angular acceleration or velocity about the arm's axis (the polar inertia's torque, which the cut does not
    spread along the arm)."""
    member = notc.member("arm")
    body = notc.model.body("arm")
    points, kinds = wecss.devices._flexible.body_points(notc.model, notc.ptos, "arm", notc.flexible["arm"])
    line = MemberLine("arm", member.start, member.end, member.section, member.material, member.nonstructural_mass,
                      (0.3, 1.2, 1.8))  # fmt: skip
    frame = build_frame([line], elements=16, points=points, rotary_inertia=False)
    basis = craig_bampton(frame, "clamp", kinds, 6, centrifugal=centrifugal)
    stations = (0.3, 1.2, 1.8)
    modes = stress_modes(frame, basis.basis, [StressPoint("arm", s, 0.0, 0.0) for s in stations], body.center_of_mass)
    rng = np.random.default_rng(2027)
    gravity = np.array([0.0, 0.0, -9.81])
    accel = rng.normal(size=3)
    alpha = np.r_[0.0, rng.normal(size=2)]
    omega = np.r_[0.0, rng.normal(size=2)] if centrifugal else np.zeros(3)
    f_d, f_c = rng.normal(size=3) * 2e3, rng.normal(size=3) * 5e3
    # the reduced model: its coordinates from the quasi-static balance, held at A
    w = omega
    rigid = np.r_[gravity - accel, alpha, w[0] ** 2, w[1] ** 2, w[2] ** 2, w[0] * w[1], w[1] * w[2], w[2] * w[0]]
    loads = frame.point_load("joint:tip", f_d) + frame.point_load("pto:cylinder", f_c)
    loads = loads + frame.rigid_motion_loads(body.center_of_mass) @ rigid
    phi = basis.basis
    q = np.linalg.solve(phi.T @ frame.stiffness @ phi, phi.T @ loads)
    reduced = modes.section_loads(q, rigid=rigid, motion=False)  # the balance above has no loads of the motion on q
    # today's free body: the same loads, the body's own load at its centre of mass (weight and d'Alembert inertia)
    # the body as the line the cut spreads: the structural model's mass (0.7 ppm below the body's 300 kg), the line's
    # inertia m L^2 / 12
    m = (member.material.density * member.section.area + member.nonstructural_mass) * member.length
    inertia = np.diag([0.0, m * member.length**2 / 12, m * member.length**2 / 12])
    body = wecss.multibody.Body("arm", m, inertia, body.center_of_mass)
    own_f = m * (gravity - accel)
    own_m = -(inertia @ alpha + np.cross(omega, inertia @ omega))
    history = BodyHistory(
        np.array([[D, C, body.center_of_mass]]), np.array([[f_d, f_c, own_f]]), np.array([[np.zeros(3)] * 2 + [own_m]]),
        gravity[None], accel[None], alpha[None], omega[None],
    )  # fmt: skip
    spots = tuple(wecss.devices.HotSpot(f"s{k}", s, 0.0, 0.0) for k, s in enumerate(stations))
    cut = section_loads((wecss.devices.Member("arm", "arm", member.start, member.end, member.section, spots, "along"),),
                        {"arm": 0}, [body], {0: history})[0]  # fmt: skip
    scale = np.abs(cut).max(axis=1, keepdims=True)
    np.testing.assert_allclose(reduced / scale, cut / scale, rtol=0, atol=1e-10)


def test_the_arm_carries_the_body_mass_and_its_reduced_model(notc):
    arm = notc.flexible_body("arm")
    assert arm.invariants.mass == pytest.approx(300.0, rel=1e-6)
    np.testing.assert_allclose(arm.invariants.center_of_mass, [-1.2, 0.0, 0.2], atol=1e-12)
    assert arm.basis.counts == {"constraint": 9, "normal": 6, "inertia_relief": 6, "centrifugal": 0, "dropped": 0}
    assert arm.interfaces == {"joint:tip": "joint", "pto:cylinder": "force"}
    assert arm.stresses.points[0].name == "arm.lug_top"
    modes = arm.generalised_modes()
    assert modes.names[0] == "flex1" and modes.n == arm.basis.n == 21
    np.testing.assert_allclose(np.diag(modes.damping), 0.02 * arm.basis.omega)


def _spec_with(notc: Device, **changes):  # type: ignore[no-untyped-def]
    spec = copy.deepcopy(dict(notc.spec))
    for path, value in changes.items():
        *head, last = path.split("__")
        node = spec
        for key in head:
            node = node[int(key)] if isinstance(node, list) else node[key]
        if value is None:
            del node[last]
        else:
            node[last] = value
    return spec


@pytest.mark.parametrize(
    ("changes", "message"),
    [
        ({"bodies__1__flexible": {"modes": 6, "stiff": True}}, r"flexible has unknown keys \['stiff'\]"),
        ({"bodies__1__flexible": {"modes": -1}}, "flexible.modes must be an integer >= 0; got -1"),
        ({"bodies__1__flexible": {"theory": "rayleigh"}}, "flexible.theory 'rayleigh'; accepted"),
        ({"bodies__1__flexible": {"damping_ratio": 2.0}}, r"flexible.damping_ratio must be a number in \[0, 1\)"),
        ({"members__0__material": None}, "member 'arm' of the flexible body 'arm' has no material"),
        ({"members__0__material": "S999"}, r"material 'S999' is not known; shipped: \['S355'\]"),
        ({"members__0__material": {"E": 2e11, "density": 7850}}, "exactly one of G"),
        ({"members__0__nonstructural_mass": 0.0}, "weighs 75.9022 kg, the body 300 kg"),
        ({"masses": [{"name": "x", "body": "floater", "point": [0, 0, 0], "mass": 1.0}]}, "'floater' is not flexible"),
        ({"masses": [{"name": "x", "body": "arm", "point": [0, 0], "mass": 1.0}]}, r"point must be \[x, y, z\]"),
        ({"bodies__0__flexible": {}}, "flexible.clamp: its joint 'ground' \\(fixed\\) has no point"),
    ],
)
def test_spec_errors_name_the_field_the_value_and_what_is_accepted(notc, changes, message):
    with pytest.raises(DeviceSpecError, match=message):
        Device.from_spec(_spec_with(notc, **changes))


def test_a_lumped_mass_and_a_given_clamp_are_read(notc):
    spec = _spec_with(
        notc,
        members__0__nonstructural_mass=93.374 - 50.0 / 2.4,
        masses=[{"name": "lug", "body": "arm", "point": [-1.2, 0.0, 0.2], "mass": 50.0, "inertia": [1.0, 2.0, 3.0]}],
    )
    device = Device.from_spec(spec)
    assert device.masses[0].name == "lug" and device.masses[0].inertia[2, 2] == 3.0
    frame = device.structure("arm")
    assert frame.masses[0].node == frame.point("pto:cylinder")[0]
    assert device.flexible_body("arm").invariants.mass == pytest.approx(300.0, rel=1e-6)
    with pytest.raises(ValueError, match="body 'floater' is not flexible"):
        device.structure("floater")


def test_a_body_of_two_members_is_one_frame(notc):
    """The arm as two members, A to C and C to D, 8 elements each: the frame of the one member with 16 (the same
    nodes), its clamped frequencies to 1e-10, and the tip deflection of the pinned, held arm to 1e-9."""
    spec = _spec_with(notc, bodies__1__flexible={"modes": 6, "elements": 8})
    arm = spec["members"][0]
    spots = [{**s, "at": 0.0} for s in arm["hot_spots"]]
    spec["members"] = [
        {**arm, "name": "arm_ac", "end": C.tolist(), "hot_spots": []},
        {**arm, "name": "arm_cd", "start": C.tolist(), "hot_spots": spots},
    ]
    split, whole = Device.from_spec(spec).structure("arm"), notc.structure("arm")
    assert sorted(split.members()) == ["arm_ac", "arm_cd"] and split.n_nodes == whole.n_nodes == 17
    np.testing.assert_allclose(np.sort(split.nodes[:, 0]), np.sort(whole.nodes[:, 0]), atol=1e-12)
    omegas = [natural_modes(f.stiffness, f.mass, fixed=f.support("clamp"), n_modes=8)[0] for f in (split, whole)]
    np.testing.assert_allclose(omegas[0], omegas[1], rtol=1e-10)
    fixed = [*split.support("clamp", ("ux", "uy", "uz", "rx", "rz")), *split.support("pto:cylinder", ("uz",))]
    u = static_response(split.stiffness, split.point_load("joint:tip", [0.0, 0.0, 1e3]), fixed)
    member = notc.member("arm")
    ei = member.material.youngs_modulus * member.section.iy
    tip = (split.point_map("joint:tip") @ u)[2]
    assert tip == pytest.approx(1e3 * OVERHANG**2 * (B1 + OVERHANG) / (3 * ei), rel=1e-9)
