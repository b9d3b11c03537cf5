"""Device specs: a declarative description (TOML file or dict) of bodies, joints, PTOs, the hydrodynamic
database and the assumptions behind every number, turned into a :class:`Device`.

Spec layout (TOML; the same keys as a dict)::

    name = "m4-111"
    description = "..."
    hydro = "m4-111"            # shipped database name, or a path (relative to the spec file); optional
    [hydro_options]             # keywords of the reader of a BEM output file (HydroData.from_capytaine, from_wamit,
                                # from_bemio): center_of_mass = {body = [x, y, z]}, displaced_volume, added_mass_inf,
                                # repair, ...; optional
    [assumptions]               # free text: what was assumed and why
    hinge_height = "0.25 m above still water ..."
    [[bodies]]                  # name, mass [kg], inertia [kg m^2] (3 diagonal values or 3x3 about the CoM),
    name = "float_1"            # center_of_mass [m] (world, reference configuration), hydro_body (optional),
    ...                         # modes (optional): the body's generalised modes, one generalised coordinate each
                                # (<body>__<name>, dimensionless; the database's DOF <hydro_body>__<name> acts on
                                # it), as a list [{name = "flex1", mass [kg m^2], stiffness [N m], damping
                                # [N m s]}] or a table {names = [...], mass, stiffness, damping} of matrices or
                                # diagonals (wecss.multibody.GeneralisedModes);
                                # flexible (optional): the body's members are its structural model, reduced for the
                                # floating frame (wecss.devices.Flexible): {modes = 6 (fixed-interface normal
                                # modes), damping_ratio = 0.0, elements = 8 (per member), theory = "euler-bernoulli" |
                                # "timoshenko", clamp = [x, y, z] (default: the parent joint's point),
                                # inertia_relief = true, centrifugal = false}
    [[joints]]                  # name, kind, child, parent (omit for the base), axis, point [m], label,
                                # damping (the joint's own viscous loss, revolute/prismatic [N m s/rad, N s/m])
    ...
    [[ptos]]                    # kind = "joint" (joint, rest) or "actuator" (body_a, point_a, body_b, point_b,
    ...                         # rest_length); damping, stiffness, force_limit, stroke_limit,
                                # end_stop_stiffness, end_stop_damping (an end stop beyond the stroke limit)
    [[members]]                 # beam members for stress recovery (optional): name, body, start, end [m] (world,
    ...                         # reference configuration), section = {kind = "tube", outer_diameter, thickness} |
                                # {kind = "box", width, height, thickness} | {kind = "given", area, iy, iz, wy, wz, wt,
                                # and optionally torsion_constant [m^4], shear_area_y, shear_area_z [m^2]},
                                # hot_spots = [{name, at [m from start], y, z [m on the section], scf}],
                                # body_mass = "centre" (default) | "along" (the body's mass spread along the member),
                                # material = "S355" | {E [Pa], G [Pa] or nu, density [kg/m^3]} (needed on a flexible
                                # body), nonstructural_mass [kg/m] (mass on the axis beyond density x area)
    [[masses]]                  # lumped masses of a flexible body's structural model (optional): name, body, point
    ...                         # [m] (its centre), mass [kg], inertia [kg m^2] about its centre (3 or 3x3)
    [[moorings]]                # a linear mooring (optional): body, stiffness = {Surge = k, ...} [N/m, N m/rad],
    ...                         # damping = {Surge = c, ...} [N s/m, N m s/rad], about the body's centre of mass
                                # (world axes), slack in the reference configuration (wecss.multibody.Mooring)
    [[drag]]                    # viscous drag on a body's DOFs, body axes (optional; acts with the scene's
    ...                         # hydrodynamics.drag): body, coefficient = {Heave = c} [N s^2/m^2, N m s^2/rad^2]
                                # and/or cd = {Heave = 1.0} with area = {Heave = A} [m^2] (c = rho Cd A / 2), linear
                                # = {Heave = b} [N s/m, N m s/rad] (wecss.multibody.BodyDrag)
    [[morison]]                 # a Morison cylinder (optional; with hydrodynamics.drag): body, start, end [m] (world,
    ...                         # reference configuration), diameter [m], cd, ca (default 1), segments (default 10)
    [[meshes]]                  # a body's surface mesh (optional; for the scene's body-exact hydrodynamics): body,
    ...                         # stl (path), position, scale, open_above; or geometry (a BEM geometry file) and
                                # freeboard [m], panel_size, sectors (wecss.devices._meshes)
"""

