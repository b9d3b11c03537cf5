"""The result Dataset of a run (DESIGN.md "Results"), built from the raw :class:`Record` every runner returns.

Dimensions: ``time``; ``dof_linear`` / ``dof_angular`` (generalised coordinates, translations and rotations kept
apart); ``pto`` (every PTO, in the device spec's order, with the coordinate ``pto_kind``: "rotary" or "linear");
``hydro_dof_linear`` / ``hydro_dof_angular`` (forces and moments on the hydrodynamic DOFs, bodies in the device
spec's order); ``body`` and ``axis`` (poses). Every per-PTO variable has the one ``pto`` dimension: a rotary PTO's
stroke is ``pto_angle`` [rad], a linear one's ``pto_displacement`` [m], each NaN for the PTOs of the other kind
(and absent when the device has none of that kind), so ``ds.pto_angle * ds.pto_power`` stays (time, pto).
Only the groups the scene's outputs ask for are present; statistics over the final window are always there.
"""

from __future__ import annotations

import datetime as _dt
import json
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import xarray as xr

from .. import __version__
from ..attributes import apply_attrs, by_pto_kind
from ..compiled import JIT, CompiledScene, hydro_velocity, poses
from ..control import PowerBound, power_bound
from ..hydro import split_dof
from ..multibody import difference
from ..waves import Ramp, energy_flux, energy_period, group_velocity, mean_period
from ._guards import fit_notes, motion_notes, step_notes, wave_notes
from ._load_amplitudes import load_amplitudes
from ._loads import Loads, recover_loads
from ._sections import hot_spot_names, hot_spot_stresses


@dataclass
class Record:
    """Raw arrays of a run at its saved steps, before they become a Dataset.

    ``time`` (n_save,) [s]; ``q`` configurations, ``v`` generalised velocities, ``a`` accelerations; PTO strokes
    ``x``, rates ``xd`` and forces ``f`` (n_save, n_pto); memory forces ``rad`` and excitation ``exc`` on the hydro
    DOFs; ``stats`` the sums over the statistics window (see :func:`window_statistics`); ``run_time`` [s] of the
    run itself. The fixed-step runs keep ``a``, ``x``, ``xd``, ``f``, ``rad`` and ``exc`` only where an output group
    reads them; otherwise these hold a single row. ``solver`` describes the run in the result's attributes: at
    least ``solver`` (its name), and whatever else the run measured (evaluations per step, its radiation model,
    ...).
    """

    time: np.ndarray
    q: np.ndarray
    v: np.ndarray
    a: np.ndarray
    x: np.ndarray
    xd: np.ndarray
    f: np.ndarray
    rad: np.ndarray
    exc: np.ndarray
    stats: np.ndarray
    run_time: float
    solver: dict[str, Any] = field(default_factory=dict)
    limits: np.ndarray | None = None
    """Per PTO (4, n_pto): steps with the force at its limit, episodes of it, steps with the stroke beyond its
    limit, episodes of that (None: the run did not count them)."""
    spectral: Any = None
    """A frequency-domain run's :class:`Spectral` record: its equilibrium and complex amplitudes (for the loads'
    amplitudes per frequency); None for the time-domain runs. (Typed Any: the runners build Records from dicts of
    arrays.)"""
    hydro_order: np.ndarray | None = None
    """The hydro DOFs of the columns of ``rad`` and ``exc``, as indices into the database's (None: its order)."""


def limit_counts(stroke: np.ndarray, control: np.ndarray, limits: tuple[np.ndarray, np.ndarray]) -> np.ndarray:
    """What the fixed-step kernels count of the PTO limits, from every-step strokes (from rest) and controller
    forces (n_steps, n_pto) of a run and the (force, stroke) limits per PTO: (4, n_pto) steps with the force at its
    limit, episodes of it, steps with the stroke beyond its limit, episodes of that."""
    force_limit, stroke_limit = limits
    rows = []
    for active in (np.abs(control) >= force_limit * (1.0 - 1e-12), np.abs(stroke) > stroke_limit):
        starts = active[0].astype(np.int64) + np.sum(active[1:] & ~active[:-1], axis=0)
        rows += [np.sum(active, axis=0), starts]
    return np.array(rows, dtype=np.int64).reshape(4, -1)


