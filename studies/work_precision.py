"""Study: run time against error (work-precision) of the nonlinear simulator, for the M4 layouts 111 and 134.

Every fixed-step integrator (Beeman predictor-corrector, RK4) x radiation method (state space, convolution) x time
step (Tp/25 to Tp/800) runs the same wave record (same seed, duration and ramp: the wave components do not depend
on the step) and is compared, at its own steps, with a tight reference on that record: the ``reference`` solver
(scipy's DOP853, rtol 1e-10, with the state-space radiation). Errors:

- ``series``: RMS over time and hinges of the hinge-angle difference, divided by the reference's RMS hinge angle;
- ``rms angle``: relative error of the RMS hinge angle after the ramp (largest over hinges);
- ``power``: relative error of the mean PTO power after the ramp (summed over PTOs);

both averaged over the same samples (the run's steps) for the run and the reference.

The paper's own method (M4 paper section 5.2) runs beside them as ``paper``: Beeman with the added mass explicit
(``solver.added_mass = "explicit"``), iterated until the accelerations change by less than 1 %
(``corrector_tol = 0.01``), with the convolution. At equal error (the ``series`` error of a paper row), the time of
the fastest wecss setting is read off each wecss setting's error-time curve (log-log interpolation between its
steps; a setting whose every step is more accurate than the paper row gives its coarsest step's time, so the ratio
is then a lower bound, marked >=), and the ratio paper / wecss is reported for every paper row.

The convolution rows are compared with the same (state-space) reference, so their error has a floor: the
difference between the convolution and the state-space fit of the same kernels, not an integration error.
Cost is the time loop (the result's ``run_time_s``, excitation included, numba on, warm cache), median of repeats.

    python studies/work_precision.py           # full: two layouts, two seas, 20 Tp; writes docs/benchmarks.md
    python studies/work_precision.py --quick   # m4-111, default sea, 4 Tp, two steps; writes to a temp folder
"""

from __future__ import annotations

import argparse
import dataclasses
import datetime
import itertools
import os
import platform
import sys
import tempfile
from pathlib import Path

import numpy as np
from _common import ROOT, write_section

from wecss.scene import SceneError
from wecss.sim import JIT, Scene, SimulationDiverged, default_scene_path, simulate

SECTION = "## Run time against error"
TARGETS = (1e-2, 1e-3, 1e-4)
RAMP = 2  # ramp of the wave record [Tp]; the statistics are taken after it
PAPER = "paper"
"""The method label of the M4 paper's own scheme: Beeman, explicit added mass iterated to 1 %, convolution."""
PAPER_TOLERANCE = 0.01


@dataclasses.dataclass(frozen=True)
class Sea:
    """A sea state of the study: a name, Hs [m] and Tp [s] (JONSWAP, gamma 3.3 as in the default scene)."""

    name: str
    height: float
    period: float


DEFAULT_SEA = Sea("default", 0.04, 1.2)
STEEP_SEA = Sea("steep", 0.10, 1.2)  # Hs / deep-water wavelength at Tp = 4.4 %


def make_scene(device: str, sea: Sea, radiation: str, method: str, divisor: int, duration: float) -> Scene:
    """The default scene on ``device`` in ``sea``, with a radiation method, solver and dt = Tp / ``divisor``."""
    base = Scene.from_toml(default_scene_path())
    paper = {
        "method": "beeman",
        "added_mass": "explicit",
        "corrector_tol": PAPER_TOLERANCE,
        "max_corrector_iterations": 100,
    }
    solver = dataclasses.replace(base.solver, dt=f"Tp/{divisor}", **(paper if method == PAPER else {"method": method}))
    return dataclasses.replace(
        base,
        device=dataclasses.replace(base.device, name=device),
        sea=dataclasses.replace(
            base.sea, height=sea.height, period=sea.period, duration=f"{duration} Tp", ramp=f"{RAMP} Tp"
        ),
        radiation=dataclasses.replace(base.radiation, method=radiation),
        solver=solver,
        outputs=dataclasses.replace(base.outputs, variables=("motion", "pto")),
    )


