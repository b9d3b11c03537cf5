"""Stress fields streamed (issue 28): the cost and memory of recording the signed von Mises stress at 500 points of
the NOTC arm over 10^5 samples (a 30-minute sea state at dt = 0.018 s) in chunks of 2000 with
``wecss.results.StressFieldRecorder``: the stresses (``StressModes.stresses``: modal coordinates, their rates and
accelerations, the 12 rigid-motion load coordinates and the frame's angular velocity: the loads of the frame's
rotation on the elastic motion among them), the streamed rainflow count and Miner sums of every point, the running
extremes and RMS, then the Dataset.

The modal series are synthetic (sinusoids at three wave periods and 2 % noise on every mode, made before the timing):
the noise gives a reversal at about every other sample, the counter's worst case. The points: the arm's 17 nodes,
30 fibres around the tube at each (the first 500). Times: the median of 5 recordings in this process (numba compiled
before), one BLAS thread; the stresses and the rainflow count alone are timed as well. Memory: the peak of Python's
allocations during one recording (``tracemalloc``: numpy's arrays included) and the state the recorder holds at the
end, beside the 400 MB one whole-field array (points x samples, float64) would take.

    OPENBLAS_NUM_THREADS=1 python studies/bench_stress_field.py           # writes the section of docs/benchmarks.md
    python studies/bench_stress_field.py --quick                          # 5000 samples, once; writes nothing
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse
import platform
import resource
import time
import tracemalloc
from datetime import date

import numpy as np
from _common import ROOT, write_section

SECTION = "## Stress fields streamed (`studies/bench_stress_field.py`)"
N_POINTS = 500
CHUNK = 2000
DT = 0.018


def arm_modes(n_points: int):  # type: ignore[no-untyped-def]
    """Stress modes of the NOTC arm at ``n_points`` points: 30 fibres around the tube at each node."""
    from wecss.devices import load
    from wecss.structure import StressPoint, stress_modes

    body = load("notc-10kw").flexible_body("arm")
    elements = body.frame.members()["arm"]
    radius = elements[0].section.z_max
    stations = [e.station for e in elements] + [elements[-1].station + elements[-1].length]
    angles = np.linspace(0.0, 2 * np.pi, 30, endpoint=False)
    points = [
        StressPoint("arm", float(s), float(radius * np.sin(a)), float(radius * np.cos(a)), 1.0, f"arm@{s:.4g}.f{k}")
        for s in stations
        for k, a in enumerate(angles)
    ][:n_points]
    return stress_modes(body.frame, body.basis.basis, points)


def modal_series(modes, n: int, seed: int = 0) -> tuple[np.ndarray, ...]:  # type: ignore[no-untyped-def]
    """The arguments of ``StressFieldRecorder.update``: modal coordinates (sinusoids at 6, 8.5 and 11 s and 2 %
    noise), their accelerations, the rigid-motion loads, the modal rates and the frame's angular velocity."""
    from wecss.structure import rigid_load_coordinates

    rng = np.random.default_rng(seed)
    t = np.arange(n)[:, None] * DT
    n_modes = modes.normal.shape[1]
    peak = np.abs(modes.normal).max(axis=0)
    scale = 10e6 / np.maximum(peak, 1e-2 * peak.max())
    q = np.zeros((n, n_modes))
    q_dot = np.zeros((n, n_modes))
    q_ddot = np.zeros((n, n_modes))
    for period in (6.0, 8.5, 11.0):
        omega = 2 * np.pi / period
        a = scale * rng.uniform(0.05, 0.4, n_modes)
        wave = np.sin(omega * t + rng.uniform(0, 2 * np.pi, n_modes))
        q += a * wave
        q_dot += omega * a * np.cos(omega * t + rng.uniform(0, 2 * np.pi, n_modes))
        q_ddot -= omega**2 * a * wave
    q += 0.02 * scale * rng.normal(size=(n, n_modes))
    spin = 0.05 * rng.normal(size=(n, 3))
    rigid = rigid_load_coordinates(np.array([0.0, 0.0, -9.81]) + 0.05 * rng.normal(size=(n, 3)),
                                   0.05 * rng.normal(size=(n, 3)), spin)  # fmt: skip
    return q, q_ddot, rigid, q_dot, spin


def record(modes, series):  # type: ignore[no-untyped-def]
    """One recording of ``series`` (:func:`modal_series`) in chunks of CHUNK samples; returns the recorder and its
    Dataset."""
    from wecss.results import StressFieldRecorder

    recorder = StressFieldRecorder(modes, DT)
    for i in range(0, series[0].shape[0], CHUNK):
        recorder.update(*(a[i : i + CHUNK] for a in series))
    return recorder, recorder.result()


def stresses_only(modes, series) -> None:  # type: ignore[no-untyped-def]
    for i in range(0, series[0].shape[0], CHUNK):
        modes.stresses(*(a[i : i + CHUNK] for a in series))