def hydro_angular(compiled: CompiledScene) -> np.ndarray:
    """Mask of the rotational hydro DOFs (roll, pitch, yaw) in the database's order."""
    return np.array([split_dof(d)[1].lower() in ("roll", "pitch", "yaw") for d in compiled.hydro.dofs], dtype=bool)


def grouped_hydro_order(compiled: CompiledScene) -> np.ndarray:
    """The hydro DOFs with the translations first and the rotations after (each in the device spec's body order,
    :func:`natural_hydro_order`): the column order in which the fixed-step runs store forces on them, so that each
    kind is one block of columns."""
    natural = natural_hydro_order(compiled)
    angular = hydro_angular(compiled)[natural]
    return np.concatenate([natural[~angular], natural[angular]]).astype(np.int64)


def _hydro_columns(record: Record, values: np.ndarray) -> np.ndarray:
    """``values`` (the record's ``rad`` or ``exc``) with the columns in the database's order."""
    if record.hydro_order is None:
        return values
    return values[:, np.argsort(record.hydro_order)]


def stats_start(compiled: CompiledScene) -> int:
    """First step of the statistics window (the last ``outputs.window`` share of the steps)."""
    n = compiled.n_steps
    return n - max(1, round(compiled.scene.outputs.window * n)) + 1


def window_statistics(compiled: CompiledScene, x: np.ndarray, xd: np.ndarray, f: np.ndarray) -> np.ndarray:
    """Sums over the statistics window of every-step PTO strokes ``x``, rates ``xd`` and forces ``f``
    (n_steps + 1, n_pto): absorbed power (the device spring left out, as conservative), stroke^2, count, stroke;
    what the fixed-step kernels accumulate as they go."""
    window = slice(stats_start(compiled), None)
    power = -(f[window] + compiled.plant.pto_spring * x[window]) * xd[window]
    xs = x[window]
    return np.stack([power.sum(0), (xs**2).sum(0), np.full(x.shape[1], float(xs.shape[0])), xs.sum(0)])


def dof_kinds(compiled: CompiledScene) -> tuple[list[str], np.ndarray]:
    """Velocity names and a mask of the angular ones (``Multibody.angular_velocities``)."""
    model = compiled.device.model
    return list(model.velocity_names), np.array(model.angular_velocities, dtype=bool)


def _tangent(compiled: CompiledScene, q: np.ndarray) -> np.ndarray:
    """Generalised coordinates as velocity-space values (a free base: CoM position and rotation vector)."""
    model = compiled.device.model
    if model.nq == model.nv:
        return q
    neutral = model.neutral_configuration()
    return np.array([difference(model, neutral, row) for row in q])


def _split(  # one variable per kind: translations [m ...] under ``lin``, rotations [rad ...] under ``ang``
    ds: dict[str, Any],
    values: np.ndarray,
    mask: np.ndarray,
    lin: str,
    ang: str,
    dims: tuple[str, str],
) -> None:
    if (~mask).any():
        ds[lin] = (("time", dims[0]), values[:, _columns(~mask)])
    if mask.any():
        ds[ang] = (("time", dims[1]), values[:, _columns(mask)])


def _columns(mask: np.ndarray) -> slice | np.ndarray:
    """The columns ``mask`` selects: a slice where they are consecutive (the variable is then a view of the
    record, no copy: a run of 10^6 saved steps holds its time series once), else their indices."""
    index = np.flatnonzero(mask)
    if index.size and index[-1] - index[0] + 1 == index.size:
        return slice(int(index[0]), int(index[-1]) + 1)
    return index


def natural_hydro_order(compiled: CompiledScene) -> np.ndarray:
    """Indices that put the hydro DOFs in the device spec's body order (the database may list its bodies
    otherwise), each body's DOFs in the database's order."""
    bodies = [b.hydro_body for b in compiled.device.model.bodies if b.hydro_body is not None]
    dofs = list(compiled.hydro.dofs)
    rank = {body: k for k, body in enumerate(bodies)}
    return np.array(
        sorted(range(len(dofs)), key=lambda i: (rank.get(split_dof(dofs[i])[0], len(rank)), i)), dtype=np.int64
    )


