"""Study: numerical stability of the nonlinear simulator under stress: the largest stable time step per integrator x
radiation method x layout and PTO, and the steep-sea check.

Largest stable step: bisection on log(dt) between a step known stable and one known unstable. A step counts as
stable when a run of the default sea state (JONSWAP Hs 0.04 m, Tp 1.2 s, gamma 3.3, seed 1, ``DURATION`` Tp with a
2 Tp ramp) (a) completes, that is no ``SimulationDiverged`` (non-finite state, a hinge past the angle bound of
1.5 rad, a Beeman corrector that does not converge) and (b) its RMS hinge angle after the ramp lies within
``RMS_BAND`` (25 %) of that of the same setting at dt = Tp/400. (b) catches a bounded but wrong oscillation.
A step the scene refuses (too coarse for the shortest wave component kept) ends the search there: the answer is
then "stable up to the coarsest step the scene accepts". PTOs: the paper's damping (6 N m s/rad); 100 x stiffer in
damping (600 N m s/rad); 100 x stiffer in stiffness (a spring of 1.07e5 N m/rad beside the 6 N m s/rad damping:
100 x the hinge's hydrostatic stiffness, 1.07e3 N m/rad on m4-111).

Steep seas: m4-111 in JONSWAP seas up to Hs 0.2 m (Tp 1.2 s) at the default step, each run saved to netCDF: the
run either completes and its file holds only finite numbers, or it stops with ``SimulationDiverged`` (its message
names the time and what diverged) and no file is written.

Long runs: the default scene (m4-134, Beeman, state-space radiation, the fastest accurate setting) for
``LONG_STEPS`` (10^6) steps. In calm water: the largest distance of the configuration from the static equilibrium
and the largest energy (kinetic plus linearised potential, 1/2 v'M v + 1/2 dq'K dq with M and K of the linear
model) over the run, at every 100th step. In the default sea: the energy per tenth of the run (bounded: no growth),
the mean PTO power of the run's own running statistic (the final half) against the means of ``WINDOW_STEPS``
(10^4)-step windows (their mean, spread and trend). The sea uses d_omega = 2 pi / (``RECORD_TP`` Tp): with the
default 2 pi / duration a 10^6-step run has 17,896 wave components (their sum per chunk of steps dominates the
cost); the record then repeats every 500 Tp (10^5 steps). The unmoored device drifts in waves (about 26 m in
5,500 s), so the translation bound is lifted for the wave run.

    python studies/stability.py           # full: m4-111 and m4-134; writes docs/benchmarks.md
    python studies/stability.py --long    # the long runs only; writes their part of the section
    python studies/stability.py --quick   # m4-111, Beeman with state space, paper PTO, coarse bisection, 2 x 10^4-step
                                          # long runs; temp folder
"""

from __future__ import annotations

import argparse
import dataclasses
import datetime
import math
import platform
import sys
import tempfile
from pathlib import Path

import numpy as np
from _common import ROOT, write_section

from wecss.results import save
from wecss.scene import SceneError
from wecss.sim import JIT, Scene, SimulationDiverged, default_scene_path, simulate

SECTION = "## Numerical stability"
LONG_SECTION = "### Long runs"
LONG_STEPS = 10**6
WINDOW_STEPS = 10**4
RECORD_TP = 500.0  # repeat period of the long run's wave record [Tp]
DURATION = 10.0  # [Tp]
RAMP = 2.0  # [Tp]
RMS_BAND = 0.25
ACCURATE_DIVISOR = 400
HINGE_STIFFNESS_111 = 1.07e3  # N m/rad: diagonal of the m4-111 hinge's generalised hydrostatic stiffness (linearize)
PTOS = {
    "paper (c = 6)": {"name": "damping", "parameters": {"damping": 6.0}},
    "100 x damping (c = 600)": {"name": "damping", "parameters": {"damping": 600.0}},
    "100 x stiffness (k = 1.07e5, c = 6)": {
        "name": "spring-damper",
        "parameters": {"damping": 6.0, "stiffness": 100 * HINGE_STIFFNESS_111},
    },
}


def make_scene(
    device: str, method: str, radiation: str, dt: float, pto: str, height: float = 0.04, duration: float = DURATION
) -> Scene:
    """The default scene on ``device`` with an integrator, radiation method, step ``dt`` [s], PTO and Hs [m]."""
    base = Scene.from_toml(default_scene_path())
    controller = PTOS[pto]
    return dataclasses.replace(
        base,
        device=dataclasses.replace(base.device, name=device),
        sea=dataclasses.replace(base.sea, height=height, duration=f"{duration} Tp", ramp=f"{RAMP} Tp"),
        radiation=dataclasses.replace(base.radiation, method=radiation),
        solver=dataclasses.replace(base.solver, method=method, dt=dt),
        controller=dataclasses.replace(
            base.controller, name=controller["name"], parameters=dict(controller["parameters"])
        ),
        outputs=dataclasses.replace(base.outputs, variables=("motion", "pto")),
    )