def hinge_angles(ds) -> tuple[np.ndarray, np.ndarray]:  # type: ignore[no-untyped-def]
    """(time [s], hinge angles [rad] (n_time, n_hinges)) of a result."""
    names = [str(n) for n in ds.dof_angular.values if "hinge" in str(n)]
    return ds.time.values, ds.angle.sel(dof_angular=names).values


def measure(scene: Scene, repeats: int) -> tuple[object, float]:
    """(last result, median loop time [s]) of ``repeats`` runs (after a warm-up run that loads numba's cache)."""
    from wecss.sim import compile_scene

    compiled = compile_scene(scene)
    ds = simulate(compiled)
    loops = []
    for _ in range(repeats):
        ds = simulate(compiled)
        loops.append(float(ds.attrs["run_time_s"]))
    return ds, float(np.median(loops))


def errors(ds, ref, ramp: float) -> dict[str, float]:  # type: ignore[no-untyped-def]
    """Relative errors of a result against the reference on the same record (see the module docstring).

    The reference is read at the result's own steps (its steps are a subset of the reference's), and the RMS
    angle and mean power of both are averaged over the same samples after the ramp [s], so that the comparison
    does not mix an integration error with the error of averaging over fewer samples.
    """
    t, a = hinge_angles(ds)
    t_ref, a_ref = hinge_angles(ref)
    index = np.searchsorted(t_ref, t - 1e-9)
    if not np.allclose(t_ref[index], t, rtol=0.0, atol=1e-9):
        raise ValueError("the reference's steps do not contain the result's steps; use a divisor of its step")
    a_ref = a_ref[index]
    after = t >= ramp - 1e-9
    rms, rms_ref = np.sqrt(np.mean(a[after] ** 2, axis=0)), np.sqrt(np.mean(a_ref[after] ** 2, axis=0))
    power = float(np.mean(ds.pto_power.values[after].sum(axis=1)))
    power_ref = float(np.mean(ref.pto_power.values[index][after].sum(axis=1)))
    return {
        "series": float(np.sqrt(np.mean((a - a_ref) ** 2)) / np.sqrt(np.mean(a_ref**2))),
        "rms": float(np.max(np.abs(rms - rms_ref) / rms_ref)),
        "power": abs(power - power_ref) / abs(power_ref),
    }


def run_case(device: str, sea: Sea, duration: float, divisors: list[int], ref_divisor: int, repeats: int) -> list[dict]:
    """All rows of one layout and sea state (a row per integrator x radiation x step, and the reference)."""
    ref_scene = make_scene(device, sea, "state_space", "reference", ref_divisor, duration)
    ref, ref_time = measure(ref_scene, 1)
    rows = [
        {"device": device, "sea": sea.name, "method": "reference (DOP853, rtol 1e-10)", "radiation": "state_space",
         "divisor": ref_divisor, "loop": ref_time, "status": "reference", "series": 0.0, "rms": 0.0, "power": 0.0}
    ]  # fmt: skip
    for radiation, methods in (("state_space", ("beeman", "rk4")), ("convolution", ("beeman", PAPER))):
        for method in methods:  # (RK4 needs the radiation as states: the scene refuses it with the convolution)
            for divisor in divisors:
                row = {"device": device, "sea": sea.name, "method": method, "radiation": radiation, "divisor": divisor}
                try:
                    ds, loop = measure(make_scene(device, sea, radiation, method, divisor, duration), repeats)
                except SimulationDiverged as err:
                    row.update(status=f"diverged at t = {err.time:.2f} s", loop=np.nan)
                except (SceneError, ValueError) as err:
                    row.update(status=f"refused: {str(err)[:80]}", loop=np.nan)
                else:
                    row.update(status="ok", loop=loop, **errors(ds, ref, RAMP * sea.period))
                rows.append(row)
                print(_line(row), flush=True)
    return rows


def _line(row: dict) -> str:
    if row["status"] not in ("ok", "reference"):
        return f"| {row['method']} | {row['radiation']} | Tp/{row['divisor']} | {row['status']} | | | |"
    return (
        f"| {row['method']} | {row['radiation']} | Tp/{row['divisor']} | {row['loop'] * 1e3:.1f} ms | "
        f"{row['series']:.2e} | {row['rms']:.2e} | {row['power']:.2e} |"
    )