def sea_state_attrs(compiled: CompiledScene) -> dict[str, Any]:
    """Energy period, mean period and energy flux of the scene's sea state (for the capture width ratio)."""
    sea = compiled.scene.sea
    hydro = compiled.hydro
    rho, g, depth = hydro.rho, hydro.g, hydro.water_depth
    out: dict[str, Any] = {"sea_kind": sea.kind}
    spectrum = compiled.spectrum
    if spectrum is not None:
        out["energy_period"] = energy_period(spectrum)
        out["mean_period"] = mean_period(spectrum)
        out["wave_energy_flux"] = energy_flux(spectrum, depth, rho, g)
        out["wave_energy_flux_source"] = "theoretical spectrum"
        if sea.period is not None:
            out["peak_period"] = float(sea.period)
        out["significant_wave_height"] = 4 * np.sqrt(spectrum.moment(0))
    elif compiled.waves is not None:
        w = compiled.waves
        variance = np.abs(w.amplitude) ** 2 / 2
        out["energy_period"] = float(2 * np.pi * np.sum(variance / w.omega) / np.sum(variance))
        out["mean_period"] = float(2 * np.pi * np.sum(variance) / np.sum(variance * w.omega))
        out["wave_energy_flux"] = float(rho * g * np.sum(variance * group_velocity(w.omega, depth, g)))
        out["wave_energy_flux_source"] = "simulated wave components"
        out["significant_wave_height"] = float(4 * np.sqrt(np.sum(variance)))
        if sea.period is not None:
            out["peak_period"] = float(sea.period)
    return out


def _notes(compiled: CompiledScene, report: dict[str, Any], motion: list[str]) -> list[str]:
    notes = [*compiled.notes, *fit_notes(compiled), *step_notes(compiled), *wave_notes(compiled), *motion]
    if compiled.device.ptos and not compiled.linear_controller:
        steps = compiled.scene.control_steps
        notes.append(
            "controller force held constant over each step (zero-order hold at the simulation step)"
            if steps == 1
            else f"controller called every {steps} steps ({steps * compiled.dt:.6g} s), its force held in between"
        )
    if report:
        notes.append(
            "controller: "
            + ", ".join(f"{k} = {v:.4g}" if isinstance(v, float) else f"{k} = {v}" for k, v in report.items())
        )
    return notes


def build_result(compiled: CompiledScene, record: Record) -> xr.Dataset:
    """The Dataset of a run from its raw record (see the module docstring)."""
    data, coords, known = series_variables(compiled, record)
    groups = set() if compiled.scene.outputs.statistics_only else set(compiled.scene.outputs.variables)
    closure = _add_loads(data, coords, compiled, record) if "loads" in groups and record.time.size else None
    return _with_statistics(compiled, record, data, coords, motion_notes(compiled, record.q, known), closure)


def statistics_dataset(compiled: CompiledScene, record: Record, motion: list[str]) -> xr.Dataset:
    """What :func:`build_result` adds to the time series: the statistics over the final window, the limits'
    counts, the power bound and the attributes (``motion``: the notes on the record's motion, from
    ``MotionSummary``); ``record`` needs only its ``stats``, ``limits``, ``run_time`` and ``solver``."""
    return _with_statistics(compiled, record, {}, {}, motion, None)


