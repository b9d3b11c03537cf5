"""wecss: time-domain dynamics, linear models and PTO control of multi-body wave energy converters.

The names a user needs are here (a hand-written list, :data:`__all__`), each loaded on first use so that
``import wecss`` stays cheap::

    import wecss

    ds = wecss.simulate(wecss.Scene.from_toml(wecss.default_scene_path()))
    print(wecss.mean_power(ds).values)

The packages hold the rest: ``wecss.hydro`` (databases), ``wecss.devices`` (the catalogue), ``wecss.waves``,
``wecss.radiation``, ``wecss.scene`` (scenes and the runners' registry), ``wecss.control`` (the controller
interface; ``wecss.control.design`` the frequency-domain design tools, ``wecss.control.mpc`` estimation and model
predictive control), ``wecss.linear`` (the linearised model), ``wecss.sim`` (runs and results), ``wecss.results``
(metrics, files, plots), ``wecss.sweep``.
"""

from __future__ import annotations

import importlib
from importlib.metadata import PackageNotFoundError, version
from typing import Any

try:
    __version__ = version("wecss")
except PackageNotFoundError:  # pragma: no cover - running from a source tree that is not installed
    __version__ = "0+unknown"

_FACE: dict[str, str] = {
    # scenes and runs
    "Scene": "wecss.scene",
    "SceneError": "wecss.scene",
    "default_scene_path": "wecss.scene",
    "available_runners": "wecss.scene",
    "simulate": "wecss.sim",
    "simulate_linear": "wecss.sim",
    "compile_scene": "wecss.control",
    "SimulationDiverged": "wecss.sim",
    # devices and data
    "Device": "wecss.devices",
    "HydroData": "wecss.hydro",
    # control
    "Controller": "wecss.control",
    "ControlContext": "wecss.control",
    "Measurement": "wecss.control",
    # the linear model
    "linearize": "wecss.linear",
    "steady_state": "wecss.linear",
    "modal_table": "wecss.linear",
    # results
    "mean_power": "wecss.results",
    "capture_width_ratio": "wecss.results",
    "rms_hinge_angle": "wecss.results",
    "save": "wecss.results",
    "open_result": "wecss.results",
    # sweeps
    "Sweep": "wecss.sweep",
    "run_sweep": "wecss.sweep",
}
"""Where each name of the face lives."""

_RENAMED: dict[str, tuple[str, str]] = {
    "load_device": ("wecss.devices", "load"),
    "load_hydro": ("wecss.hydro", "load"),
}
"""Names of the face that are another name in their package (``wecss.devices.load`` is ``wecss.load_device``)."""

__all__ = sorted([*_FACE, *_RENAMED, "__version__"])


def __getattr__(name: str) -> Any:
    if name in _FACE:
        value = getattr(importlib.import_module(_FACE[name]), name)
    elif name in _RENAMED:
        module, attribute = _RENAMED[name]
        value = getattr(importlib.import_module(module), attribute)
    else:
        raise AttributeError(f"module 'wecss' has no attribute {name!r}")
    globals()[name] = value  # loaded once
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *__all__})
