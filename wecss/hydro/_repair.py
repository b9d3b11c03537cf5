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
    n_omega : int
        Frequencies before the repair.
    added_mass_inf_change : float
        Largest relative change of a diagonal A_inf entry (0 when A_inf was kept): an A_inf taken at the highest
        frequency is taken again at the highest frequency kept when the repair drops the top of the range.
    """

    asymmetry: dict[str, tuple[float, str, str, float]]
    irregular: IrregularFrequencyReport
    n_omega: int = 0
    added_mass_inf_change: float = 0.0

    @property
    def share_changed(self) -> float:
        """Share of the frequencies the repair replaced or dropped (0 to 1)."""
        return len(self.irregular.omega) / self.n_omega if self.n_omega else 0.0

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
        if self.added_mass_inf_change:
            parts.append(
                "added_mass_inf taken again at the highest frequency kept (largest change of a diagonal entry "
                f"{self.added_mass_inf_change:.1%})"
            )
        return "; ".join(parts) if parts else "nothing to repair"


#: Start of the ``added_mass_inf_source`` attribute of an A_inf the readers took at the highest frequency.
HIGHEST_FREQUENCY_SOURCE = "added mass at the highest frequency"


def repair(ds: xr.Dataset, *, method: str = "interpolate") -> tuple[xr.Dataset, RepairReport]:
    """Symmetrise the added-mass and damping matrices (M + M^T) / 2 and remove irregular-frequency artefacts
    (``method`` as in :func:`wecss.hydro.remove_irregular_frequencies`: ``"interpolate"`` or ``"drop"``).

    An A_inf that a reader took at the highest frequency (``added_mass_inf_source``) is taken again at the highest
    frequency kept when the top of the range is dropped as an artefact.

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
    out, irregular = remove_irregular_frequencies(out, method=method)
    change = 0.0
    source = str(ds.attrs.get("added_mass_inf_source", ""))
    top = float(out.omega.values[-1])
    if source.startswith(HIGHEST_FREQUENCY_SOURCE) and top < float(ds.omega.values[-1]) and "added_mass_inf" in out:
        before = np.abs(np.diagonal(out.added_mass_inf.values))
        out["added_mass_inf"] = out.added_mass_inf.copy(data=out.added_mass.values[-1])
        after = np.abs(np.diagonal(out.added_mass_inf.values))
        change = float(np.max(np.abs(after - before) / np.where(before > 0, before, np.inf)))
        out.attrs["added_mass_inf_source"] = (
            f"{HIGHEST_FREQUENCY_SOURCE} kept by the repair, omega = {top:.6g} rad/s (approximation)"
        )
    report = RepairReport(asymmetry, irregular, int(ds.sizes["omega"]), change)
    out.attrs["repairs"] = str(report)
    return out, report