def hinge_rms(ds) -> float:  # type: ignore[no-untyped-def]
    """Largest RMS hinge angle after the ramp [rad]."""
    names = [str(n) for n in ds.dof_angular.values if "hinge" in str(n)]
    after = ds.time.values >= RAMP * ds.attrs["peak_period"] - 1e-9
    return float(np.max(np.sqrt(np.mean(ds.angle.sel(dof_angular=names).values[after] ** 2, axis=0))))


def trial(device: str, method: str, radiation: str, dt: float, pto: str, rms_ref: float | None) -> tuple[str, float]:
    """('stable' | 'unstable' | 'refused', RMS hinge angle [rad] or nan) of one run, with the reason in the status."""
    try:
        ds = simulate(make_scene(device, method, radiation, dt, pto))
    except SimulationDiverged as err:
        return f"unstable (diverged at t = {err.time:.3g} s)", math.nan
    except SceneError as err:
        return f"refused ({str(err)[:60]})", math.nan
    rms = hinge_rms(ds)
    if rms_ref is not None and not abs(rms - rms_ref) <= RMS_BAND * rms_ref:
        return f"unstable (RMS hinge angle {rms:.3g} rad against {rms_ref:.3g} rad)", rms
    return "stable", rms


def largest_stable(device: str, method: str, radiation: str, pto: str, iterations: int) -> dict:
    """Bisection on log(dt) for the largest stable step; a dict for the table row."""
    tp = 1.2
    fine = tp / ACCURATE_DIVISOR
    status, rms_ref = trial(device, method, radiation, fine, pto, None)
    row = {"device": device, "method": method, "radiation": radiation, "pto": pto, "evaluations": 1}
    if status != "stable":
        return {**row, "largest": math.nan, "note": f"not stable even at Tp/{ACCURATE_DIVISOR}: {status}"}
    stable, unstable, note = fine, tp / 2, ""
    status, _ = trial(device, method, radiation, unstable, pto, rms_ref)
    row["evaluations"] += 1
    if status == "stable":
        return {**row, "largest": unstable, "note": "stable at the coarsest step tried (Tp/2)"}
    first_failure = status
    for _ in range(iterations):
        dt = math.sqrt(stable * unstable)
        status, _ = trial(device, method, radiation, dt, pto, rms_ref)
        row["evaluations"] += 1
        if status == "stable":
            stable = dt
        else:
            unstable, first_failure = dt, status
    note = f"next step up: {first_failure}" if not note else note
    return {**row, "largest": stable, "unstable": unstable, "note": note}


def steep_sea(heights: list[float], radiation: str, out: Path) -> list[dict]:
    """m4-111, Beeman, default step, in seas of growing Hs: completes with a finite file, or diverges with no file."""
    import xarray as xr

    rows = []
    for height in heights:
        path = out / f"steep_{radiation}_{height:.2f}.nc"
        path.unlink(missing_ok=True)
        scene = make_scene("m4-111", "beeman", radiation, 1.2 / 200, "paper (c = 6)", height, duration=20.0)
        try:
            ds = simulate(scene)
            save(ds, path)
        except SimulationDiverged as err:
            rows.append({"height": height, "radiation": radiation, "result": str(err).split(";")[0],
                         "file": "written" if path.exists() else "none"})  # fmt: skip
            continue
        with xr.open_dataset(path) as saved:
            finite = all(np.all(np.isfinite(v.values)) for v in saved.data_vars.values() if v.dtype.kind == "f")
        rows.append({"height": height, "radiation": radiation, "result": f"completed, RMS hinge angle "
                     f"{hinge_rms(ds):.3g} rad", "file": "finite" if finite else "NON-FINITE VALUES"})  # fmt: skip
    return rows


def long_scene(steps: int, calm: bool) -> Scene:
    """The default scene (Beeman, state space) for ``steps`` steps, in calm water or the default sea."""
    base = Scene.from_toml(default_scene_path())
    tp = float(base.sea.period or 1.2)
    every = 100 if calm else 1
    sea = (
        dataclasses.replace(base.sea, kind="calm", duration=steps * base.dt, ramp=0.0)
        if calm
        else dataclasses.replace(base.sea, duration=steps * base.dt, d_omega=2 * math.pi / (RECORD_TP * tp))
    )
    return dataclasses.replace(
        base,
        sea=sea,
        radiation=dataclasses.replace(base.radiation, method="state_space"),
        solver=dataclasses.replace(base.solver, method="beeman", translation_bound=1e4),
        outputs=dataclasses.replace(base.outputs, variables=("motion",) if calm else ("motion", "pto"), every=every),
    )


