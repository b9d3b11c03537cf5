"""The WEC Control Competition (WECCCOMP) study: the Wavestar in the competition's scored sea states, in the
nonlinear simulator, scored by the competition's criterion (``wecss.results.wecccomp_score``), for the best
damping (tuned per sea state), the best reactive spring-damper within the force limit, MPC with perfect preview
and causal MPC (excitation estimator and AR predictor).

    python studies/wecccomp.py            # all six sea states (prints the markdown table for docs/control.md)
    python studies/wecccomp.py --quick    # sea state 1, 40 s (CI smoke run)

Needs the competition's WAMIT data in ../shared/data (skips with a message when they are absent). The
competition's hinge friction (1.8 N m s/rad) is the device's own loss (the hinge's ``damping`` in the wavestar
spec): no controller owns it and it is not PTO power.
"""

from __future__ import annotations

import argparse
import csv
import sys
import time
from pathlib import Path

from wecss.results import wecccomp_score
from wecss.sim import Scene, simulate

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT.parent / "shared" / "data"
WAVESTAR = DATA / "wamit" / "wavestar" / "wavestar.out"
SEA_STATES = DATA / "wecccomp" / "sea_states.csv"

CONTROLLERS: dict[str, dict] = {
    "best damping": {"name": "optimal-damping"},
    "reactive (within limits)": {"name": "reactive"},
    "MPC, perfect preview": {"name": "mpc", "parameters": {"preview": "perfect", "horizon": 30, "efficiency": 0.7}},
    "MPC, causal": {"name": "mpc", "parameters": {"preview": "causal", "horizon": 30, "efficiency": 0.7}},
}
"""The compared controllers (scene controller sections; MPC at a control period of ten solver steps)."""


def sea_states() -> dict[int, dict[str, float]]:
    """The competition's sea states by id: hm0_m, tp_s, gamma, ramp_s, end_s."""
    with SEA_STATES.open() as f:
        rows = csv.DictReader(line for line in f if not line.startswith("#"))
        return {int(r["id"]): {k: float(v) for k, v in r.items() if k != "id"} for r in rows}


def wecccomp_scene(state: int, controller: dict, duration: float | None = None) -> Scene:
    """The Wavestar in sea state ``state`` (its ramp and end time unless ``duration`` [s] is given), dt = Tp/200,
    state-space radiation, with ``controller`` (a planning one at ten solver steps)."""
    row = sea_states()[state]
    dt = row["tp_s"] / 200
    control = dict(controller)
    if control["name"] == "mpc":
        control["dt"] = 10 * dt
    return Scene.from_dict(
        {
            "device": {"name": "wavestar", "hydro": str(WAVESTAR)},
            "sea": {
                "kind": "jonswap", "height": row["hm0_m"], "period": row["tp_s"], "gamma": row["gamma"],
                "duration": duration or row["end_s"], "ramp": row["ramp_s"],
            },
            "solver": {"dt": dt},
            "radiation": {"method": "state_space"},
            "controller": control,
            "outputs": {"variables": ["pto"]},
        }
    )  # fmt: skip


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args()
    if not WAVESTAR.is_file() or not SEA_STATES.is_file():
        print(f"skipped: the WECCCOMP data are not in {DATA}")
        return
    states = [1] if args.quick else sorted(sea_states())
    duration = 40.0 if args.quick else None
    print("| sea state | controller | EC [W] | mean P_elec [W] | mean P_abs [W] | abs f 98 [N] | abs z 98 [m] | "
          "share of bound | MPC fallbacks | run [s] |")  # fmt: skip
    print("|---|---|---|---|---|---|---|---|---|---|")
    for state in states:
        for label, controller in CONTROLLERS.items():
            start = time.perf_counter()
            ds = simulate(wecccomp_scene(state, controller, duration))
            seconds = time.perf_counter() - start
            score = wecccomp_score(ds, start=min(25.0, 0.5 * float(ds.time.values[-1])))
            fallbacks = ds.attrs.get("controller_fallbacks", "-")
            print(
                f"| {state} | {label} | {score['ec']:.4f} | {score['mean_electrical_power']:.4f} | "
                f"{score['mean_absorbed_power']:.4f} | {score['force_98']:.1f} | {score['stroke_98']:.4f} | "
                f"{ds.attrs['share_of_power_bound']:.3f} | {fallbacks} | {seconds:.1f} |",
                flush=True,
            )
    sys.stdout.flush()


if __name__ == "__main__":
    main()
