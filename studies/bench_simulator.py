"""Benchmark: the nonlinear MFM simulator per time step, for the M4 layouts 111, 132 and 134, with convolution and
with state-space radiation, beside the paper's 4.4 ms per step (Table 3, MATLAB, 111 layout). Also the embedded
default scene end to end (M4 134, JONSWAP Hs 0.04 m, Tp 1.2 s, 100 Tp, dt = Tp/200: 20,000 steps) and the pure
numpy/Python path without numba; RK4 beside Beeman on the state-space scenes; the whole ``wecss run`` command
with the default scene's radiation (convolution) and with ``radiation.method = "state_space"``. Writes the tables
into ``docs/benchmarks.md`` (section "Simulator"), opening with the issue 15 targets (per step, the command, the
linear run) in one table, so one run of this script re-times all three.

Times are medians of repeated runs of ``simulate`` on a compiled scene: the time loop alone (with the excitation)
and the whole call (with the result Dataset: poses, elevation); compilation, the impulse response and the
state-space fit are done once before and reported apart. The
first run of a new process also compiles the numba kernels (cached on disk afterwards); it is not counted.

    python studies/bench_simulator.py           # full: three layouts, 3 repeats of the 100 Tp scene
    python studies/bench_simulator.py --quick   # m4-111 only, 10 Tp, 1 repeat (CI smoke run; writes nothing)

Run it with OPENBLAS_NUM_THREADS=1 (as the ``wecss run`` commands here are): on a shared machine the CPU-time
columns are the closer estimate of an idle machine's wall time.
"""

from __future__ import annotations

import argparse
import dataclasses
import datetime
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

from wecss.sim import JIT, Scene, compile_scene, simulate

SECTION = "## Simulator"
PAPER_STEP = 4.4e-3  # s per step, M4 paper Table 3 (MATLAB, 111 layout)


def with_solver(scene: Scene, method: str) -> Scene:
    """``scene`` with another ``solver.method``."""
    return dataclasses.replace(scene, solver=dataclasses.replace(scene.solver, method=method))


def timed(scene: Scene, repeats: int) -> tuple[float, float, float, dict, float]:
    """(compile time, median time of simulate(), median time of its time loop, attrs of the last run, median CPU
    time of simulate()) [s]."""
    start = time.perf_counter()
    compiled = compile_scene(scene)
    compile_time = time.perf_counter() - start
    simulate(compiled)  # warm-up: numba compilation or cache load
    runs, loops, cpus, attrs = [], [], [], {}
    for _ in range(repeats):
        start, start_cpu = time.perf_counter(), time.process_time()
        ds = simulate(compiled)
        runs.append(time.perf_counter() - start)
        cpus.append(time.process_time() - start_cpu)
        loops.append(float(ds.attrs["run_time_s"]))
        attrs = dict(ds.attrs)
    return compile_time, float(np.median(runs)), float(np.median(loops)), attrs, float(np.median(cpus))


def command_times(repeats: int, quick: bool) -> dict[str, tuple[float, float, float]]:
    """Per radiation method: median (wall, CPU, time loop) [s] of the whole ``wecss run`` command on the default
    scene (10 Tp for ``quick``), warm numba cache, each run in a fresh process (``_common.wall``)."""
    from wecss.results import open_result

    work = Path(tempfile.mkdtemp())
    base = [sys.executable, "-m", "wecss.cli", "run"]
    if quick:
        scene = work / "short.toml"
        text = (ROOT / "wecss" / "data" / "scenes" / "default.toml").read_text()
        scene.write_text(text.replace('"100 Tp"', '"10 Tp"').replace('ramp = "5 Tp"', 'ramp = "1 Tp"'))
        base.append(str(scene))
    loops: list[float] = []

    def read_and_clear() -> None:  # the loop time of the last run, then a clean folder for the next
        if (work / "r.nc").exists():
            with open_result(work / "r.nc") as ds:
                loops.append(float(ds.attrs["run_time_s"]))
        for name in ("r.nc", "r.png"):
            (work / name).unlink(missing_ok=True)

    out = {}
    for method in ("convolution", "state_space"):
        command = [*base, "-o", str(work / "r.nc"), "-q", "--set", f'radiation.method="{method}"']
        if not quick:  # warm the numba cache (a smoke run's one run may pay for it: its numbers are not kept)
            subprocess.run(command, env=ENV, cwd=work, check=True, capture_output=True)
        read_and_clear()
        loops.clear()
        run, cpu = wall(command, repeats, work, read_and_clear)
        read_and_clear()
        out[method] = (run, cpu, float(np.median(loops)))
    return out