def series_variables(
    compiled: CompiledScene, record: Record, elevation: np.ndarray | None = None
) -> tuple[dict[str, Any], dict[str, Any], tuple[np.ndarray, np.ndarray] | None]:
    """The time-series variables and their coordinates of the output groups (``loads`` aside) and the poses
    when they were computed (for the notes). ``elevation``: the ``elevation`` group's values at ``record.time``
    when the caller has them (:func:`elevation_series`)."""
    scene = compiled.scene
    groups = set() if scene.outputs.statistics_only else set(scene.outputs.variables)
    names, angular = dof_kinds(compiled)
    # hydro-DOF columns in the device spec's body order; the fixed-step runs store them so already, translations
    # first (``Record.hydro_order``: each kind is then a view of the record), the other runs in the database's order
    stored = natural_hydro_order(compiled) if record.hydro_order is None else record.hydro_order
    hydro_dofs = [compiled.hydro.dofs[i] for i in stored]
    stored_angular = hydro_angular(compiled)[stored]
    exc, rad = (
        (record.exc[:, stored], record.rad[:, stored]) if record.hydro_order is None else (record.exc, record.rad)
    )
    pto_names = [p.name for p in compiled.device.ptos]
    rotary = np.array([kind == "rotary" for kind in compiled.pto_kinds], dtype=bool)
    data: dict[str, Any] = {}
    coords: dict[str, Any] = {}
    n_t = record.time.size
    if n_t and groups:
        coords["time"] = record.time
    lin_names = [n for n, a in zip(names, angular, strict=True) if not a]
    ang_names = [n for n, a in zip(names, angular, strict=True) if a]
    if "motion" in groups:
        _split(data, _tangent(compiled, record.q), angular, "displacement", "angle", ("dof_linear", "dof_angular"))
        _split(data, record.v, angular, "velocity", "angular_velocity", ("dof_linear", "dof_angular"))
        _split(data, record.a, angular, "acceleration", "angular_acceleration", ("dof_linear", "dof_angular"))
    if "pto" in groups and pto_names:
        data.update(by_pto_kind(record.x, rotary, ("pto_angle", "pto_displacement"), ("time", "pto")))
        data.update(by_pto_kind(record.xd, rotary, ("pto_angular_velocity", "pto_velocity"), ("time", "pto")))
        data.update(by_pto_kind(record.f, rotary, ("pto_torque", "pto_force"), ("time", "pto")))
        # absorbed power: the device spring's force -k x is conservative and left out
        data["pto_power"] = (("time", "pto"), -(record.f + compiled.plant.pto_spring * record.x) * record.xd)
        coords.update(_pto_coordinates(compiled))
    if "excitation" in groups and n_t:
        _split(
            data,
            exc,
            stored_angular,
            "excitation_force",
            "excitation_moment",
            ("hydro_dof_linear", "hydro_dof_angular"),
        )
    if "radiation" in groups and n_t:
        _split(
            data,
            rad,
            stored_angular,
            "radiation_force",
            "radiation_moment",
            ("hydro_dof_linear", "hydro_dof_angular"),
        )
        u = np.array([hydro_velocity(compiled.plant, qq, vv) for qq, vv in zip(record.q, record.v, strict=True)])
        _split(
            data,
            u[:, stored],
            stored_angular,
            "hydro_velocity",
            "hydro_angular_velocity",
            ("hydro_dof_linear", "hydro_dof_angular"),
        )
    if "elevation" in groups and n_t:
        eta = elevation_series(compiled, record.time) if elevation is None else elevation
        data["wave_elevation"] = (("time",), eta)
    known = None  # the poses, computed once for the output and the notes
    if "poses" in groups and n_t:
        position, rotation = known = poses(compiled.plant, np.ascontiguousarray(record.q))
        data["body_position"] = (("time", "body", "axis"), position)
        data["body_rotation"] = (("time", "body", "axis"), rotation)
        coords["body"] = list(compiled.device.model.body_names)
        coords["axis"] = ["x", "y", "z"]
    for dim, values in (("dof_linear", lin_names), ("dof_angular", ang_names)):
        if any(dim in v[0] for v in data.values()):
            coords[dim] = values
    for dim, mask in (("hydro_dof_linear", ~stored_angular), ("hydro_dof_angular", stored_angular)):
        if any(dim in v[0] for v in data.values()):
            coords[dim] = [d for d, m in zip(hydro_dofs, mask, strict=True) if m]
    return data, coords, known


def elevation_series(compiled: CompiledScene, time: np.ndarray) -> np.ndarray:
    """The undisturbed elevation at ``time`` [m] as the run applied it (with the start ramp). Its evaluation
    depends on the whole of ``time`` (one FFT where the record is periodic, else a recurrence): to round-off, and
    exactly when evaluated on the same times."""
    scene = compiled.scene
    eta = compiled.waves.elevation(time) if compiled.waves is not None else np.zeros(time.size)
    if scene.sea.ramp_s > 0 and scene.solver.method != "frequency":  # as applied: with the start ramp
        eta = eta * Ramp(scene.sea.ramp_s)(time)
    return eta


