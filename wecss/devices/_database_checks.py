"""A device checked against its hydrodynamic database before a run (issue 31: each of these ran to the end with
no word): a body's ``hydro_body`` naming another body's data, or another layout's database (the body far from the
data's body); a float far above the water or deep under it; a mass typed in the wrong unit (grams as kilograms)
against the buoyancy; an added mass far beyond any body's; a negative heave hydrostatic stiffness; a database of too
few frequencies.

The body size is V^(1/3) [m] from the database's displaced volume, as in the run's validity notes
(``wecss/sim/_guards.py``). The limits are wide: each refused case is off by an order of magnitude or more.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ..hydro import HydroData
from ..multibody import Body
from ._spec import DeviceSpecError

HORIZONTAL_LIMIT: float = 0.5
"""A body's centre of mass may lie at most this multiple of its size V^(1/3) from its database body's centre of
buoyancy horizontally (a floating body's weight and buoyancy act along one vertical; the M4's nearest floats are
1.9 sizes apart, and a stern float of m4-132 sits 0.25 m, 0.96 sizes, from the one of m4-134 with its name:
another float's data, or another layout's, is refused)."""

VERTICAL_LIMIT: float = 3.0
"""... and at most this multiple of its size vertically (a spar's centre of mass lies deep below its centre of
buoyancy: RM3's spar, 8 m below for a size of 9.6 m)."""

MASS_RATIO_RANGE: tuple[float, float] = (0.01, 10.0)
"""Accepted range of a body's mass over its displaced mass rho V (1 for a float in its own equilibrium; the
NOTC float 0.79; a body held by its joints may differ, by less than ten times)."""

ADDED_MASS_RATIO_LIMIT: float = 100.0
"""Largest infinite-frequency added mass of a body's translation over its displaced mass rho V (a heaving
hemisphere 0.5, a thin flat float a few)."""

NEGATIVE_HEAVE_TOLERANCE: float = 1e-6
"""A database body's heave hydrostatic stiffness C33 below minus this fraction of rho g V^(2/3) is refused: C33 is
rho g times the waterplane area, never negative (0 for a submerged body); a negative one makes the body sink or
rise without end, which a run would show only late, as a drift."""

MIN_FREQUENCIES: int = 10
"""Fewest frequencies of a database a run accepts: the radiation memory and the excitation are interpolated
between them, and fewer cannot resolve a resonance."""


def check_against_database(name: str, bodies: Sequence[Body], hydro: HydroData) -> None:
    """Refuse a device ``name`` whose ``bodies`` (``wecss.multibody.Body``) do not fit their database.

    Raises
    ------
    DeviceSpecError
        Naming the device, the body, its ``hydro_body``, the value found and what is accepted.
    """
    ds = hydro.dataset
    n_omega = int(ds.sizes.get("omega", 0))
    if n_omega < MIN_FREQUENCIES:
        raise DeviceSpecError(
            f"device {name!r}: its hydrodynamic database has {n_omega} frequencies; accepted: at least "
            f"{MIN_FREQUENCIES} (the radiation memory and the excitation are interpolated between them)"
        )
    for body in bodies:
        if body.hydro_body is None:
            continue
        where = f"device {name!r}, body {body.name!r} (hydro_body {body.hydro_body!r})"
        volume = float(ds.displaced_volume.sel(body=body.hydro_body))
        if not volume > 0:
            continue  # a body without buoyancy in the data: nothing to compare with
        size = volume ** (1 / 3)
        com = np.asarray(body.center_of_mass, dtype=float)
        cob = np.asarray(ds.center_of_buoyancy.sel(body=body.hydro_body).values, dtype=float)
        if np.all(np.isfinite(cob)):
            horizontal, vertical = float(np.hypot(*(com[:2] - cob[:2]))), float(abs(com[2] - cob[2]))
            for what, distance, limit in (
                ("horizontally", horizontal, HORIZONTAL_LIMIT),
                ("vertically", vertical, VERTICAL_LIMIT),
            ):
                if distance > limit * size:
                    raise DeviceSpecError(
                        f"{where}: its centre of mass {np.round(com, 4).tolist()} m lies {distance:.4g} m "
                        f"{what} from the database body's centre of buoyancy {np.round(cob, 4).tolist()} m; accepted: "
                        f"within {limit:g} x its size V^(1/3) = {size:.4g} m (another body's data, another layout's "
                        "database, or a body placed away from the water?)"
                    )
        heave = f"{body.hydro_body}__Heave"
        if heave in hydro.dofs:
            c33 = float(ds.hydrostatic_stiffness.sel(influenced_dof=heave, radiating_dof=heave))
            scale = hydro.rho * hydro.g * size**2
            if c33 < -NEGATIVE_HEAVE_TOLERANCE * scale:
                raise DeviceSpecError(
                    f"{where}: the database's hydrostatic stiffness in heave (hydrostatic_stiffness "
                    f"[{heave}, {heave}]) is {c33:.6g} N/m; accepted: 0 or more (rho g times the waterplane area, "
                    f"about rho g V^(2/3) = {scale:.4g} N/m for this body): a sign error in the data?"
                )
        ratio = body.mass / (hydro.rho * volume)
        low, high = MASS_RATIO_RANGE
        if not low <= ratio <= high:
            raise DeviceSpecError(
                f"{where}: mass {body.mass:.6g} kg is {ratio:.4g} times its displaced mass rho V = "
                f"{hydro.rho * volume:.6g} kg; accepted: {low:g} to {high:g} times (a mass in the wrong unit?)"
            )
        for axis in ("Surge", "Sway", "Heave"):
            dof = f"{body.hydro_body}__{axis}"
            if dof not in hydro.dofs:
                continue
            added = float(ds.added_mass_inf.sel(influenced_dof=dof, radiating_dof=dof))
            if added > ADDED_MASS_RATIO_LIMIT * hydro.rho * volume:
                raise DeviceSpecError(
                    f"{where}: the database's infinite-frequency added mass in {axis.lower()} is {added:.6g} kg, "
                    f"{added / (hydro.rho * volume):.4g} times its displaced mass rho V; accepted: up to "
                    f"{ADDED_MASS_RATIO_LIMIT:g} times (coefficients scaled or in the wrong unit?)"
                )