from __future__ import annotations

import math
import tomllib
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from ..multibody import ActuatorPTO, Body, BodyDrag, Joint, JointPTO, Mooring, MorisonElement, Multibody
from ..tomlfile import read_toml

_TOP_KEYS = {
    "name", "description", "hydro", "hydro_options", "assumptions", "bodies", "joints", "ptos", "members", "moorings",
    "drag", "morison", "meshes", "masses",
}  # fmt: skip
_BODY_KEYS = {"name", "mass", "inertia", "center_of_mass", "hydro_body", "modes", "flexible"}
_JOINT_KEYS = {"name", "kind", "child", "parent", "axis", "point", "label", "damping"}
_LIMIT_KEYS = {"force_limit", "stroke_limit", "end_stop_stiffness", "end_stop_damping"}
_JOINT_PTO_KEYS = {"name", "kind", "joint", "damping", "stiffness", "rest", *_LIMIT_KEYS}
_ACTUATOR_KEYS = {
    "name", "kind", "body_a", "point_a", "body_b", "point_b", "damping", "stiffness", "rest_length", *_LIMIT_KEYS,
}  # fmt: skip


class DeviceSpecError(ValueError):
    """A device spec is malformed (unknown or missing keys, bad values)."""


#: The spec's numeric fields: a finite number or a list of finite numbers.
_NUMERIC_KEYS = {
    "mass", "inertia", "center_of_mass", "axis", "point", "damping", "stiffness", "rest", "rest_length",
    "point_a", "point_b", *_LIMIT_KEYS,
}  # fmt: skip


def _check_numbers(where: str, entry: Mapping[str, Any]) -> None:
    """Refuse a numeric field (:data:`_NUMERIC_KEYS`) of ``entry`` that is not a finite number or a (nested) list of
    finite numbers (an inertia may be 3 x 3); the message names the field and the value (the bodies, joints and PTOs
    check the ranges and shapes)."""
    for key in sorted(_NUMERIC_KEYS & set(entry)):
        value = entry[key]
        items = _flattened(value)
        numbers = bool(items) and all(isinstance(x, int | float) and not isinstance(x, bool) for x in items)
        if not (numbers and all(math.isfinite(x) for x in items)):
            raise DeviceSpecError(f"{where}: {key} = {value!r}: expected a finite number or a list of finite numbers")


def _flattened(value: Any) -> list[Any]:
    """The leaves of nested lists (a value that is not a list: itself)."""
    if not isinstance(value, list):
        return [value]
    return [leaf for item in value for leaf in _flattened(item)]


def _check_keys(where: str, entry: Mapping[str, Any], allowed: set[str], required: set[str]) -> None:
    unknown = sorted(set(entry) - allowed)
    if unknown:
        raise DeviceSpecError(f"{where}: unknown keys {unknown}; accepted: {sorted(allowed)}")
    missing = sorted(required - set(entry))
    if missing:
        raise DeviceSpecError(f"{where}: missing keys {missing}")


