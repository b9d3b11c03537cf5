"""The modal table (``wecss.linear.modal_table``) in water and in air, with the mode shapes on the nodes of a device's
elastic bodies (issue 28): a rigid device's table unchanged (reference files made before the elastic bodies came
in), the NOTC device with its arm elastic against the device's modal analysis (``structural_modes``, issue 27's
own linear assembly, same reduced basis), the split of a node's motion into the floating frame's rigid motion and
the structure's deformation, and the refusals."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import wecss.devices
import wecss.hydro
from tests.sim.scenes import elastic_notc_spec
from wecss.control import compile_scene
from wecss.linear import format_modal_table, modal_table
from wecss.multibody import kinematics
from wecss.scene import Scene

DATA = Path(__file__).parent / "data"
CALM = {"kind": "calm", "period": None, "duration": 10.0, "ramp": 0.0}


def _needs(database: str) -> None:
    if database not in wecss.hydro.available():
        pytest.skip(f"shipped database {database} not generated yet")


def _compiled(device: str, **solver: object):
    """A calm-water scene of ``device`` with its default (linear damping) controller."""
    return compile_scene(
        Scene.from_dict(
            {"device": {"name": device}, "sea": CALM, "solver": {"dt": 0.01, **solver}, "radiation": {"method": "none"}}
        )
    )


@pytest.mark.parametrize("device", ["m4-134", "notc-10kw"])
def test_a_rigid_device_s_modal_table_is_unchanged(device):
    """Periods, damping ratios, shapes, names and attributes of a rigid device's table in water as before the node
    shapes and the option in air came in (reference files written by the code of commit d53c34e), to 1e-12 of each
    variable's largest value."""
    _needs(device)
    table = modal_table(_compiled(device))
    with xr.open_dataset(DATA / f"modal_table_{device}.nc") as stored:
        reference = stored.load()
    assert set(table.variables) == set(reference.variables) and table.attrs == reference.attrs
    for name in reference.variables:
        assert table[name].dims == reference[name].dims and table[name].attrs == reference[name].attrs
        if table[name].dtype.kind == "f":
            # 1e-12 of each variable's largest finite value: a shape's entries at round-off (1e-10 of its unit
            # entry) move with the LAPACK build by 1e-14, which a relative tolerance on them would take for a change
            values = np.abs(reference[name].values)
            scale = float(values[np.isfinite(values)].max(initial=0.0))
            np.testing.assert_allclose(table[name].values, reference[name].values, rtol=1e-12, atol=1e-12 * scale)
        else:
            np.testing.assert_array_equal(table[name].values, reference[name].values)
    assert "node" not in table.dims


def test_bad_requests_are_refused():
    _needs("notc-10kw")
    compiled = _compiled("notc-10kw")
    with pytest.raises(ValueError, match=r"water must be True .* or False .*; got 'air'"):
        modal_table(compiled, water="air")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=r"water must be True"):
        modal_table(compiled, water=0)  # type: ignore[arg-type]
    for bad in (-1, 2.5, True):
        with pytest.raises(ValueError, match=r"iterations must be an integer >= 0"):
            modal_table(compiled, iterations=bad)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match=r"modal_table takes a CompiledScene .*; got Scene"):
        modal_table(compiled.scene)
    with pytest.raises(ValueError, match=r"needs a controller with linear gains"):
        modal_table(dataclasses.replace(compiled, linear_controller=False))


def test_in_air_a_rigid_device_rests_on_its_springs():
    """The rigid NOTC in air: the float's hinge is a mechanism (no stiffness without water) and the arm swings on
    the cylinder's spring: the eigenvalue of (K, M*) of the multibody core, no gravity, about the reference."""
    _needs("notc-10kw")
    from scipy.linalg import eigh

    from wecss.multibody import Dynamics, StaticModel

    compiled = _compiled("notc-10kw")
    table = modal_table(compiled, water=False)
    model = compiled.device.model
    q = model.neutral_configuration()
    stiffness = StaticModel(model, 0.0, None, compiled.device.ptos).stiffness(q)
    squares = eigh(stiffness, Dynamics(model).terms(q, np.zeros(model.nv)).mass, eigvals_only=True)
    assert np.isinf(table.period.values[0]) and squares[0] == pytest.approx(0.0, abs=1e-9)
    assert table.period.values[1] == pytest.approx(2 * np.pi / np.sqrt(squares[1]), rel=1e-10)
    assert table.converged.values.all() and table.attrs["method"].startswith("in air")
    assert format_modal_table(table).startswith("natural periods in air")


