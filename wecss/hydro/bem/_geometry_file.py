"""Geometry files: a TOML description of floats, frequencies, water and mesh, read into a :class:`BEMSpec`.

Layout (every key is checked; unknown keys are errors)::

    name = "m4-111"
    description = "..."

    [water]          rho = 1000.0, g = 9.81, depth = inf
    [frequencies]    start, stop, step [rad/s]; zero = true (omega = 0, deep water only)
    [waves]          directions_deg = [0.0]
    [mesh]           panel_size [m] (along the meridian), aspect_ratio (panel width / height, default 3); lid = true
    [solver]         method = "direct" (or "indirect": Capytaine's boundary integral equation)

    [float_types.<type>]    any body key below, shared by the floats that name this type
    [[bodies]]              name, type (optional), x, y [m] and any body key:
        diameter [m], bottom ("flat", "hemispherical", "rounded", "conical"), fillet_radius [m],
        cone_height [m], draft [m] (default: from mass = rho * volume), mass [kg] (default: rho * volume),
        center_of_mass_z [m], inertia = [Ixx, Iyy, Izz] about the centre of mass [kg m^2],
        dofs = ["Surge", "Heave", "Pitch"]
"""

from __future__ import annotations

import math
import os
import tomllib
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from ...tomlfile import read_toml
from ._mesh import DEFAULT_ASPECT_RATIO
from ._profile import AxisymmetricProfile
from ._spec import BEMSpec, FloatBody, omega_grid

_TOP_KEYS = {"name", "description", "water", "frequencies", "waves", "mesh", "solver", "float_types", "bodies"}
_SOLVER_KEYS = {"method"}
_WATER_KEYS = {"rho", "g", "depth"}
_FREQUENCY_KEYS = {"start", "stop", "step", "zero"}
_WAVE_KEYS = {"directions_deg"}
_MESH_KEYS = {"panel_size", "aspect_ratio", "lid"}
_BODY_KEYS = {
    "diameter", "bottom", "fillet_radius", "cone_height", "draft", "mass", "center_of_mass_z", "inertia", "dofs",
}  # fmt: skip
_PLACED_KEYS = {"name", "type", "x", "y"}


class GeometryFileError(ValueError):
    """A geometry file is malformed: the message names the file, the table and the key."""


def read_geometry(path: str | os.PathLike[str]) -> BEMSpec:
    """Read a geometry file (TOML, layout in the module docstring) into a :class:`BEMSpec`.

    Parameters
    ----------
    path : path-like
        The ``.toml`` file.

    Returns
    -------
    BEMSpec
        With ``name`` from the file (default: the file's stem).

    Raises
    ------
    FileNotFoundError
        If the file does not exist.
    GeometryFileError
        If the TOML is invalid, a table or key is unknown or missing, or a value is rejected (the message
        says where and why).
    """
    file = Path(path)
    if not file.is_file():
        raise FileNotFoundError(f"no geometry file at {str(file)!r}")
    try:
        data = read_toml(file)
    except tomllib.TOMLDecodeError as err:
        raise GeometryFileError(f"{file.name}: invalid TOML: {err}") from None
    where = file.name
    _check(data, _TOP_KEYS, where)
    water = _table(data, "water", _WATER_KEYS, where)
    freq = _table(data, "frequencies", _FREQUENCY_KEYS, where)
    waves = _table(data, "waves", _WAVE_KEYS, where)
    mesh = _table(data, "mesh", _MESH_KEYS, where)
    solver = _table(data, "solver", _SOLVER_KEYS, where)
    rho = float(water.get("rho", 1000.0))
    g = float(water.get("g", 9.81))
    depth = float(water.get("depth", math.inf))
    types = data.get("float_types", {})
    if not isinstance(types, Mapping):
        raise GeometryFileError(f"{where}: [float_types] must be a table of tables")
    bodies_data = data.get("bodies")
    if not isinstance(bodies_data, list) or not bodies_data:
        raise GeometryFileError(f"{where}: needs at least one [[bodies]] table")
    try:
        bodies = tuple(_body(entry, types, rho, f"{where} [[bodies]] #{k + 1}") for k, entry in enumerate(bodies_data))
        omega = omega_grid(
            float(_need(freq, "start", where)), float(_need(freq, "stop", where)), float(_need(freq, "step", where))
        )
        directions = tuple(math.radians(float(d)) for d in waves.get("directions_deg", [0.0]))
        return BEMSpec(
            bodies=bodies,
            omega=omega,
            panel_size=float(_need(mesh, "panel_size", where)),
            panel_aspect_ratio=float(mesh.get("aspect_ratio", DEFAULT_ASPECT_RATIO)),
            water_depth=depth,
            rho=rho,
            g=g,
            wave_directions=directions,
            lid=bool(mesh.get("lid", True)),
            zero_frequency=bool(freq.get("zero", math.isinf(depth))),
            method=str(solver.get("method", "direct")),
            name=str(data.get("name", file.stem)),
        )
    except GeometryFileError:
        raise
    except (TypeError, ValueError) as err:
        raise GeometryFileError(f"{where}: {err}") from None


