"""The non-causal optimum's cost (``wecss.control.design.noncausal_optimum``): wall time per WECCCOMP Wavestar sea
state, with the competition's limits (60 N, 0.08 m) on the linear model over the run's periodic record, for the
mechanical objective (the certified QP, started from ADMM's active set) and the electrical one (efficiency 0.7:
nonconvex ADMM, then the convex-concave procedure). Medians of ``--repeats`` calls after one warm-up call per sea
state (the linear model is made once, outside the timing); BLAS threads pinned to one. Writes the section
"Non-causal optimum" of ``docs/benchmarks.md``.

    python studies/bench_optimum.py            # six sea states, both objectives, 3 repeats
    python studies/bench_optimum.py --quick    # SS5, mechanical, one call (writes nothing)
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import argparse
import datetime
import platform
import time
import warnings

import numpy as np
from _common import ROOT, write_section
from wecccomp import WAVESTAR, wecccomp_scene

from wecss.control import compile_scene
from wecss.control.design import noncausal_optimum

SECTION = "## Non-causal optimum"
EFFICIENCY = 0.7


def measure(state: int, objectives: tuple[str, ...], repeats: int) -> list[dict]:
    """One row per objective: the optimum [W], its bound [W], the method and the median wall time [s]."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the Wavestar's WAMIT file: symmetrised and interpolated entries
        sc = wecccomp_scene(state, {"name": "damping"})
        compiled = compile_scene(sc)
    context, exc = compiled.control_context, compiled.excitation
    model = context.linear_model()
    rows = []
    for objective in objectives:

        def call(objective: str = objective):
            return noncausal_optimum(
                model, exc.omega, exc.coefficients, float(sc.sea.duration), force_limit=context.force_limit,
                stroke_limit=context.stroke_limit, objective=objective,
                efficiency=EFFICIENCY if objective == "electrical" else None,
            )  # fmt: skip

        call()  # warm-up
        times, opt = [], None
        for _ in range(repeats):
            start = time.perf_counter()
            opt = call()
            times.append(time.perf_counter() - start)
        assert opt is not None
        rows.append(
            {
                "state": state, "objective": objective, "value": opt.value, "bound": opt.upper_bound,
                "harmonics": opt.periodic.n_harmonics, "method": opt.method, "seconds": float(np.median(times)),
                "spread": (min(times), max(times)),
            }
        )  # fmt: skip
        print(
            f"SS{state} {objective:10s} {opt.value:.6f} W (bound {opt.upper_bound:.6f} W, {opt.method}) "
            f"median {np.median(times):.2f} s",
            flush=True,
        )
    return rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    if not WAVESTAR.exists():
        print(f"skipped: {WAVESTAR} is absent (../shared/data)")
        return
    if args.quick:
        measure(5, ("mechanical",), 1)
        return
    rows = [row for state in range(1, 7) for row in measure(state, ("mechanical", "electrical"), args.repeats)]
    lines = [
        SECTION,
        "",
        f"`python studies/bench_optimum.py` on {platform.machine()}, Python {platform.python_version()}, BLAS threads "
        f"pinned to 1, {datetime.date.today().isoformat()}; the WECCCOMP Wavestar, 60 N / 0.08 m, the linear "
        f"model over each sea state's periodic record (force basis from the record's first harmonic to twice the "
        f"waves' highest), efficiency {EFFICIENCY} for the electrical objective (its value evaluated 16 times finer "
        f"than the samples). Medians of {args.repeats} calls after a warm-up (min-max "
        "beside).",
        "",
        "| sea state | objective | optimum [W] | bound [W] | harmonics | method | time [s] (min-max) |",
        "|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        lines.append(
            f"| SS{r['state']} | {r['objective']} | {r['value']:.6f} | {r['bound']:.6f} | {r['harmonics']} | "
            f"{r['method']} | {r['seconds']:.2f} ({r['spread'][0]:.2f}-{r['spread'][1]:.2f}) |"
        )
    lines += [
        "",
        "Target (issue 30): at most 5 s per Wavestar sea state. The bound is the certified dual bound of the "
        "mechanical programme (its optimum to within the duality gap) and eta times it for the electrical one.",
    ]
    write_section(ROOT / "docs" / "benchmarks.md", SECTION, "\n".join(lines))
    print("updated docs/benchmarks.md")


if __name__ == "__main__":
    main()
