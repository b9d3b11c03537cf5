"""Study: the NOTC 10 kW arm's structural modes beside paper 003's Table 6, and the arm section that reproduces the
paper's stress per unit tip load.

Paper 003 (Wang et al.) lists six modal frequencies of its flexible multibody model (Table 6: 1.05, 36.14, 46.68,
77.73, 83.41, 122.98 Hz; modes 1, 2, 4 in plane, 3 and 5 out of plane, 6 torsion) without the sections of its arm,
piston, cylinder and bracket. Here the arm is the device spec's flexible member (``notc-10kw``: S355, 300 kg spread
along 2.40 m, Euler-Bernoulli elements) and the cylinder its PTO spring (100 kN/m, massless):

1. the stress at the cylinder lug C for 1 kN at the tip, pinned at A and held at C (the paper's mesh study, its
   Table 2: 11.6 MPa), for the spec's tube and for the EN 10210 tube whose section modulus gives 11.6 MPa;
2. the modes of the arm alone in air, as the paper's model has no float (both tubes), and of the device with its
   float, in air and in water (``wecss.devices.structural_modes``).

    python studies/notc_modes.py           # writes docs/structure.md (its NOTC section) and docs/notc_modes.png
    python studies/notc_modes.py --quick   # the same numbers, into a temporary folder
"""

from __future__ import annotations

import argparse
import copy
import tempfile
import time
from pathlib import Path

import numpy as np
from _common import ROOT, write_section

import wecss.devices
from wecss.devices import Device
from wecss.results import plot_structural_modes
from wecss.structure import StressPoint, static_response, stress_modes

PAPER = [(1.05, "in plane"), (36.14, "in plane"), (46.68, "out of plane"), (77.73, "in plane"),
         (83.41, "out of plane"), (122.98, "torsion")]  # fmt: skip
"""Paper 003, Table 6 and Sec. 5.2.3."""
TUBES = {"168.3 x 8.0": (0.1683, 0.008), "139.7 x 8.0": (0.1397, 0.008)}
"""Circular hollow sections (EN 10210): the spec's, and the one whose W = 103 cm^3 gives 11.6 MPa at C."""
SECTION = "## The NOTC arm's modes beside paper 003's Table 6"
KINDS = ("in plane", "out of plane", "torsion")


def spec_with(tube: tuple[float, float], float_body: bool = True) -> dict:  # type: ignore[type-arg]
    """The NOTC spec with the arm's tube (its 300 kg kept by the non-structural mass), with or without the float."""
    spec = copy.deepcopy(dict(wecss.devices.load("notc-10kw").spec))
    arm = spec["members"][0]
    diameter, wall = tube
    arm["section"] = {"kind": "tube", "outer_diameter": diameter, "thickness": wall}
    area = np.pi / 4 * (diameter**2 - (diameter - 2 * wall) ** 2)
    arm["nonstructural_mass"] = 300.0 / 2.4 - 7850.0 * area
    arm["hot_spots"] = [{**s, "z": diameter / 2 if s["z"] > 0 else -diameter / 2} for s in arm["hot_spots"]]
    if not float_body:
        spec["bodies"] = [b for b in spec["bodies"] if b["name"] != "floater"]
        spec["joints"] = [j for j in spec["joints"] if j["name"] != "tip"]
        spec["meshes"] = [m for m in spec.get("meshes", []) if m["body"] != "floater"]
        spec.pop("hydro")
    return spec


def unit_load(device: Device) -> tuple[float, float, float]:
    """(stress at C [Pa], its closed form M c / I, tip deflection [m]) for 1 kN up at the tip, pinned at A, held
    vertically at C."""
    frame = device.structure("arm")
    member = device.member("arm")
    fixed = [*frame.support("clamp", ("ux", "uy", "uz", "rx", "rz")), *frame.support("pto:cylinder", ("uz",))]
    u = static_response(frame.stiffness, frame.point_load("joint:tip", [0.0, 0.0, 1e3]), fixed)
    spot = member.hot_spots[0]
    sigma = stress_modes(frame, np.eye(frame.n_dof), [StressPoint("arm", spot.at, 0.0, spot.z)]).stresses(u)
    closed = 1e3 * (member.length - spot.at) * spot.z / member.section.iy
    return float(abs(sigma["normal"][0])), closed, float((frame.point_map("joint:tip") @ u)[2])


