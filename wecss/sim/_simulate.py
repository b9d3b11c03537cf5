"""``simulate(scene)``: the one entry point for every run: the scene's ``solver.method`` names its runner
(``wecss.scene.runner``), which runs the compiled scene into a record; every run returns the same Dataset layout."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import xarray as xr

from ..compiled import CompiledScene, scene_inputs
from ..control import ControlledScene, Controller, attach_controller, compile_scene
from ..files import refuse_overwrite
from ..interrupts import interrupts_surfaced
from ..netcdf import partial_path, storage_encoding, write_netcdf
from ..provenance import with_relative_paths
from ..scene import Scene
from ._alpha import with_elastic_choice
from ._dataset import build_result
from ._drift_check import drift_check, record_drift
from ._guards import check_sea
from ._stream import ResultStream, streamable
from ._tolerance import choose_step


def simulate(
    scene: Scene | CompiledScene | str | Path,
    *,
    controller: Controller | None = None,
    progress: bool = False,
    path: str | os.PathLike[str] | None = None,
    compress: int = 0,
    float32: bool = False,
) -> xr.Dataset:
    """Run a scene.

    ``solver.method`` names the runner (``wecss.scene.available_runners()``): "beeman", "beeman-explicit", "rk4"
    or "reference" integrate the nonlinear MFM equations; "linear" steps the linearised model exactly
    (``wecss.linear``); "frequency" evaluates the exact frequency-domain steady state at the scene's time steps.

    Parameters
    ----------
    scene : Scene, CompiledScene, or path to a scene TOML file
    controller : wecss.control.Controller, optional
        A controller instance to run instead of the scene's ``controller`` section (which the result's notes then
        say was not used). With a compiled scene, give the plant (``wecss.compiled.compile_plant``) or a scene.
    progress : bool
        Print a progress bar on standard error (nonlinear runs).
    path : file name, optional
        Write the result to this netCDF file, the same content as ``wecss.results.save`` writes. The fixed-step
        runs (Beeman, RK4) stream it: their time series are appended chunk by chunk as the run goes (memory stays flat
        whatever the number of saved steps; the file ``NAME.partial.nc`` is readable after every chunk, its
        ``run_status`` attribute says how far it got, and it stays there when the run fails or is interrupted;
        the complete file is renamed to ``path``). The other runs, and runs with the ``loads`` output group (it
        needs the whole record), are built whole and then saved.
    compress, float32 : as ``wecss.results.save`` (only with ``path``).

    Returns
    -------
    xarray.Dataset
        Time series and statistics as the scene's outputs ask (see ``wecss.sim.build_result``), with the scene
        (JSON) and the run's solver, settings, timings and notes in the attributes. A streamed run's is opened
        lazily from its file (values are read when used; close it, or use it in a ``with`` block, when done).

    With ``solver.tolerance``, the integrator and the step are chosen first (``wecss.sim.choose_step``: short
    pilot runs); the result's ``scene`` attribute is the scene that ran (its method and step), and its attributes
    ``solver_tolerance``, ``tolerance_estimate`` and ``tolerance_choice`` record the choice.

    A run whose bodies drift (the drift note, ``wecss.sim._drift``) is run again at half the step, its motion only
    (about twice the run's time; not for runs over ``MAX_CHECK_STEPS`` steps): the note then says which part of the
    drift is the integrator's error and which is physical (``wecss.sim._drift_check``).

    Raises
    ------
    SceneError
        On a malformed scene (before any time is spent); a sea steeper than waves can be (height over the
        wavelength at the peak period above 1/7); Beeman at a step past its stability limit for the plant's fastest
        undamped mode.
    wecss.files.WriteFailed
        (an OSError) If the result file cannot be written (a full disk: the message says so and what became of the
        file).
    SimulationDiverged
        If the state becomes non-finite, a hinge passes its bound, the corrector fails, or energy grows in calm
        water; the exception carries the time, step and state.
    KeyboardInterrupt
        On Ctrl-C, also inside a compiled kernel (where numba reports it as a SystemError).
    ValueError
        For ``compress`` or ``float32`` without ``path``, or a ``compress`` level outside 0-9.
    wecss.files.OverwriteError
        (a ValueError) If ``path`` (or its ``.partial.nc``) is an input of the run: the scene file, the device spec
        or a file it names, the database, ``sea.file``, or inside the radiation-fit cache; checked before the run,
        nothing is written.
    """
    if path is None and (compress or float32):
        raise ValueError(
            f"compress={compress!r} and float32={float32!r} say how to write the result file: give path too "
            "(or save the returned Dataset with wecss.results.save)"
        )
    storage_encoding(xr.Dataset(), compress=compress, float32=float32)  # refuses bad options before the run
    inputs: dict[str, Path] = {}
    if isinstance(scene, str | Path):
        inputs["scene file"] = Path(scene)
        scene = Scene.from_toml(scene)
    if path is not None and isinstance(scene, Scene | CompiledScene):  # before any work
        plain = scene if isinstance(scene, Scene) else scene.scene
        refuse_overwrite(result_files(path), {**inputs, **scene_inputs(plain)})
    choice = None
    if isinstance(scene, Scene) and scene.solver.step_chosen:  # the step from solver.tolerance, before the run
        choice = choose_step(scene, controller)
        scene = choice.scene
    if isinstance(scene, ControlledScene):
        if controller is not None:
            raise ValueError("this compiled scene has a controller already; give the plant (compile_plant) or a scene")
        controlled = scene
    elif isinstance(scene, CompiledScene):
        controlled = attach_controller(scene, controller)
    elif isinstance(scene, Scene):
        controlled = compile_scene(scene, controller)
    else:
        raise TypeError(f"simulate takes a Scene, a CompiledScene or a scene file; got {type(scene).__name__}")
    controlled = with_elastic_choice(controlled)  # generalised-alpha where the elastic modes need it
    check_sea(controlled)  # a sea steeper than waves can be: an input error, refused before the run
    runner = controlled.scene.runner
    chosen = choice.attrs() if choice is not None else {}
    if path is not None and streamable(controlled):
        return _streamed(controlled, progress, path, compress, float32, chosen)
    with interrupts_surfaced():  # Ctrl-C inside a compiled kernel is an interrupt, not a failure of the run
        record = runner.run(controlled, progress=progress)
    record.solver.update(chosen)
    q = record.series.get("q")
    check = drift_check(controlled, record_drift(controlled, q)) if q is not None and q.shape[0] >= 2 else None
    ds = build_result(controlled, record, check)
    if path is not None:
        ds.attrs = with_relative_paths(ds.attrs, path)  # the input files' paths from the result's folder
        write_netcdf(ds, path, compress=compress, float32=float32)
    return ds


def result_files(path: str | os.PathLike[str]) -> dict[str, Path]:
    """The files ``simulate(..., path=path)`` may write: the result and, when streamed, its partial file."""
    return {"result file": Path(path), "partial result file": partial_path(Path(path))}


def _streamed(
    controlled: ControlledScene,
    progress: bool,
    path: str | os.PathLike[str],
    compress: int,
    float32: bool,
    chosen: dict[str, Any],
) -> xr.Dataset:
    stream = ResultStream(controlled, path, compress=compress, float32=float32)
    try:
        with interrupts_surfaced():
            record = controlled.scene.runner.run(controlled, progress=progress, stream=stream)
    except BaseException as err:
        stream.stop(err)
        raise
    record.solver.update(chosen)
    stream.motion.check = drift_check(controlled, stream.motion.drift())
    return xr.open_dataset(stream.finish(record), engine="netcdf4")
