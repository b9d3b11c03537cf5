"""The one table of ``long_name`` and ``units`` for every variable and coordinate wecss writes.

Datasets made by wecss take their CF-style attributes from :data:`VARIABLE_ATTRS` through
:func:`apply_attrs`, so the same name always carries the same meaning and units.
Translations and rotations are kept apart: no attribute ever says "m or rad".
"""

from __future__ import annotations

from collections.abc import Hashable, Mapping

import numpy as np
import xarray as xr

VARIABLE_ATTRS: Mapping[str, Mapping[str, str]] = {
    # coordinates
    "omega": {"long_name": "angular frequency", "units": "rad/s"},
    "wave_direction": {"long_name": "direction of wave propagation, from +x towards +y", "units": "rad"},
    "radiating_dof": {"long_name": "degree of freedom of the moving body (body__Dof)"},
    "influenced_dof": {"long_name": "degree of freedom on which the force acts (body__Dof)"},
    "body": {"long_name": "body name"},
    "axis": {"long_name": "Cartesian axis"},
    "axis_col": {"long_name": "Cartesian axis (second index of a tensor)"},
    # hydrodynamic database
    "added_mass": {
        "long_name": "radiation added mass A(omega)",
        "units": "kg, kg m, kg m^2 (translation-translation, translation-rotation, rotation-rotation)",
    },
    "radiation_damping": {
        "long_name": "radiation damping B(omega)",
        "units": "N s/m, N s, N m s/rad (translation-translation, translation-rotation, rotation-rotation)",
    },
    "added_mass_inf": {
        "long_name": "infinite-frequency added mass A_inf",
        "units": "kg, kg m, kg m^2 (translation-translation, translation-rotation, rotation-rotation)",
    },
    "added_mass_zero": {
        "long_name": "zero-frequency added mass A_0",
        "units": "kg, kg m, kg m^2 (translation-translation, translation-rotation, rotation-rotation)",
    },
    "excitation": {
        "long_name": "wave excitation force per unit wave amplitude, Re[X exp(+i omega t)]",
        "units": "N/m (translations), N m/m (rotations)",
    },
    "froude_krylov": {
        "long_name": "Froude-Krylov force per unit wave amplitude, Re[X exp(+i omega t)]",
        "units": "N/m (translations), N m/m (rotations)",
    },
    "diffraction": {
        "long_name": "diffraction force per unit wave amplitude, Re[X exp(+i omega t)]",
        "units": "N/m (translations), N m/m (rotations)",
    },
    "hydrostatic_stiffness": {
        "long_name": "linear stiffness of the hydrostatic pressure force (buoyancy only, no gravity)",
        "units": "N/m, N, N m/rad (translation-translation, translation-rotation, rotation-rotation)",
    },
    "mass": {"long_name": "body mass", "units": "kg"},
    "inertia": {"long_name": "rotational inertia tensor about the centre of mass", "units": "kg m^2"},
    "center_of_mass": {"long_name": "centre of mass at equilibrium", "units": "m"},
    "center_of_buoyancy": {"long_name": "centre of buoyancy at equilibrium", "units": "m"},
    "displaced_volume": {"long_name": "displaced volume at equilibrium", "units": "m^3"},
    "reference_point": {
        "long_name": "point about which the body's rotational coefficients are given",
        "units": "m",
    },
    # simulation results
    "time": {"long_name": "time", "standard_name": "time", "units": "s"},
    "dof_linear": {"long_name": "translational generalised coordinate (joint__label)"},
    "dof_angular": {"long_name": "rotational generalised coordinate (joint__label)"},
    "pto": {"long_name": "power take-off (in the device spec's order)"},
    "pto_kind": {"long_name": "kind of power take-off: rotary (on a revolute joint) or linear (prismatic or actuator)"},
    "hydro_dof_linear": {"long_name": "translational degree of freedom of the hydrodynamic database (body__Dof)"},
    "hydro_dof_angular": {"long_name": "rotational degree of freedom of the hydrodynamic database (body__Dof)"},
    # generalised modes of bodies (wecss.multibody.GeneralisedModes): coordinates [1], forces [J] per unit coordinate
    "dof_generalised": {"long_name": "generalised coordinate of a body's generalised mode (body__mode)"},
    "hydro_dof_generalised": {"long_name": "generalised mode of the hydrodynamic database (body__mode)"},
    "generalised_coordinate": {"long_name": "coordinate of a body's generalised mode", "units": "1"},
    "generalised_velocity": {"long_name": "rate of a body's generalised mode", "units": "1/s"},
    "generalised_acceleration": {"long_name": "acceleration of a body's generalised mode", "units": "1/s^2"},
    "excitation_generalised_force": {
        "long_name": "wave excitation on a generalised mode (work per unit coordinate)",
        "units": "J",
    },
    "radiation_generalised_force": {
        "long_name": "radiation memory force on a generalised mode (without the A_inf part)",
        "units": "J",
    },
    "hydro_generalised_velocity": {
        "long_name": "rate of a generalised mode of the hydrodynamic database",
        "units": "1/s",
    },
    "displacement": {"long_name": "translational generalised coordinate", "units": "m"},
    "angle": {"long_name": "rotational generalised coordinate", "units": "rad"},
    "velocity": {"long_name": "translational generalised velocity", "units": "m/s"},
    "angular_velocity": {"long_name": "rotational generalised velocity", "units": "rad/s"},
    "acceleration": {"long_name": "translational generalised acceleration", "units": "m/s^2"},
    "angular_acceleration": {"long_name": "rotational generalised acceleration", "units": "rad/s^2"},
    "pto_angle": {
        "long_name": "rotary PTO stroke: joint angle from the spring's rest angle (NaN for linear PTOs)",
        "units": "rad",
    },
    "pto_angular_velocity": {"long_name": "rotary PTO stroke rate (NaN for linear PTOs)", "units": "rad/s"},
    "pto_torque": {
        "long_name": "rotary PTO torque (spring, controller), positive driving the angle up (NaN for linear PTOs)",
        "units": "N m",
    },
    "pto_displacement": {"long_name": "linear PTO stroke from the rest length (NaN for rotary PTOs)", "units": "m"},
    "pto_velocity": {"long_name": "linear PTO stroke rate (NaN for rotary PTOs)", "units": "m/s"},
    "pto_force": {
        "long_name": "linear PTO force (spring, controller), positive extending (NaN for rotary PTOs)",
        "units": "N",
    },
    "pto_power": {
        "long_name": "power absorbed by the PTO, -(force - device spring force) * stroke rate",
        "units": "W",
    },
    "mean_pto_power": {"long_name": "mean absorbed PTO power over the statistics window", "units": "W"},
    "rms_pto_angle": {
        "long_name": "RMS rotary PTO angle about its mean over the statistics window (NaN for linear PTOs)",
        "units": "rad",
    },
    "rms_pto_displacement": {
        "long_name": "RMS linear PTO stroke about its mean over the statistics window (NaN for rotary PTOs)",
        "units": "m",
    },
    "power_bound": {
        "long_name": "complex-conjugate bound of mean absorbed power for the wave components (linear, unconstrained)",
        "units": "W",
    },
    "force_limit_time": {
        "long_name": "time the controller's force was saturated at the PTO's force limit",
        "units": "s",
    },
    "force_limit_episodes": {"long_name": "times the controller's force reached the PTO's force limit", "units": "1"},
    "stroke_limit_time": {"long_name": "time the PTO stroke was beyond its limit (end stop engaged)", "units": "s"},
    "stroke_limit_episodes": {"long_name": "times the PTO stroke passed its limit (end stop engaged)", "units": "1"},
    # frequency-domain steady state (wecss.linear.steady_state)
    "wave_amplitude": {
        "long_name": "complex amplitude of the undisturbed wave elevation at the origin, Re[X exp(+i omega t)]",
        "units": "m",
    },
    "excitation_force": {"long_name": "wave excitation force, world axes", "units": "N"},
    "excitation_moment": {"long_name": "wave excitation moment about the centre of mass, world axes", "units": "N m"},
    "radiation_force": {"long_name": "radiation memory force (without the A_inf part), world axes", "units": "N"},
    "radiation_moment": {"long_name": "radiation memory moment (without the A_inf part), world axes", "units": "N m"},
    "hydro_velocity": {"long_name": "velocity of the centre of mass, world axes", "units": "m/s"},
    "hydro_angular_velocity": {"long_name": "angular velocity, world axes", "units": "rad/s"},
    "wave_elevation": {
        "long_name": "undisturbed wave elevation at the origin, as applied (with the start ramp)",
        "units": "m",
    },
    "body_position": {"long_name": "position of the body's centre of mass, world frame", "units": "m"},
    "body_rotation": {"long_name": "rotation vector of the body from its reference orientation", "units": "rad"},
    "joint_reaction_force": {
        "long_name": "reaction force of the joint on its child's subtree, world axes",
        "units": "N",
    },
    "joint_reaction_moment": {
        "long_name": "reaction moment of the joint on its child's subtree about the joint point, world axes",
        "units": "N m",
    },
    "joint_reaction_force_local": {"long_name": "joint reaction force, axes of the child body", "units": "N"},
    "joint_reaction_moment_local": {"long_name": "joint reaction moment, axes of the child body", "units": "N m"},
    "pto_end_force": {"long_name": "PTO force on the body at each end, at the attachment, world axes", "units": "N"},
    "pto_end_moment": {
        "long_name": "PTO moment (joint PTO torque) on the body at each end, world axes",
        "units": "N m",
    },
    "hot_spot": {"long_name": "hot spot of a beam member (member.spot)"},
    "section_axis": {"long_name": "member axes: x along the member from start to end, z up across it"},
    "section_force": {
        "long_name": "section force at the hot spot's station (N along x, shears Vy, Vz), member axes",
        "units": "N",
    },
    "section_moment": {
        "long_name": "section moment at the hot spot's station about the section centre (T, My, Mz), member axes",
        "units": "N m",
    },
    "axial_stress": {"long_name": "axial stress N/A at the hot spot, times its SCF (tension positive)", "units": "Pa"},
    "bending_stress": {"long_name": "bending stress My z/Iy - Mz y/Iz at the hot spot, times its SCF", "units": "Pa"},
    "normal_stress": {"long_name": "normal stress (axial plus bending) at the hot spot, times its SCF", "units": "Pa"},
    "shear_stress": {"long_name": "torsional shear stress T/W_t at the hot spot, times its SCF", "units": "Pa"},
    "von_mises_stress": {"long_name": "von Mises stress at the hot spot", "units": "Pa"},
    "signed_von_mises_stress": {
        "long_name": "signed von Mises stress at the hot spot: the sign of the largest principal stress (Eq. 53)",
        "units": "Pa",
    },
}
"""Attributes by variable name. Coefficient matrices mix units by block, as the text says."""


