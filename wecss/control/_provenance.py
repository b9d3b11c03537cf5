"""What a result records of the controller that ran: its registered name, its class, the arguments it was made
with (defaults included) and the linear gains it applied (tuned ones included), so that a run can be made again
from its file (``wecss run --from``) or, for a controller that is not registered, says which class it needs."""

from __future__ import annotations

import inspect
import json
from typing import Any

import numpy as np

from ..plugins import entry_points
from ._protocol import Controller
from ._registry import ENTRY_POINT_GROUP

UNREGISTERED = "unregistered"
"""The ``controller`` attribute of a result whose controller class is not registered under ``wecss.controllers``."""


def registered_name(controller: Controller) -> str | None:
    """The name under which the class of ``controller`` is registered (entry-point group ``wecss.controllers``),
    or None."""
    cls = type(controller)
    for ep in entry_points(ENTRY_POINT_GROUP):
        module, _, attr = ep.value.partition(":")
        if module == cls.__module__ and attr == cls.__qualname__:
            return ep.name
    for ep in entry_points(ENTRY_POINT_GROUP):  # registered under another module path (a re-export)
        try:
            if ep.load() is cls:
                return ep.name
        except Exception:
            continue
    return None


def class_path(controller: Controller) -> str:
    """``module.QualifiedName`` of the controller's class."""
    cls = type(controller)
    return f"{cls.__module__}.{cls.__qualname__}"


def _plain(value: Any) -> Any:
    """``value`` as JSON values (numpy arrays and scalars to lists and numbers, tuples to lists), or raise
    TypeError for what JSON cannot hold."""
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, tuple | list):
        return [_plain(v) for v in value]
    if isinstance(value, dict):
        return {str(k): _plain(v) for k, v in value.items()}
    if value is None or isinstance(value, bool | int | float | str):
        return value
    raise TypeError(f"{type(value).__name__} is not a JSON value")


def made_with(controller: Controller) -> tuple[dict[str, Any], list[str]]:
    """The keyword arguments ``controller`` was made with, its class's defaults filled in, as JSON values; and
    the names of those that are not JSON values (recorded as their ``repr``: such a controller cannot be made
    again from a file)."""
    args, kwargs = getattr(controller, "_made_with", ((), {}))
    init = type(controller).__init__
    if init is object.__init__:  # no parameters
        return {}, ["(arguments)"] if args or kwargs else []
    try:
        bound = inspect.signature(init).bind(None, *args, **kwargs)  # None for self
    except (TypeError, ValueError):  # a signature inspect cannot read
        return {"args": [repr(a) for a in args], **{k: repr(v) for k, v in kwargs.items()}}, ["(arguments)"]
    bound.apply_defaults()
    out: dict[str, Any] = {}
    opaque: list[str] = []
    for name, value in list(bound.arguments.items())[1:]:
        try:
            out[name] = _plain(value)
        except TypeError:
            out[name] = repr(value)
            opaque.append(name)
    return out, opaque


def controller_attrs(controller: Controller, *, given: bool) -> dict[str, Any]:
    """The result attributes of the controller that ran (``given``: given to ``simulate`` instead of made from
    the scene's ``controller`` section).

    ``controller`` its registered name (or "unregistered"), ``controller_class`` its class, ``controller_source``
    "scene" or "given to simulate", ``controller_parameters`` the JSON of its arguments with defaults,
    ``controller_parameters_opaque`` the arguments JSON cannot hold ("" for none), and, for a linear feedback,
    ``controller_gains``, the JSON of the gains it applied per PTO in the ``pto`` order, ``damping``
    [N s/m or N m s/rad] and ``stiffness`` [N/m or N m/rad] (after its ``setup``: the tuned gains of
    ``optimal-damping`` and ``reactive``)."""
    parameters, opaque = made_with(controller)
    attrs: dict[str, Any] = {
        "controller": registered_name(controller) or UNREGISTERED,
        "controller_class": class_path(controller),
        "controller_source": "given to simulate" if given else "scene",
        "controller_parameters": json.dumps(parameters, sort_keys=True),
        "controller_parameters_opaque": ", ".join(opaque),
    }
    gains = controller.linear_gains()
    if gains is not None:  # JSON: a netCDF attribute of one number reads back as a scalar, not a list
        damping, stiffness = (np.asarray(g, dtype=float).tolist() for g in gains)
        attrs["controller_gains"] = json.dumps({"damping": damping, "stiffness": stiffness})
    return attrs
