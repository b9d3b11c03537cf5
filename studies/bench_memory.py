"""Peak memory of long runs saved every step (issue 15): the default scene (m4-134, Beeman, state-space radiation,
dt = Tp/200, default outputs) for N steps, with the sea's d_omega = 2 pi / (100 Tp) (the default 2 pi / duration
only costs time on a long run: the excitation is evaluated per chunk) and the translation bound lifted (the
unmoored device drifts about 26 m in 10^6 steps).

Each case runs in a fresh process and reports its peak resident memory (``ru_maxrss``, as ``/usr/bin/time -v``):

- ``dataset``: ``simulate(scene)`` then ``save(ds, path)`` (the whole record in memory, then written);
- ``stream``: ``simulate(scene, path=...)`` (each chunk of steps appended to the file as the run goes);
- ``statistics``: ``outputs.statistics_only`` (nothing saved per step; the floor).

``python studies/bench_memory.py --steps 100000 1000000`` prints a table (memory does not depend on the machine's
load; times do and are not reported). ``--quick`` runs 20,000 steps of each mode and writes nothing into docs/.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
import resource
import subprocess
import sys
import tempfile
from pathlib import Path

MODES = ("dataset", "stream", "statistics")


def long_scene(steps: int, statistics_only: bool):  # type: ignore[no-untyped-def]
    """The default scene for ``steps`` steps (see the module docstring)."""
    from wecss.sim import Scene, default_scene_path

    base = Scene.from_toml(default_scene_path())
    tp = float(base.sea.period or 1.2)
    return dataclasses.replace(
        base,
        sea=dataclasses.replace(base.sea, duration=steps * base.dt, d_omega=2 * math.pi / (100 * tp)),
        radiation=dataclasses.replace(base.radiation, method="state_space"),
        solver=dataclasses.replace(base.solver, method="beeman", translation_bound=1e4),
        outputs=dataclasses.replace(base.outputs, statistics_only=statistics_only),
    )


def worker(mode: str, steps: int, folder: str) -> None:
    """One case in this process; prints a JSON line with the peak RSS [bytes] and the file's size."""
    from wecss.results import save
    from wecss.sim import simulate

    scene = long_scene(steps, mode == "statistics")
    path = Path(folder) / f"{mode}-{steps}.nc"
    if mode == "stream":
        ds = simulate(scene, path=path)
        ds.close()
    else:
        ds = simulate(scene)
        save(ds, path)
        del ds
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
    print(json.dumps({"mode": mode, "steps": steps, "peak_rss": peak, "file_bytes": path.stat().st_size}))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--steps", type=int, nargs="+", default=[100_000])
    parser.add_argument("--modes", nargs="+", choices=MODES, default=list(MODES))
    parser.add_argument("--quick", action="store_true", help="20,000 steps of each mode; writes nothing into docs/")
    parser.add_argument("--worker", nargs=3, metavar=("MODE", "STEPS", "FOLDER"), help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.worker:
        worker(args.worker[0], int(args.worker[1]), args.worker[2])
        return
    steps = [20_000] if args.quick else args.steps
    print("| mode | steps | peak RSS [GB] | file [GB] |")
    print("|---|---|---|---|")
    with tempfile.TemporaryDirectory() as folder:
        for n in steps:
            for mode in args.modes:
                done = subprocess.run(
                    [sys.executable, __file__, "--worker", mode, str(n), folder],
                    check=True,
                    capture_output=True,
                    text=True,
                )
                row = json.loads(done.stdout.strip().splitlines()[-1])
                print(f"| {mode} | {n:,} | {row['peak_rss'] / 1e9:.3f} | {row['file_bytes'] / 1e9:.3f} |", flush=True)


if __name__ == "__main__":
    main()