def _energy(ds, model, names: tuple[str, ...]) -> np.ndarray:  # type: ignore[no-untyped-def]
    """1/2 v'M v + 1/2 dq'K dq [J] at the saved steps (M, K of the linear model about the equilibrium; ``names``
    the model's generalised velocities, in its order)."""
    saved = [*map(str, ds.dof_linear.values), *map(str, ds.dof_angular.values)]
    order = [saved.index(n) for n in names]
    q = np.concatenate([ds.displacement.values, ds.angle.values], axis=1)[:, order]
    v = np.concatenate([ds.velocity.values, ds.angular_velocity.values], axis=1)[:, order]
    dq = q - model.q0[None]
    return 0.5 * np.einsum("ti,ij,tj->t", v, model.mass, v) + 0.5 * np.einsum("ti,ij,tj->t", dq, model.stiffness, dq)


def long_runs(steps: int, window_steps: int) -> dict:
    """Calm-water drift and energy, and the wave run's energy per tenth and windowed mean power (a dict)."""
    from wecss.linear import linearize
    from wecss.sim import compile_scene

    out: dict = {"steps": steps, "window_steps": window_steps}
    calm = compile_scene(long_scene(steps, calm=True))
    model = linearize(calm)
    ds = simulate(calm)
    q = np.concatenate([ds.displacement.values, ds.angle.values], axis=1)
    out["calm_drift"] = float(np.max(np.abs(q - model.q0[None])))
    out["calm_energy"] = float(np.max(np.abs(_energy(ds, model, calm.device.model.velocity_names))))
    out["calm_loop"] = float(ds.attrs["run_time_s"])
    waves = compile_scene(long_scene(steps, calm=False))
    ds = simulate(waves)
    out["loop"] = float(ds.attrs["run_time_s"])
    energy = _energy(ds, linearize(waves), waves.device.model.velocity_names)
    ramp = round(waves.scene.sea.ramp_s / waves.dt)
    tenths = np.array_split(energy[ramp:], 10)
    out["energy_tenths"] = [float(np.max(t)) for t in tenths]
    power = ds.pto_power.values.sum(axis=1)
    n_windows = (power.size - ramp) // window_steps
    windows = power[ramp : ramp + n_windows * window_steps].reshape(n_windows, window_steps).mean(axis=1)
    out["windows"] = windows
    out["long_mean"] = float(ds.mean_pto_power.values.sum())  # the kernel's running sums over the final half
    out["record_mean"] = float(power[ramp:].mean())
    out["trend"] = float(np.polyfit(np.arange(n_windows), windows, 1)[0] * n_windows)  # change over the run [W]
    return out


def long_report(r: dict) -> str:
    """The long runs' part of the section."""
    w = r["windows"]
    mean, std = float(np.mean(w)), float(np.std(w, ddof=1))
    tenths = r["energy_tenths"]
    return "\n".join(
        [
            LONG_SECTION,
            "",
            f"The default scene (m4-134, Beeman, state-space radiation, dt = Tp/200) for {r['steps']:.0e} steps "
            f"(measured {datetime.datetime.now(datetime.UTC).strftime('%Y-%m-%d')}; the machine may be shared: loop "
            f"times are wall times). Wave record d_omega = 2 pi / ({RECORD_TP:g} Tp), see the study's docstring.",
            "",
            "| measure | value |",
            "|---|---|",
            f"| calm water: largest \\|q - q_eq\\| (every 100th step) | {r['calm_drift']:.2e} (m or rad) |",
            f"| calm water: largest energy 1/2 v'Mv + 1/2 dq'K dq | {r['calm_energy']:.2e} J |",
            f"| calm water: time loop | {r['calm_loop']:.0f} s |",
            "| waves: largest energy per tenth of the run (after the ramp) | "
            + ", ".join(f"{e:.3g}" for e in tenths)
            + " J |",
            f"| waves: last tenth / first tenth | {tenths[-1] / tenths[0]:.3f} |",
            f"| waves: mean PTO power, the run's statistic (final half) | {r['long_mean'] * 1e3:.4f} mW |",
            f"| waves: mean PTO power over the whole record after the ramp | {r['record_mean'] * 1e3:.4f} mW |",
            f"| waves: {w.size} windows of {r['window_steps']:.0e} steps: mean +- std | "
            f"{mean * 1e3:.4f} +- {std * 1e3:.4f} mW |",
            f"| waves: (final-half statistic - window mean) / window std | {(r['long_mean'] - mean) / std:+.2f} |",
            f"| waves: linear trend of the window means over the run | {r['trend'] * 1e3:+.4f} mW "
            f"({r['trend'] / mean:+.2%}) |",
            f"| waves: time loop | {r['loop']:.0f} s |",
            "",
        ]
    )