def by_pto_kind(
    values: np.ndarray, rotary: np.ndarray, names: tuple[str, str], dims: tuple[str, ...]
) -> dict[str, tuple[tuple[str, ...], np.ndarray]]:
    """A per-PTO quantity as Dataset variables on the one ``pto`` dimension (the last of ``dims``), one variable
    per kind so units never mix: ``names`` = (rotary name [rad ...], linear name [m ...]), each NaN for the PTOs of
    the other kind (``rotary`` a mask per PTO); a kind no PTO has gives no variable. When every PTO is of one
    kind its variable is ``values`` itself (no copy: a long run's time series are held once)."""
    out = {}
    for name, mask in zip(names, (rotary, ~rotary), strict=True):
        if mask.all():
            out[name] = (dims, values)
        elif mask.any():
            out[name] = (dims, np.where(mask, values, np.nan))
    return out


_DERIVED = {
    "_amplitude": "complex amplitude per wave component, Re[X exp(+i omega t)], linearised about equilibrium, of the ",
    "_equilibrium": "at equilibrium (no waves): ",
}
"""Suffixes of the loads group's frequency-domain variables and how their long names begin."""


def attrs_for(name: Hashable) -> dict[str, str]:
    """Return a copy of the attributes of variable ``name`` (empty when the name is unknown); a name ending in
    ``_amplitude`` or ``_equilibrium`` takes its base variable's units."""
    key = str(name)
    for suffix, lead in _DERIVED.items():
        base = key.removesuffix(suffix)
        if base != key and base in VARIABLE_ATTRS:
            out = dict(VARIABLE_ATTRS[base])
            out["long_name"] = lead + out["long_name"]
            return out
    return dict(VARIABLE_ATTRS.get(key, {}))


def apply_attrs(ds: xr.Dataset) -> xr.Dataset:
    """Return ``ds`` with ``long_name`` and ``units`` set from the table on every known name.

    Existing attributes other than these two are kept.
    """
    out = ds.copy()
    for name, variable in out.variables.items():  # the variables themselves (a DataArray per name costs more)
        extra = attrs_for(str(name))
        if extra:
            variable.attrs.update(extra)
    return out
