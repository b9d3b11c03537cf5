"""Benchmark (issue 29): cost per step, peak memory and set-up cost of the default scene (m4-134, Beeman,
state-space radiation, dt = Tp/200) against its duration, 100 to 10,000 Tp with the default wave record
(d_omega = 2 pi / duration: the wave components grow with the duration, 320 to 32,000 kept).

Each case runs in a fresh process (peak ``ru_maxrss``), statistics only or streamed to a file (saved every
``STREAM_EVERY`` steps, as a user keeping a decimated record would), with the translation bound lifted (the
unmoored device drifts). It reports the time loop per step (the result's ``run_time_s``, which includes the
excitation), the compile time and its set-up parts (the wave components, the excitation coefficients, the A_inf
correction and the block transform's set-up, each timed again after the compile), and for comparison what the
excitation cost per step before issue 29 on runs too long for one table (the sums of the components per chunk of
2000 steps, which ``CompiledScene.excitation_at`` still does). Medians over repeats; OPENBLAS_NUM_THREADS=1.
Writes the section "Long runs: cost per step and memory against the duration" of ``docs/benchmarks.md``.

    python studies/bench_long_runs.py                  # 100, 1000, 10,000 Tp; 3 repeats
    python studies/bench_long_runs.py --repeats 5
    python studies/bench_long_runs.py --quick          # 10 and 100 Tp, statistics only, once; writes nothing
"""

from __future__ import annotations

import argparse
import dataclasses
import datetime
import json
import os
import platform
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from _common import ENV, ROOT, write_section

SECTION = "## Long runs: cost per step and memory against the duration"
MODES = ("statistics", "stream")
STREAM_EVERY: int = 20
"""Saved steps of the streamed runs: every 20th (10 per Tp)."""
OLD_CHUNK: int = 2000
"""Steps of the chunk the sums of components were made for before issue 29 (the loop's chunk)."""


def long_scene(periods: float, mode: str):  # type: ignore[no-untyped-def]
    """The default scene for ``periods`` Tp (see the module docstring)."""
    from wecss.sim import Scene, default_scene_path

    base = Scene.from_toml(default_scene_path())
    return dataclasses.replace(
        base,
        sea=dataclasses.replace(base.sea, duration=f"{periods:g} Tp"),
        solver=dataclasses.replace(base.solver, translation_bound=1e4),
        outputs=dataclasses.replace(
            base.outputs, statistics_only=mode == "statistics", every=STREAM_EVERY if mode == "stream" else 1
        ),
    )


def _timed(func):  # type: ignore[no-untyped-def]
    start = time.perf_counter()
    value = func()
    return value, time.perf_counter() - start


