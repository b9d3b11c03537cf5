"""Benchmark: what a user waits for around the time loop: ``import wecss`` and ``import wecss.sim``, the whole
``wecss run`` command on the embedded default scene (warm numba cache), ``compile_scene`` of a second sea state of
the same device, and the cost per step against the run length (100 Tp and 500 Tp: the wave components grow with
the duration, d_omega = 2 pi / duration). Medians of repeated runs, each import and command in a fresh process,
OPENBLAS_NUM_THREADS=1; wall and CPU time; and the command step by step (CPU time of each step, as the command runs
and with ``--allow-dask``). Writes the section "Start-up, whole command and run length" of ``docs/benchmarks.md``.

    python studies/bench_startup.py           # full: 5 repeats
    python studies/bench_startup.py --quick   # 1 repeat, a 10 Tp scene instead of the default command; temp folder
"""

from __future__ import annotations

import argparse
import dataclasses
import datetime
import json
import os
import platform
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from _common import ENV, ROOT, wall, write_section
from _scenes import layout_scene

SECTION = "## Start-up, whole command and run length"


STAGES = """
import json, sys, time
cpu, wall = [time.process_time()], [time.perf_counter()]  # CPU so far: the interpreter's start-up
def mark():
    cpu.append(time.process_time())
    wall.append(time.perf_counter())
from wecss import command_process
command_process.enter("run", allow_dask=sys.argv[3] == "allow-dask")  # as the command sets up its process
import wecss.cli
from wecss.compiled import scene_inputs
from wecss.results import plot_summary
from wecss.sim import Scene, compile_scene, simulate
mark()
scene = Scene.from_toml(sys.argv[1])
scene_inputs(scene)
compiled = compile_scene(scene)
mark()
ds = simulate(compiled, progress=False, path=sys.argv[2] + ".nc")
mark()
import matplotlib.pyplot as plt
plt.close(plot_summary(ds, sys.argv[2] + ".png"))
mark()
text = wecss.cli.run_summary(ds)
ds.close()
mark()
heavy = ("dask", "dask.array", "distributed", "numba", "matplotlib", "scipy.signal", "scipy.integrate")
loaded = [m for m in heavy if sys.modules.get(m)]
print(json.dumps({"cpu": [b - a for a, b in zip(cpu, cpu[1:])], "start": cpu[0], "wall": wall[-1] - wall[0],
                  "loop": float(ds.attrs["run_time_s"]), "loaded": loaded}))
"""
"""The steps of ``wecss run`` (as the command takes them, with the same calls) with the CPU time of each, in a
fresh process set up as the command's (``wecss.command_process``): argv scene, output stem, "default" (dask kept
out, as the command) or "allow-dask" (as ``--allow-dask``)."""

STAGE_NAMES = (
    "interpreter start-up (CPU before the first line)",
    "imports (wecss.cli and what `run` imports)",
    "read the scene, compile_scene (database read included)",
    "simulate, streamed to the file: numba's cached kernels, the time loop, the netCDF parts and statistics",
    "summary plot (matplotlib import included)",
    "summary table (mean power, CWR, RMS angle), file closed",
)


def stages(scene: Path, work: Path, repeats: int, mode: str) -> tuple[list[float], float, float, list[str]]:
    """Median CPU time of each of the command's steps [s] (start-up first), the median wall time from the first
    line to the last [s], the median time loop (wall, as the result records it) [s] and the heavy modules the
    run loaded; fresh processes, numba cache warm."""
    runs, walls, loops, loaded = [], [], [], []
    for _ in range(repeats):
        for name in ("s.nc", "s.png"):
            (work / name).unlink(missing_ok=True)
        command = [sys.executable, "-c", STAGES, str(scene), str(work / "s"), mode]
        out = subprocess.run(command, env=ENV, cwd=work, check=True, capture_output=True, text=True)
        data = json.loads(out.stdout.strip().splitlines()[-1])
        runs.append([data["start"], *data["cpu"]])
        walls.append(data["wall"])
        loops.append(data["loop"])
        loaded = data["loaded"]
    medians = [float(v) for v in np.median(runs, axis=0)]
    return medians, float(np.median(walls)), float(np.median(loops)), loaded


def stage_table(scene: Path, work: Path, repeats: int) -> list[str]:
    """The Markdown table of the command's steps, as the command runs and with ``--allow-dask``, and the line of
    the modules loaded."""
    modes = {mode: stages(scene, work, repeats, mode) for mode in ("default", "allow-dask")}
    (steps, wall_in, loop, loaded), (other, _, other_loop, other_loaded) = modes["default"], modes["allow-dask"]
    return [
        "| step of `wecss run` | CPU time | CPU time, `--allow-dask` |",
        "|---|---|---|",
        *[f"| {name} | {steps[k]:.2f} s | {other[k]:.2f} s |" for k, name in enumerate(STAGE_NAMES)],
        f"| all steps | {sum(steps):.2f} s | {sum(other):.2f} s |",
        f"| (the time loop, inside simulate; wall) | {loop:.2f} s | {other_loop:.2f} s |",
        f"| (wall time from the first line to the last) | {wall_in:.2f} s | |",
        "",
        f"Loaded by the run: {', '.join(loaded)}; with `--allow-dask`: {', '.join(other_loaded)}.",
    ]