def _hz(value: float) -> str:
    return "0" if value < 1e-6 else f"{value:.3g}"


def _first(ds, wanted: str) -> float:  # type: ignore[no-untyped-def]
    """The frequency of the first mode of a kind [Hz]."""
    return next(float(ds.frequency[k]) for k in range(ds.sizes["mode"]) if kind(ds, k) == wanted)


def kind(ds, k: int) -> str:  # type: ignore[no-untyped-def]
    """The largest strain-energy share of mode k (kinetic when there is no strain energy)."""
    shares = ds.energy_share.isel(mode=k).sel(energy="strain").values
    if np.any(np.isnan(shares)):
        return "mechanism"
    return KINDS[int(np.argmax(shares))]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="write into a temporary folder (CI)")
    args = parser.parse_args(argv)
    out = Path(tempfile.mkdtemp()) if args.quick else ROOT / "docs"
    start = time.perf_counter()
    lines = [SECTION, ""]
    lines.append(
        "Made by `python studies/notc_modes.py`. The paper publishes the arm's length (2.40 m) and material (S355, "
        "its Table 1), not its section, nor those of its piston, cylinder and bracket; its modal analysis is of the "
        "flexible multibody model 'in free vibration (no loads)', whose parts are the arm, piston, cylinder and "
        "bracket (no float: its loads act at the arm tip). Assumed here (device spec `notc-10kw`): the arm a "
        "straight circular tube from the pivot A to the tip D, its 300 kg spread uniformly (the tube plus a "
        "non-structural mass on its axis), the cylinder and piston a massless spring of 100 kN/m from the bracket "
        "point B (1.0 m above A) to the lug C (1.2 m from A), the bracket rigid; Euler-Bernoulli elements with the "
        "sections' rotary inertia, 16 along the arm."
    )
    lines += ["", "### The arm section and the paper's stress per unit tip load", ""]
    lines.append("1 kN up at the tip D, the arm pinned at A (a revolute joint about y) and held vertically at C:")
    lines += ["", "| tube [mm] | W [cm^3] | stress at C, FE [MPa] | M c / I [MPa] | tip deflection [mm] | paper |",
              "|---|---|---|---|---|---|"]  # fmt: skip
    for name, tube in TUBES.items():
        device = Device.from_spec(spec_with(tube))
        sigma, closed, tip = unit_load(device)
        w = device.member("arm").section.iy / (tube[0] / 2)
        paper = "11.6 MPa (Table 2, 0.010 m mesh; 11.8 at 0.005 m)" if name.startswith("139") else ""
        lines.append(f"| {name} | {w * 1e6:.1f} | {sigma / 1e6:.2f} | {closed / 1e6:.2f} | {tip * 1e3:.3f} | {paper} |")
    lines += [
        "",
        "The spec's tube gives 7.78 MPa (the section's value of `docs/notc.md`); the EN 10210 tube 139.7 x 8.0 "
        "(W = 103.1 cm^3) gives 11.64 MPa, the paper's 11.6 MPa, if its maximum is the nominal bending stress at the "
        "lug (an FE model of the real arm also holds any local concentration there).",
    ]
    cases = {
        "arm alone, air, 168.3 x 8.0": (spec_with(TUBES["168.3 x 8.0"], False), False),
        "arm alone, air, 139.7 x 8.0": (spec_with(TUBES["139.7 x 8.0"], False), False),
        "with float, air, 168.3 x 8.0": (spec_with(TUBES["168.3 x 8.0"]), False),
        "with float, water, 168.3 x 8.0": (spec_with(TUBES["168.3 x 8.0"]), True),
    }
    results = {}
    for label, (spec, water) in cases.items():
        results[label] = Device.from_spec(spec).structural_modes(water=water, n_modes=8)
    lines += ["", "### Modes", ""]
    lines.append("| mode | paper [Hz] | paper's kind | " + " | ".join(f"wecss: {k} [Hz]" for k in cases) + " |")
    lines.append("|---" * (3 + len(cases)) + "|")
    for k in range(8):
        paper = PAPER[k] if k < len(PAPER) else ("", "")
        cells = [f"{_hz(float(ds.frequency[k]))} ({kind(ds, k)})" for ds in results.values()]
        lines.append(f"| {k + 1} | {paper[0]} | {paper[1]} | " + " | ".join(cells) + " |")
    alone = results["arm alone, air, 168.3 x 8.0"]
    lines += [
        "",
        "Kinds by the largest share of the mode's strain energy (`energy_share`; mechanism: no strain energy, the "
        "float's pitch on its hinge without gravity). Damping ratios, kinetic shares and the shapes: "
        "`wecss modes notc-10kw`.",
        "",
        f"- The lowest mode is the arm swinging on the cylinder's spring, in plane, as the paper's first: "
        f"{float(alone.frequency[0]):.3g} Hz for the arm alone (J_A = 576 kg m^2 on k (a b1 / c)^2 = 59.0 kN m/rad), "
        f"{float(results['with float, air, 168.3 x 8.0'].frequency[1]):.3g} Hz with the float in air, "
        f"{float(results['with float, water, 168.3 x 8.0'].frequency[1]):.3g} Hz in water (the float's heave "
        "added mass and hydrostatic spring; the lowest wet mode is the float pitching on its hinge). The paper's "
        "1.05 Hz lies between; its arm's mass and inertia are not published (1.05 Hz for the arm alone needs "
        "J_A = 1356 kg m^2).",
        f"- The bending modes of the arm alone start out of plane (the pivot holds the arm against yawing: a "
        f"cantilever sideways) at {_first(alone, 'out of plane'):.3g} Hz, in plane (pinned at A, the soft spring "
        f"at C, free at D) at {[float(alone.frequency[k]) for k in range(8) if kind(alone, k) == 'in plane'][1]:.3g} "
        f"Hz for the spec's tube; the 139.7 x 8.0 tube lowers them by about sqrt(I) (1.34). The paper's modes 2-5 "
        "(36-83 Hz, in plane first) also hold the piston, cylinder and bracket, which are not modelled here, and "
        "an arm whose section and mass distribution are unknown: the orders of magnitude agree, the modes do not.",
        f"- Torsion: the arm alone twists at {_first(alone, 'torsion'):.3g} Hz, pi / (2 L) sqrt(G / rho), only the "
        "tube's own polar inertia turning (the non-structural mass sits on the axis); with the float hinged at its "
        f"tip the twist rolls the float, at {_first(results['with float, air, 168.3 x 8.0'], 'torsion'):.3g} Hz. The "
        "paper's torsion mode at 123 Hz depends on the arm's fittings and end cylinders, which are not published.",
        "",
        "What is modelled and left out: `wecss.devices.structural_modes` (its docstring); the float's database has "
        "surge, heave and pitch only, so out-of-plane motion of the float has no added mass or hydrostatics.",
        "",
        "![NOTC modes in water](notc_modes.png)",
    ]
    text = "\n".join(lines)
    write_section(out / "structure.md", SECTION, text)
    import matplotlib.pyplot as plt

    plt.close(plot_structural_modes(results["with float, water, 168.3 x 8.0"], out / "notc_modes.png"))
    print(text)
    print(f"\nwrote {out / 'structure.md'} and {out / 'notc_modes.png'} in {time.perf_counter() - start:.1f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
