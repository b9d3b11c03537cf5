"""The hydrodynamic terms beyond the linear database as arrays (``[hydrodynamics]`` of a scene): the incident wave
for the kernels, the viscous terms (body drag, linear damping, Morison elements) and the Morison elements' added
mass; built once per compilation, empty when the scene asks for none."""

from __future__ import annotations

import numpy as np

from ..devices import Device
from ..multibody import kinematics
from ..scene import Hydrodynamics
from ..waves import Ramp, WaveComponents, wavenumber
from ._viscous import ViscousArrays, no_viscous
from ._wave_kinematics import WaveArrays, no_waves


def wave_arrays(waves: WaveComponents | None, depth: float, g: float, ramp: Ramp | None) -> WaveArrays:
    """The incident wave of ``waves`` (None: calm) in water of ``depth`` [m] for the kernels."""
    if waves is None or not waves.omega.size:
        return no_waves()
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
