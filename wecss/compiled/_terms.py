"""The hydrodynamic terms beyond the linear database as arrays (``[hydrodynamics]`` of a scene): the incident wave
for the kernels, the viscous terms (body drag, linear damping, Morison elements) and the Morison elements' added
mass, and the body-exact pressure forces on the bodies' meshes; built once per compilation, empty when the scene
asks for none."""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING, Any

import numpy as np

from ..devices import Device
from ..multibody import HydroCoupling, kinematics
from ..scene import Hydrodynamics
from ..waves import Ramp, WaveComponents, wavenumber
from ._body_exact import PressureArrays, no_pressure
from ._froude_krylov import linear_froude_krylov
from ._pressure import mesh_arrays
from ._viscous import ViscousArrays, no_viscous
from ._wave_field import calm_field, field_arrays
from ._wave_kinematics import WaveArrays, no_waves

if TYPE_CHECKING:  # pragma: no cover
    from ..hydro.mesh import SurfaceMesh


def wave_arrays(waves: WaveComponents | None, depth: float, g: float, ramp: Ramp | None) -> WaveArrays:
    """The incident wave of ``waves`` (None: calm) in water of ``depth`` [m] for the kernels."""
    if waves is None or not waves.omega.size:
        return no_waves()
    if waves.directional:
        raise ValueError("the kernels' incident wave has one direction of propagation; these waves are directional")
    return WaveArrays(
        np.ascontiguousarray(waves.omega, dtype=float),
        np.ascontiguousarray(wavenumber(waves.omega, depth, g), dtype=float),
        np.ascontiguousarray(waves.amplitude, dtype=complex),
        np.array([np.cos(waves.direction), np.sin(waves.direction)]),
        np.array([float(depth)]),
        np.array([0.0 if ramp is None else float(ramp.duration)]),
    )


def viscous_arrays(
    device: Device, q0: np.ndarray, hydrodynamics: Hydrodynamics, wave: WaveArrays, rho: float
) -> tuple[ViscousArrays, np.ndarray | None]:
    """The device's viscous terms when the scene asks for them (``hydrodynamics.drag``), with the Morison
    elements' added mass at the equilibrium ``q0`` as a Cartesian matrix (None when there is none).

    Raises
    ------
    ValueError
        If the scene asks for drag and the device declares none (``[[drag]]`` or ``[[morison]]``).
    """
    if not hydrodynamics.drag:
        return no_viscous(), None
    if not device.drag and not device.morison:
        raise ValueError(
            f"hydrodynamics.drag = true, but device {device.name!r} declares no [[drag]] or [[morison]] entries"
        )
    model = device.model
    state = kinematics(model, q0)
    names = list(model.body_names)
    drag_body = np.array([names.index(d.body) for d in device.drag], dtype=np.int64)
    quadratic = np.array([d.quadratic(rho) for d in device.drag]).reshape(-1, 6)
    linear = np.array([d.linear for d in device.drag]).reshape(-1, 6)
    points = np.array([state.position[i] for i in drag_body]).reshape(-1, 3)
    body, point, axis, inertia, drag = [], [], [], [], []
    added = np.zeros((model.n_cart, model.n_cart))
    for element in device.morison:
        i = names.index(element.body)
        rot, com = state.rotation[i], state.position[i]
        reference = model.bodies[i].center_of_mass
        mids, unit, length = element.segment_points()
        volume = np.pi * element.diameter**2 / 4 * length
        for mid in mids:
            offset_body = mid - reference  # body axes are the world's at the reference configuration
            body.append(i)
            point.append(offset_body)
            axis.append(unit)
            inertia.append(rho * (1 + element.ca) * volume)
            drag.append(0.5 * rho * element.cd * element.diameter * length)
            offset = rot @ offset_body
            if com[2] + offset[2] < 0 and element.ca > 0:  # submerged at equilibrium: its added mass
                normal = np.eye(3) - np.outer(rot @ unit, rot @ unit)
                cross = np.array([[0, -offset[2], offset[1]], [offset[2], 0, -offset[0]], [-offset[1], offset[0], 0]])
                block = (
                    rho
                    * element.ca
                    * volume
                    * np.block([[normal, -normal @ cross], [cross @ normal, -cross @ normal @ cross]])
                )
                rows = model.cart_start[i] + np.arange(6)
                added[np.ix_(rows, rows)] += block
    arrays = ViscousArrays(
        wave,
        drag_body,
        np.ascontiguousarray(quadratic),
        np.ascontiguousarray(linear),
        np.ascontiguousarray(points),
        np.asarray(body, dtype=np.int64),
        np.asarray(point, dtype=float).reshape(-1, 3),
        np.asarray(axis, dtype=float).reshape(-1, 3),
        np.asarray(inertia, dtype=float),
        np.asarray(drag, dtype=float),
        np.array([1.0 if hydrodynamics.relative_drag else 0.0]),
    )
    return arrays, (added if np.any(added) else None)


