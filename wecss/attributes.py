"""The one place wecss looks up ``long_name`` and ``units`` of every variable and coordinate it writes: the
hydrodynamic databases' table here, and the result variables' from the output table (``wecss.outputs``).

Datasets made by wecss take their CF-style attributes from :data:`VARIABLE_ATTRS` through
:func:`apply_attrs`, so the same name always carries the same meaning and units.
Translations and rotations are kept apart: no attribute ever says "m or rad".
"""

from __future__ import annotations

from collections.abc import Hashable, Mapping

import numpy as np
import xarray as xr

from .outputs import variable_attrs

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
    # frequency-domain steady state (wecss.linear.steady_state); the results' variables come from wecss.outputs
    "wave_amplitude": {
        "long_name": "complex amplitude of the undisturbed wave elevation at the origin, Re[X exp(+i omega t)]",
        "units": "m",
    },
    # stress fields and fatigue maps of a run (wecss.results.StressFieldRecorder)
    "member": {"long_name": "member the stress point lies on"},
    "station": {"long_name": "distance of the stress point's section from its member's start", "units": "m"},
    "y": {"long_name": "stress point's y on its section (member axes)", "units": "m"},
    "z": {"long_name": "stress point's z on its section (member axes)", "units": "m"},
    "scf": {"long_name": "stress concentration factor at the point (in its stresses)", "units": "1"},
    "damage": {
        "long_name": "Palmgren-Miner sum of the record's rainflow cycles (residue as half cycles)",
        "units": "1",
    },
    "life_years": {
        "long_name": "fatigue life: the record's duration over its Miner sum (paper 003, Eq. 55), 365-day years",
        "units": "year",
    },
    "signed_von_mises_max": {"long_name": "largest signed von Mises stress of the record", "units": "Pa"},
    "signed_von_mises_min": {"long_name": "smallest signed von Mises stress of the record", "units": "Pa"},
    "von_mises_rms": {"long_name": "root mean square of the von Mises stress over the record", "units": "Pa"},
    "series_point": {"long_name": "stress point whose time series is kept"},
    "series_time": {"long_name": "time from the record's first sample of the kept series", "units": "s"},
    "signed_von_mises_series": {
        "long_name": "signed von Mises stress at the kept points (the sign of the largest principal stress, Eq. 53)",
        "units": "Pa",
    },
    **variable_attrs(),
}
"""Attributes by variable name: the hydrodynamic databases' here, a run's from the output table
(``wecss.outputs``). Coefficient matrices mix units by block, as the text says."""


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