def pure_python_step(device: str) -> float:
    """Seconds per step of the state-space scene without numba (short run in a subprocess, WECSS_JIT=0; the second
    run, after the first has paid the lazy imports)."""
    code = (
        "import time, dataclasses, sys; sys.path.insert(0, 'studies')\n"
        "from _scenes import layout_scene\n"
        "from wecss.sim import compile_scene, simulate\n"
        f"sc = layout_scene({device!r}, 'state_space', 0.6, 0.1)\n"
        "c = compile_scene(sc); simulate(c)\n"  # the first run also pays the lazy imports
        "t = time.perf_counter(); ds = simulate(c); print((time.perf_counter() - t) / c.n_steps)\n"
    )
    env = {**os.environ, "WECSS_JIT": "0"}
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True, cwd=ROOT)
    return float(out.stdout.strip().splitlines()[-1])


def linear_times(scene: Scene, repeats: int) -> dict[str, float]:
    """Median seconds on one scene: the linear run (its loop, and the whole call with the Dataset), the
    frequency-domain solution at every step, the nonlinear run's loop, and the linearisation (first and cached)."""
    from wecss.linear import steady_state
    from wecss.sim import linearize, simulate_linear

    compiled = compile_scene(scene)
    start = time.perf_counter()
    model = linearize(compiled, cache=False)
    model.modal_steps(compiled.dt)
    first = time.perf_counter() - start
    cached = []
    for _ in range(repeats):
        start = time.perf_counter()
        linearize(compile_scene(scene))
        cached.append(time.perf_counter() - start)
    simulate_linear(compiled, model)  # warm-up
    loop, whole, fd = [], [], []
    for _ in range(max(repeats, 5)):
        start = time.perf_counter()
        ds = simulate_linear(compiled, model)
        whole.append(time.perf_counter() - start)
        loop.append(float(ds.attrs["run_time_s"]))
        start = time.perf_counter()
        steady_state(compiled, compiled.time)
        fd.append(time.perf_counter() - start)
    nonlinear = [float(simulate(compiled).attrs["run_time_s"]) for _ in range(repeats)]
    return {
        "loop": float(np.median(loop)),
        "whole": float(np.median(whole)),
        "fd": float(np.median(fd)),
        "nonlinear": float(np.median(nonlinear)),
        "linearize": first,
        "recompile_cached": float(np.median(cached)),
        "states": float(model.n_states),
        "modes": float(model.modal_form.n_modes),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args()
    devices = ["m4-111"] if args.quick else ["m4-111", "m4-132", "m4-134"]
    duration, repeats = ("10 Tp", 1) if args.quick else ("100 Tp", 3)
    rows = []
    for device in devices:
        for radiation, method in (("state_space", "beeman"), ("state_space", "rk4"), ("convolution", "beeman")):
            if method == "rk4" and device == "m4-132":
                continue
            scene = with_solver(layout_scene(device, radiation, duration), method)
            compile_time, run, loop, attrs, cpu = timed(scene, repeats)
            steps = int(attrs["n_steps"])
            rows.append((device, radiation, method, attrs["radiation"], compile_time, run, loop, steps, attrs, cpu))
            print(
                f"{device} {radiation} {method}: loop {loop / steps * 1e6:.1f} us/step, simulate() {run:.2f} s "
                f"(CPU {cpu:.2f} s)",
                flush=True,
            )
    pure = pure_python_step("m4-111")
    lin = linear_times(layout_scene(devices[-1], "state_space", duration), repeats)
    commands = command_times(repeats, args.quick)
    load = os.getloadavg()[0]
    numba = "on" if JIT else "off (numba not installed: the pure path)"
    when = datetime.datetime.now(datetime.UTC).strftime("%Y-%m-%d")
    per_step = {(d, rad, m): loop / steps for d, rad, m, _, _, _, loop, steps, _, _ in rows}
    last = devices[-1]
    targets = [
        *[
            (f"{d} state space, Beeman, time loop per step", f"{per_step[(d, 'state_space', 'beeman')] * 1e6:.1f} us",
             goal)
            for d, goal in (("m4-111", "10 us"), ("m4-134", "20 us"))
            if d in devices
        ],
        *[
            (f"{d} state space, RK4, time loop per step", f"{per_step[(d, 'state_space', 'rk4')] * 1e6:.1f} us", "")
            for d in ("m4-111", "m4-134")
            if d in devices
        ],
        *[
            (f"`wecss run`{' (10 Tp)' if args.quick else ''}, {m.replace('_', ' ')}: whole command, wall (CPU)",
             f"{commands[m][0]:.2f} s ({commands[m][1]:.2f} s)", "3 s")
            for m in ("convolution", "state_space")
        ],
        *[
            (f"`wecss run`{' (10 Tp)' if args.quick else ''}, {m.replace('_', ' ')}: its time loop",
             f"{commands[m][2]:.2f} s", "0.4 s")
            for m in ("convolution", "state_space")
        ],
        (f"linear run of {last} ({duration}), loop with the excitation", f"{lin['loop'] * 1e3:.1f} ms", "15 ms"),
        ("the same with the Dataset (whole simulate_linear())", f"{lin['whole'] * 1e3:.1f} ms", "40 ms"),
    ]  # fmt: skip
    lines = [
        SECTION,
        "",
        f"`OPENBLAS_NUM_THREADS=1 python studies/bench_simulator.py{' --quick' if args.quick else ''}` on "
        f"{platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}, numba {numba}, {when}; "
        f"load average {load:.1f} at the end of the run{' (under load: wall times are inflated)' if load > 1.5 else ''}"
        f"; JONSWAP Hs 0.04 m, Tp 1.2 s, gamma 3.3, {duration}, dt = Tp/200 = 6 ms, Beeman predictor-corrector "
        f"(tolerance 1e-6), PTO damping 6 N m s/rad; medians of {repeats} runs after a warm-up run.",
        "",
        "Targets (issue 15):",
        "",
        "| what | measured | target |",
        "|---|---|---|",
        *[f"| {what} | {value} | {goal} |" for what, value, goal in targets],
        "",
        "| layout | radiation | integrator | model | time loop per step | whole simulate() per step | simulate() "
        "(CPU) | evaluations per step | paper's 4.4 ms per step / ours | compile scene (IRF; fit from cache) |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for device, radiation, method, model, compile_time, run, loop, steps, attrs, cpu in rows:
        evaluations = f"{attrs['evaluations_per_step']:.2f}" if "evaluations_per_step" in attrs else "4"
        lines.append(
            f"| {device} | {radiation.replace('_', ' ')} | {method} | {model.split(';')[0].split(', every')[0]} | "
            f"{loop / steps * 1e6:.1f} us | {run / steps * 1e6:.1f} us | {run:.2f} s ({cpu:.2f} s) | "
            f"{evaluations} | {PAPER_STEP / (run / steps):,.0f} | {compile_time:.2f} s |"
        )
    lines += [
        "",
        f"Pure Python/numpy path (WECSS_JIT=0, same kernels uncompiled), m4-111 with state-space radiation: "
        f"{pure * 1e3:.2f} ms per step.",
        "",
        f"Linear model of the same {devices[-1]} scene (issue 6; medians of {max(repeats, 5)} runs):",
        "",
        "| what | time | nonlinear loop / this |",
        "|---|---|---|",
        f"| linear run, exact first-order hold in {lin['modes']:.0f} modal coordinates ({lin['states']:.0f} states), "
        f"loop with the excitation | {lin['loop'] * 1e3:.1f} ms | {lin['nonlinear'] / lin['loop']:.0f} |",
        f"| the same, whole simulate_linear() with the Dataset (poses, elevation) | {lin['whole'] * 1e3:.1f} ms | "
        f"{lin['nonlinear'] / lin['whole']:.0f} |",
        f"| exact frequency-domain solution from A(omega), B(omega), evaluated at every step | "
        f"{lin['fd'] * 1e3:.1f} ms | {lin['nonlinear'] / lin['fd']:.0f} |",
        f"| nonlinear run (state space), loop | {lin['nonlinear']:.2f} s | 1 |",
        f"| linearize() with its modal form and step, first call (fit from cache) | {lin['linearize'] * 1e3:.0f} ms "
        "| |",
        f"| compile_scene() + linearize() again (model cached by scene fingerprint) | "
        f"{lin['recompile_cached'] * 1e3:.0f} ms | |",
        "",
        "Targets (issue 6): the linear run at most 50 ms open loop, the frequency-domain solution at most 20 ms.",
        "",
        "Targets (issue 5): 111 with state-space radiation at most 20 us per step; the default 134 scene "
        "(20,000 steps) in at most 2 s with state-space radiation and 10 s with convolution. The paper reports "
        "4-8 minutes per 134 sea state.",
    ]
    print("\n".join(lines))
    if not args.quick:  # a smoke run's numbers do not replace the measured table
        write_section(ROOT / "docs" / "benchmarks.md", SECTION, "\n".join(lines))


if __name__ == "__main__":
    main()
