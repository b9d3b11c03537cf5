"""Benchmark: radiation memory force per time step for the M4 134 layout (24 coupled DOFs), convolution against
state space. Writes the table into ``docs/benchmarks.md`` (section "Radiation force per step").

Per step, the convolution pushes the newest velocity into the ring buffer and forms the history sum plus the
newest term; the state-space model advances its states exactly over the step (zero-order hold on the velocity,
x+ = Phi x + Gamma v, precomputed) and forms -C x. Times are medians over repeated runs of many steps, on one
core's worth of numpy; the ratio is measured in the same run.

    python studies/bench_radiation.py           # m4-134, 5 repeats of 2000 steps
    python studies/bench_radiation.py --quick   # notc-10kw (3 DOFs: its fits take seconds), 3 repeats of 200 steps (CI)
"""

from __future__ import annotations

import argparse
import platform

import numpy as np
from _common import ROOT, bench, write_section
from scipy.linalg import expm
from scipy.sparse import csr_matrix

import wecss.hydro
from wecss.radiation import FitSettings, RadiationConvolution, fit_radiation, impulse_response

SECTION = "## Radiation force per step"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args()
    name = "notc-10kw" if args.quick else "m4-134"
    steps, repeats = (200, 3) if args.quick else (2000, 5)
    hydro = wecss.hydro.load(name)
    n = len(hydro.dofs)
    dt = 1.2 / 200  # default scene: Tp = 1.2 s, dt = Tp / 200
    irf = impulse_response(hydro)
    conv = RadiationConvolution(irf, dt)
    rng = np.random.default_rng(0)
    v = rng.normal(size=n) * 0.01

    def state_space_step(method: str):
        """Per-step update of a fitted model: exact zero-order hold, x+ = Phi x + Gamma v, force -C x; sparse
        products for the block-diagonal per-entry models."""
        model = fit_radiation(hydro, FitSettings(method=method), irf=irf).model
        nx = model.n_states
        big = np.zeros((nx + n, nx + n))
        big[:nx, :nx] = model.A
        big[:nx, nx:] = model.B
        e = expm(big * dt)
        phi, gamma, c = e[:nx, :nx], e[:nx, nx:], model.C
        if method != "era-mimo":
            phi, gamma, c = csr_matrix(np.where(np.abs(phi) > 1e-14, phi, 0.0)), csr_matrix(gamma), csr_matrix(c)
        x = np.zeros(nx)

        def step() -> None:
            nonlocal x
            x = phi @ x + gamma @ v
            _ = -(c @ x)

        return step, nx

    def step_convolution() -> None:
        conv.push(v)
        conv.force(v)

    t_conv = bench(step_convolution, steps, repeats)
    results = {}
    for method in ("prony", "era-mimo"):
        step, nx = state_space_step(method)
        results[method] = (bench(step, steps, repeats), nx)
    t_ss, nx = results["prony"]
    memory_steps = round(conv.memory / dt)
    print(
        f"{name}: convolution {t_conv * 1e6:.1f} us/step ({memory_steps} memory steps), "
        f"state space {t_ss * 1e6:.1f} us/step ({nx} states), ratio {t_conv / t_ss:.1f}"
    )
    if args.quick:
        return
    text = f"""{SECTION}

`python studies/bench_radiation.py` on {platform.processor() or platform.machine()}, numpy {np.__version__};
{name} ({n} coupled DOFs), dt = Tp/200 = {dt * 1e3:.1f} ms; medians of {repeats} runs of {steps} steps.

| method | size | time per step | ratio to state space |
|---|---|---|---|
| convolution (ring buffer, history sum + newest term) | {memory_steps} memory steps ({conv.memory:.2f} s) \
x {n}x{n} kernel | {t_conv * 1e6:.1f} us | {t_conv / t_ss:.1f} |
| state space (per-entry Prony, exact ZOH step, sparse) | {nx} states | {t_ss * 1e6:.1f} us | 1.0 |
| state space (MIMO Hankel-SVD, exact ZOH step) | {results["era-mimo"][1]} states | \
{results["era-mimo"][0] * 1e6:.1f} us | {results["era-mimo"][0] / t_ss:.2f} |

The paper's MATLAB code took 4.4 ms per step for the whole 111 model (Table 3)."""
    write_section(ROOT / "docs" / "benchmarks.md", SECTION, text)
    print("updated docs/benchmarks.md")


if __name__ == "__main__":
    main()