def _pto_coordinates(compiled: CompiledScene) -> dict[str, Any]:
    """The ``pto`` dimension's names and the ``pto_kind`` coordinate."""
    kinds = ["rotary" if kind == "rotary" else "linear" for kind in compiled.pto_kinds]
    return {"pto": [p.name for p in compiled.device.ptos], "pto_kind": ("pto", kinds)}


def _with_statistics(
    compiled: CompiledScene,
    record: Record,
    data: dict[str, Any],
    coords: dict[str, Any],
    motion: list[str],
    closure: float | None,
) -> xr.Dataset:
    """The Dataset of the variables ``data`` (the time series) with the statistics and the attributes."""
    scene = compiled.scene
    pto_names = [p.name for p in compiled.device.ptos]
    rotary = np.array([kind == "rotary" for kind in compiled.pto_kinds], dtype=bool)
    count = max(1.0, float(record.stats[2, 0])) if record.stats.size else 1.0
    if pto_names:
        data["mean_pto_power"] = (("pto",), record.stats[0] / count)
        if record.limits is not None:  # how often and how long each limit acted, over the whole run
            data["force_limit_time"] = (("pto",), record.limits[0] * compiled.dt)
            data["force_limit_episodes"] = (("pto",), record.limits[1])
            data["stroke_limit_time"] = (("pto",), record.limits[2] * compiled.dt)
            data["stroke_limit_episodes"] = (("pto",), record.limits[3])
        mean = record.stats[3] / count
        rms = np.sqrt(np.maximum(record.stats[1] / count - mean**2, 0.0))  # about the window's mean, as the metric
        data.update(by_pto_kind(rms, rotary, ("rms_pto_angle", "rms_pto_displacement"), ("pto",)))
        coords.update(_pto_coordinates(compiled))
    n_steps = compiled.n_steps
    report = compiled.controller.report() if compiled.device.ptos else {}
    attrs: dict[str, Any] = {
        "title": f"wecss simulation of {compiled.device.name}",
        "Conventions": "CF-1.10",
        "history": f"{_dt.datetime.now(_dt.UTC).isoformat(timespec='seconds')} wecss {__version__}: simulate "
        f"({scene.solver.method})",
        "wecss_version": __version__,
        "scene": scene.to_json(),
        "device": compiled.device.name,
        "solver": scene.solver.method,
        "time_step": compiled.dt,
        "n_steps": n_steps,
        "saved_every": scene.outputs.every,
        "statistics_window": scene.outputs.window,
        "radiation": str(compiled.radiation_summary),
        "controller": scene.controller.name,
        "controller_class": f"{type(compiled.controller).__module__}.{type(compiled.controller).__qualname__}",
        "controller_parameters": json.dumps(scene.controller.parameters),
        "controller_linear_gains_in_equations": int(compiled.linear_controller),
        "numba": int(JIT),
        "run_time_s": record.run_time,
        "steps_per_second": n_steps / record.run_time if record.run_time > 0 else float("inf"),
        "seed": scene.sea.seed,
        "notes": "; ".join(_notes(compiled, report, motion)) or "none",
        "rho": compiled.hydro.rho,
        "g": compiled.hydro.g,
        "moorings": json.dumps([m.to_dict() for m in compiled.device.moorings]) if compiled.device.moorings else "none",
    }
    attrs.update({f"controller_{k}": v for k, v in report.items()})
    attrs.update(record.solver)  # each run describes its own solver (and its radiation model where it has its own)
    attrs.update(sea_state_attrs(compiled))
    if closure is not None:
        attrs["loads_closure_residual"] = closure
    if compiled.radiation_fit is not None:  # the state-space fit's passivity and stability, where a user chose it
        report = compiled.radiation_fit.report.attrs
        attrs["radiation_fit_passivity_margin"] = float(report["passivity_margin"])
        attrs["radiation_fit_passive"] = int(report.get("passive", float(report["passivity_margin"]) >= 0))
        attrs["radiation_fit_stable"] = int(report["stable"])
        attrs["radiation_fit_repair"] = str(report["repair"])
    if pto_names and compiled.excitation is not None and compiled.excitation.omega.size:
        try:
            bound = power_bound_of(compiled)
        except ValueError as err:  # a reported quantity: the run stands without it, and says why
            note = f"no complex-conjugate power bound: {err}"
            attrs["notes"] = note if attrs["notes"] == "none" else f"{attrs['notes']}; {note}"
        else:
            data["power_bound"] = (("pto",), bound.per_pto)
            attrs["share_of_power_bound"] = float(np.sum(data["mean_pto_power"][1]) / bound.total)
    ds = xr.Dataset(data, coords=coords, attrs=attrs)
    return apply_attrs(ds)


