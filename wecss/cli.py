"""The ``wecss`` command.

``wecss info`` lists the shipped hydrodynamic databases; ``wecss info DEVICE`` (a catalogue name such as
``m4-134``, or a spec ``.toml``) prints bodies, joints, generalised coordinates, masses and the undamped natural
periods; ``wecss info FILE.nc`` or a database name describes a hydrodynamic database or a simulation result.

``wecss run [SCENE.toml] [-o RESULT.nc]`` simulates a scene (without one: the embedded default, M4 134 in a
JONSWAP sea) and writes the result and a PNG summary plot; ``--set sea.period=1.4`` overrides a scene value (dotted
paths, validated by the scene). ``wecss run --from RESULT.nc`` runs a result's recorded scene and controller again
after checking its input files' SHA-256 (``wecss.sim.scene_from_result``). ``wecss plot RESULT.nc`` plots a result
(a sweep's combined.nc or folder: ``wecss.results.plot_sweep``; ``--animate``: ``wecss.results.animate``).
The commands but ``sweep`` keep dask out of their process (``wecss.dask_free``; ``run --allow-dask`` lets it in).

``wecss modes DEVICE`` prints the natural modes of a device with its flexible bodies, in air and in water
(``wecss.devices.structural_modes``): frequency, damping ratio and the in-plane / out-of-plane / torsion shares of
each mode's strain and kinetic energy; ``--png FILE`` plots the mode shapes.

``wecss sweep SWEEP.toml -o FOLDER`` runs a sweep (``wecss.sweep``): in this process, in a pool of processes
(``--processes N``), or on Dask (``--dask [--workers N]``, ``--scheduler tcp://...``); started again it resumes;
``--retry-failed`` runs the failed cases again.

Exit status: 0 done, 1 a sweep with failed cases, 2 bad input (one line, no traceback; also an output that would
overwrite an input of the run), 3 a diverged run, 4 an output file that could not be written (a full disk: the
message names the file and what became of it), 130 after Ctrl-C, 143 after SIGTERM.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

from . import __version__, command_process
from .dask_free import refusal_hint
from .files import WriteFailed, refuse_overwrite
from .interrupts import Terminated, sigterm_raises


def _info(target: str | None) -> int:
    from . import devices, hydro

    if target is None:
        catalogue = devices.available()
        print(f"wecss {__version__}: devices ({len(catalogue)}; `wecss info NAME` for one)\n")
        for name in catalogue:
            print(f"  {name:12s} {devices.load(name).description}")
        print()
        names = hydro.available()
        if not names:
            print("no shipped hydrodynamic databases found in", hydro.DATA_DIR)
            return 1
        print(f"shipped hydrodynamic databases ({len(names)})\n")
        for name in names:
            start = time.perf_counter()
            data = hydro.load(name)
            elapsed = time.perf_counter() - start
            print(f"[{name}] loaded in {elapsed * 1e3:.0f} ms")
            print(data.summary())
            print()
        return 0
    path = Path(target)
    if path.suffix == ".nc" and path.is_file() and _is_result(path):
        from .results import open_result

        ds = open_result(path)
        print(ds)
        print()
        print(_partial_summary(ds) if "run_status" in ds.attrs else run_summary(ds))
        return 0
    if path.suffix == ".toml" or target in devices.available():
        device = devices.Device.from_spec(path) if path.suffix == ".toml" else devices.load(target)
        print(device.info())
        print(_modes(target))
        return 0
    if path.suffix == ".nc" and path.is_file() and not hydro.is_wecss_database(path):
        raise ValueError(
            f"{target!r} is neither a wecss result nor a wecss database (no rho, g, water_depth, source, convention "
            "attributes); for Capytaine output use HydroData.from_capytaine or name it as a device spec's hydro "
            "(docs/byo-bem.md)"
        )
    if path.suffix == ".nc" or path.exists():
        data = hydro.HydroData.from_netcdf(path)
    elif target in hydro.available():
        data = hydro.load(target)
    else:
        known = sorted(set(devices.available()) | set(hydro.available()))
        raise ValueError(f"{target!r} is neither a file nor a known device or database; known: {', '.join(known)}")
    print(data.summary())
    return 0


def _modes(device: str) -> str:
    """The modal table of a device in calm water (its own hydrodynamic database), or why there is none."""
    from .control import compile_scene
    from .linear import format_modal_table, modal_table
    from .scene import Scene, SceneError

    calm = {"kind": "calm", "period": None, "duration": 10.0, "ramp": 0.0}
    try:
        scene = Scene.from_dict(
            {"device": {"name": device}, "sea": calm, "solver": {"dt": 0.01}, "radiation": {"method": "none"}}
        )
        return format_modal_table(modal_table(compile_scene(scene)))
    except (SceneError, ValueError, FileNotFoundError) as err:
        return f"modal table: not available ({err})"


def format_structural_modes(ds: Any) -> str:
    """The table of a structural modal analysis (``wecss.devices.structural_modes``) as text."""
    import numpy as np

    medium = "in water" if ds.attrs["medium"] == "water" else "in air (no gravity, no water)"
    lines = [
        f"{ds.attrs['device']}: structural modes {medium}; {ds.attrs['model']} model, {ds.attrs['coordinates']} "
        f"coordinates, flexible bodies: {ds.attrs['flexible_bodies']}",
        f"{'mode':>4} {'f [Hz]':>10} {'zeta':>8}   strain energy in / out of plane / torsion [%]   kinetic [%]",
    ]

    def shares(values: Any) -> str:
        return "     -" * 3 if np.any(np.isnan(values)) else "".join(f"{100 * v:6.1f}" for v in values)

    for k in range(ds.sizes["mode"]):
        mode = ds.isel(mode=k)
        zeta = float(mode.damping_ratio)
        lines.append(
            f"{int(mode.mode):4d} {float(mode.frequency):10.4g} {'-' if np.isnan(zeta) else f'{zeta:.4f}':>8}   "
            f"{shares(mode.energy_share.sel(energy='strain').values):>18}{'':28}"
            f"{shares(mode.energy_share.sel(energy='kinetic').values)}"
        )
    return "\n".join(lines)


def _structural_modes(args: argparse.Namespace) -> int:
    from . import devices

    target = args.device
    device = devices.Device.from_spec(target) if target.endswith(".toml") else devices.load(target)
    media = [m for m, wanted in (("air", not args.water), ("water", not args.air)) if wanted]
    pictures: dict[str, Path] = {}
    if args.png:
        png = Path(args.png)
        pictures = {m: png if len(media) == 1 else png.with_name(f"{png.stem}-{m}{png.suffix}") for m in media}
        check_outputs({f"picture ({m})": (p, ".png") for m, p in pictures.items()}, inputs={})
    for medium in media:
        try:
            ds = device.structural_modes(water=medium == "water", model=args.model, n_modes=args.n)
        except (ValueError, FileNotFoundError) as err:
            if len(media) == 1:
                raise
            print(f"{device.name}: structural modes in {medium}: not available ({err})\n")
            continue
        print(format_structural_modes(ds))
        print(f"notes: {ds.attrs['notes']}\n")
        if medium in pictures:
            import matplotlib.pyplot as plt

            from .results import plot_structural_modes

            plt.close(plot_structural_modes(ds, pictures[medium], modes=min(args.n, 6)))
            print(f"wrote {pictures[medium]}\n")
    return 0


def _is_result(path: Path) -> bool:
    from .netcdf import global_attributes

    return "scene" in global_attributes(path)


def _partial_summary(ds: Any) -> str:
    """What a partial result file (``NAME.partial.nc``, a streamed run that stopped or is still going) holds."""
    lines = [f"partial result: {ds.attrs['run_status']}"]
    if "time" in ds.dims and ds.sizes["time"]:
        time = ds["time"].values
        lines.append(f"{ds.sizes['time']} saved steps, t = {float(time[0]):.6g} to {float(time[-1]):.6g} s")
    lines.append("the statistics, the solver's attributes and the summary are written when a run finishes")
    return "\n".join(lines)


def run_summary(ds: Any) -> str:
    """The table printed after a run: mean power per PTO, CWR, RMS hinge angle, timings."""
    import numpy as np

    from .results import capture_width_ratio, mean_power, rms_hinge_angle

    lines = [
        f"{ds.attrs.get('title', 'result')}: {ds.attrs.get('solver')} dt {ds.attrs.get('time_step'):.4g} s, "
        f"{ds.attrs.get('n_steps')} steps; radiation: {ds.attrs.get('radiation')}"
    ]
    if "tolerance_choice" in ds.attrs:  # the step chosen from solver.tolerance
        lines.append(str(ds.attrs["tolerance_choice"]))
    power = mean_power(ds)
    rms = rms_hinge_angle(ds) if ("pto_angle" in ds or "rms_pto_angle" in ds) else None
    lines.append(f"{'PTO':<12}{'mean power [W]':>16}{'RMS angle [deg]':>18}")
    for name in power.pto.values:
        angle = ""
        if rms is not None and np.isfinite(float(rms.sel(pto=name))):  # NaN for linear PTOs
            angle = f"{np.degrees(float(rms.sel(pto=name))):18.3f}"
        lines.append(f"{name:<12}{float(power.sel(pto=name)):16.5g}{angle}")
    lines.append(f"{'total':<12}{float(power.sum()):16.5g}")
    if "wave_energy_flux" in ds.attrs:
        cwr = capture_width_ratio(ds)
        line = f"capture width ratio {float(cwr):.4g} (energy period Te = {cwr.attrs['energy_period_used_s']:.4g} s)"
        try:
            paper = capture_width_ratio(ds, convention="paper")
            line += f"; {float(paper):.4g} with the paper's Te = {paper.attrs['energy_period_used_s']:.4g} s"
        except ValueError:
            pass
        lines.append(line)
    lines.append(
        f"run time {ds.attrs['run_time_s']:.3g} s, {ds.attrs['steps_per_second']:,.0f} steps/s"
        f" (numba {'on' if ds.attrs.get('numba') else 'off'})"
    )
    if ds.attrs.get("notes", "none") != "none":
        lines.append(f"notes: {ds.attrs['notes']}")
    return "\n".join(lines)


def _run(
    scene_path: str | None,
    output: str | None,
    png: str | None,
    quiet: bool,
    overrides: Sequence[str] = (),
    *,
    compress: int = 0,
    float32: bool = False,
    from_result: str | None = None,
) -> int:
    from .compiled import scene_inputs
    from .netcdf import partial_path
    from .results import plot_summary
    from .sim import Scene, default_scene_path, scene_from_result, simulate

    if from_result is not None:
        if scene_path is not None:
            raise ValueError(f"give a scene file or --from RESULT.nc, not both; got {scene_path!r} and {from_result!r}")
        path = Path(from_result)
        recorded, found = scene_from_result(path)  # inputs checked against their SHA-256
        for line in found:
            print(f"wecss: {line}", file=sys.stderr)
        scene = _with_overrides(recorded, overrides)
        inputs = {"result file read by --from": path, **scene_inputs(scene)}
        out = Path(output) if output else Path(f"{path.stem}-rerun.nc")
    else:
        path = Path(scene_path) if scene_path else default_scene_path()
        scene = _with_overrides(Scene.from_toml(path), overrides)
        inputs = {"scene file": path, **scene_inputs(scene)}
        out = Path(output) if output else Path(f"{'wecss-default' if scene_path is None else path.stem}.nc")
    picture = Path(png) if png else out.with_suffix(".png")
    check_outputs(
        {"result": (out, ".nc"), "partial result": (partial_path(out), ".nc"), "picture": (picture, ".png")},
        inputs=inputs,
    )
    if not quiet:
        print(f"{'scene of the result' if from_result else 'scene'} {path}", file=sys.stderr)
    runnable: Any = scene
    if from_result is not None:  # compiled first: its radiation fit and linear gains against the run's
        from .control import compile_scene
        from .netcdf import global_attributes
        from .sim import fit_difference, gains_difference

        runnable = compile_scene(scene)
        recorded_attrs = global_attributes(path)
        for difference in (fit_difference(recorded_attrs, runnable), gains_difference(recorded_attrs, runnable)):
            if difference is not None:
                print(f"wecss: warning: {difference}", file=sys.stderr)
    # written as the run goes (Beeman, RK4: streamed, memory flat); the series are read back for the plot alone
    with simulate(runnable, progress=not quiet, path=out, compress=compress, float32=float32) as ds:
        plotted = "time" in ds.dims and any(name in ds for name in ("wave_elevation", "pto_power"))
        if plotted:  # the summary plot needs the elevation or the PTO series
            import matplotlib.pyplot as plt

            fig = plot_summary(ds, picture)
            plt.close(fig)
        print(run_summary(ds))
    print(f"wrote {out}" + (f" and {picture}" if plotted else ""))
    return 0


def _with_overrides(scene: Any, overrides: Sequence[str]) -> Any:
    """``scene`` with the ``--set`` assignments applied (``wecss.sweep.apply_overrides``; imported only then)."""
    if not overrides:
        return scene
    from .sweep import apply_overrides

    return apply_overrides(scene, overrides)


def _sweep(args: argparse.Namespace) -> int:
    from .sweep import Sweep, run_sweep

    sweep = Sweep.from_toml(args.sweep)
    folder = Path(args.output) if args.output else Path(Path(args.sweep).stem)
    print(f"sweep {sweep.name}: {len(sweep.cases)} cases into {folder}", file=sys.stderr)
    ds = run_sweep(
        sweep,
        folder,
        **sweep_executor(args),
        retry_failed=args.retry_failed,
        progress=None if args.quiet else sys.stderr,
        compress=args.compress,
        float32=args.float32,
    )
    print(
        f"{ds.attrs['cases_done']} done, {ds.attrs['cases_failed']} failed, {ds.attrs['cases_pending']} pending; "
        f"wrote {folder / 'combined.nc'}"
    )
    return 1 if ds.attrs["cases_failed"] else 0


def sweep_executor(args: argparse.Namespace) -> dict[str, Any]:
    """The executor arguments of ``run_sweep`` from the command's flags: none, ``executor="sequential"``;
    ``--processes N``, ``executor="processes", workers=N`` (N = 1: in this process, as the default);
    ``--dask [--workers N]``, ``executor="dask"`` with a LocalCluster of N workers (default: one per core);
    ``--scheduler ADDRESS``, ``executor="dask", scheduler=ADDRESS``.

    Raises
    ------
    ValueError
        For ``--processes`` below 1, and for ``--workers`` without ``--dask`` (the pool's size is ``--processes N``).
    """
    if args.processes is not None and args.processes < 1:
        raise ValueError(f"--processes must be an integer >= 1; got {args.processes}")
    if args.workers is not None and not (args.dask or args.scheduler):
        raise ValueError(
            f"--workers {args.workers} sets the size of the Dask LocalCluster (--dask); "
            "for a pool of processes give --processes N"
        )
    if args.dask or args.scheduler:
        return {"executor": "dask", "workers": args.workers, "scheduler": args.scheduler}
    if args.processes is not None and args.processes != 1:
        return {"executor": "processes", "workers": args.processes}
    return {"executor": "sequential"}


def check_outputs(outputs: dict[str, tuple[Path, str]], inputs: Mapping[str, Path]) -> None:
    """Refuse, before any work, output files that would overwrite an input (``inputs``: label to file or folder,
    ``wecss.files.refuse_overwrite``) or each other, that lack their suffix, that name a folder, or whose folder
    cannot be written.

    Raises
    ------
    ValueError
        Naming the output, what was received and what is accepted (for an input: its field and the file).
    """
    seen: dict[Path, str] = {}
    for label, (path, suffix) in outputs.items():
        if path.suffix.lower() != suffix:
            raise ValueError(f"the {label} file must end in {suffix}; got {str(path)!r}")
        if path.is_dir():
            raise ValueError(f"the {label} file {str(path)!r} is a folder; give a file name ending in {suffix}")
        resolved = path.resolve()
        if resolved in seen:
            raise ValueError(f"the {label} file {str(path)!r} is also the {seen[resolved]} file; give another name")
        seen[resolved] = label
        folder = resolved.parent
        if not folder.is_dir():
            raise ValueError(f"the folder of the {label} file, {str(folder)!r}, does not exist")
        try:
            with tempfile.TemporaryFile(dir=folder):
                pass
        except OSError as err:
            raise ValueError(f"cannot write the {label} file in {str(folder)!r}: {err.strerror}") from None
    refuse_overwrite({f"{label} file": path for label, (path, _) in outputs.items()}, inputs)


def _plot(args: argparse.Namespace) -> int:
    """``wecss plot``: a result's summary plot, a sweep's combined dataset (``combined.nc`` or its folder), or with
    ``--animate`` an animation of a result's bodies."""
    from .results import open_result, plot_summary

    source = Path(args.result)
    if source.is_dir():
        if not (source / "combined.nc").is_file():
            raise ValueError(f"the folder {str(source)!r} has no combined.nc; give a result file or a sweep's folder")
        source = source / "combined.nc"
    animation_options = {"--fps": args.fps, "--stride": args.stride}
    if not args.animate and any(v is not None for v in animation_options.values()):
        given = [k for k, v in animation_options.items() if v is not None]
        raise ValueError(f"{' and '.join(given)} set the animation: give --animate too")
    ds = open_result(source)
    sweep = "sweep_mode" in ds.attrs
    if not sweep and (args.variable is not None or args.select):
        raise ValueError(f"--variable and --select choose what a sweep's plot shows; {str(source)!r} is no sweep")
    if sweep:
        if args.animate:
            raise ValueError(f"{str(source)!r} is a sweep's combined dataset: animate one of its case files")
        return _plot_sweep(ds, source, args)
    if "scene" not in ds.attrs or "time" not in ds.dims:
        raise ValueError(
            f"{str(source)!r} is not a wecss result (no 'scene' attribute or 'time' dimension): nothing to plot"
        )
    if args.animate:
        return _animate(ds, source, args)
    picture = Path(args.output) if args.output else source.with_suffix(".png")
    check_outputs({"picture": (picture, ".png")}, inputs={"result file": source})
    import matplotlib.pyplot as plt

    plt.close(plot_summary(ds, picture))
    print(f"wrote {picture}")
    return 0


def _plot_sweep(ds: Any, source: Path, args: argparse.Namespace) -> int:
    from .results import plot_sweep

    picture = Path(args.output) if args.output else source.with_suffix(".png")
    check_outputs({"picture": (picture, ".png")}, inputs={"combined dataset": source})
    select: dict[str, Any] = {}
    for item in args.select or []:
        name, sep, value = item.partition("=")
        if not sep or not name:
            raise ValueError(f"--select takes DIM=VALUE (e.g. pto=pto_3 or sea.height=0.04); got {item!r}")
        try:
            select[name] = float(value)
        except ValueError:
            select[name] = value
    import matplotlib.pyplot as plt

    plt.close(plot_sweep(ds, args.variable or "total_power", select=select or None, path=picture))
    print(f"wrote {picture}")
    return 0


def _animate(ds: Any, source: Path, args: argparse.Namespace) -> int:
    from .results import animate, check_animation

    movie = Path(args.output) if args.output else source.with_suffix(".gif")
    suffix = movie.suffix.lower()
    if suffix not in (".gif", ".mp4"):
        raise ValueError(f"the animation file must end in .gif or .mp4; got {str(movie)!r}")
    check_outputs({"animation": (movie, suffix)}, inputs={"result file": source})
    fps = 20 if args.fps is None else args.fps
    stride = check_animation(ds, stride=args.stride, fps=fps)
    animate(ds, movie, stride=stride, fps=fps)
    print(f"wrote {movie} ({len(range(0, ds.sizes['time'], stride))} frames, every {stride} saved steps)")
    return 0


def _storage_options(parser: argparse.ArgumentParser) -> None:
    """``--compress LEVEL`` and ``--float32``: how result files are stored (``wecss.netcdf.write_netcdf``)."""
    parser.add_argument(
        "--compress",
        type=int,
        default=0,
        choices=range(10),
        metavar="LEVEL",
        help="zlib level of the result files, 0 (none, default) to 9 (smallest); lossless",
    )
    parser.add_argument(
        "--float32",
        action="store_true",
        help="store the results' variables in single precision (half the size; relative error 6e-8)",
    )


EXIT_WRITE_FAILED: int = 4
"""The exit status of a command whose output file could not be written (``wecss.files.WriteFailed``)."""

EXIT_STATUSES: str = (
    "exit status: 0 done; 1 a sweep with failed cases; 2 bad input (one line, no traceback); 3 a diverged run; "
    f"{EXIT_WRITE_FAILED} an output file could not be written (a full disk); 130 after Ctrl-C; 143 after SIGTERM"
)


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of the ``wecss`` command."""
    parser = argparse.ArgumentParser(
        prog="wecss", description="Multi-body wave energy converter toolkit.", epilog=EXIT_STATUSES
    )
    parser.add_argument("--version", action="version", version=f"wecss {__version__}")
    sub = parser.add_subparsers(dest="command", required=True)
    info = sub.add_parser("info", help="describe a device, a shipped hydrodynamic database or a netCDF file")
    info.add_argument(
        "target", nargs="?", help="device or database name, device spec (.toml), database or result (.nc)"
    )
    run = sub.add_parser("run", help="simulate a scene (default: the embedded M4 134 scene)", epilog=EXIT_STATUSES)
    run.add_argument("scene", nargs="?", help="scene file (.toml); without it the embedded default runs")
    run.add_argument(
        "--from",
        dest="from_result",
        metavar="RESULT.nc",
        help="run again the scene and controller recorded in a result file, after checking that every input file "
        "it records (device spec, database, elevation record) has the same SHA-256 (found where the run read it "
        "or where it moved with the result); a changed file is an error naming it and both checksums",
    )
    run.add_argument(
        "-o", "--output", help="result file (.nc); default: <scene name>.nc, with --from <result>-rerun.nc, here"
    )
    run.add_argument("--png", help="summary plot (.png); default: next to the result")
    run.add_argument("-q", "--quiet", action="store_true", help="no progress bar")
    run.add_argument(
        "--allow-dask",
        action="store_true",
        help="let dask be imported in this run (a controller or runner plugin that uses it); without it the "
        "command keeps dask out of its process, as xarray would import it for nothing (about 0.35 s)",
    )
    _storage_options(run)
    run.add_argument(
        "--set",
        action="append",
        default=[],
        metavar="PATH=VALUE",
        help="override a scene value (dotted path, TOML value), e.g. --set sea.period=1.4; repeatable",
    )
    sweep = sub.add_parser("sweep", help="run a sweep file (.toml): cases over sea states and designs, resumable")
    sweep.add_argument("sweep", help="sweep file (.toml) with [sweep] axes and the base [scene]")
    sweep.add_argument("-o", "--output", help="folder of the case files and combined.nc; default: the file's name")
    where = sweep.add_mutually_exclusive_group()
    where.add_argument(
        "--processes", type=int, metavar="N", help="run the cases in a pool of N processes (1: in this process)"
    )
    where.add_argument("--dask", action="store_true", help="run on a Dask LocalCluster (one worker per core)")
    where.add_argument("--scheduler", help="address of an existing Dask scheduler, e.g. tcp://host:8786")
    sweep.add_argument("--workers", type=int, metavar="N", help="workers of the Dask LocalCluster (default: the cores)")
    sweep.add_argument("--retry-failed", action="store_true", help="run the cases that failed before again")
    sweep.add_argument("-q", "--quiet", action="store_true", help="no progress line")
    _storage_options(sweep)
    modes = sub.add_parser(
        "modes", help="natural modes of a device with its flexible bodies, in air and in water (structural model)"
    )
    modes.add_argument("device", help="device name (wecss info lists them) or device spec (.toml)")
    medium = modes.add_mutually_exclusive_group()
    medium.add_argument("--air", action="store_true", help="in air only (no gravity, no water)")
    medium.add_argument("--water", action="store_true", help="in water only (about the static equilibrium)")
    modes.add_argument(
        "--model", choices=["full", "reduced"], default="full",
        help="flexible bodies: every finite-element DOF (default) or their reduced (Craig-Bampton) bases",
    )  # fmt: skip
    modes.add_argument("-n", type=int, default=10, metavar="N", help="number of modes (default 10)")
    modes.add_argument("--png", help="plot the mode shapes (.png); with both media FILE-air.png and FILE-water.png")
    plot = sub.add_parser(
        "plot", help="the summary plot of a result (PNG), the plot of a sweep (PNG), or an animation (--animate)"
    )
    plot.add_argument("result", help="result file (.nc), or a sweep's combined.nc or its folder")
    plot.add_argument(
        "-o", "--output", help="picture (.png), with --animate .gif or .mp4 (ffmpeg); default: next to the input"
    )
    plot.add_argument("--animate", action="store_true", help="animate the bodies (side and top views) of a result")
    plot.add_argument("--fps", type=int, help="--animate: frames per second (default 20)")
    plot.add_argument("--stride", type=int, help="--animate: saved steps per frame (default: at most 150 frames)")
    plot.add_argument("--variable", help="a sweep: the statistic to plot (default total_power)")
    plot.add_argument(
        "--select", action="append", metavar="DIM=VALUE", help="a sweep: fix a dimension beyond two (repeatable)"
    )
    warm = sub.add_parser(
        "precompile",
        help="compile the time loops into numba's cache (minutes, once per install; later runs load them)",
    )
    warm.add_argument("--jobs", type=int, default=2, help="processes compiling at once (default 2)")
    return parser


def _silence_stdout() -> None:
    """Point standard output at the null device, so that the interpreter's final flush into a closed pipe does not
    print a second error."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError):  # no file descriptor behind sys.stdout (captured in tests)
        pass


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``wecss`` command; returns the exit status (130 after Ctrl-C, 143 after SIGTERM: the
    files being written are cleaned up, a streamed result's partial file says it stopped).

    Without ``argv`` (the process's own command line: the ``wecss`` command, ``python -m wecss.cli``) the process
    is the command's (``wecss.command_process``: dask kept out of every command but ``sweep`` and ``run
    --allow-dask``, the garbage collector tuned for a short process). With ``argv`` (a call from Python) the
    calling process is left as it is."""
    args = build_parser().parse_args(argv)
    own = argv is None
    if own:
        command_process.enter(args.command, allow_dask=getattr(args, "allow_dask", False))
    try:
        with sigterm_raises():
            return _command(args)
    finally:
        if own:
            command_process.leave()


def _command(args: argparse.Namespace) -> int:
    try:
        if args.command == "info":
            return _info(args.target)
        if args.command == "run":
            return _run(
                args.scene,
                args.output,
                args.png,
                args.quiet,
                args.set,
                compress=args.compress,
                float32=args.float32,
                from_result=args.from_result,
            )
        if args.command == "sweep":
            return _sweep(args)
        if args.command == "plot":
            return _plot(args)
        if args.command == "modes":
            return _structural_modes(args)
        if args.command == "precompile":
            from .sim import precompile

            precompile(args.jobs)
            return 0
    except ImportError as err:
        hint = refusal_hint(err)
        print(f"wecss: error: {err}" + (f"; {hint}: give run --allow-dask" if hint else ""), file=sys.stderr)
        return 2
    except WriteFailed as err:  # before OSError: a failed write is no bad input (nor a diverged run)
        print(f"wecss: write failed: {err}", file=sys.stderr)
        return EXIT_WRITE_FAILED
    except (ValueError, FileNotFoundError) as err:
        print(f"wecss: error: {err}", file=sys.stderr)
        return 2
    except BrokenPipeError:  # the reader stopped early (wecss info | head): end quietly
        _silence_stdout()
        return 141
    except OSError as err:  # a file or folder the system refused: no traceback for a user of the command
        print(f"wecss: error: {err}", file=sys.stderr)
        return 2
    except RuntimeError as err:  # SimulationDiverged
        print(f"wecss: {type(err).__name__}: {err}", file=sys.stderr)
        return 3
    except Terminated:
        print("wecss: terminated (SIGTERM); finished files were kept, no half-written file left", file=sys.stderr)
        return 143
    except KeyboardInterrupt:
        print("wecss: interrupted; finished files were kept, no half-written file left", file=sys.stderr)
        return 130
    return 0  # pragma: no cover - argparse rejects unknown commands


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