def _body(entry: Any, types: Mapping[str, Any], rho: float, where: str) -> FloatBody:
    if not isinstance(entry, Mapping):
        raise GeometryFileError(f"{where}: must be a table")
    _check(entry, _BODY_KEYS | _PLACED_KEYS, where)
    values: dict[str, Any] = {}
    if "type" in entry:
        kind = entry["type"]
        if kind not in types:
            raise GeometryFileError(f"{where}: unknown float type {kind!r}; defined: {', '.join(types) or 'none'}")
        _check(types[kind], _BODY_KEYS, f"{where} (type {kind!r})")
        values.update(types[kind])
    values.update({k: v for k, v in entry.items() if k != "type"})
    name = str(_need(values, "name", where))
    where = f"{where} ({name!r})"
    radius = float(_need(values, "diameter", where)) / 2
    bottom = values.get("bottom", "flat")
    shape = {
        "fillet_radius": float(values.get("fillet_radius", 0.0)),
        "cone_height": float(values.get("cone_height", 0.0)),
    }
    mass = values.get("mass")
    try:
        if "draft" in values:
            profile = AxisymmetricProfile(radius, float(values["draft"]), bottom, **shape)
        elif mass is not None:
            profile = AxisymmetricProfile.with_volume(float(mass) / rho, radius=radius, bottom=bottom, **shape)
        else:
            raise GeometryFileError(
                f"{where}: give 'draft' or 'mass' (the draft then follows from mass = rho * volume)"
            )
        return FloatBody(
            name=name,
            profile=profile,
            center_of_mass_z=float(_need(values, "center_of_mass_z", where)),
            inertia=tuple(_need(values, "inertia", where)),
            position=(float(values.get("x", 0.0)), float(values.get("y", 0.0))),
            mass=None if mass is None else float(mass),
            dofs=tuple(values.get("dofs", ("Surge", "Heave", "Pitch"))),
        )
    except GeometryFileError:
        raise
    except (TypeError, ValueError) as err:
        raise GeometryFileError(f"{where}: {err}") from None


def _check(table: Mapping[str, Any], accepted: set[str], where: str) -> None:
    unknown = sorted(set(table) - accepted)
    if unknown:
        raise GeometryFileError(f"{where}: unknown keys {unknown}; accepted: {sorted(accepted)}")


def _table(data: Mapping[str, Any], name: str, accepted: set[str], where: str) -> Mapping[str, Any]:
    table = data.get(name, {})
    if not isinstance(table, Mapping):
        raise GeometryFileError(f"{where}: [{name}] must be a table")
    _check(table, accepted, f"{where} [{name}]")
    return table


def _need(table: Mapping[str, Any], key: str, where: str) -> Any:
    if key not in table:
        raise GeometryFileError(f"{where}: missing key {key!r}")
    return table[key]