def _add_loads(data: dict[str, Any], coords: dict[str, Any], compiled: CompiledScene, record: Record) -> float:
    """The ``loads`` group (see ``wecss.sim._loads``); returns the closure residual."""
    loads = recover_loads(
        compiled,
        record.q,
        record.v,
        record.a,
        (record.x, record.xd, record.f),
        _hydro_columns(record, record.rad + record.exc),
    )
    _loads_variables(data, coords, compiled, loads, ("time",), "")
    if record.spectral is not None and record.spectral.omega.size:  # amplitudes per wave frequency
        equilibrium, amplitudes = load_amplitudes(compiled, record.spectral)
        _loads_variables(data, coords, compiled, equilibrium, ("time",), "_equilibrium")
        for name, (dims, values) in list(data.items()):
            if name.endswith("_equilibrium"):
                data[name] = (dims[1:], values[0])
        _loads_variables(data, coords, compiled, amplitudes, ("omega",), "_amplitude")
        coords["omega"] = record.spectral.omega
    return loads.closure


def _loads_variables(
    data: dict[str, Any], coords: dict[str, Any], compiled: CompiledScene, loads: Loads, lead: tuple[str], suffix: str
) -> None:
    """The ``loads`` group's variables from ``loads`` (leading dimension ``lead``), names ending in ``suffix``."""
    joint, pto, spot = ("joint", "axis"), ("pto", "pto_end", "axis"), ("hot_spot", "section_axis")
    data[f"joint_reaction_force{suffix}"] = ((*lead, *joint), loads.joint_force)
    data[f"joint_reaction_moment{suffix}"] = ((*lead, *joint), loads.joint_moment)
    data[f"joint_reaction_force_local{suffix}"] = ((*lead, *joint), loads.joint_force_local)
    data[f"joint_reaction_moment_local{suffix}"] = ((*lead, *joint), loads.joint_moment_local)
    coords["joint"] = [j.name for j in compiled.device.model.ordered_joints]
    coords["axis"] = ["x", "y", "z"]
    if compiled.device.ptos:
        data[f"pto_end_force{suffix}"] = ((*lead, *pto), loads.pto_body_force)
        data[f"pto_end_moment{suffix}"] = ((*lead, *pto), loads.pto_body_moment)
        coords["pto_end"] = ["a", "b"]
    if loads.section.shape[1]:  # the device's members: section loads and stresses at their hot spots
        members = compiled.device.members
        coords["hot_spot"] = hot_spot_names(members)
        coords["section_axis"] = ["x", "y", "z"]
        data[f"section_force{suffix}"] = ((*lead, *spot), loads.section[..., :3])
        data[f"section_moment{suffix}"] = ((*lead, *spot), loads.section[..., 3:])
        for key, values in hot_spot_stresses(members, loads.section).items():
            data[f"{key}_stress{suffix}"] = ((*lead, "hot_spot"), values)


def power_bound_of(compiled: CompiledScene) -> PowerBound:
    """The complex-conjugate bound of the scene's wave components on its open plant (the exact frequency-domain
    model; ``wecss.control.power_bound``), which every result in waves reports with its share of it."""
    assert compiled.excitation is not None
    exc = compiled.excitation
    return power_bound(compiled.control_context.linear_model(), exc.omega, exc.coefficients)
