"""Sweep throughput: cases per minute of an m4-134 statistics-only sweep, in this process (sequential) and on a local
Dask cluster of 2 workers; the compile time per case after the first and the share of a case spent outside the time
loop (compile, result, file).

    python studies/bench_sweep.py            # 100 cases (10 Tp x 10 seeds); the "Sweeps" section of docs/benchmarks.md
    python studies/bench_sweep.py --quick    # 4 short cases into a temporary folder; writes nothing in docs/
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


def sweep(quick: bool) -> Sweep:
    scene = Scene.from_toml(default_scene_path()).to_dict()
    scene["radiation"] = {"method": "state_space"}
    scene["outputs"] = {"statistics_only": True, "variables": []}
    if quick:
        scene["sea"]["duration"] = "10 Tp"
        scene["sea"]["ramp"] = "2 Tp"
    periods = (1.0, 1.4) if quick else tuple(round(0.8 + 0.1 * i, 1) for i in range(10))
    seeds = (1, 2) if quick else tuple(range(1, 11))
    return Sweep(scene, (("sea.period", periods), ("sea.seed", seeds)), name="bench")


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


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args(argv)
    spec = sweep(args.quick)
    rows = {}
    with tempfile.TemporaryDirectory() as tmp:
        rows["sequential (this process)"] = measure(Path(tmp) / "seq", spec)
        try:
            import dask.distributed  # noqa: F401

            rows["local Dask, 2 workers"] = measure(Path(tmp) / "dask", spec, executor="dask", workers=2)
        except ImportError:
            print("dask not installed: the Dask row is skipped", file=sys.stderr)
    seq = rows["sequential (this process)"]
    # per case outside the time loop, sequential: (wall per case - time loop) / wall per case
    per_case = seq["wall_s"] / seq["cases"]
    overhead = (per_case - seq["loop_median_s"]) / per_case
    print(json.dumps({**rows, "overhead_share_sequential": overhead}, indent=1))
    if args.quick:
        return 0
    lines = [
        "## Sweeps",
        "",
        f"`python studies/bench_sweep.py` on {platform.machine()}, Python {platform.python_version()}, "
        "OPENBLAS_NUM_THREADS=1, 2 cores shared with other jobs: a 100-case m4-134 statistics-only sweep "
        "(`sea.period` 0.8-1.7 s x `sea.seed` 1-10, JONSWAP Hs 0.04 m, 100 Tp, dt = Tp/200, Beeman, state-space "
        "radiation, damping 6 N m s/rad), one run each.",
        "",
        "| runner | cases | wall time | cases per minute | compile, first case | compile per case after the first "
        "(median) | simulate() per case (median) | time loop per case (median) |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for name, r in rows.items():
        lines.append(
            f"| {name} | {r['cases']} | {r['wall_s']:.1f} s | {r['cases_per_min']:.1f} | {r['compile_first_s']:.2f} s "
            f"| {r['compile_after_s']:.3f} s | {r['run_median_s']:.2f} s | {r['loop_median_s']:.2f} s |"
        )
    lines += [
        "",
        f"Per-case overhead outside the time loop (sequential: wall time per case minus the median time loop, over "
        f"the wall time per case; compile, result Dataset, netCDF file, combining): {overhead:.1%} (target <= 10 %).",
        f"Load average at the end of the run: {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores (other jobs "
        "share the machine: compare the time loop per case with the Simulator table's quiet-machine numbers).",
    ]
    write_section(ROOT / "docs" / "benchmarks.md", "## Sweeps", "\n".join(lines))
    print("wrote the Sweeps section of docs/benchmarks.md")
    return 0


if __name__ == "__main__":
    sys.exit(main())