def recommendations(rows: list[dict]) -> list[str]:
    """Per accuracy target (series error), the fastest wecss setting that reaches it (the paper's method is not
    one)."""
    lines = []
    for target in TARGETS:
        ok = [r for r in rows if r["status"] == "ok" and r["series"] <= target and r["method"] != PAPER]
        if not ok:
            lines.append(f"| {target:.0e} | none of the settings tried | |")
            continue
        best = min(ok, key=lambda r: r["loop"])
        lines.append(
            f"| {target:.0e} | {best['method']}, {best['radiation']}, dt = Tp/{best['divisor']} | "
            f"{best['loop'] * 1e3:.1f} ms |"
        )
    return lines


def _time_at(rows: list[dict], error: float) -> tuple[float, bool]:
    """Loop time [s] of one setting's runs (``rows``, ok, any order) at ``error`` by log-log interpolation between
    the neighbouring steps, and whether it is exact (False: every run is more accurate; the coarsest run's time,
    an upper bound of the time at ``error``). NaN when no run reaches ``error``."""
    runs = sorted((r for r in rows if r["status"] == "ok" and r["series"] > 0), key=lambda r: r["divisor"])
    if not runs or min(r["series"] for r in runs) > error:
        return float("nan"), True
    if all(r["series"] <= error for r in runs):
        return runs[0]["loop"], False
    for coarse, fine in itertools.pairwise(runs):
        if fine["series"] <= error < coarse["series"]:
            w = np.log(error / coarse["series"]) / np.log(fine["series"] / coarse["series"])
            return float(np.exp((1 - w) * np.log(coarse["loop"]) + w * np.log(fine["loop"]))), True
    fine = min((r for r in runs if r["series"] <= error), key=lambda r: r["loop"])  # (errors not monotonic)
    return fine["loop"], False


def paper_ratios(rows: list[dict]) -> list[dict]:
    """Per ok paper row: the fastest wecss setting at its error and the time ratio paper / wecss."""
    out = []
    settings = sorted(
        {(r["method"], r["radiation"]) for r in rows if r["method"] not in (PAPER,) and r["status"] == "ok"}
    )
    for paper in (r for r in rows if r["method"] == PAPER and r["status"] == "ok"):
        best: tuple[float, bool, str] | None = None
        for method, radiation in settings:
            sel = [r for r in rows if (r["method"], r["radiation"]) == (method, radiation)]
            time, exact = _time_at(sel, paper["series"])
            if np.isfinite(time) and (best is None or time < best[0]):
                best = (time, exact, f"{method}, {radiation}")
        if best is not None:
            out.append({"paper": paper, "wecss": best[2], "time": best[0], "exact": best[1],
                        "ratio": paper["loop"] / best[0]})  # fmt: skip
    return out


def _ratio_lines(rows: list[dict]) -> list[str]:
    lines = []
    for r in paper_ratios(rows):
        bound = "" if r["exact"] else ">= "
        lines.append(
            f"| Tp/{r['paper']['divisor']} | {r['paper']['series']:.2e} | {r['paper']['loop'] * 1e3:.1f} ms | "
            f"{r['wecss']} | {r['time'] * 1e3:.1f} ms | {bound}{r['ratio']:.1f} |"
        )
    return lines or ["| (no paper row completed) | | | | | |"]


