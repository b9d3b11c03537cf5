"""A run made again from its result file (``wecss run --from RESULT.nc``): the recorded scene, its input files
found and checked against their SHA-256 (``wecss.provenance``), and the controller that ran, made again from its
registered name and recorded parameters (a class recorded under the built-in controllers' former package name,
``controllers``, is read under its name now, ``wecss_controllers``, with a note)."""

from __future__ import annotations

import dataclasses
import json
import os
from collections.abc import Mapping
from pathlib import Path

import numpy as np

from ..compiled import SHIPPED_DATA_DIR
from ..control import ENTRY_POINT_GROUP, UNREGISTERED, ControlledScene, controller_attrs, create, registered_name
from ..netcdf import global_attributes
from ..plugins import entry_points
from ..provenance import INPUTS_ATTR, find_inputs
from ..scene import ControllerChoice, Scene
from ._attrs import FIT_ATTR, fit_digest

SCENE_PATH_FIELDS = {
    ("device", "name"): "device spec of device.name",
    ("device", "hydro"): "hydrodynamic database (device.hydro)",
    ("sea", "file"): "(sea.file)",
}
"""The scene fields that may hold a file's path, each with the end of the field of its input record
(``wecss.compiled.recorded_inputs``)."""


RENAMED_MODULES: dict[str, str] = {"controllers": "wecss_controllers"}
"""Top-level modules of registered controllers renamed since results recorded them (``controller_class``): the
built-in controllers imported as ``controllers`` before issue 31, a name that collided with any user folder called
``controllers`` on ``sys.path``."""


def renamed_class(recorded: str) -> tuple[str, str | None]:
    """The class path a result's ``controller_class`` stands for now (``controllers._damping.LinearDamping`` ->
    ``wecss_controllers._damping.LinearDamping``), and a note saying so (None when the name did not change)."""
    top, dot, rest = recorded.partition(".")
    if not dot or top not in RENAMED_MODULES:
        return recorded, None
    now = f"{RENAMED_MODULES[top]}.{rest}"
    return now, (
        f"the run's controller class {recorded} is read as {now} (the built-in controllers' package was renamed "
        f"from {top!r} to {RENAMED_MODULES[top]!r})"
    )


def _is_path(key: str, value: object) -> bool:
    """Whether a scene value names a file (``sea.file`` always; a device or database when it looks like a path),
    not a catalogue or shipped name (as ``Scene.from_dict`` decides)."""
    return isinstance(value, str) and (key == "file" or "/" in value or value.endswith((".toml", ".nc", ".out")))


def scene_from_result(path: str | os.PathLike[str]) -> tuple[Scene, list[str]]:
    """The scene that makes the run of the result file ``path`` again, and what was found on the way (inputs
    moved beside the result, a result that records no checksums).

    Every input file the result records must have its recorded SHA-256, where the run read it or at its path
    relative to the result (a folder moved as a whole); the scene's paths then point at the files found. A
    controller given to ``simulate`` becomes the scene's ``controller`` section when its class is registered
    (``wecss.controllers`` entry points) and its parameters were recorded.

    Raises
    ------
    FileNotFoundError
        If there is no file at ``path``.
    ValueError
        If the file is not a complete wecss result; if an input file changed or is missing
        (``wecss.provenance.InputChangedError``: the file and both SHA-256); if the controller that ran cannot be
        made again by name (the message names its class and parameters).
    """
    if not Path(path).is_file():
        raise FileNotFoundError(f"no result file at {str(path)!r}")
    attrs = global_attributes(path)
    if "scene" not in attrs:
        raise ValueError(f"{str(path)!r} is not a wecss result (no 'scene' attribute): nothing to run again")
    if "run_status" in attrs:
        raise ValueError(f"{str(path)!r} is a partial result ({attrs['run_status']}); run its scene again instead")
    found: list[str] = []
    if INPUTS_ATTR not in attrs:
        found.append(
            f"{str(path)!r} records no input files (made before wecss recorded them): its inputs are not checked"
        )
    data = json.loads(str(attrs["scene"]))
    inputs = find_inputs(attrs, path, SHIPPED_DATA_DIR)
    for (section, key), ending in SCENE_PATH_FIELDS.items():
        value = data.get(section, {}).get(key)
        checked = next((f for f in inputs if f.field.endswith(ending)), None)
        # the scene's path may be relative to the folder the run was made in: it then points at the checked file
        if checked is not None and _is_path(key, value):
            data[section][key] = str(checked.found)
    found += [f"the {f.field} was not at {str(f.recorded)!r}; found at {str(f.found)!r}" for f in inputs if f.moved]
    scene = Scene.from_dict(data)
    if attrs.get("controller_source", "scene") != "scene":
        scene = dataclasses.replace(scene, controller=_given_controller(attrs, scene.controller.dt))
    elif "controller_class" in attrs:
        _same_class(scene.controller.name, str(attrs["controller_class"]))
    note = renamed_class(str(attrs.get("controller_class", "")))[1]
    return scene, found + ([] if note is None else [note])


