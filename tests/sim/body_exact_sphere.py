"""A radiation-free floating sphere for the body-exact tests: a device spec, a database with only hydrostatics, and a
fine surface mesh revolved from a semicircle (written as an STL file), all in a test's temporary folder."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from wecss.hydro import HydroData
from wecss.hydro._build import build_dataset
from wecss.hydro.mesh import arc_points, revolve, write_stl

RHO, G = 1000.0, 9.81


def sphere_mesh_triangles(radius: float, segments: int = 64, sectors: int = 64) -> np.ndarray:
    """Triangles (n, 3, 3) of a sphere centred at the origin: a semicircle meridian (volume-preserving chords)
    revolved with area-preserving sectors."""
    meridian = arc_points((0.0, 0.0), radius, math.pi / 2, -math.pi / 2, segments)
    meridian[0, 0] = meridian[-1, 0] = 0.0  # the poles on the axis
    return revolve(meridian, sectors, name="sphere").triangles


def write_sphere_device(folder: Path, radius: float = 1.0, *, segments: int = 64, sectors: int = 64) -> Path:
    """A sphere of radius ``radius`` [m], half immersed (mass rho 2/3 pi R^3), on a vertical slider, with a database
    of its linear hydrostatics alone (no radiation, no added mass, no excitation) and its mesh; returns the spec."""
    volume = 2.0 / 3.0 * math.pi * radius**3
    mass = RHO * volume
    inertia = 0.4 * mass * radius**2
    omega = np.linspace(0.1, 10.0, 12)
    zeros = np.zeros((omega.size, 1, 1))
    dataset = build_dataset(
        omega=omega,
        dofs=["sphere__Heave"],
        wave_direction=np.array([0.0]),
        added_mass=zeros.copy(),
        radiation_damping=zeros.copy(),
        added_mass_inf=np.zeros((1, 1)),
        excitation=np.zeros((omega.size, 1, 1), dtype=complex),
        hydrostatic_stiffness=np.array([[RHO * G * math.pi * radius**2]]),
        bodies=["sphere"],
        mass=np.array([mass]),
        inertia=np.eye(3)[None] * inertia,
        center_of_mass=np.zeros((1, 3)),
        center_of_buoyancy=np.array([[0.0, 0.0, -3.0 / 8.0 * radius]]),
        displaced_volume=np.array([volume]),
        reference_point=np.zeros((1, 3)),
        rho=RHO,
        g=G,
        water_depth=np.inf,
        source="half-immersed sphere, hydrostatics only (test data)",
    )
    HydroData(dataset).to_netcdf(folder / "sphere.nc")
    write_stl(folder / "sphere.stl", sphere_mesh_triangles(radius, segments, sectors))
    spec = f"""
name = "sphere"
description = "a half-immersed sphere on a vertical slider (test device)"
hydro = "sphere.nc"

[[bodies]]
name = "ground"
mass = 1.0
inertia = [1.0, 1.0, 1.0]
center_of_mass = [0.0, 0.0, {2 * radius}]

[[bodies]]
name = "sphere"
mass = {mass!r}
inertia = [{inertia!r}, {inertia!r}, {inertia!r}]
center_of_mass = [0.0, 0.0, 0.0]
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
point = [0.0, 0.0, 0.0]

[[meshes]]
body = "sphere"
stl = "sphere.stl"
"""
    path = folder / "sphere.toml"
    path.write_text(spec)
    return path


def linear_period(radius: float = 1.0) -> float:
    """The small-amplitude period of the half-immersed sphere without added mass [s]: 2 pi sqrt(2 R / (3 g))."""
    return 2 * math.pi * math.sqrt(2 * radius / (3 * G))


def upward_crossing_periods(time: np.ndarray, x: np.ndarray) -> np.ndarray:
    """The intervals [s] between successive upward zero crossings of ``x`` (linear interpolation)."""
    below = np.flatnonzero((x[:-1] < 0) & (x[1:] >= 0))
    crossings = time[below] - x[below] * (time[below + 1] - time[below]) / (x[below + 1] - x[below])
    return np.diff(crossings)