@pytest.fixture(scope="module")
def elastic(tmp_path_factory):
    """The NOTC scene with its arm elastic (``dynamics = "elastic"``; generalised-alpha, which takes the arm's
    modes at the wave step) and the same device for ``structural_modes``."""
    _needs("notc-10kw")
    compiled = _compiled(elastic_notc_spec(tmp_path_factory.mktemp("spec")), method="generalized-alpha")
    device = wecss.devices.load("notc-10kw")
    device = dataclasses.replace(device, flexible={"arm": dataclasses.replace(device.flexible["arm"],
                                                                              dynamics="elastic")})  # fmt: skip
    return compiled, device


def _shape_error(ours: np.ndarray, theirs: np.ndarray) -> float:
    """Largest difference of two shapes after the least-squares scale (sign and normalisation), relative to the
    largest entry of ``theirs``."""
    ours, theirs = ours.ravel(), theirs.ravel()
    scale = (ours @ theirs) / (ours @ ours)
    return float(np.abs(scale * ours - theirs).max() / np.abs(theirs).max())


def test_in_air_the_elastic_notc_has_the_modal_analysis_frequencies_and_node_shapes(elastic):
    """The NOTC device in air (no water, no gravity), its arm elastic: the modal table's natural frequencies and
    damping ratios (the PTO's, the structure's) equal those of the device's modal analysis with the same reduced
    basis (``structural_modes(water=False, model="reduced", pto_damping=True)``: a linear assembly of its own) to
    1e-8 (measured 1.2e-10, 1.2e-10), and the shapes on the arm's 17 nodes, translation and rotation (global and
    elastic parts summed), to 1e-6 of their largest entry up to sign and normalisation (measured 6.4e-12 and
    6.9e-9), for the 11 modes with stiffness: all well separated (neighbours at least 25 % apart)."""
    compiled, device = elastic
    table = modal_table(compiled, water=False)
    theirs = device.structural_modes(water=False, model="reduced", n_modes=12, pto_damping=True)
    assert table.attrs["elastic_bodies"] == "arm" and table.converged.values.all()
    assert np.isinf(table.period.values[0]) and float(theirs.frequency[0]) == pytest.approx(0.0, abs=1e-6)
    ours = 1 / table.period.values[1:12]
    assert np.all(ours[1:] / ours[:-1] > 1.25)
    frequency = np.abs(ours / theirs.frequency.values[1:] - 1).max()
    damping = np.abs(table.damping_ratio.values[1:12] / theirs.damping_ratio.values[1:] - 1).max()
    assert list(table.node.values) == list(theirs.node.values)
    np.testing.assert_array_equal(table.node_position.values, theirs.node_position.values)  # at rest: undeformed
    moves = [_shape_error(table.node_displacement.isel(mode=m).sum("part").values,
                          theirs.node_displacement.isel(mode=m).values) for m in range(1, 12)]  # fmt: skip
    turns = [_shape_error(table.node_rotation.isel(mode=m).sum("part").values,
                          theirs.node_rotation.isel(mode=m).values) for m in range(1, 12)]  # fmt: skip
    print(
        f"NOTC in air, arm elastic, modal table against structural_modes: frequencies {frequency:.1e}, damping "
        f"ratios {damping:.1e}, node translations {max(moves):.1e}, rotations {max(turns):.1e} "
        f"({np.round(ours, 4).tolist()} Hz)"
    )
    assert frequency <= 1e-8 and damping <= 1e-8
    assert max(moves) <= 1e-6 and max(turns) <= 1e-6