def fit_difference(attrs: Mapping[str, object], controlled: ControlledScene) -> str | None:
    """What differs between the radiation fit a result records (``radiation_fit_sha256``) and the fit of
    ``controlled`` (its scene compiled again), or None. A fit is made again from the (checked) database when the
    cache does not hold it, or a damaged cache entry was replaced: its matrices may then differ in their last bits."""
    recorded = attrs.get(FIT_ATTR)
    now = fit_digest(controlled)
    if not recorded or recorded == now:
        return None
    return (
        f"the radiation fit differs from the run's (SHA-256 of its matrices {now or 'none'}, the run's {recorded}): "
        "it was made again or replaced in the fit cache; the results may differ"
    )


GAINS_RTOL: float = 1e-9
"""Relative difference below which the linear gains of a run made again count as the run's (a tuned controller's
gains on a fit made again)."""


def gains_difference(attrs: Mapping[str, object], controlled: ControlledScene) -> str | None:
    """What differs between the linear gains a result records (``controller_gains``) and those the controller of
    ``controlled`` (made again and set up) applies, or None. They differ when ``--set`` changed the controller, and
    when the controller that ran was changed after it was made, or an argument given to it changed afterwards: the
    result records the arguments it was made with, and the gains it applied."""
    recorded = attrs.get("controller_gains")
    if not isinstance(recorded, str):
        return None
    text = controller_attrs(controlled.controller, given=controlled.controller_given).get("controller_gains")
    then, now = json.loads(recorded), None if text is None else json.loads(text)
    if now is not None and then.keys() == now.keys():
        pairs = [(np.asarray(then[k], dtype=float), np.asarray(now[k], dtype=float)) for k in then]
        if all(a.shape == b.shape and np.allclose(b, a, rtol=GAINS_RTOL, atol=0.0) for a, b in pairs):
            return None
    return (
        f"the controller's linear gains differ from the run's (now {now}, the run's {then}): the run's controller "
        "was changed after it was made, or --set changed it; the results will differ"
    )


def _same_class(name: str, recorded: str) -> None:
    """Refuse a controller name that now makes another class than the one that ran."""
    for ep in entry_points(ENTRY_POINT_GROUP):
        if ep.name == name:
            module, _, attr = ep.value.partition(":")
            now = f"{module}.{attr}"
            loaded = ep.load()
            if renamed_class(recorded)[0] not in (now, f"{loaded.__module__}.{loaded.__qualname__}"):
                raise ValueError(
                    f"the controller {name!r} of this run was class {recorded}; the name now makes {now}: install the "
                    "package that registered it, or run the scene from Python with that class"
                )
            return


def _given_controller(attrs: dict[str, object], dt: float | str | None) -> ControllerChoice:
    """The scene's controller section for a controller that was given to ``simulate``."""
    name, cls = str(attrs.get("controller")), str(attrs.get("controller_class"))
    parameters = json.loads(str(attrs.get("controller_parameters", "{}")))
    how = f"run the scene from Python: simulate(scene, controller={cls}(**{parameters}))"
    if name == UNREGISTERED:
        raise ValueError(
            f"this run's controller was given to simulate: class {cls}, parameters {parameters}; it is not "
            f"registered (entry-point group wecss.controllers), so --from cannot make it: {how}"
        )
    opaque = str(attrs.get("controller_parameters_opaque", ""))
    if opaque:
        raise ValueError(
            f"this run's controller ({name!r}, class {cls}) was given to simulate with parameters that the file "
            f"cannot hold ({opaque}): {how}"
        )
    now = create(name, **parameters)
    if registered_name(now) != name or f"{type(now).__module__}.{type(now).__qualname__}" != renamed_class(cls)[0]:
        raise ValueError(
            f"the controller name {name!r} now makes {type(now).__module__}.{type(now).__qualname__}, not the class "
            f"that ran ({cls}): {how}"
        )
    return ControllerChoice(name=name, parameters=parameters, dt=dt)