def pressure_arrays(
    device: Device,
    coupling: HydroCoupling,
    q0: np.ndarray,
    hydrodynamics: Hydrodynamics,
    waves: WaveComponents | None,
    ramp: Ramp | None,
    notes: list[str],
) -> PressureArrays:
    """The body-exact pressure forces of the scene (``wecss.compiled._body_exact``; none unless the scene asks for
    them): every hydro body's mesh, its reference force, tangent and pose at the equilibrium ``q0`` (remainder) or
    the database's buoyancy and stiffness (replace), the linear Froude-Krylov coefficients to subtract, and the
    incident field. Notes (appended to ``notes``) say how each mesh compares with the database.

    Raises
    ------
    ValueError
        If a hydro body has no mesh, or the "replace" formulation meets a database without Froude-Krylov forces.
    """
    if not hydrodynamics.body_exact:
        return no_pressure()
    model = device.model
    hydro = coupling.hydro
    rho, g = hydro.rho, hydro.g
    owners = [i for i, b in enumerate(model.bodies) if b.hydro_body is not None]
    declared = {m.body for m in device.meshes}
    missing = [model.bodies[i].name for i in owners if model.bodies[i].name not in declared]
    if missing:
        raise ValueError(
            f"body-exact hydrodynamics need a surface mesh of every hydro body; device {device.name!r} declares none "
            f"for {', '.join(missing)} (add [[meshes]] entries to its spec)"
        )
    meshes = [device.surface_mesh(model.bodies[i].name) for i in owners]
    state = kinematics(model, q0)
    with_hs = hydrodynamics.hydrostatics == "body-exact"
    with_fk = hydrodynamics.froude_krylov == "body-exact" and waves is not None and waves.omega.size > 0
    replace = hydrodynamics.form == "replace"
    n_mb = len(owners)
    reference, tangent, delta_ref = np.zeros((n_mb, 6)), np.zeros((n_mb, 6, 6)), np.zeros((n_mb, 6))
    for b, (i, mesh) in enumerate(zip(owners, meshes, strict=True)):
        body = model.bodies[i]
        comparison = mesh.compare_with(hydro, str(body.hydro_body))
        differs = comparison.disagreements()
        notes.append(
            f"mesh of {body.name}: {mesh.n_faces} triangles; "
            + ("agrees with the database (" + str(comparison).split(": ", 1)[1] + ")" if not differs else
               "differs from the database: " + "; ".join(differs))
        )  # fmt: skip
        rows = model.cart_start[i] + np.arange(6)
        if replace:
            reference[b] = coupling.buoyancy[rows]
            tangent[b] = -coupling.stiffness[np.ix_(rows, rows)]
        else:
            pose = (state.position[i], state.rotation[i])
            delta_ref[b] = _delta(pose, body.center_of_mass)
            reference[b] = _buoyancy(mesh, *pose, rho, g)
            tangent[b] = _buoyancy_tangent(mesh, delta_ref[b], body.center_of_mass, rho, g)
    linear_fk = np.zeros((n_mb, waves.omega.size if with_fk and waves is not None else 0, 6), dtype=complex)
    field = calm_field(rho=rho, g=g)
    if with_fk and waves is not None:
        unit = dataclasses.replace(waves, amplitude=np.ones(waves.omega.size, dtype=complex))
        if replace:
            linear_fk[:] = _database_froude_krylov(coupling, owners, model, unit)
        else:
            for b, (i, mesh) in enumerate(zip(owners, meshes, strict=True)):
                linear_fk[b] = linear_froude_krylov(
                    mesh, state.position[i], state.rotation[i], unit, hydro.water_depth, rho, g
                )
        names = [model.bodies[i].name for i in owners]
        poses = [(state.position[i], state.rotation[i]) for i in owners]
        notes.extend(_coarse_notes(meshes, names, poses, waves, hydro.water_depth, g))
        field = field_arrays(
            waves,
            depth=hydro.water_depth,
            rho=rho,
            g=g,
            regions=_regions(meshes, [state.position[i] for i in owners], waves),
            ramp=0.0 if ramp is None else float(ramp.duration),
        )
    mode = 1 if hydrodynamics.surface == "instantaneous" and with_fk else 0
    return PressureArrays(
        mesh=mesh_arrays(meshes),
        field=field,
        owner=np.asarray(owners, dtype=np.int64),
        settings=np.array([mode, int(with_hs), int(with_fk)], dtype=np.int64),
        reference=reference,
        tangent=np.ascontiguousarray(tangent),
        delta_ref=delta_ref,
        linear_fk=np.ascontiguousarray(linear_fk),
        water=np.array([rho, g]),
    )