def read_spec(source: str | Path | Mapping[str, Any]) -> tuple[dict[str, Any], Path | None]:
    """Return the spec as a dict and the folder relative paths are taken from (None for a dict).

    Raises
    ------
    FileNotFoundError
        If a path does not exist.
    DeviceSpecError
        If the TOML cannot be parsed.
    """
    if isinstance(source, Mapping):
        return dict(source), None
    path = Path(source)
    if not path.is_file():
        raise FileNotFoundError(f"no device spec at {str(path)!r}")
    try:
        return read_toml(path), path.parent
    except tomllib.TOMLDecodeError as err:
        raise DeviceSpecError(f"{path}: {err}") from None
    except UnicodeDecodeError as err:
        raise DeviceSpecError(
            f"{path}: not a text file (byte {err.start} is {err.object[err.start : err.start + 1]!r}, not UTF-8); "
            "a device spec is a UTF-8 TOML file"
        ) from None


def hydro_source(spec: Mapping[str, Any], folder: Path | None) -> str | None:
    """The database a spec names: a catalogue name as written, a file path resolved against the spec's folder."""
    hydro = spec.get("hydro")
    if hydro is not None and folder is not None and ("/" in hydro or hydro.endswith((".nc", ".out", ".h5"))):
        return str((folder / hydro).resolve())
    return hydro


def spec_inputs(path: str | Path) -> dict[str, Path]:
    """The files a device built from the spec file ``path`` is read from, each under what it is: the spec and, when
    it names them, its database file (``hydro``) and its mesh files (``meshes[i].stl``, ``meshes[i].geometry``);
    resolved paths.

    Raises
    ------
    FileNotFoundError
        If the spec does not exist.
    DeviceSpecError
        If the TOML cannot be parsed.
    """
    spec, folder = read_spec(path)
    hydro = hydro_source(spec, folder)
    files = {"device spec": Path(path).resolve()}
    if hydro is not None and Path(hydro).is_file():
        files["hydrodynamic database named by the device spec (hydro)"] = Path(hydro)
    meshes = spec.get("meshes", [])
    for i, entry in enumerate(meshes if isinstance(meshes, list) else []):
        for key in ("stl", "geometry"):
            value = entry.get(key) if isinstance(entry, Mapping) else None
            if isinstance(value, str) and folder is not None and (folder / value).is_file():
                files[f"mesh file of the device spec (meshes[{i}].{key})"] = (folder / value).resolve()
    return files


def spec_files(path: str | Path) -> tuple[Path, ...]:
    """The files a device built from the spec file ``path`` is read from (:func:`spec_inputs`, for a cache that
    must see any change).

    Raises
    ------
    FileNotFoundError
        If the spec does not exist.
    DeviceSpecError
        If the TOML cannot be parsed.
    """
    return tuple(spec_inputs(path).values())


