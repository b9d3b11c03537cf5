"""The heaving sphere of the OES wave energy modelling task (IEA OES Task 10): radius 5 m, centre at the still water
level, mass rho 2/3 pi R^3, centre of gravity 2 m below the centre, on a heave slider, with its public WAMIT
database and mesh (``../shared/data/oes-sphere/``). Linear against body-exact hydrostatics and Froude-Krylov force:

- free decays released from rest 1, 3 and 5 m above the equilibrium: the first periods and the first trough;
- regular waves of steepness H / lambda = 0.002 and 0.01, periods 3-11 s, with and without the optimal damper
  (c = |Z(omega)|, the damping that absorbs most in a regular wave): heave amplitude per wave amplitude and the
  absorbed power.

    python studies/sphere_decay.py            # writes docs/nonlinear_hydro.md (section "The OES heaving sphere")
                                              # and docs/sphere_decay.png
    python studies/sphere_decay.py --quick    # one decay and one wave, printed (CI smoke run)
"""

from __future__ import annotations

import argparse
import math
import sys
import tempfile
from pathlib import Path

import numpy as np

from wecss.hydro import HydroData
from wecss.sim import Scene, simulate

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT.parent / "shared" / "data" / "oes-sphere"
RADIUS, RHO, CENTRE_OF_GRAVITY = 5.0, 1000.0, -2.0
RELEASES = (1.0, 3.0, 5.0)
PERIODS = tuple(float(t) for t in range(3, 12))
STEEPNESS = (0.002, 0.01)
BODY_EXACT = {"hydrostatics": "body-exact", "froude_krylov": "body-exact"}


def write_spec(folder: Path) -> Path:
    """The sphere on a heave slider with a joint PTO (its damping set per run), the WAMIT database and the STL."""
    mass = RHO * 2.0 / 3.0 * math.pi * RADIUS**3
    spec = f"""
name = "oes-sphere"
description = "OES Task 10 heaving sphere: R 5 m, centre at the still water level, centre of gravity 2 m below it"
hydro = "{DATA / "sphere.h5"}"

[assumptions]
inertia = "Ixx = Iyy = 1.690e6, Izz = 2.606e6 kg m^2 (the task's values; only heave moves)"

[[bodies]]
name = "ground"
mass = 1.0
inertia = [1.0, 1.0, 1.0]
center_of_mass = [0.0, 0.0, 10.0]

[[bodies]]
name = "sphere"
mass = {mass!r}
inertia = [1.690e6, 1.690e6, 2.606e6]
center_of_mass = [0.0, 0.0, {CENTRE_OF_GRAVITY}]
hydro_body = "sphere"

[[joints]]
name = "base"
kind = "fixed"
child = "ground"

[[joints]]
name = "slider"
kind = "prismatic"
child = "sphere"
parent = "ground"
axis = [0.0, 0.0, 1.0]
point = [0.0, 0.0, {CENTRE_OF_GRAVITY}]

[[ptos]]
name = "pto"
kind = "joint"
joint = "slider"

[[meshes]]
body = "sphere"
stl = "{DATA / "oes_task10_sphere.stl"}"
"""
    path = folder / "oes-sphere.toml"
    path.write_text(spec)
    return path


def optimal_damping(hydro: HydroData, omega: float) -> float:
    """|Z(omega)| = sqrt(B^2 + (omega (m + A) - K / omega)^2) in heave [N s/m]."""
    ds = hydro.dataset
    i = hydro.dofs.index("sphere__Heave")
    a = float(np.interp(omega, hydro.omega, ds.added_mass.values[:, i, i]))
    b = float(np.interp(omega, hydro.omega, ds.radiation_damping.values[:, i, i]))
    k = float(ds.hydrostatic_stiffness.values[i, i])
    m = RHO * 2.0 / 3.0 * math.pi * RADIUS**3
    return math.hypot(b, omega * (m + a) - k / omega)


def decay(spec: Path, release: float, hydrodynamics: dict[str, str], periods: float) -> tuple[np.ndarray, float]:
    """Heave displacement of a free decay and its time step."""
    dt = 0.02
    scene = Scene.from_dict(
        {
            "device": {"name": str(spec)},
            "sea": {"kind": "calm", "period": None, "duration": periods * 6.0, "ramp": 0.0},
            "solver": {"method": "beeman", "dt": dt},
            "radiation": {"method": "convolution"},
            "initial": {"displacement": {"slider__heave": release}},
            "hydrodynamics": hydrodynamics,
            "controller": {"name": "damping", "parameters": {"damping": 0.0}},
            "outputs": {"variables": ["motion"]},
        }
    )
    run = simulate(scene)
    return run.displacement.sel(dof_linear="slider__heave").values, dt


def decay_summary(x: np.ndarray, dt: float) -> tuple[float, float]:
    """The first period (upward crossings of the equilibrium, interpolated) [s] and the first trough [m]."""
    below = np.flatnonzero((x[:-1] < 0) & (x[1:] >= 0))
    crossings = (below - x[below] / (x[below + 1] - x[below])) * dt
    period = float(crossings[1] - crossings[0]) if crossings.size > 1 else float("nan")
    return period, float(np.min(x[: below[0] + 1])) if below.size else float("nan")


