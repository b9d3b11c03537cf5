"""Sweep throughput (issue 29): a power matrix of nonlinear m4-134 cases, statistics only (JONSWAP, 100 Tp, dt =
Tp/200, Beeman, state-space radiation, damping 6 N m s/rad), on a grid of 10 peak periods x 10 heights x 10 seeds
(1,000 cases), with each executor of ``run_sweep``: this process (sequential), a pool of 2 worker processes and a
local Dask cluster of 2 workers; cases per minute, the compile time per case after the first, and the share of a case
spent outside the time loop (compile, result, file, combining).

    OPENBLAS_NUM_THREADS=1 python studies/bench_sweep.py      # the "Sweeps" section of docs/benchmarks.md
    python studies/bench_sweep.py --quick                     # 4 short cases into a temporary folder; writes nothing

``--cases N`` runs the first N cases of the grid (a multiple of 100: the first N / 100 periods) on the pool and Dask
(default 1,000), ``--sequential-cases`` in this process (default 200: 1,000 there would take twice as long as the
pool).
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import ROOT, write_section

from wecss.results import open_result
from wecss.scene import Scene, default_scene_path
from wecss.sweep import Executor, Sweep, run_sweep

PERIODS = tuple(round(0.8 + 0.1 * i, 1) for i in range(10))  # s
HEIGHTS = tuple(round(0.02 + 0.005 * i, 3) for i in range(10))  # m
SEEDS = tuple(range(1, 11))


def sweep(quick: bool, cases: int = 1000) -> Sweep:
    """The grid, or its first ``cases`` cases (a multiple of 100: the first periods, every height and seed)."""
    scene = Scene.from_toml(default_scene_path()).to_dict()
    scene["radiation"] = {"method": "state_space"}
    scene["outputs"] = {"statistics_only": True, "variables": []}
    if quick:
        scene["sea"]["duration"] = "10 Tp"
        scene["sea"]["ramp"] = "2 Tp"
        return Sweep(scene, (("sea.period", (1.0, 1.4)), ("sea.seed", (1, 2))), name="bench")
    per_period = len(HEIGHTS) * len(SEEDS)
    if cases % per_period or not 0 < cases <= per_period * len(PERIODS):
        raise SystemExit(f"cases must be a multiple of {per_period} up to {per_period * len(PERIODS)}; got {cases}")
    periods = PERIODS[: cases // per_period]
    return Sweep(scene, (("sea.period", periods), ("sea.height", HEIGHTS), ("sea.seed", SEEDS)), name="bench")


def measure(
    folder: Path, spec: Sweep, executor: Executor = "sequential", workers: int | None = None
) -> dict[str, float]:
    start = time.perf_counter()
    ds = run_sweep(spec, folder, executor=executor, workers=workers, progress=None)
    wall = time.perf_counter() - start
    run = json.loads(ds.attrs["sweep_run"])
    loops = [open_result(p).attrs["run_time_s"] for p in sorted(folder.glob("c[0-9]*.nc"))]
    n = len(spec.cases)
    return {
        "cases": n,
        "failed": int(ds.attrs["cases_failed"]),
        "wall_s": wall,
        "cases_per_min": 60 * n / wall,
        "compile_first_s": run["compile_time_s"][0],
        "compile_after_s": float(np.median(run["compile_time_s"][1:])) if n > 1 else float("nan"),
        "run_median_s": float(np.median(run["run_time_s"])),
        "loop_median_s": float(np.median(loops)),
    }


def _row(name: str, r: dict[str, float], workers: int) -> str:
    # the share of a worker's time outside the time loop: (wall x workers / cases - loop) / (wall x workers / cases)
    per_case = r["wall_s"] * workers / r["cases"]
    outside = (per_case - r["loop_median_s"]) / per_case
    return (
        f"| {name} | {r['cases']:.0f} | {r['failed']:.0f} | {r['wall_s']:.1f} s | {r['cases_per_min']:.1f} | "
        f"{per_case:.3f} s | {r['loop_median_s']:.3f} s | {outside:.1%} | {r['compile_first_s']:.2f} s | "
        f"{r['compile_after_s']:.3f} s | {r['run_median_s']:.3f} s |"
    )


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--cases", type=int, default=1000, help="cases of the grid on the pool and Dask")
    parser.add_argument("--sequential-cases", type=int, default=200, help="cases of the grid in this process")
    args = parser.parse_args(argv)
    plan: list[tuple[str, Executor, int, Sweep]] = [
        ("sequential (this process)", "sequential", 1, sweep(args.quick, args.sequential_cases)),
        ("pool of 2 worker processes", "processes", 2, sweep(args.quick, args.cases)),
    ]
    try:
        import dask.distributed  # noqa: F401

        plan.append(("local Dask cluster, 2 workers", "dask", 2, sweep(args.quick, args.cases)))
    except ImportError:
        print("dask not installed: the Dask row is skipped", file=sys.stderr)
    rows: dict[str, tuple[dict[str, float], int]] = {}
    with tempfile.TemporaryDirectory() as tmp:
        for name, executor, workers, spec in plan:
            folder = Path(tmp) / executor
            rows[name] = (measure(folder, spec, executor, None if executor == "sequential" else workers), workers)
            print(name, json.dumps(rows[name][0]), flush=True)
    if args.quick:
        return 0
    load = os.getloadavg()[0]
    lines = [
        "## Sweeps",
        "",
        f"`OPENBLAS_NUM_THREADS=1 python studies/bench_sweep.py` on {platform.machine()}, {os.cpu_count()} cores, "
        f"Python {platform.python_version()}, {time.strftime('%Y-%m-%d')}, load average {load:.1f} at the end: "
        "nonlinear m4-134 cases, statistics only (JONSWAP, 100 Tp, dt = Tp/200: 20,000 Beeman steps, state-space "
        "radiation, damping 6 N m s/rad), on a grid of `sea.period` 0.8-1.7 s x `sea.height` 0.02-0.065 m x "
        "`sea.seed` 1-10 (the first cases of it where fewer are run: periods vary slowest), one sweep per executor "
        "into a new folder (each worker process starts cold: imports, cached kernels, first compile).",
        "",
        "| executor | cases | failed | wall time | cases per minute | wall per case per worker | time loop per case "
        "(median) | outside the time loop | compile, first case | compile per case after the first (median) | "
        "simulate() per case (median) |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    lines += [_row(name, r, workers) for name, (r, workers) in rows.items()]
    pool = rows.get("pool of 2 worker processes")
    if pool is not None:
        r = pool[0]
        thousand = 1000 * r["wall_s"] / r["cases"]
        lines += [
            "",
            f"Target (issue 29): 1,000 cases in at most 4 minutes on the 2-core machine, the overhead outside the time "
            f"loop at most 15 % of a case. The pool ran {r['cases']:.0f} cases in {r['wall_s']:.0f} s "
            f"({thousand / 60:.2f} min per 1,000 cases).",
        ]
    write_section(ROOT / "docs" / "benchmarks.md", "## Sweeps", "\n".join(lines))
    print("wrote the Sweeps section of docs/benchmarks.md")
    return 0


if __name__ == "__main__":
    sys.exit(main())