def plot(rows: list[dict], path: Path) -> None:
    """Log-log plot of the series error against the loop time, one panel per layout and sea state."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    cases = sorted({(r["device"], r["sea"]) for r in rows})
    fig, axes = plt.subplots(1, len(cases), figsize=(4.5 * len(cases), 4), squeeze=False)
    for ax, (device, sea) in zip(axes[0], cases, strict=True):
        for radiation, style in (("state_space", "-"), ("convolution", "--")):
            for method, marker in (("beeman", "o"), ("rk4", "s"), (PAPER, "^")):
                sel = [
                    r for r in rows
                    if (r["device"], r["sea"], r["radiation"], r["method"]) == (device, sea, radiation, method)
                    and r["status"] == "ok" and r["series"] > 0
                ]  # fmt: skip
                if sel:
                    label = "paper (explicit added mass, 1 %)" if method == PAPER else f"{method}, {radiation}"
                    ax.loglog([r["loop"] for r in sel], [r["series"] for r in sel], style, marker=marker,
                              label=label)  # fmt: skip
        ax.set_title(f"{device}, {sea} sea")
        ax.set_xlabel("time loop [s]")
        ax.set_ylabel("hinge-angle error (relative RMS)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def report(rows: list[dict], duration: float, repeats: int, picture: str) -> str:
    """The Markdown section: the setting, one table per layout and sea state, the recommendations, the figure."""
    when = datetime.datetime.now(datetime.UTC).strftime("%Y-%m-%d")
    text = [
        SECTION,
        "",
        f"`python studies/work_precision.py` on {platform.machine()}, Python {platform.python_version()}, "
        f"numba {'on' if JIT else 'off'}, OPENBLAS_NUM_THREADS=1, {when}; JONSWAP gamma 3.3, Tp 1.2 s, {duration:g} Tp "
        f"(ramp 2 Tp), seed 1, linear PTO damping 6 N m s/rad. Reference: the `reference` solver (DOP853, rtol 1e-10, "
        "state-space radiation) on the same record. Errors relative to the reference: `series` the RMS of the "
        "hinge-angle difference over time and hinges / the RMS hinge angle; `rms angle` of the RMS hinge angle; "
        "`power` of the mean PTO power (both after the ramp, over the same samples for run and reference). RK4 runs "
        "only with the state-space radiation (the scene refuses RK4 with the convolution). "
        f"Time: the time loop, median of {repeats} runs after a warm-up. Convolution "
        "rows carry the convolution/state-space model difference as an error floor (not an integration error). "
        f"The machine ({os.cpu_count()} cores) may be shared with other jobs: times compare within a table.",
        "",
    ]
    for device, sea in sorted({(r["device"], r["sea"]) for r in rows}):
        case = [r for r in rows if (r["device"], r["sea"]) == (device, sea)]
        text += [
            f"### {device}, {sea} sea (Hs {'0.04' if sea == 'default' else '0.10'} m)",
            "",
            "| integrator | radiation | dt | time loop | series | rms angle | power |",
            "|---|---|---|---|---|---|---|",
            *[_line(r) for r in case],
            "",
            "Fastest setting per accuracy target (series error):",
            "",
            "| target | setting | time loop |",
            "|---|---|---|",
            *recommendations(case),
            "",
            "The paper's method (Beeman, added mass explicit and iterated to 1 %, convolution) against the fastest "
            "wecss setting at the same series error, in this run:",
            "",
            "| paper dt | series | paper loop | fastest wecss setting at that error | its loop | ratio |",
            "|---|---|---|---|---|---|",
            *_ratio_lines(case),
            "",
        ]
    text += [f"![work-precision]({picture})", ""]
    return "\n".join(text)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="m4-111, default sea, 4 Tp, two steps (CI smoke run)")
    parser.add_argument("--out", help="output folder (default: docs/ for a full run, a temporary folder for --quick)")
    args = parser.parse_args(argv)
    if args.quick:
        cases, duration, divisors, ref_divisor, repeats = [("m4-111", DEFAULT_SEA)], 4.0, [50, 100], 100, 1
    else:
        cases = [(d, s) for d in ("m4-111", "m4-134") for s in (DEFAULT_SEA, STEEP_SEA)]
        duration, divisors, ref_divisor, repeats = 20.0, [25, 50, 100, 200, 400, 800], 800, 3
    out = Path(args.out) if args.out else (Path(tempfile.mkdtemp()) if args.quick else ROOT / "docs")
    out.mkdir(parents=True, exist_ok=True)
    rows: list[dict] = []
    for device, sea in cases:
        print(f"{device}, {sea.name} sea", flush=True)
        rows += run_case(device, sea, duration, divisors, ref_divisor, repeats)
    picture = "work_precision.png"
    plot(rows, out / picture)
    text = report(rows, duration, repeats, picture)
    if args.quick or args.out:
        (out / "work_precision.md").write_text(text)
        print(f"wrote {out / 'work_precision.md'} and {out / picture}")
    else:
        write_section(ROOT / "docs" / "benchmarks.md", SECTION, text)
        print(f"wrote the section {SECTION!r} of docs/benchmarks.md and docs/{picture}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