def counter_only(modes, series) -> float:  # type: ignore[no-untyped-def]
    """Time of the streamed rainflow count alone (``StreamingRainflow.update`` on each chunk's stresses, then
    ``damage``) [s]."""
    from wecss.results import StreamingRainflow

    counter = StreamingRainflow(len(modes.points))
    spent = 0.0
    for i in range(0, series[0].shape[0], CHUNK):
        signed = modes.stresses(*(a[i : i + CHUNK] for a in series))["signed_von_mises"]
        start = time.perf_counter()
        counter.update(signed)
        spent += time.perf_counter() - start
    start = time.perf_counter()
    counter.damage()
    return spent + time.perf_counter() - start


def median_time(func, repeats: int) -> float:  # type: ignore[no-untyped-def]
    runs = []
    for _ in range(repeats):
        start = time.perf_counter()
        func()
        runs.append(time.perf_counter() - start)
    return float(np.median(runs))


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="5000 samples, once; writes nothing into docs/")
    parser.add_argument("--samples", type=int, default=100_000, help="samples per point (default 100000)")
    parser.add_argument("--repeats", type=int, default=5, help="recordings timed (default 5, the median is given)")
    args = parser.parse_args(argv)
    samples, repeats = (5000, 1) if args.quick else (args.samples, args.repeats)

    modes = arm_modes(N_POINTS)
    series = modal_series(modes, samples)
    record(modes, [a[:50] for a in series])  # compile the counting loop (numba) before timing

    total = median_time(lambda: record(modes, series), repeats)
    products = median_time(lambda: stresses_only(modes, series), repeats)
    counting = float(np.median([counter_only(modes, series) for _ in range(repeats)]))
    tracemalloc.start()
    recorder, ds = record(modes, series)
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    held = recorder.counter.nbytes
    residue = int(recorder.counter.residue_lengths.max())
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    whole = N_POINTS * samples * 8 / 1e6
    from wecss.compiled import JIT

    lines = [
        SECTION,
        "",
        f"{N_POINTS} stress points of the NOTC arm (30 fibres around the tube at each node), {samples:,} samples "
        f"(dt = {DT} s, {samples * DT / 60:.0f} min) in chunks of {CHUNK}: `StressFieldRecorder.update` with modal "
        "coordinates, their rates and accelerations, the rigid-motion loads and the frame's angular velocity, then "
        "`result()`. Synthetic modal series with "
        "2 % noise (a reversal at about every other sample: the counter's worst case). "
        f"{date.today().isoformat()}, {platform.machine()}, one BLAS thread, numba {'on' if JIT else 'off'}, "
        f"load {os.getloadavg()[0]:.1f}; median of {repeats}.",
        "",
        "| | value |",
        "|---|---|",
        f"| whole recording (stresses, rainflow, extremes, RMS, Dataset) | {total:.2f} s |",
        "| of which the stresses (`StressModes.stresses`: three products at the points, two at the cuts) | "
        f"{products:.2f} s |",
        f"| of which the rainflow count and Miner sums (`StreamingRainflow`, timed alone) | {counting:.2f} s |",
        f"| per sample and point | {1e9 * total / (samples * N_POINTS):.1f} ns |",
        f"| peak of Python's allocations during a recording (`tracemalloc`) | {peak / 1e6:.1f} MB |",
        f"| held by the rainflow counters at the end (residue up to {residue} points) | {held / 1e3:.1f} kB |",
        f"| the whole field as one array (points x samples, float64), for comparison | {whole:.0f} MB |",
        f"| peak resident memory of the process (`ru_maxrss`, inputs of {sum(a.nbytes for a in series) / 1e6:.0f}"
        f" MB included) | {rss:.0f} MB |",
        "",
        f"The shortest life: {float(ds.life_years.min()):.3g} years at "
        f"{ds.point.values[int(np.argmin(ds.life_years.values))]} (synthetic loads: it says nothing about the arm).",
        "",
        "How to read it: the recorder's memory does not grow with the record (the residue of each point's "
        "count, a few numbers per point, and the chunk's arrays: the stresses of 2000 x 500 samples are 8 MB "
        "each, and the products make five of them); the whole field would be 400 MB per 10^5 samples. The "
        "rest of the time is the extremes, the RMS and the input checks. The noise makes this the counter's "
        "worst case (a cycle for about every other sample); about half of its time is the S-N curve evaluated"
        " per cycle (`SNCurve.cycles_to_failure`, a logarithm and a power), the rest the compiled loop. The "
        "stresses are BLAS products per chunk: three at the points (modal coordinates, accelerations, rigid-motion "
        "loads), two at the cuts (the frame's rotation and angular velocity times the modal coordinates and "
        "rates: 17 cuts of six loads, against 500 points) and the cuts' loads carried to the points "
        "(`StressModes.stresses` used `numpy.einsum`, about eight times slower on these sizes, before this "
        "section).",
    ]
    text = "\n".join(lines)
    print(text)
    if not args.quick:
        write_section(ROOT / "docs" / "benchmarks.md", SECTION, text)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