def worker(mode: str, periods: float, folder: str) -> None:
    """One case in this process; prints a JSON line."""
    from wecss.compiled import added_mass_correction, make_waves
    from wecss.sim import compile_scene, simulate
    from wecss.waves import excitation_model

    simulate(compile_scene(long_scene(8, "statistics")))  # loads numba's cached kernels (not the loop's cost)
    scene = long_scene(periods, mode)
    compiled, compile_s = _timed(lambda: compile_scene(scene))
    path = Path(folder) / f"{mode}-{periods:g}.nc"
    ds, simulate_s = _timed(lambda: simulate(compiled, path=path) if mode == "stream" else simulate(compiled))
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
    run_s = float(ds.attrs["run_time_s"])
    ds.close()
    # the set-up's parts, timed again (the compile above made them once)
    hydro, waves = compiled.hydro, compiled.waves
    _, waves_s = _timed(lambda: make_waves(scene, hydro))
    _, excitation_s = _timed(lambda: excitation_model(hydro, waves))
    inside = (waves.omega >= hydro.omega[0]) & (waves.omega <= hydro.omega[-1])
    data = hydro.dataset
    _, correction_s = _timed(
        lambda: added_mass_correction(
            compiled.radiation, compiled.dt, hydro.omega, data.added_mass.values, data.added_mass_inf.values,
            waves.omega[inside], np.abs(waves.amplitude[inside]) ** 2,
        )
    )  # fmt: skip
    n_h = compiled.plant.hydro_index.size
    sampled, blocks_s = _timed(lambda: compiled.excitation.sampled(compiled.dt, 2**22 // n_h))
    # the excitation now: the run's table (when it fits) or one block of samples, per step
    if compiled.n_steps * n_h < 2**22:
        _, now_s = _timed(lambda: compiled.excitation_at(np.arange(compiled.n_steps + 1) * compiled.dt))
        now = now_s / compiled.n_steps
    else:
        assert sampled is not None
        _, now_s = _timed(lambda: sampled(0, sampled.block))
        now = now_s / sampled.block
    old_steps = min(OLD_CHUNK, compiled.n_steps)
    _, old_s = _timed(lambda: compiled.excitation_at((1000 + np.arange(old_steps + 1)) * compiled.dt))
    print(
        json.dumps(
            {
                "mode": mode, "periods": periods, "steps": compiled.n_steps, "components": int(waves.omega.size),
                "run_s": run_s, "per_step": run_s / compiled.n_steps, "simulate_s": simulate_s,
                "compile_s": compile_s, "waves_s": waves_s, "excitation_s": excitation_s,
                "correction_s": correction_s, "blocks_s": blocks_s, "block": sampled.block if sampled else 0,
                "old_per_step": old_s / old_steps, "now_per_step": now, "peak_rss": peak,
                "file_bytes": path.stat().st_size if path.exists() else 0,
            }
        )
    )  # fmt: skip


def run_case(mode: str, periods: float, folder: str) -> dict:  # type: ignore[type-arg]
    done = subprocess.run(
        [sys.executable, __file__, "--worker", mode, str(periods), folder],
        env=ENV,
        check=True,
        capture_output=True,
        text=True,
    )
    return json.loads(done.stdout.strip().splitlines()[-1])  # type: ignore[no-any-return]


def _median(rows: list[dict], key: str) -> float:  # type: ignore[type-arg]
    return float(np.median([r[key] for r in rows]))


def table(results: dict[tuple[str, float], list[dict]]) -> str:  # type: ignore[type-arg]
    lines = [
        "| duration | mode | steps | wave components | time loop per step | ratio to 100 Tp | peak RSS | "
        "excitation per step: now (table or blocks) | sums per chunk (runs over one table before issue 29) |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for (mode, periods), rows in results.items():
        base = results.get((mode, 100.0)) or rows
        per_step = _median(rows, "per_step")
        lines.append(
            f"| {periods:g} Tp | {mode} | {rows[0]['steps']:,} | {rows[0]['components']:,} | {per_step * 1e6:.2f} us "
            f"| {per_step / _median(base, 'per_step'):.3f} | {_median(rows, 'peak_rss') / 1e9:.3f} GB "
            f"| {_median(rows, 'now_per_step') * 1e6:.2f} us | {_median(rows, 'old_per_step') * 1e6:.1f} us |"
        )
    lines += [
        "",
        "Set-up (medians, statistics-only cases): compile_scene of the case after the 8-Tp warm-up (the device, "
        "its database and radiation fit already in memory, as for a sweep's cases), and its parts timed again "
        "after it:",
        "",
        "| duration | wave components | compile_scene | wave components | excitation coefficients | A_inf correction "
        "| block transform set-up (samples per block) |",
        "|---|---|---|---|---|---|---|",
    ]
    for (mode, periods), rows in results.items():
        if mode != "statistics":
            continue
        lines.append(
            f"| {periods:g} Tp | {rows[0]['components']:,} | {_median(rows, 'compile_s'):.2f} s "
            f"| {_median(rows, 'waves_s') * 1e3:.0f} ms | {_median(rows, 'excitation_s') * 1e3:.0f} ms "
            f"| {_median(rows, 'correction_s') * 1e3:.0f} ms | {_median(rows, 'blocks_s') * 1e3:.0f} ms "
            f"({rows[0]['block']:,}) |"
        )
    return "\n".join(lines) + "\n\n" + READING


READING = """\
How to read it. The wave components grow with the duration (d_omega = 2 pi / duration). A run whose excitation
fits in one table (2**22 values: about 870 Tp on m4-134) evaluates it once by one inverse FFT; a longer run did,
before issue 29, sum its components per chunk of 2000 steps (the last column: about 115 us per step at 1000 Tp and
670 us at 10,000 Tp, on top of the loop's own cost; 6000 Tp ran at about 300 steps per second). It now evaluates it
in blocks of about 2**22 values, one chirp-z transform each (`wecss.waves.BlockSum`): the excitation's column
"now", whose cost per step does not depend on the run's length or its components (about 2 to 3 times the one-table
FFT's, that is about 1 us per step more than a short run, some 7 % of a quiet machine's 11.6 us step) and whose
memory is the block's (the peak RSS grows by the block between 100 and 1000 Tp; beyond it by the components'
coefficients, 24 x 16 bytes each, in the compiled scene and the block transform, and by the power bound of the
statistics window, which transforms the window's excitation whole, n_h x the window's steps values: 0.19 GB of the
10,000-Tp run's 0.67 GB, where it held several copies of the transform, 1.02 GB, before 2026-11-27). The set-up
grows linearly with the components, at most a few tenths of a second at 10,000 Tp: the A_inf correction sums the
memory response over the frequencies before the matrices (`wecss.compiled.weighted_memory_response`; before: 3.5 s
at 6000 Tp) and the power bound solves the frequencies in blocks (before: 0.6 GB of matrices at 10,000 Tp, a peak
of 1.0 GB). On a shared machine the loop's ratios to 100 Tp move with the load (read them against the spread of the
repeats); the excitation's columns are the part of a step that depends on the duration."""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--periods", type=float, nargs="+", default=[100.0, 1000.0, 10_000.0])
    parser.add_argument("--modes", nargs="+", choices=MODES, default=list(MODES))
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--quick", action="store_true", help="10 and 100 Tp, statistics only, once; writes nothing")
    parser.add_argument("--worker", nargs=3, metavar=("MODE", "PERIODS", "FOLDER"), help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.worker:
        worker(args.worker[0], float(args.worker[1]), args.worker[2])
        return
    periods = [10.0, 100.0] if args.quick else args.periods
    modes = ["statistics"] if args.quick else args.modes
    repeats = 1 if args.quick else args.repeats
    results: dict[tuple[str, float], list[dict]] = {(m, p): [] for p in periods for m in modes}  # type: ignore[type-arg]
    with tempfile.TemporaryDirectory() as folder:
        for _ in range(repeats):  # repeats interleaved, so a change of the machine's load touches every case
            for key in results:
                results[key].append(run_case(*key, folder))
                print(json.dumps(results[key][-1]), flush=True)
    text = table(results)
    print(text)
    if args.quick:
        return
    load = os.getloadavg()[0]
    head = (
        f"`OPENBLAS_NUM_THREADS=1 python studies/bench_long_runs.py --repeats {repeats}` on {platform.machine()}, "
        f"{os.cpu_count()} cores, Python {platform.python_version()}, {datetime.date.today()}; load average "
        f"{load:.1f} at the end (the machine was shared: times are wall times of a loaded machine, ratios between "
        "interleaved cases are the figures to read); each case in a fresh process (an 8-Tp run first loads the "
        "kernels), medians of the repeats. The "
        "default scene (m4-134, Beeman, state-space radiation, dt = Tp/200), statistics only or streamed to a "
        f"file (every {STREAM_EVERY}th step saved), for a duration of 100 to 10,000 Tp with the default record "
        "(d_omega = 2 pi / duration)."
    )
    write_section(ROOT / "docs" / "benchmarks.md", SECTION, f"{SECTION}\n\n{head}\n\n{text}\n")


if __name__ == "__main__":
    main()