def _delta(pose: tuple[np.ndarray, np.ndarray], com0: np.ndarray) -> np.ndarray:
    """(CoM displacement, rotation vector) of a pose from the reference pose [m, rad], as the kernels take it."""
    from scipy.spatial.transform import Rotation

    return np.concatenate([pose[0] - com0, Rotation.from_matrix(pose[1]).as_rotvec()])


def _buoyancy(mesh: SurfaceMesh, position: np.ndarray, rotation: np.ndarray, rho: float, g: float) -> np.ndarray:
    """The hydrostatic force and moment about the centre of mass (world) in calm water at a pose [N, N m]: rho g V
    upwards through the centre of buoyancy (exact for the mesh)."""
    displaced = mesh.displaced(position, rotation)
    force = np.array([0.0, 0.0, rho * g * displaced.volume])
    return np.concatenate([force, np.cross(displaced.center_of_buoyancy - position, force)])


BUOYANCY_STEPS: tuple[float, float] = (1e-6, 1e-6)
"""Central-difference steps of the hydrostatic tangent: translation (times the mesh's extent) and rotation [rad]."""


def _buoyancy_tangent(mesh: SurfaceMesh, delta: np.ndarray, com0: np.ndarray, rho: float, g: float) -> np.ndarray:
    """d(hydrostatic force, moment)/d delta at ``delta`` by central differences (6, 6) (columns: delta's)."""
    from scipy.spatial.transform import Rotation

    extent = float(np.max(np.ptp(mesh.vertices, axis=0)))
    out = np.zeros((6, 6))
    for j in range(6):
        h = BUOYANCY_STEPS[0] * extent if j < 3 else BUOYANCY_STEPS[1]
        values = []
        for sign in (1.0, -1.0):
            d = delta.copy()
            d[j] += sign * h
            values.append(_buoyancy(mesh, com0 + d[:3], Rotation.from_rotvec(d[3:]).as_matrix(), rho, g))
        out[:, j] = (values[0] - values[1]) / (2 * h)
    return out


