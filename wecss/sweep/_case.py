"""One case of a sweep, as a worker runs it: the scene from its JSON, compiled and simulated; any exception becomes
a recorded failure."""

from __future__ import annotations

import time
import traceback
from dataclasses import dataclass

import xarray as xr

from ..interrupts import interrupt_behind


@dataclass(frozen=True)
class CaseOutcome:
    """What a worker sends back: the result (None on failure), the error text, and the compile and run times [s]."""

    result: xr.Dataset | None
    error: str | None
    compile_s: float
    run_s: float


def run_case(scene_json: str) -> CaseOutcome:
    """Compile and run one case (in a worker); any exception becomes a recorded failure, but an interrupt
    (KeyboardInterrupt, also as the cause of another exception) is raised: the case is not done, never failed.

    The compiled plant's parts that the case's swept values do not change are cached per process by
    ``wecss.compiled`` (device, hydrodynamic coupling, equilibrium, radiation kernel). A case with
    ``solver.tolerance`` has its step chosen first (``wecss.sim.choose_step``, counted in the compile time), as
    ``simulate`` does.
    """
    from ..control import compile_scene
    from ..scene import Scene
    from ..sim import choose_step, simulate

    start = time.perf_counter()
    compiled_at = start
    try:
        scene = Scene.from_json(scene_json)
        choice = choose_step(scene) if scene.solver.step_chosen else None  # solver.tolerance: step chosen first
        compiled = compile_scene(choice.scene if choice is not None else scene)
        compiled_at = time.perf_counter()
        ds = simulate(compiled)
        if choice is not None:
            ds.attrs.update(choice.attrs())
    except Exception as err:  # recorded with its traceback; the sweep goes on
        if interrupt_behind(err) is not None:  # Ctrl-C is no failure of the case: it stays to be done
            raise KeyboardInterrupt from None
        text = f"{type(err).__name__}: {err}\n" + "".join(traceback.format_exception(err)[-3:])
        return CaseOutcome(None, text, compiled_at - start, time.perf_counter() - compiled_at)
    end = time.perf_counter()
    ds.attrs["sweep_compile_time_s"] = compiled_at - start
    return CaseOutcome(ds, None, compiled_at - start, end - compiled_at)