def in_process(repeats: int, quick: bool) -> dict[str, float]:
    """compile_scene of a second sea state (state space and convolution) [s]; loop time per step at 100 Tp and
    500 Tp (m4-134, state space) [s]."""
    from wecss.sim import compile_scene, simulate

    out: dict[str, float] = {}
    for method in ("state_space", "convolution"):
        base = layout_scene("m4-134", method, "10 Tp" if quick else "100 Tp")
        compile_scene(base)
        second, cpu = [], []
        for k in range(repeats):
            sea = dataclasses.replace(base.sea, height=0.05 + 0.001 * k, seed=2 + k)
            start, start_cpu = time.perf_counter(), time.process_time()
            compile_scene(dataclasses.replace(base, sea=sea))
            second.append(time.perf_counter() - start)
            cpu.append(time.process_time() - start_cpu)
        out[f"second compile {method}"] = float(np.median(second))
        out[f"second compile cpu {method}"] = float(np.median(cpu))
    for duration in ("10 Tp", "50 Tp") if quick else ("100 Tp", "500 Tp"):
        compiled = compile_scene(layout_scene("m4-134", "state_space", duration))
        simulate(compiled)
        loops = [float(simulate(compiled).attrs["run_time_s"]) for _ in range(repeats)]
        out[f"step {duration}"] = float(np.median(loops)) / compiled.n_steps
        out[f"components {duration}"] = float(compiled.excitation.omega.size)  # type: ignore[union-attr]
    return out


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="1 repeat, short scenes (CI smoke run)")
    args = parser.parse_args(argv)
    repeats = 1 if args.quick else 5
    work = Path(tempfile.mkdtemp())
    py = sys.executable
    rows = [
        ("`import wecss`", *wall([py, "-c", "import wecss"], repeats, work), "0.8 s (issue 15)"),
        ("`import wecss.sim`", *wall([py, "-c", "import wecss.sim"], repeats, work), "0.8 s (issue 15)"),
    ]
    if args.quick:
        scene = work / "short.toml"
        text = (ROOT / "wecss" / "data" / "scenes" / "default.toml").read_text()
        scene.write_text(
            text.replace('duration = "100 Tp"', 'duration = "10 Tp"').replace('ramp = "5 Tp"', 'ramp = "1 Tp"')
        )
        command = [py, "-m", "wecss.cli", "run", str(scene), "-o", str(work / "r.nc"), "-q"]
        label = "`wecss run` of the default scene shortened to 10 Tp"
    else:
        command = [py, "-m", "wecss.cli", "run", "-o", str(work / "r.nc"), "-q"]
        label = "`wecss run` (embedded default: m4-134, state space, 20,000 steps), whole command"
    if not args.quick:  # warm the numba cache (a smoke run's one run may pay for it: its numbers are not kept)
        subprocess.run(command, env=ENV, cwd=work, check=True, capture_output=True)

    def fresh() -> None:
        for name in ("r.nc", "r.png"):
            (work / name).unlink(missing_ok=True)

    rows.append((label, *wall(command, repeats, work, fresh), "1.5 s (issue 29)"))
    rows.append(
        (
            "the same with `--allow-dask` (dask imported, as before)",
            *wall([*command, "--allow-dask"], repeats, work, fresh),
            "",
        )
    )
    scene_file = scene if args.quick else ROOT / "wecss" / "data" / "scenes" / "default.toml"
    breakdown = stage_table(scene_file, work, repeats)
    extra = in_process(repeats, args.quick)
    for method in ("state_space", "convolution"):
        name = f"`compile_scene` of a second sea state (m4-134, {method.replace('_', ' ')})"
        rows.append(
            (name, extra[f"second compile {method}"], extra[f"second compile cpu {method}"], "0.2 s (issue 15)")
        )
    durations = ("10 Tp", "50 Tp") if args.quick else ("100 Tp", "500 Tp")
    when = datetime.datetime.now(datetime.UTC).strftime("%Y-%m-%d")
    lines = [
        SECTION,
        "",
        f"`python studies/bench_startup.py` on {platform.machine()}, {os.cpu_count()} cores, load average "
        f"{os.getloadavg()[0]:.1f} at the end, "
        f"Python {platform.python_version()}, OPENBLAS_NUM_THREADS=1, {when}; medians of {repeats} runs, each "
        "import and command in a fresh process, numba cache warm.",
        "",
        "| what | wall time | CPU time | target (wall) |",
        "|---|---|---|---|",
        *[f"| {name} | {value:.2f} s | {cpu:.2f} s | {target} |" for name, value, cpu, target in rows],
        "",
        "Cost per step against the run length (m4-134, state space, Beeman, dt = Tp/200; the wave components grow "
        "with the duration; the excitation is evaluated once per run, by one inverse FFT):",
        "",
        "| duration | wave components | time loop per step |",
        "|---|---|---|",
        *[f"| {d} | {extra[f'components {d}']:.0f} | {extra[f'step {d}'] * 1e6:.1f} us |" for d in durations],
        "",
        "The same command step by step: each step's CPU time in a fresh process (medians), the same calls as "
        "`wecss run` makes, the interpreter's start-up first (the whole command's CPU time above also holds the "
        "interpreter's exit). The command keeps dask out of its process (`wecss.dask_free`): with the dask extra "
        "installed xarray would import dask.array when it makes its first variable and distributed when it "
        "writes a netCDF file; the second column lets it in (`--allow-dask`), as every run did before:",
        "",
        *breakdown,
        "",
    ]
    text = "\n".join(lines)
    print(text)
    if not args.quick:
        write_section(ROOT / "docs" / "benchmarks.md", SECTION, text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
