"""Runs of the NOTC device with its arm elastic (issue 28): the regular fatigue sea state (H 0.28 m, T 6.2 s, 40
periods) and a 30-minute JONSWAP sea (Hs 0.5 m, Tp 6.2 s), with the generalised-alpha runner at dt 0.05 s (the wave
step: the arm's modes are too fast for an explicit step), against the rigid device (its arm frozen) in the same
scenes with the same runner and step, and with Beeman (the default runner) at dt 0.05 s; and the elastic arm with all
its modal coordinates held quasi-static (``flexible.quasi_static_above = 0``).

The targets of the issue: the flexible regular run within 1 s of wall time, at most 3 times the rigid run's time
loop per step; the 30-minute sea within 3 s. Times: the median over ``--repeats`` runs in this process (numba
compiled and the scenes compiled before, so the times are the time loop's, ``run_time_s``, and the whole
``simulate`` call's), one BLAS thread.

    OPENBLAS_NUM_THREADS=1 python studies/bench_flexible.py     # writes the section of docs/benchmarks.md
    python studies/bench_flexible.py --quick                    # 4 periods, 2 minutes of sea, once; writes nothing
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse
import functools
import platform
import tempfile
import time
from datetime import date
from importlib import resources
from pathlib import Path

import numpy as np
from _common import ROOT, write_section

SECTION = "## Flexible NOTC arm in the time loop (`studies/bench_flexible.py`)"
T = 6.2


def elastic_spec(folder: Path, held: bool = False) -> str:
    """The NOTC spec with its arm elastic (``held``: all its modal coordinates held quasi-static), written to
    ``folder``."""
    raw = (resources.files("wecss") / "data" / "devices" / "notc-10kw.toml").read_text()
    line = "flexible = { modes = 6, damping_ratio = 0.01, elements = 16 }"
    path = folder / ("notc-held.toml" if held else "notc-elastic.toml")
    extra = ", quasi_static_above = 0" if held else ""
    path.write_text(raw.replace(line, line[:-2] + f', dynamics = "elastic"{extra} }}'))
    return str(path)


def scene(device: str, sea: dict, method: str):  # type: ignore[no-untyped-def]
    from wecss.scene import Scene

    return Scene.from_dict({
        "device": {"name": device}, "sea": sea, "controller": {"name": "damping", "parameters": {}},
        "radiation": {"method": "state_space"}, "solver": {"method": method, "dt": 0.05},
        "outputs": {"variables": ["motion", "pto"]},
    })  # fmt: skip


def timed(sc, repeats: int) -> tuple[float, float, int, float]:  # type: ignore[no-untyped-def]
    """Median loop time [s], median call time [s], steps and evaluations per step of ``repeats`` runs."""
    from wecss.sim import compile_scene, simulate

    compiled = compile_scene(sc)
    simulate(compiled)  # compiled kernels warm
    loops, calls = [], []
    for _ in range(repeats):
        start = time.perf_counter()
        ds = simulate(compiled)
        calls.append(time.perf_counter() - start)
        loops.append(float(ds.attrs["run_time_s"]))
    evaluations = float(ds.attrs.get("evaluations_per_step", np.nan))
    return float(np.median(loops)), float(np.median(calls)), ds.sizes["time"] - 1, evaluations


@functools.cache
def _evaluation_loops():  # type: ignore[no-untyped-def]
    """Compiled loops of ``configure`` and ``respond`` (numba imported here: the quick run does not time them)."""
    import numba

    from wecss.compiled.kernels import configure, respond

    @numba.njit
    def configure_loop(p, q, force, w, n):  # type: ignore[no-untyped-def]
        for _ in range(n):
            configure(p, q, force, 0.0, w)

    @numba.njit
    def respond_loop(p, v, newest, command, w, n):  # type: ignore[no-untyped-def]
        for _ in range(n):
            respond(p, v, newest, command, w)

    return configure_loop, respond_loop


def evaluation_costs(sc, repeats: int, n: int = 20000) -> tuple[float, float]:  # type: ignore[no-untyped-def]
    """Median cost [us] of one ``configure`` and one ``respond`` (the two halves of an evaluation of the equations)
    at the scene's equilibrium, small random velocities, over ``n`` calls in a compiled loop per run."""
    from wecss.compiled import kernels
    from wecss.sim import compile_scene

    configure_loop, respond_loop = _evaluation_loops()
    compiled = compile_scene(sc)
    p = compiled.plant
    w = kernels.workspace(p)
    v = np.random.default_rng(0).normal(size=p.twists.shape[0]) * 0.01
    force = np.zeros(p.hydro_index.shape[0])
    newest = np.zeros((force.size, force.size))
    command = np.zeros(p.pto_damping.shape[0])
    configure_loop(p, compiled.q0, force, w, 2)
    respond_loop(p, v, newest, command, w, 2)
    costs = []
    for loop, args in ((configure_loop, (p, compiled.q0, force, w)), (respond_loop, (p, v, newest, command, w))):
        times = []
        for _ in range(repeats):
            start = time.perf_counter()
            loop(*args, n)
            times.append((time.perf_counter() - start) / n * 1e6)
        costs.append(float(np.median(times)))
    return costs[0], costs[1]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="short runs, once; write nothing")
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()
    repeats = 1 if args.quick else args.repeats
    load = os.getloadavg()[0]  # (1-minute)
    periods, minutes = (4, 2.0) if args.quick else (40, 30.0)
    regular = {"kind": "regular", "height": 0.28, "period": T, "duration": periods * T, "ramp": T}
    irregular = {"kind": "jonswap", "height": 0.5, "period": T, "duration": minutes * 60.0, "ramp": 2 * T}
    with tempfile.TemporaryDirectory() as folder:
        flexible, held = elastic_spec(Path(folder)), elastic_spec(Path(folder), held=True)
        rows = []
        for label, sea in ((f"regular, {periods} periods", regular), (f"JONSWAP, {minutes:g} min", irregular)):
            for device, method, name in ((flexible, "generalized-alpha", "elastic arm, generalized-alpha"),
                                         (held, "generalized-alpha", "elastic arm held quasi-static, gen.-alpha"),
                                         ("notc-10kw", "generalized-alpha", "rigid arm, generalized-alpha"),
                                         ("notc-10kw", "beeman", "rigid arm, beeman")):  # fmt: skip
                loop, call, steps, evaluations = timed(scene(device, sea, method), repeats)
                rows.append((label, name, steps, evaluations, loop, call, 1e6 * loop / steps))
                print(f"{label:22s} {name:32s} {steps:6d} steps {evaluations:5.2f} eval/step loop {loop:7.3f} s "
                      f"call {call:7.3f} s  {1e6 * loop / steps:7.1f} us/step", flush=True)  # fmt: skip
    if args.quick:
        return
    sea = {"kind": "regular", "height": 0.28, "period": T, "duration": 2 * T, "ramp": T}
    with tempfile.TemporaryDirectory() as folder:
        costs = {name: evaluation_costs(scene(device, sea, "generalized-alpha"), repeats)
                 for name, device in (("elastic", elastic_spec(Path(folder))), ("rigid", "notc-10kw"))}  # fmt: skip
    for name, (conf, resp) in costs.items():
        print(f"{name}: configure {conf:.2f} us, respond {resp:.2f} us", flush=True)
    table = [
        "| sea | model, runner (dt 0.05 s) | steps | evaluations per step | loop [s] | call [s] | loop per step [us] |",
        "|---|---|---|---|---|---|---|",
    ]
    table += [f"| {a} | {b} | {c} | {d:.2f} | {e:.3f} | {f:.3f} | {g:.1f} |" for a, b, c, d, e, f, g in rows]
    ratio = {label: rows[i][6] / rows[i + 2][6] for i, label in ((0, "regular"), (4, "irregular"))}
    held_ratio = {label: rows[i][6] / rows[i + 1][6] for i, label in ((1, "regular"), (5, "irregular"))}
    text = "\n".join([
        SECTION, "",
        f"{date.today()}, {platform.processor() or platform.machine()}, {os.cpu_count()} cores, medians of {repeats} "
        f"runs in one process (numba and the scenes compiled before), one BLAS thread, load average {load:.1f} at the "
        "start (a shared machine: the ratios of one run are the figures to compare). NOTC device, its arm elastic "
        "(21 modal coordinates: 6 fixed-interface modes, 12 interface and 3 inertia-relief vectors) or frozen.", "",
        *table, "",
        f"Elastic against rigid, loop per step with the same runner: {ratio['regular']:.2f} (regular), "
        f"{ratio['irregular']:.2f} (irregular); held quasi-static (`flexible.quasi_static_above = 0`) against "
        f"rigid: {held_ratio['regular']:.2f} (regular), {held_ratio['irregular']:.2f} (irregular); the issue's "
        "targets: 1 s for the regular run, 3 s for the 30-minute "
        "sea, at most 3 times the rigid run's loop per step.", "",
        "One evaluation of the equations, its two halves (median cost of a call in a compiled loop at the "
        "equilibrium, small random velocities): `configure` (kinematics, loads, M* and its factor) "
        f"{costs['elastic'][0]:.1f} us elastic, {costs['rigid'][0]:.1f} us rigid; `respond` (velocity terms, PTO "
        f"forces, the solve) {costs['elastic'][1]:.1f} us elastic, {costs['rigid'][1]:.1f} us rigid.",
    ])  # fmt: skip
    write_section(ROOT / "docs" / "benchmarks.md", SECTION, text)


if __name__ == "__main__":
    main()