def build_model(spec: Mapping[str, Any]) -> tuple[Multibody, tuple[JointPTO | ActuatorPTO, ...]]:
    """The multibody tree and PTOs of a spec.

    Raises
    ------
    DeviceSpecError
        On unknown or missing keys, or values the bodies, joints and PTOs reject (the message says where).
    """
    _check_keys("device spec", spec, _TOP_KEYS, {"name", "bodies", "joints"})
    name = spec["name"]
    bodies = []
    for k, entry in enumerate(spec["bodies"]):
        where = f"device {name!r}, bodies[{k}]"
        _check_keys(where, entry, _BODY_KEYS, {"name", "mass", "inertia", "center_of_mass"})
        _check_numbers(where, entry)
        try:
            bodies.append(Body(**{k: v for k, v in entry.items() if k != "flexible"}))
        except (TypeError, ValueError) as err:
            raise DeviceSpecError(f"{where}: {err}") from None
    joints = []
    for k, entry in enumerate(spec["joints"]):
        where = f"device {name!r}, joints[{k}]"
        _check_keys(where, entry, _JOINT_KEYS, {"name", "kind", "child"})
        _check_numbers(where, entry)
        try:
            joints.append(Joint(**entry))
        except (TypeError, ValueError) as err:
            raise DeviceSpecError(f"{where}: {err}") from None
    try:
        model = Multibody(bodies, joints)
    except ValueError as err:
        raise DeviceSpecError(f"device {name!r}: {err}") from None
    ptos: list[JointPTO | ActuatorPTO] = []
    for k, entry in enumerate(spec.get("ptos", [])):
        where = f"device {name!r}, ptos[{k}]"
        kind = entry.get("kind")
        fields = {key: value for key, value in entry.items() if key != "kind"}
        _check_numbers(where, entry)
        try:
            if kind == "joint":
                _check_keys(where, entry, _JOINT_PTO_KEYS, {"name", "kind", "joint"})
                joint_pto = JointPTO(**fields)
                joint = model.joint(joint_pto.joint)
                if joint.kind not in ("revolute", "prismatic"):
                    raise ValueError(
                        f"joint {joint_pto.joint!r} is {joint.kind}; a joint PTO needs a revolute or prismatic joint"
                    )
                pto: JointPTO | ActuatorPTO = joint_pto
            elif kind == "actuator":
                _check_keys(where, entry, _ACTUATOR_KEYS, {"name", "kind", "point_a", "point_b"})
                fields.setdefault("body_a", None)
                fields.setdefault("body_b", None)
                for side in ("body_a", "body_b"):
                    if fields[side] is not None:
                        model.body(fields[side])
                pto = ActuatorPTO(**fields)
            else:
                raise ValueError(f"kind must be 'joint' or 'actuator'; got {kind!r}")
        except (TypeError, ValueError) as err:
            raise DeviceSpecError(f"{where}: {err}") from None
        ptos.append(pto)
    names = [p.name for p in ptos]
    if len(set(names)) != len(names):
        raise DeviceSpecError(f"device {name!r}: duplicate PTO names {names}")
    return model, tuple(ptos)


def build_moorings(spec: Mapping[str, Any], model: Multibody) -> tuple[Mooring, ...]:
    """The spec's ``[[moorings]]`` (empty when it has none).

    Raises
    ------
    DeviceSpecError
        On unknown or missing keys, unknown bodies or DOFs, bad values (the message says which entry).
    """
    entries = spec.get("moorings", [])
    if not isinstance(entries, list):
        raise DeviceSpecError(f"device {spec['name']!r}: moorings must be a list of tables ([[moorings]])")
    out = []
    for k, entry in enumerate(entries):
        where = f"device {spec['name']!r}, moorings[{k}]"
        try:
            mooring = Mooring.from_spec(entry)
            model.body(mooring.body)
        except (TypeError, ValueError) as err:
            raise DeviceSpecError(f"{where}: {err}") from None
        out.append(mooring)
    return tuple(out)


def build_viscous(spec: Mapping[str, Any], model: Multibody) -> tuple[tuple[BodyDrag, ...], tuple[MorisonElement, ...]]:
    """The spec's ``[[drag]]`` and ``[[morison]]`` entries (empty when it has none).

    Raises
    ------
    DeviceSpecError
        On unknown or missing keys, unknown bodies, bad values, or two drag entries on one body (the message says
        which entry).
    """
    out: dict[str, list[Any]] = {"drag": [], "morison": []}
    for key, kind in (("drag", BodyDrag), ("morison", MorisonElement)):
        entries = spec.get(key, [])
        if not isinstance(entries, list):
            raise DeviceSpecError(f"device {spec['name']!r}: {key} must be a list of tables ([[{key}]])")
        for k, entry in enumerate(entries):
            where = f"device {spec['name']!r}, {key}[{k}]"
            if not isinstance(entry, Mapping):
                raise DeviceSpecError(f"{where}: must be a table; got {entry!r}")
            try:
                item = kind.from_spec(entry)
                model.body(item.body)
            except (TypeError, ValueError, KeyError) as err:
                raise DeviceSpecError(f"{where}: {err}") from None
            out[key].append(item)
    bodies = [d.body for d in out["drag"]]
    twice = sorted({b for b in bodies if bodies.count(b) > 1})
    if twice:
        raise DeviceSpecError(f"device {spec['name']!r}: more than one [[drag]] entry for bodies {twice}")
    return tuple(out["drag"]), tuple(out["morison"])
