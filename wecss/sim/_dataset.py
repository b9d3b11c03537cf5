"""The result Dataset of a run, built from its :class:`Record` by the output table (``wecss.outputs``).

Every row of the table whose group the scene asks for (and every statistic) becomes a variable, made from its
quantity (``_quantities``) and split by its kind: ``dof_linear`` / ``dof_angular`` / ``dof_generalised`` for the
generalised coordinates, ``hydro_dof_*`` for the hydrodynamic DOFs (bodies in the device spec's order), one
variable per PTO kind over the ``pto`` dimension (NaN for the PTOs of the other kind, absent when the device has
none of that kind), so ``ds.pto_angle * ds.pto_power`` stays (time, pto). Only the groups the scene's outputs ask
for are present; statistics over the final window are always there. A streamed run builds its time series part by
part with :func:`series_variables` and the rest at the end with :func:`statistics_dataset`.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import xarray as xr

from ..attributes import apply_attrs
from ..control import ControlledScene
from ..outputs import STREAMED_GROUPS, Variable, variables_of
from ._attrs import result_attrs
from ._guards import DriftCheck, motion_notes
from ._layout import columns, hydro_kinds, rotary_ptos, velocity_kinds
from ._quantities import Quantities
from ._record import Record
from ._sections import hot_spot_names


def output_groups(controlled: ControlledScene) -> set[str]:
    """The output groups a run of ``controlled`` keeps (none for a statistics-only run)."""
    outputs = controlled.scene.outputs
    return set() if outputs.statistics_only else set(outputs.variables)


def _dof_columns(qs: Quantities, dim: str) -> tuple[np.ndarray, np.ndarray]:
    """Kinds and names of the columns of a variable on the kind dimension ``dim``."""
    controlled = qs.controlled
    if dim.startswith("hydro_dof"):
        stored = qs.stored_hydro
        return hydro_kinds(controlled)[stored], np.array(controlled.hydro.dofs)[stored]
    return velocity_kinds(controlled), np.array(controlled.device.model.velocity_names)


def _coordinate(qs: Quantities, dim: str) -> Any:
    """The values of the coordinate ``dim`` (the kind dimensions are set where their variables are made)."""
    controlled = qs.controlled
    fixed: dict[str, Any] = {"axis": ["x", "y", "z"], "section_axis": ["x", "y", "z"], "pto_end": ["a", "b"]}
    if dim in fixed:
        return fixed[dim]
    if dim == "time":
        return qs.record.time
    if dim == "pto":
        return [p.name for p in controlled.device.ptos]
    if dim == "body":
        return list(controlled.device.model.body_names)
    if dim == "joint":
        return [j.name for j in controlled.device.model.ordered_joints]
    if dim == "hot_spot":
        return hot_spot_names(controlled.device.members)
    if dim == "fibre_point":
        return list(qs.get("fibre_field").names)
    if dim == "omega":
        return qs.record.spectral.omega
    if dim == "probe":
        names = controlled.scene.outputs.probe_names
        return list(names) if names is not None else np.arange(len(controlled.scene.outputs.probe_points))
    raise KeyError(f"no coordinate for dimension {dim!r}")


def _select(qs: Quantities, v: Variable, values: np.ndarray, coords: dict[str, Any]) -> np.ndarray | None:
    """The part of ``values`` the variable ``v`` keeps (its ``kind``), or None when it keeps nothing."""
    if v.kind is None:
        return values
    if "pto" not in v.dims:  # a DOF kind, on its kind's dimension
        dim = v.dims[1]
        kinds, names = _dof_columns(qs, dim)
        mask = kinds == v.kind
        if not mask.any():
            return None
        coords[dim] = list(names[mask])
        return values[:, columns(mask)]
    rotary = rotary_ptos(qs.controlled)  # a PTO kind, over every PTO
    mask = rotary if v.kind == "rotary" else ~rotary
    if mask.all():
        return values
    return np.where(mask, values, np.nan) if mask.any() else None


def _add(qs: Quantities, rows: tuple[Variable, ...], data: dict[str, Any], coords: dict[str, Any]) -> None:
    """The variables of ``rows`` (with their spectral forms where the run has them) into ``data``, their
    coordinates into ``coords``."""
    n_t = qs.record.time.size
    for v in rows:
        if v.dims[0] == "time" and not n_t:
            continue
        values = qs.get(v.quantity)
        if values is None:
            continue
        selected = _select(qs, v, values, coords)
        if selected is None:
            continue
        data[v.name] = (v.dims, selected)
        equilibrium, amplitudes = qs.spectral(v.quantity) if v.spectral else (None, None)
        if equilibrium is not None:
            data[f"{v.name}_equilibrium"] = (v.dims[1:], equilibrium[0])
        if amplitudes is not None:
            data[f"{v.name}_amplitude"] = (("omega", *v.dims[1:]), amplitudes)
    used = dict.fromkeys(dim for dims, _ in data.values() for dim in dims)  # in the order of first use
    for dim in used:
        if dim not in coords:  # (a set here gave the file's coordinates an order that changed from run to run)
            coords[dim] = _coordinate(qs, dim)
    if "pto" in used:
        coords["pto_kind"] = ("pto", list(qs.controlled.pto_kinds))
    if "probe" in used:
        probes = np.array(qs.controlled.scene.outputs.probe_points, dtype=float).reshape(-1, 2)
        coords["probe_x"] = ("probe", probes[:, 0])
        coords["probe_y"] = ("probe", probes[:, 1])


def series_variables(
    controlled: ControlledScene,
    record: Record,
    elevation: np.ndarray | None = None,
    elevation_probe: np.ndarray | None = None,
) -> tuple[dict[str, Any], dict[str, Any], tuple[np.ndarray, np.ndarray] | None]:
    """The time-series variables of the streamed output groups and their coordinates, and the poses when they were
    computed (for the notes). ``elevation``, ``elevation_probe``: the ``elevation`` and ``elevation_probe``
    quantities at ``record.time`` when the caller has them (:func:`elevation_series`, :func:`probe_series`)."""
    groups = output_groups(controlled) & set(STREAMED_GROUPS)
    qs = Quantities(controlled, record, elevation, elevation_probe=elevation_probe)
    data: dict[str, Any] = {}
    coords: dict[str, Any] = {}
    if record.time.size and groups:
        coords["time"] = record.time
    _add(qs, tuple(v for v in variables_of(groups) if v.group != "statistics"), data, coords)
    return data, coords, qs._values.get("poses")


def build_result(controlled: ControlledScene, record: Record, drift: DriftCheck | None = None) -> xr.Dataset:
    """The Dataset of a run from its record (see the module docstring); ``drift``: a re-run at half the step that
    splits a drift into its numerical and physical parts in the notes (``wecss.sim._drift_check``)."""
    groups = output_groups(controlled)
    qs = Quantities(controlled, record)
    data: dict[str, Any] = {}
    coords: dict[str, Any] = {}
    if record.time.size and groups:
        coords["time"] = record.time
    _add(qs, variables_of(groups), data, coords)
    motion = motion_notes(controlled, record["q"], qs._values.get("poses"), drift)
    return _finish(qs, data, coords, motion)


def statistics_dataset(controlled: ControlledScene, record: Record, motion: list[str]) -> xr.Dataset:
    """What :func:`build_result` adds to the time series: the statistics over the final window, the limits'
    counts, the power bound and the attributes (``motion``: the notes on the record's motion, from
    ``MotionSummary``); ``record`` needs only its ``stats``, ``limits``, ``run_time`` and ``solver``."""
    qs = Quantities(controlled, record)
    data: dict[str, Any] = {}
    coords: dict[str, Any] = {}
    _add(qs, variables_of(set()), data, coords)
    return _finish(qs, data, coords, motion)


def _finish(qs: Quantities, data: dict[str, Any], coords: dict[str, Any], motion: list[str]) -> xr.Dataset:
    """The Dataset of ``data`` with the run's attributes."""
    loads = qs._values.get("loads")
    attrs = result_attrs(
        qs.controlled,
        qs.record,
        motion,
        later_notes=qs.notes,
        mean_power=None if "mean_pto_power" not in data else data["mean_pto_power"][1],
        bound=None
        if "power_bound_spectral" not in data
        else (data["power_bound"][1] if "power_bound" in data else None, data["power_bound_spectral"][1]),
        closure=None if loads is None else loads.closure,
    )
    return apply_attrs(xr.Dataset(data, coords=coords, attrs=attrs))
