"""Small scenes and a simple passive radiation model for the simulator tests."""

from __future__ import annotations

import dataclasses
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np

from wecss.compiled import from_state_space
from wecss.control import ControlContext, Controller
from wecss.radiation import RadiationStateSpace
from wecss.sim import CompiledScene, Scene, compile_scene
from wecss_controllers import LinearDamping


def scene(device: str = "m4-111", **sections: dict[str, Any]) -> Scene:
    """A scene from section dicts, with short defaults (JONSWAP Hs 0.04 m, Tp 1.2 s, 20 s)."""
    data: dict[str, Any] = {
        "device": {"name": device},
        "sea": {"kind": "jonswap", "height": 0.04, "period": 1.2, "duration": 20.0, "ramp": 3.0},
        "outputs": {"variables": ["motion", "pto"]},
    }
    for key, value in sections.items():
        data[key] = {**data.get(key, {}), **value}
    return Scene.from_dict(data)


NOTC_FLEXIBLE = "flexible = { modes = 6, damping_ratio = 0.01, elements = 16 }"
"""The NOTC spec's flexible table of its arm."""


def elastic_notc_spec(folder: Path, extra: str = "", name: str = "notc-elastic.toml") -> str:
    """The shipped NOTC spec with its arm elastic (``dynamics = "elastic"`` and ``extra``, e.g.
    ``", quasi_static_above = 30"``, added to its flexible table), written to ``folder / name``; its path."""
    raw = (resources.files("wecss") / "data" / "devices" / "notc-10kw.toml").read_text()
    assert raw.count(NOTC_FLEXIBLE) == 1
    path = Path(folder) / name
    path.write_text(raw.replace(NOTC_FLEXIBLE, NOTC_FLEXIBLE[:-2] + f', dynamics = "elastic"{extra} }}'))
    return str(path)


def simple_state_space(compiled: CompiledScene) -> RadiationStateSpace:
    """A passive diagonal memory model, K_ii(t) = k_i exp(-t) cos(5 t) with k_i the database's largest B_ii:
    Re K_hat = k (26 + omega^2) / |(1 + i omega)^2 + 25|^2 > 0. Cheap, stable, passive: enough for the tests that
    need state-space radiation but not an accurate one."""
    dofs = tuple(compiled.hydro.dofs)
    n = len(dofs)
    peak = np.max(np.abs(np.diagonal(compiled.hydro.dataset.radiation_damping.values, axis1=1, axis2=2)), axis=0)
    a = np.zeros((2 * n, 2 * n))
    b = np.zeros((2 * n, n))
    c = np.zeros((n, 2 * n))
    for i in range(n):
        a[2 * i : 2 * i + 2, 2 * i : 2 * i + 2] = [[-1.0, 5.0], [-5.0, -1.0]]
        b[2 * i, i] = 1.0
        c[i, 2 * i] = peak[i]
    return RadiationStateSpace(a, b, c, dofs, "given")


def with_state_space(compiled: CompiledScene, model: RadiationStateSpace | None = None) -> CompiledScene:
    """The compiled scene with a state-space memory (default :func:`simple_state_space`), no A_inf correction."""
    arrays, summary = from_state_space(model or simple_state_space(compiled), compiled.dt)
    return dataclasses.replace(compiled, radiation=arrays, radiation_summary=summary)


def compiled_with_state_space(sc: Scene) -> CompiledScene:
    """Compile ``sc`` without memory, then give it :func:`simple_state_space` (and keep the scene's solver)."""
    none = dataclasses.replace(sc, radiation=dataclasses.replace(sc.radiation, method="none"))
    return with_state_space(compile_scene(none))


class HeldDamping(Controller):
    """Linear damping without ``linear_gains``: the simulators call it once per step and hold its force."""

    needs_state = False

    def __init__(self, damping: float = 6.0) -> None:
        self.inner = LinearDamping(damping)

    def setup(self, context: ControlContext) -> None:
        self.inner.setup(context)

    def compute(self, t: float, measurement: Any) -> np.ndarray:
        return self.inner.compute(t, measurement)


def held(compiled: CompiledScene) -> CompiledScene:
    """``compiled`` with its linear damping replaced by :class:`HeldDamping` (6 N m s/rad)."""
    plant = compiled.plant._replace(pto_damping=np.zeros_like(compiled.plant.pto_damping))
    controller = HeldDamping()
    controller.setup(compiled.control_context)
    return dataclasses.replace(compiled, plant=plant, controller=controller, linear_controller=False)
