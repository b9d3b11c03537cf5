"""A test-only device for directional seas: a float heaving on a vertical slider at (X0, Y0), with a synthetic
database on 24 headings (every 15 degrees) in water DEPTH deep. No shipped or reference database has more than one
heading, so its coefficients are made up, smooth and physically shaped: the hydrostatic stiffness of a waterplane
of radius R, a constant added mass, a damping peaked near 3 rad/s, and a heave excitation whose magnitude depends on
the heading (as for a body longer than it is wide), C33 exp(-k d) (1 + 0.5 cos^2 beta), with the phase of the
incident wave at the float's position, exp(-i k (X0 cos beta + Y0 sin beta)) (the database's convention: referred to
the wave at the origin)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from wecss.hydro import HydroData
from wecss.hydro._build import build_dataset
from wecss.waves import wavenumber

RHO, G = 1000.0, 9.81
RADIUS, DRAFT = 1.0, 0.5
X0, Y0 = 2.0, 1.0
DEPTH = 5.0
HEADINGS_DEG = np.arange(0.0, 360.0, 15.0)
OMEGA = np.linspace(0.2, 8.0, 80)
AREA = math.pi * RADIUS**2
MASS = RHO * AREA * DRAFT
STIFFNESS = RHO * G * AREA
ADDED_MASS = 0.4 * MASS


def damping(omega: np.ndarray) -> np.ndarray:
    """B33(omega) [N s/m]: a smooth peak near 3 rad/s."""
    return 0.3 * MASS * 3.0 * np.exp(-(((omega - 3.0) / 1.5) ** 2))


def excitation(omega: np.ndarray, heading: float) -> np.ndarray:
    """X33(omega, beta) [N/m] (see the module docstring)."""
    k = wavenumber(omega, DEPTH, G)
    shape = 1.0 + 0.5 * math.cos(heading) ** 2
    return STIFFNESS * np.exp(-k * DRAFT) * shape * np.exp(-1j * k * (X0 * math.cos(heading) + Y0 * math.sin(heading)))


def write_device(folder: Path, headings_deg: np.ndarray = HEADINGS_DEG) -> Path:
    """Write the database (``float.nc``) and the device spec (``float.toml``) into ``folder``; return the spec."""
    headings = np.deg2rad(np.asarray(headings_deg, dtype=float))
    n = OMEGA.size
    x = np.stack([excitation(OMEGA, b) for b in headings], axis=1)[:, :, None]  # (omega, heading, dof)
    dataset = build_dataset(
        omega=OMEGA,
        dofs=["float__Heave"],
        wave_direction=headings,
        added_mass=np.full((n, 1, 1), ADDED_MASS),
        radiation_damping=damping(OMEGA).reshape(n, 1, 1),
        added_mass_inf=np.array([[ADDED_MASS]]),
        excitation=x,
        hydrostatic_stiffness=np.array([[STIFFNESS]]),
        bodies=["float"],
        mass=np.array([MASS]),
        inertia=np.eye(3)[None] * MASS * 0.3,
        center_of_mass=np.array([[X0, Y0, 0.0]]),
        center_of_buoyancy=np.array([[X0, Y0, -DRAFT / 2]]),
        displaced_volume=np.array([AREA * DRAFT]),
        reference_point=np.array([[X0, Y0, 0.0]]),
        rho=RHO,
        g=G,
        water_depth=DEPTH,
        source="synthetic heave float on 24 headings (test data)",
    )
    HydroData(dataset).to_netcdf(folder / "float.nc")
    spec = f"""
name = "float"
description = "a float heaving on a vertical slider (test device with a synthetic database on several headings)"
hydro = "float.nc"

[[bodies]]
name = "ground"
mass = 1.0
inertia = [1.0, 1.0, 1.0]
center_of_mass = [{X0}, {Y0}, 2.0]

[[bodies]]
name = "float"
mass = {MASS!r}
inertia = [{MASS * 0.3!r}, {MASS * 0.3!r}, {MASS * 0.3!r}]
center_of_mass = [{X0}, {Y0}, 0.0]
hydro_body = "float"

[[joints]]
name = "base"
kind = "fixed"
child = "ground"

[[joints]]
name = "slider"
kind = "prismatic"
child = "float"
parent = "ground"
axis = [0.0, 0.0, 1.0]
point = [{X0}, {Y0}, 0.0]

[[ptos]]
name = "pto"
kind = "joint"
joint = "slider"
damping = 2000.0
"""
    path = folder / "float.toml"
    path.write_text(spec)
    return path