def regular(spec: Path, period: float, steepness: float, damping: float, hydrodynamics: dict[str, str],
            cycles: float) -> tuple[float, float]:  # fmt: skip
    """Heave amplitude per wave amplitude (from the last ten cycles) and the mean absorbed power [W]."""
    wavelength = 9.81 * period**2 / (2 * math.pi)  # deep water (the database's 200 m depth is deep at these periods)
    height = steepness * wavelength
    scene = Scene.from_dict(
        {
            "device": {"name": str(spec)},
            "sea": {"kind": "regular", "height": height, "period": period, "duration": cycles * period,
                    "ramp": 3 * period},
            "solver": {"method": "beeman", "dt": period / 100},
            "radiation": {"method": "convolution"},
            "hydrodynamics": hydrodynamics,
            "controller": {"name": "damping", "parameters": {"damping": damping}},
            "outputs": {"variables": ["motion", "pto"], "window": min(1.0, 10.0 / cycles)},
        }
    )  # fmt: skip
    run = simulate(scene)
    x = run.displacement.sel(dof_linear="slider__heave").values
    last = x[-(10 * 100) :]
    return float((last.max() - last.min()) / height), float(run.mean_pto_power.values.sum())


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="one decay and one wave, printed")
    args = parser.parse_args(argv)
    if not (DATA / "sphere.h5").is_file():
        print(f"skipped: the OES sphere's data are not in {DATA}")
        return 0
    with tempfile.TemporaryDirectory() as tmp:
        spec = write_spec(Path(tmp))
        hydro = HydroData.from_bemio(DATA / "sphere.h5")
        releases = RELEASES[:1] if args.quick else RELEASES
        decays = []
        for release in releases:
            row = [release]
            for hyd in ({}, {"hydrostatics": "body-exact"}):
                x, dt = decay(spec, release, hyd, 2.5 if args.quick else 4.0)
                row += list(decay_summary(x, dt))
            decays.append(row)
            print("decay", " ".join(f"{v:.4g}" for v in row), flush=True)
        periods = PERIODS[3:4] if args.quick else PERIODS
        waves = []
        for steepness in STEEPNESS[-1:] if args.quick else STEEPNESS:
            for period in periods:
                c = optimal_damping(hydro, 2 * math.pi / period)
                row = [steepness, period]
                for damping in (0.0, c):
                    for hyd in ({}, BODY_EXACT):
                        row += list(regular(spec, period, steepness, damping, hyd, 12.0 if args.quick else 40.0))
                waves.append(row)
                print("wave", " ".join(f"{v:.4g}" for v in row), flush=True)
        if args.quick:
            return 0
        write_results(decays, waves)
    return 0


def write_results(decays: list[list[float]], waves: list[list[float]]) -> None:
    """The tables into docs/nonlinear_hydro.md and the figure docs/sphere_decay.png."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from _common import write_section

    lines = [
        "Free decays (heave, released from rest; radiation by convolution, Beeman dt 0.02 s):",
        "",
        "| release [m] | linear: first period [s] | first trough [m] | body-exact: first period [s] | first trough [m] "
        "| period ratio |",
        "|---|---|---|---|---|---|",
    ]
    for a, t_lin, x_lin, t_nl, x_nl in decays:
        lines.append(f"| {a:g} | {t_lin:.4f} | {x_lin:.4f} | {t_nl:.4f} | {x_nl:.4f} | {t_nl / t_lin:.4f} |")
    lines += [
        "",
        "Regular waves (40 cycles, the last 10 analysed): heave amplitude per wave amplitude without a damper (RAO) "
        "and the mean power with the optimal damper |Z(omega)|, linear and body-exact (hydrostatics and "
        "Froude-Krylov):",
        "",
        "| H/lambda | T [s] | RAO linear | RAO body-exact | P linear [kW] | P body-exact [kW] | P ratio |",
        "|---|---|---|---|---|---|---|",
    ]
    for row in waves:
        s, t, rao_l, _, rao_n, _, _, p_l, _, p_n = row
        lines.append(
            f"| {s:g} | {t:g} | {rao_l:.4f} | {rao_n:.4f} | {p_l / 1e3:.3f} | {p_n / 1e3:.3f} | "
            f"{p_n / p_l if p_l else float('nan'):.4f} |"
        )
    heading = "## The OES heaving sphere (`studies/sphere_decay.py`)"
    text = "\n".join([heading, "", *lines, "", "![the OES sphere in regular waves](sphere_decay.png)"])
    write_section(ROOT / "docs" / "nonlinear_hydro.md", heading, text)
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for steepness, style in zip(STEEPNESS, ("-", "--"), strict=True):
        rows = np.array([r for r in waves if r[0] == steepness])
        axes[0].plot(rows[:, 1], rows[:, 2], "k" + style, label=f"linear, H/lambda {steepness:g}")
        axes[0].plot(rows[:, 1], rows[:, 4], "r" + style, label=f"body-exact, H/lambda {steepness:g}")
        axes[1].plot(rows[:, 1], rows[:, 7] / 1e3, "k" + style, label=f"linear, H/lambda {steepness:g}")
        axes[1].plot(rows[:, 1], rows[:, 9] / 1e3, "r" + style, label=f"body-exact, H/lambda {steepness:g}")
    axes[0].set(xlabel="wave period [s]", ylabel="heave amplitude / wave amplitude [-]", title="no damper")
    axes[1].set(xlabel="wave period [s]", ylabel="mean power [kW]", title="optimal damper |Z|")
    for ax in axes:
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(ROOT / "docs" / "sphere_decay.png", dpi=120)


if __name__ == "__main__":
    raise SystemExit(main())
