"""Modal analysis of a device with flexible bodies (``wecss.devices.structural_modes``): the NOTC arm made stiff
swings on its PTO spring at the closed-form frequency in air, and in water gives the rigid device's natural
periods; a flexible cantilever with a rigid body welded at its tip has the modes of one frame with that body as a
lumped mass (the floating frame's transport of a child); the reduced model bounds the full one from above; the
energy shares say in-plane, out-of-plane and torsion as the shapes are."""

from __future__ import annotations

import copy

import numpy as np
import pytest

import wecss.devices
import wecss.hydro
from wecss.devices import Device
from wecss.structure import MATERIALS, LumpedMass, MemberLine, Section, build_frame, natural_modes

STIFF = {"E": 2e17, "nu": 0.3, "density": 7850.0}  # the arm a million times stiffer, same mass


@pytest.fixture(scope="module")
def notc() -> Device:
    return wecss.devices.load("notc-10kw")


def _stiff(notc: Device, **body):  # type: ignore[no-untyped-def]
    spec = copy.deepcopy(dict(notc.spec))
    spec["members"][0]["material"] = STIFF
    spec["bodies"][1].update(body)
    return Device.from_spec(spec)


def test_a_stiff_arm_swings_on_the_pto_spring_at_the_closed_form_frequency_in_air(notc):
    """In air (no gravity): J_A omega^2 = k (a b1 / c)^2, J_A the arm's inertia about the pivot plus the float's mass
    at the tip (the float, hinged at D above its centre of mass, translates without turning); the float's pitch
    has no stiffness (a mechanism at 0 Hz)."""
    device = _stiff(notc)
    ds = device.structural_modes(water=False, n_modes=3)
    member = device.member("arm")
    mu = member.material.density * member.section.area + member.nonstructural_mass
    length = member.length
    inertia = mu * length**3 / 3 + member.material.density * member.section.iy * length  # the sections' rotary inertia
    j_a = inertia + device.model.body("floater").mass * length**2
    a, b1 = 1.0, 1.2
    k_theta = 1e5 * (a * b1) ** 2 / (a**2 + b1**2)
    assert float(ds.frequency[0]) < 1e-4
    assert float(ds.frequency[1]) == pytest.approx(np.sqrt(k_theta / j_a) / (2 * np.pi), rel=1e-8)  # 2.1e-9
    assert ds.energy_share.sel(mode=2, energy="strain", share="in_plane") == pytest.approx(1.0, abs=1e-12)
    assert list(ds.dof_angular.values) == ["pivot__pitch", "tip__pitch"] and ds.sizes["dof_linear"] == 0
    assert not [name for name, v in ds.data_vars.items() if " or " in v.attrs.get("units", "")]  # units apart


def test_a_stiff_arm_in_water_has_the_rigid_devices_natural_periods(notc):
    """With A_inf (no fixed point), the two lowest modes of the stiff arm equal Device.natural_periods of the rigid
    device whose arm has the structural model's mass and inertia."""
    if "notc-10kw" not in wecss.hydro.available():
        pytest.skip("shipped database notc-10kw not generated yet")
    invariants = _stiff(notc).flexible_body("arm").invariants
    device = _stiff(notc, mass=invariants.mass, inertia=np.diag(invariants.inertia).tolist())
    ds = device.structural_modes(n_modes=2, iterations=0)
    periods = np.sort(device.natural_periods()["periods"])[::-1]
    np.testing.assert_allclose(1 / ds.frequency.values, periods, rtol=1e-8)  # 6.8e-10


def _cantilever_with_a_welded_mass(elements: int = 6) -> tuple[dict, list]:  # type: ignore[type-arg]
    start, end = [0.0, 0.0, 0.0], [1.5, 0.3, 0.4]
    tip_mass = {"name": "lump", "mass": 40.0, "inertia": [0.5, 0.8, 1.1], "center_of_mass": [1.6, 0.35, 0.3]}
    spec = {
        "name": "cantilever",
        "bodies": [
            {"name": "beam", "mass": 1.0, "inertia": [1.0, 1.0, 1.0], "center_of_mass": [0.75, 0.15, 0.2],
             "flexible": {"elements": elements, "clamp": start}},
            tip_mass,
        ],
        "joints": [
            {"name": "ground", "kind": "fixed", "child": "beam"},
            {"name": "weld", "kind": "weld", "parent": "beam", "child": "lump"},
        ],
        "members": [{"name": "m", "body": "beam", "start": start, "end": end, "material": "S355",
                     "section": {"kind": "box", "width": 0.06, "height": 0.1, "thickness": 0.004}}],
    }  # fmt: skip
    return spec, [start, end, tip_mass]


