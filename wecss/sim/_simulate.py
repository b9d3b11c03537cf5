"""``simulate(scene)``: the one entry point for nonlinear, linear and frequency-domain runs, chosen by the scene's
``solver.method``; every run returns the same Dataset layout."""

from __future__ import annotations

from pathlib import Path

import xarray as xr

from ..compiled import CompiledScene
from ..control import Controller, attach_controller, compile_scene
from ..scene import Scene
from ._frequency import run_frequency_domain
from ._linear import simulate_linear
from ._nonlinear import run_fixed_step, run_reference
from ._result import build_result


def simulate(
    scene: Scene | CompiledScene | str | Path, *, controller: Controller | None = None, progress: bool = False
) -> xr.Dataset:
    """Run a scene.

    ``solver.method`` chooses the run: "beeman", "rk4" or "reference" integrate the nonlinear MFM equations;
    "linear" steps the linearised model exactly (``wecss.linear``); "frequency" evaluates the exact
    frequency-domain steady state at the scene's time steps.

    Parameters
    ----------
    scene : Scene, CompiledScene, or path to a scene TOML file
    controller : wecss.control.Controller, optional
        A controller instance to run instead of the scene's ``controller`` section (which the result's notes then
        say was not used). With a compiled scene, give the plant (``wecss.compiled.compile_plant``) or a scene.
    progress : bool
        Print a progress bar on standard error (nonlinear runs).

    Returns
    -------
    xarray.Dataset
        Time series and statistics as the scene's outputs ask (see ``wecss.sim.build_result``), with the scene
        (JSON) and the run's solver, settings, timings and notes in the attributes.

    Raises
    ------
    SceneError
        On a malformed scene (before any time is spent).
    SimulationDiverged
        If the state becomes non-finite, a hinge passes its bound, the corrector fails, or energy grows in calm
        water; the exception carries the time, step and state.
    """
    if isinstance(scene, str | Path):
        scene = Scene.from_toml(scene)
    if isinstance(scene, CompiledScene):
        compiled = scene if controller is None else attach_controller(scene, controller)
    elif isinstance(scene, Scene):
        compiled = compile_scene(scene, controller)
    else:
        raise TypeError(f"simulate takes a Scene, a CompiledScene or a scene file; got {type(scene).__name__}")
    method = compiled.scene.solver.method
    if method == "linear":
        return simulate_linear(compiled, hold=compiled.scene.solver.linear_hold)
    if method == "frequency":
        record = run_frequency_domain(compiled)
    elif method == "reference":
        record = run_reference(compiled, progress)
    else:
        record = run_fixed_step(compiled, progress)
    return build_result(compiled, record)