def report(rows: list[dict], steep: list[dict], iterations: int) -> str:
    """The Markdown section: the criterion, the table of largest stable steps, the steep-sea table."""
    when = datetime.datetime.now(datetime.UTC).strftime("%Y-%m-%d")
    text = [
        SECTION,
        "",
        f"`python studies/stability.py` on {platform.machine()}, Python {platform.python_version()}, numba "
        f"{'on' if JIT else 'off'}, {when}. Criterion: a step is stable when a {DURATION:g} Tp run of the default "
        f"sea state (ramp {RAMP:g} Tp) completes without `SimulationDiverged` and its RMS hinge angle after the ramp "
        f"lies within {RMS_BAND:.0%} of that at dt = Tp/{ACCURATE_DIVISOR}. Bisection on log(dt) from Tp/"
        f"{ACCURATE_DIVISOR} (stable) and Tp/2, {iterations} halvings of the bracket (the true limit lies between the "
        "two columns). Tp = 1.2 s.",
        "",
        "| layout | integrator | radiation | PTO | largest stable dt | smallest failing dt | runs | "
        "why the step above fails |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        largest = f"{r['largest'] * 1e3:.1f} ms (Tp/{1.2 / r['largest']:.0f})" if np.isfinite(r["largest"]) else "-"
        unstable = f"{r['unstable'] * 1e3:.1f} ms" if "unstable" in r else "-"
        text.append(
            f"| {r['device']} | {r['method']} | {r['radiation']} | {r['pto']} | {largest} | {unstable} | "
            f"{r['evaluations']} | {r['note']} |"
        )
    text += [
        "",
        "Steep seas: m4-111, Beeman, dt = Tp/200, 20 Tp, JONSWAP Tp 1.2 s, gamma 3.3, each run saved to netCDF.",
        "",
        "| Hs | radiation | result | file |",
        "|---|---|---|---|",
        *[f"| {r['height']:.2f} m | {r['radiation']} | {r['result']} | {r['file']} |" for r in steep],
        "",
    ]
    return "\n".join(text)


def _write_long(text: str) -> None:
    """Put the long runs' part at the end of the stability section of docs/benchmarks.md (replacing an older one)."""
    path = ROOT / "docs" / "benchmarks.md"
    doc = path.read_text()
    if LONG_SECTION in doc:
        write_section(path, LONG_SECTION, text)
        return
    start = doc.index(SECTION)
    end = doc.find("\n## ", start + len(SECTION))
    section = doc[start : end if end >= 0 else len(doc)]
    write_section(path, SECTION, section.rstrip() + "\n\n" + text)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="m4-111, Beeman + state space, paper PTO (CI smoke run)")
    parser.add_argument("--long", action="store_true", help="only the long runs (10^6 steps; minutes)")
    parser.add_argument("--out", help="output folder (default: docs/benchmarks.md for a full run, temp for --quick)")
    args = parser.parse_args(argv)
    steps, window = (2 * 10**4, 2 * 10**3) if args.quick else (LONG_STEPS, WINDOW_STEPS)
    out = Path(args.out) if args.out else Path(tempfile.mkdtemp())
    out.mkdir(parents=True, exist_ok=True)
    if args.long:
        text = long_report(long_runs(steps, window))
        print(text, flush=True)
        if args.quick or args.out:
            (out / "stability_long.md").write_text(text)
        else:
            _write_long(text)
        return 0
    if args.quick:
        devices, combos, ptos, iterations, heights = (
            ["m4-111"],
            [("beeman", "state_space")],
            ["paper (c = 6)"],
            2,
            [0.2],
        )
    else:
        devices = ["m4-111", "m4-134"]
        combos = [("beeman", "state_space"), ("rk4", "state_space"), ("beeman", "convolution")]
        ptos, iterations, heights = list(PTOS), 6, [0.05, 0.1, 0.15, 0.2]
    rows = []
    for device in devices:
        for method, radiation in combos:
            for pto in ptos:
                row = largest_stable(device, method, radiation, pto, iterations)
                rows.append(row)
                print(row, flush=True)
    steep = []
    for radiation in ("state_space",) if args.quick else ("state_space", "convolution"):
        steep += steep_sea(heights, radiation, out)
        print(steep[-len(heights) :], flush=True)
    if any(r["file"] not in ("finite", "none") for r in steep):
        print("a steep-sea run wrote non-finite values or a file after diverging", file=sys.stderr)
    text = report(rows, steep, iterations) + "\n" + long_report(long_runs(steps, window))
    if args.quick or args.out:
        (out / "stability.md").write_text(text)
        print(f"wrote {out / 'stability.md'}")
    else:
        write_section(ROOT / "docs" / "benchmarks.md", SECTION, text)
        print(f"wrote the section {SECTION!r} of docs/benchmarks.md")
    return 1 if any(r["file"] not in ("finite", "none") for r in steep) else 0


if __name__ == "__main__":
    sys.exit(main())
