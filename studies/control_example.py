"""Worked example of docs/control.md: a PTO controller designed on wecss's linear model with python-control and
run in closed loop in both simulators.

The design: each PTO's damping tuned to the sea state's peak frequency, c_p = 1 / |Y_pp(i omega_p)| with Y the
open plant's admittance from PTO forces to PTO stroke rates (the optimal damping of a single PTO in a regular wave
at omega_p, |Z_i|). python-control evaluates Y from the state-space model, radiation states included.

    python studies/control_example.py           # m4-134, the default sea state, 100 Tp
    python studies/control_example.py --quick   # 10 Tp (CI smoke run)
"""

from __future__ import annotations

import argparse
import dataclasses

import numpy as np

from wecss.control import ControlContext, Controller, Measurement
from wecss.sim import Scene, default_scene_path, simulate


class PeakTunedDamping(Controller):
    """Damping per PTO tuned at the peak frequency: c_p = 1 / |Y_pp(i omega_p)| [N m s/rad]."""

    def setup(self, context: ControlContext) -> None:
        plant = context.linear_model().state_space  # the open plant: PTO forces are inputs
        ptos = context.pto_names
        admittance = plant[[f"stroke_rate__{n}" for n in ptos], [f"force__{n}" for n in ptos]]
        omega_p = 2 * np.pi / context.sea.period
        y = np.atleast_2d(admittance(1j * omega_p))  # python-control evaluates the transfer matrix
        self.damping = 1.0 / np.abs(np.diag(y))

    def linear_gains(self) -> tuple[np.ndarray, np.ndarray]:
        return self.damping, np.zeros_like(self.damping)

    def compute(self, t: float, measurement: Measurement) -> np.ndarray:
        return -self.damping * measurement.velocity


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args()
    base = Scene.from_toml(default_scene_path())
    scene = dataclasses.replace(
        base,
        sea=dataclasses.replace(base.sea, duration="10 Tp" if args.quick else "100 Tp"),
        radiation=dataclasses.replace(base.radiation, method="state_space"),
    )
    controller = PeakTunedDamping()
    for method in ("beeman", "linear"):
        run = dataclasses.replace(scene, solver=dataclasses.replace(scene.solver, method=method))
        ds = simulate(run, controller=controller)
        print(
            f"{method:7s} damping {np.round(controller.damping, 3)} N m s/rad: mean power per PTO "
            f"{np.round(ds.mean_pto_power.values * 1e3, 3)} mW, total {ds.mean_pto_power.values.sum() * 1e3:.3f} mW"
        )


if __name__ == "__main__":
    main()