def test_a_rigid_body_welded_to_a_flexible_one_moves_with_its_joint_point():
    """The welded body rides on the elastic motion of its joint point (its centre of mass, off the member): the
    device's modes in air equal those of one frame carrying that body as a lumped mass, to 1e-9."""
    spec, (start, end, tip) = _cantilever_with_a_welded_mass()
    section = Section.box(0.06, 0.1, 0.004)
    steel = MATERIALS["S355"]
    spec["bodies"][0]["mass"] = steel.density * section.area * float(np.linalg.norm(np.subtract(end, start)))
    device = Device.from_spec(spec)
    ds = device.structural_modes(water=False, n_modes=6)
    frame = build_frame(
        [MemberLine("m", np.array(start), np.array(end), section, steel)], elements=6, points={"clamp": start},
        masses=[LumpedMass("lump", np.array(tip["center_of_mass"]), 40.0, np.diag(tip["inertia"]))],
    )  # fmt: skip
    omega, _ = natural_modes(frame.stiffness, frame.mass, fixed=frame.node_dofs(frame.point("clamp")[0]), n_modes=6)
    np.testing.assert_allclose(ds.frequency.values, omega / (2 * np.pi), rtol=1e-9)


def test_the_reduced_model_bounds_the_full_one_from_above(notc):
    full = notc.structural_modes(water=False, n_modes=8)
    reduced = notc.structural_modes(water=False, n_modes=8, model="reduced")
    f, r = full.frequency.values[1:], reduced.frequency.values[1:]
    assert np.all(r >= f * (1 - 1e-9))
    assert np.all(r / f - 1 < 2e-3)  # 6 normal modes, 9 constraint and 6 inertia-relief vectors: 9e-4 at 96 Hz
    assert reduced.attrs["coordinates"] == 2 + 21 and full.attrs["coordinates"] == 2 + 16 * 6


def test_energy_shares_and_shapes_of_the_notc_arm(notc):
    ds = notc.structural_modes(water=False, n_modes=6)
    shares = ds.energy_share.sel(energy="strain")
    np.testing.assert_allclose(shares.isel(mode=slice(1, None)).sum("share"), 1.0, atol=1e-12)
    kinetic = ds.energy_share.sel(energy="kinetic").sum("share")
    np.testing.assert_allclose(kinetic, 1.0, atol=1e-12)
    assert np.all(np.isnan(shares.sel(mode=1)))  # the float's free pitch: no strain energy
    assert float(shares.sel(mode=2, share="in_plane")) > 0.999  # the arm on the PTO spring
    assert float(shares.sel(mode=3, share="out_of_plane")) > 0.9  # sideways bending with the float
    assert float(shares.sel(mode=4, share="torsion")) > 0.9  # twist, the float rolling
    assert float(shares.sel(mode=6, share="in_plane")) > 0.999  # vertical bending
    largest = np.linalg.norm(ds.point_displacement.values, axis=2).max(axis=1)
    np.testing.assert_allclose(largest, 1.0, rtol=1e-12)
    assert ds.node_position.sizes["node"] == 17 and set(ds.segment_kind.values) == {"element", "body", "pto"}
    # out-of-plane modes move the nodes along y only, in-plane ones in x-z only
    assert np.abs(ds.node_displacement.sel(mode=3, axis=["x", "z"])).max() < 1e-9
    assert np.abs(ds.node_displacement.sel(mode=6, axis="y")).max() < 1e-9


def test_bad_requests_are_refused(notc):
    with pytest.raises(ValueError, match=r"model 'exact'; accepted: \['full', 'reduced'\]"):
        notc.structural_modes(model="exact")
    with pytest.raises(ValueError, match="n_modes must be an integer >= 1"):
        notc.structural_modes(n_modes=0)
    with pytest.raises(ValueError, match="plane_normal must be a non-zero vector"):
        notc.structural_modes(plane_normal=[0, 0, 0])


def test_without_flexible_bodies_the_modes_are_the_linear_models_modal_table():
    """M4 111 (rigid): the frequencies and, with the PTO damping, the damping ratios of the linear model's modal
    table (``wecss.linear.modal_table``: from the compiled plant, another code path), to 1e-8."""
    if "m4-111" not in wecss.hydro.available():
        pytest.skip("shipped database m4-111 not generated yet")
    from wecss.control import compile_scene
    from wecss.linear import modal_table
    from wecss.scene import Scene

    calm = {"kind": "calm", "period": None, "duration": 10.0, "ramp": 0.0}
    scene = Scene.from_dict({"device": {"name": "m4-111"}, "sea": calm, "solver": {"dt": 0.01},
                             "radiation": {"method": "none"}})  # fmt: skip
    table = modal_table(compile_scene(scene))
    ds = wecss.devices.load("m4-111").structural_modes(n_modes=4, pto_damping=True)
    periods = table.period.values  # longest first; the free surge has no stiffness
    assert np.isinf(periods[0]) and float(ds.frequency[0]) == 0.0
    np.testing.assert_allclose(1 / ds.frequency.values[1:], periods[1:], rtol=1e-8)
    np.testing.assert_allclose(ds.damping_ratio.values[1:], table.damping_ratio.values[1:], rtol=1e-8)
