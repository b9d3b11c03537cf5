"""Benchmark: what a user waits for around the time loop: ``import wecss`` and ``import wecss.sim``, the whole
``wecss run`` command on the embedded default scene (warm numba cache), ``compile_scene`` of a second sea state of
the same device, and the cost per step against the run length (100 Tp and 500 Tp: the wave components grow with
the duration, d_omega = 2 pi / duration). Medians of repeated runs, each import and command in a fresh process,
OPENBLAS_NUM_THREADS=1; wall and CPU time. Writes the section "Start-up, whole command and run length" of
``docs/benchmarks.md``.

    python studies/bench_startup.py           # full: 5 repeats
    python studies/bench_startup.py --quick   # 1 repeat, a 10 Tp scene instead of the default command; temp folder
"""

from __future__ import annotations

import argparse
import dataclasses
import datetime
import os
import platform
import resource
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np
from _common import ROOT, write_section

SECTION = "## Start-up, whole command and run length"
ENV = {**os.environ, "OPENBLAS_NUM_THREADS": "1", "PYTHONPATH": str(ROOT)}


def wall(command: list[str], repeats: int, cwd: Path, before: Callable[[], None] = lambda: None) -> tuple[float, float]:
    """Median (wall time, CPU time: user + system) [s] of a command in a fresh process. On a shared machine the CPU
    time is the closer estimate of the wall time on an idle one."""
    runs, cpus = [], []
    for _ in range(repeats):
        before()
        usage = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.perf_counter()
        subprocess.run(command, env=ENV, cwd=cwd, check=True, capture_output=True)
        runs.append(time.perf_counter() - start)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpus.append(after.ru_utime - usage.ru_utime + after.ru_stime - usage.ru_stime)
    return float(np.median(runs)), float(np.median(cpus))


def in_process(repeats: int, quick: bool) -> dict[str, float]:
    """compile_scene of a second sea state (state space and convolution) [s]; loop time per step at 100 Tp and
    500 Tp (m4-134, state space) [s]."""
    sys.path.insert(0, str(ROOT / "studies"))
    from bench_simulator import layout_scene

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
        label = "`wecss run` (embedded default: m4-134, convolution, 20,000 steps), whole command"
    subprocess.run(command, env=ENV, cwd=work, check=True, capture_output=True)  # warm the numba cache

    def fresh() -> None:
        for name in ("r.nc", "r.png"):
            (work / name).unlink(missing_ok=True)

    rows.append((label, *wall(command, repeats, work, fresh), "3 s"))
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
    ]
    text = "\n".join(lines)
    print(text)
    if not args.quick:
        write_section(ROOT / "docs" / "benchmarks.md", SECTION, text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