def test_in_water_the_elastic_notc_differs_from_the_modal_analysis_by_its_static_loads(elastic):
    """In water the two models are not the same linearisation: the modal table's (the linear model's) is about
    the elastic device's own equilibrium, the arm deflected by its weight and the float's load (4e-3 in the
    largest modal coordinate), with every term of the static loads' Jacobian, the geometric stiffness of gravity,
    buoyancy and the cylinder's load on the elastic coordinates included, and the mass M(xi) at the deflection;
    ``structural_modes`` is about the rigid device's equilibrium, the arm undeformed, and leaves the static loads'
    geometric stiffness on the elastic coordinates out. Their stiffness matrices differ by 5.6e-5 of the largest
    entry, their masses by 1.4e-5. With the added mass A_inf on both sides (``iterations=0``; above the database's
    12 rad/s the table holds A(omega) at its last frequency, ``structural_modes`` takes A_inf: 2.4 % on the
    float's mode at 110 Hz), the 12 lowest frequencies agree to 1e-3 (measured 4.0e-4, the arm's pitch with the
    float), and the shapes on the nodes of the modes the arm carries (its nodes move at least 10 % of the
    device's largest point translation: all but the float's pitch) to 3e-2 (measured 1.4e-2 in the arm's axial
    mode with the float at 110 Hz, whose small bending part the static loads' geometric stiffness changes; below
    7e-4 in the others but two, 3.6e-3 and 3.3e-3, where the frame's rigid motion and the deformation nearly cancel
    on the nodes); the nodes sit where the deflection puts them (1.5e-4 m from the undeformed ones)."""
    compiled, device = elastic
    table = modal_table(compiled, water=True, iterations=0)
    theirs = device.structural_modes(water=True, model="reduced", n_modes=12, iterations=0)
    frequency = np.abs(1 / table.period.values[:12] / theirs.frequency.values - 1)
    carried = [
        m for m in range(12) if np.linalg.norm(theirs.node_displacement.isel(mode=m).values, axis=-1).max() > 0.1
    ]
    moves = [_shape_error(table.node_displacement.isel(mode=m).sum("part").values,
                          theirs.node_displacement.isel(mode=m).values) for m in carried]  # fmt: skip
    offset = np.abs(table.node_position.values - theirs.node_position.values).max()
    print(
        f"NOTC in water, arm elastic: frequencies {frequency.max():.1e} ({np.array2string(frequency, precision=1)}), "
        f"node translations {np.array2string(np.array(moves), precision=1)} in modes {carried}, node positions "
        f"{offset:.1e} m"
    )
    assert frequency.max() <= 1e-3
    assert len(carried) == 11 and max(moves) <= 3e-2
    assert 1e-5 < offset <= 1e-3  # the deflection at the equilibrium: the nodes are not the undeformed ones


@pytest.mark.parametrize("water", [False, True])
def test_a_node_s_motion_is_the_floating_frame_s_rigid_motion_and_the_structure_s(elastic, water):
    """The global part of every mode's node motion is a rigid motion (one rotation for all nodes, the translations
    w x r apart), the elastic part vanishes at the clamp (the pivot's node); at the nodes of the float's hinge and
    the cylinder's lug their sum is the multibody core's velocity Jacobian of those attachments (its product of
    exponentials) applied to the shape: to 1e-12 in air (undeformed), to 1e-4 in water (measured 3.5e-5, the
    product's second order in the 4e-3 deflection)."""
    compiled, _ = elastic
    table = modal_table(compiled, water=water)
    model = compiled.device.model
    arm = model.body_names.index("arm")
    moves = table.node_displacement.values  # (mode, part, node, axis)
    turns = table.node_rotation.values
    at = table.node_position.values
    glob = moves[:, 0]
    spin = turns[:, 0, :1]  # (mode, 1, axis)
    np.testing.assert_allclose(turns[:, 0], np.broadcast_to(spin, turns[:, 0].shape), rtol=0, atol=1e-14)
    rigid = glob[:, :1] + np.cross(spin, at[None] - at[None, :1])
    np.testing.assert_allclose(glob, rigid, rtol=0, atol=1e-12 * np.abs(glob).max())
    assert np.abs(moves[:, 1, 0]).max() == 0.0 and np.abs(turns[:, 1, 0]).max() == 0.0
    # at the attachments: the multibody core's Jacobian about the same configuration
    frame = compiled.device.flexible_body("arm").frame
    q = compiled.q0 if water else model.neutral_configuration()
    state = kinematics(model, q)
    tolerance = 1e-4 if water else 1e-12
    for attachment, point in (("tip", "joint:tip"), ("pto:cylinder", "pto:cylinder")):
        node, _ = frame.point(point)
        where, jacobian = state.point(arm, attachment)
        core = np.einsum("av,mv->ma", jacobian, table.shape.values)
        ours = moves[:, :, node].sum(axis=1)
        error = np.abs(ours - core).max() / np.abs(core).max()
        print(
            f"{attachment} ({'water' if water else 'air'}): {error:.1e}, position {np.abs(at[node] - where).max():.1e}"
        )
        assert error <= tolerance
        assert np.abs(at[node] - where).max() <= (1e-6 if water else 1e-15)


