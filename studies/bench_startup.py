"""Benchmark: what a user waits for around the time loop: ``import wecss`` and ``import wecss.sim``, the whole
``wecss run`` command on the embedded default scene (warm numba cache), ``compile_scene`` of a second sea state of
the same device, and the cost per step against the run length (100 Tp and 500 Tp: the wave components grow with
the duration, d_omega = 2 pi / duration). Medians of repeated runs, each import and command in a fresh process,
OPENBLAS_NUM_THREADS=1; wall and CPU time; and the command step by step (CPU time of each step, with and without
dask visible to xarray). Writes the section "Start-up, whole command and run length" of ``docs/benchmarks.md``.

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
if sys.argv[3] == "hidden":  # as on an install without the dask extra: xarray then imports no dask
    sys.modules["dask"] = sys.modules["distributed"] = None
cpu = [time.process_time()]
def mark():
    cpu.append(time.process_time())
from wecss.results import plot_summary, save
from wecss.sim import Scene, compile_scene, default_scene_path, simulate
mark()
scene = Scene.from_toml(sys.argv[1])
compiled = compile_scene(scene)
mark()
ds = simulate(compiled, progress=False)
mark()
save(ds, sys.argv[2] + ".nc")
mark()
plot_summary(ds, sys.argv[2] + ".png")
mark()
loaded = [m for m in ("dask.array", "distributed", "numba", "scipy.signal", "scipy.integrate") if sys.modules.get(m)]
print(json.dumps({"cpu": [b - a for a, b in zip(cpu, cpu[1:])], "loop": ds.attrs["run_time_s"], "loaded": loaded}))
"""
"""The command's steps (as ``wecss run`` takes them) with the CPU time [s] of each, in a fresh process:
argv scene, output stem, "hidden" to hide dask from xarray."""

STAGE_NAMES = (
    "imports (wecss.results, wecss.sim)",
    "compile_scene (database read included)",
    "simulate: loading numba's cached kernels, the time loop, the Dataset",
    "save (netCDF)",
    "summary plot (matplotlib import included)",
)


def stages(scene: Path, work: Path, repeats: int, hidden: bool) -> tuple[list[float], float, list[str]]:
    """Median CPU time of each of the command's steps [s], the median time loop (wall, as the result records
    it) [s] and the heavy modules the run loaded; fresh processes, numba cache warm."""
    runs, loops, loaded = [], [], []
    for _ in range(repeats):
        command = [sys.executable, "-c", STAGES, str(scene), str(work / "s"), "hidden" if hidden else "visible"]
        out = subprocess.run(command, env=ENV, cwd=work, check=True, capture_output=True, text=True)
        data = json.loads(out.stdout.strip().splitlines()[-1])
        runs.append(data["cpu"])
        loops.append(data["loop"])
        loaded = data["loaded"]
    return [float(v) for v in np.median(runs, axis=0)], float(np.median(loops)), loaded


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
        ("`import wecss`", *wall([py, "-c", "import wecss"], repeats, work), "0.8 s"),
        ("`import wecss.sim`", *wall([py, "-c", "import wecss.sim"], repeats, work), "0.8 s"),
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
    subprocess.run(command, env=ENV, cwd=work, check=True, capture_output=True)  # warm the numba cache

    def fresh() -> None:
        for name in ("r.nc", "r.png"):
            (work / name).unlink(missing_ok=True)

    rows.append((label, *wall(command, repeats, work, fresh), "3 s"))
    scene_file = scene if args.quick else ROOT / "wecss" / "data" / "scenes" / "default.toml"
    breakdown = {hidden: stages(scene_file, work, repeats, hidden) for hidden in (False, True)}
    extra = in_process(repeats, args.quick)
    for method in ("state_space", "convolution"):
        name = f"`compile_scene` of a second sea state (m4-134, {method.replace('_', ' ')})"
        rows.append((name, extra[f"second compile {method}"], extra[f"second compile cpu {method}"], "0.2 s"))
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
        "| what | wall time | CPU time | target (issue 15, wall) |",
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
        "The same command step by step (CPU time of each step in a fresh process, medians; the time loop is the "
        "result's run_time_s, wall). With the dask extra installed xarray imports dask.array when it makes its "
        "first variable and distributed when it writes a netCDF file (to ask for a dask scheduler); the second "
        "column hides dask from xarray, as on an install without that extra:",
        "",
        "| step | CPU time | CPU time, dask hidden |",
        "|---|---|---|",
        *[
            f"| {name} | {breakdown[False][0][k]:.2f} s | {breakdown[True][0][k]:.2f} s |"
            for k, name in enumerate(STAGE_NAMES)
        ],
        f"| all steps | {sum(breakdown[False][0]):.2f} s | {sum(breakdown[True][0]):.2f} s |",
        f"| (the time loop, inside simulate) | {breakdown[False][1]:.2f} s | {breakdown[True][1]:.2f} s |",
        "",
        f"Loaded by the run: {', '.join(breakdown[False][2])}; with dask hidden: {', '.join(breakdown[True][2])}.",
        "",
    ]
    text = "\n".join(lines)
    print(text)
    if not args.quick:
        write_section(ROOT / "docs" / "benchmarks.md", SECTION, text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
