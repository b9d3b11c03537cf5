"""Repair of raw BEM data: symmetrisation of added mass and damping, and removal of irregular-frequency artefacts.

Panel codes give added-mass and damping matrices that are symmetric only to their discretisation error, which
reaches several per cent on body-to-body couplings (RM3 in WAMIT and in Capytaine alike), and small negative
damping or spikes near irregular frequencies. ``HydroData.from_wamit``, ``from_capytaine`` and ``from_bemio``
repair by default and say what changed (a :class:`HydroDataWarning` and the ``repairs`` attribute); pass
``repair=False`` to keep the data as read.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import xarray as xr

from ._irregular import IrregularFrequencyReport, remove_irregular_frequencies
from ._validate import SYMMETRY_RTOL, relative_asymmetry

_SYMMETRIC = ("added_mass", "radiation_damping", "added_mass_inf", "added_mass_zero")


@dataclass(frozen=True)
class RepairReport:
    """What :func:`repair` changed.

    Attributes
    ----------
    asymmetry : dict of str to (float, str, str, float)
        Per matrix variable: largest relative asymmetry |M_ij - M_ji| / sqrt(P_i P_j) before symmetrisation,
        the two DOFs and the frequency [rad/s] (nan for frequency-independent matrices).
    irregular : IrregularFrequencyReport
        What the removal of irregular-frequency artefacts changed.
    """

    asymmetry: dict[str, tuple[float, str, str, float]]
    irregular: IrregularFrequencyReport

    @property
    def changed(self) -> bool:
        """True when something beyond the validation tolerances was changed."""
        return bool(self.irregular.omega) or any(a > SYMMETRY_RTOL for a, *_ in self.asymmetry.values())

    def __str__(self) -> str:
        parts = []
        for name, (value, i, j, omega) in self.asymmetry.items():
            if value > SYMMETRY_RTOL:
                at = f" at omega = {omega:.4g} rad/s" if np.isfinite(omega) else ""
                parts.append(f"symmetrised {name} (largest asymmetry {value:.3g} between {i} and {j}{at})")
        if self.irregular.omega:
            parts.append(str(self.irregular))
        return "; ".join(parts) if parts else "nothing to repair"


def repair(ds: xr.Dataset) -> tuple[xr.Dataset, RepairReport]:
    """Symmetrise the added-mass and damping matrices (M + M^T) / 2 and remove irregular-frequency artefacts.

    Returns
    -------
    (xarray.Dataset, RepairReport)
        The repaired dataset (with a ``repairs`` attribute saying what changed) and the report.
    """
    out = ds.copy()
    asymmetry: dict[str, tuple[float, str, str, float]] = {}
    for name in _SYMMETRIC:
        if name not in ds:
            continue
        rel = relative_asymmetry(ds, name)
        index = np.unravel_index(np.argmax(rel), rel.shape)
        omega = float(ds.omega.values[index[0]]) if rel.ndim == 3 else float("nan")
        dof_i = str(ds.influenced_dof.values[index[-2]])
        dof_j = str(ds.radiating_dof.values[index[-1]])
        asymmetry[name] = (float(rel[index]), dof_i, dof_j, omega)
        values = ds[name].values
        out[name] = ds[name].copy(data=0.5 * (values + np.swapaxes(values, -1, -2)))
    out, irregular = remove_irregular_frequencies(out)
    report = RepairReport(asymmetry, irregular)
    out.attrs["repairs"] = str(report)
    return out, report