@pytest.mark.parametrize("water", [True, False])
def test_the_modal_table_with_held_coordinates_is_the_condensed_model_s(tmp_path, water):
    """The NOTC arm's coordinates above 30 Hz held quasi-static: one mode per kept coordinate (4), each the
    solution of the full equations with the held columns of mass and damping left out, written here as the
    descriptor pencil (K, M_m) with M_m = M(omega) less its held columns (no condensation in the oracle): at each
    mode's own frequency (the fixed point on A(omega) in water; in air no frequency dependence) omega^2 is a finite
    eigenvalue of that pencil (to 1e-8) and the shape, on every coordinate, its right eigenvector (to 1e-8 of the
    largest entry); the damping ratio is the first-order one of the damped pencil, psi' C_m phi / (2 omega
    psi' M_m phi) with its left eigenvector psi (to 1e-8). The held coordinates' shape entries are not zero."""
    from scipy.linalg import eig

    _needs("notc-10kw")
    spec = elastic_notc_spec(tmp_path, ", quasi_static_above = 30", "notc-held.toml")
    compiled = _compiled(spec, method="generalized-alpha")
    held = compiled.device.model.quasi_static_velocities
    table = modal_table(compiled, water=water)
    assert table.sizes["mode"] == int(np.count_nonzero(~held)) == 4 and table.converged.values.all()
    assert table.sizes["dof"] == held.size and "node_displacement" in table
    from wecss.linear import linearize

    lin = linearize(compiled)
    kept = (~held).astype(float)
    low, high = float(lin.hydro.omega[0]), float(lin.hydro.omega[-1])
    for mode in range(table.sizes["mode"]):
        period = float(table.period[mode])
        if np.isinf(period):  # in air the device's pivot turns freely (no water, no gravity)
            assert not water
            continue
        omega = 2 * np.pi / period
        if water:
            added, radiation = lin.hydro.at(np.array([np.clip(omega, low, high)]))
            bw = lin.hydro_jacobian
            mass = lin.database_mass + bw.T @ added[0] @ bw
            damping = lin.damping + bw.T @ radiation[0] @ bw
        else:  # in air: the table's own rest and matrices are the oracle's inputs (no frequency dependence)
            from wecss.linear._modes import _in_air

            matrices = _in_air(compiled)
            mass, damping = matrices.mass(0.0), matrices.damping(0.0)
        stiffness = lin.stiffness if water else _in_air(compiled).stiffness
        values, left, right = eig(stiffness, mass * kept, left=True, right=True)
        finite = np.isfinite(values) & (np.abs(values) < 1e12)
        k = int(np.argmin(np.abs(values[finite] - omega**2)))
        value, psi, phi = values[finite][k], left[:, finite][:, k], right[:, finite][:, k]
        assert abs(value - omega**2) <= 1e-8 * omega**2
        phi = np.real(phi / phi[np.argmax(np.abs(phi))])
        shape = table.shape.values[mode]
        assert np.abs(shape - phi).max() <= 1e-8
        assert np.abs(shape[held]).max() > 1e-6
        zeta = np.real(psi.conj() @ (damping * kept) @ phi) / (2 * omega * np.real(psi.conj() @ (mass * kept) @ phi))
        assert float(table.damping_ratio[mode]) == pytest.approx(zeta, rel=1e-8)
    print(format_modal_table(table))