def _database_froude_krylov(coupling: HydroCoupling, owners: list[int], model: Any, unit: WaveComponents) -> np.ndarray:
    """The database's Froude-Krylov force per unit amplitude of each component (n_mb, n_w, 6), world axes.

    Raises
    ------
    ValueError
        If the database holds no ``froude_krylov`` forces.
    """
    from ..hydro import HydroData
    from ..waves import excitation_coefficients

    ds = coupling.hydro.dataset
    if "froude_krylov" not in ds:
        raise ValueError(
            "hydrodynamics.formulation = 'replace' takes the database's Froude-Krylov force out; this database holds "
            "none (froude_krylov): use the 'remainder' formulation or a database with it"
        )
    fk = HydroData(ds.assign(excitation=ds["froude_krylov"]))
    inside = (unit.omega >= fk.omega[0]) & (unit.omega <= fk.omega[-1])
    x = np.zeros((len(fk.dofs), unit.omega.size), dtype=complex)
    x[:, inside] = excitation_coefficients(fk, unit.omega[inside], unit.direction)
    out = np.zeros((len(owners), unit.omega.size, 6), dtype=complex)
    for row, cart in enumerate(coupling.index):
        body = int(np.searchsorted(model.cart_start, cart, side="right") - 1)
        if body in owners and cart - model.cart_start[body] < 6:
            out[owners.index(body), :, cart - model.cart_start[body]] = x[row]
    return out


def _regions(meshes: list[SurfaceMesh], centres: list[np.ndarray], waves: WaveComponents) -> np.ndarray:
    """World boxes the bodies' points can reach (n_mb, 2, 3) [m]: each mesh's bounding sphere about its centre of
    mass at the equilibrium, widened by its radius or by three significant wave heights, whichever is larger
    (a point outside is evaluated by direct sums and noted)."""
    hs = 4.0 * float(np.sqrt(0.5 * np.sum(np.abs(waves.amplitude) ** 2)))
    out = np.zeros((len(meshes), 2, 3))
    for b, (mesh, centre) in enumerate(zip(meshes, centres, strict=True)):
        radius = float(np.max(np.linalg.norm(mesh.vertices, axis=1)))
        reach = radius + max(radius, 3.0 * hs)
        out[b, 0] = centre - reach
        out[b, 1] = centre + reach
    return out


PANELS_PER_WAVELENGTH: float = 10.0
"""A mesh is noted as coarse for a sea state when its longest wetted edge exceeds the shortest significant
wavelength over this number."""


def _coarse_notes(
    meshes: list[SurfaceMesh],
    names: list[str],
    poses: list[tuple[np.ndarray, np.ndarray]],
    waves: WaveComponents,
    depth: float,
    g: float,
) -> list[str]:
    """Notes on meshes whose wetted panels at the equilibrium ``poses`` (position, rotation) are long against the
    sea's shortest significant wavelength (at the frequency below which 95 % of the variance lies)."""
    energy = np.abs(waves.amplitude) ** 2
    order = np.argsort(waves.omega)
    cumulative = np.cumsum(energy[order]) / np.sum(energy)
    omega = float(waves.omega[order][min(int(np.searchsorted(cumulative, 0.95)), order.size - 1)])
    wavelength = 2 * np.pi / float(wavenumber(np.array([omega]), depth, g)[0])
    out = []
    for name, mesh, pose in zip(names, meshes, poses, strict=True):
        corners = mesh.posed(*pose)
        wet = corners[:, :, 2].min(axis=1) < 0.0
        edges = np.linalg.norm(corners - np.roll(corners, 1, axis=1), axis=2)[wet]
        longest = float(edges.max()) if edges.size else 0.0
        if longest > wavelength / PANELS_PER_WAVELENGTH:
            out.append(
                f"mesh of {name} coarse for the sea state: edges up to {longest:.3g} m against a shortest significant "
                f"wavelength of {wavelength:.3g} m (more than 1/{PANELS_PER_WAVELENGTH:g} of it)"
            )
    return out
