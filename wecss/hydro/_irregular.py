"""Detection and removal of irregular-frequency artefacts in BEM results.

Irregular frequencies of a surface-piercing body without a lid show as narrow spikes and negative
bands in the radiation damping (and matching jumps in added mass and excitation). A point is flagged
for a diagonal damping entry when it is negative beyond :data:`NEGATIVE_RTOL` of the entry's peak, or when
it departs from the cubic through its two neighbours on each side by more than :data:`SPIKE_RTOL` of the
peak (worst point first, each flagged point then replaced by interpolation before the next search, so
that one spike does not flag its neighbours). Only diagonal entries are tested: they are the ones whose
sign physics fixes.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import xarray as xr

from ._peaks import negligible_dofs

SPIKE_RTOL: float = 0.2
"""A point departing from its leave-one-out cubic prediction by more than this fraction of the peak is a spike.

Measured: the physical interference peaks of the eight-float M4 134 array at 15-18 rad/s (sampled every 0.1 rad/s)
depart by up to 0.13; the irregular-frequency spikes of the lid-less Wavestar WAMIT run by 0.27-0.28."""

NEGATIVE_RTOL: float = 1e-3
"""Diagonal damping below -NEGATIVE_RTOL * peak is flagged."""

_FREQUENCY_VARIABLES = ("added_mass", "radiation_damping", "excitation", "froude_krylov", "diffraction")


def _loo_error(omega: np.ndarray, values: np.ndarray) -> np.ndarray:
    """Leave-one-out error: each point minus the cubic through its two neighbours on each side (0 at the ends).

    The cubic is the Lagrange interpolant at the neighbours' own frequencies, so uneven spacing is fine.
    """
    err = np.zeros_like(values)
    if values.size < 5:
        return err
    offsets = (-2, -1, 1, 2)
    x0 = omega[2:-2]
    xs = [omega[2 + k : omega.size - 2 + k] for k in offsets]
    ys = [values[2 + k : values.size - 2 + k] for k in offsets]
    pred = np.zeros_like(x0)
    for a, (xa, ya) in enumerate(zip(xs, ys, strict=True)):
        weight = np.ones_like(x0)
        for b, xb in enumerate(xs):
            if b != a:
                weight *= (x0 - xb) / (xa - xb)
        pred += weight * ya
    err[2:-2] = values[2:-2] - pred
    return err


def _spikes(omega: np.ndarray, series: np.ndarray, peak: float, known: np.ndarray) -> np.ndarray:
    """Flag spikes in one damping series, worst first, until none is left above SPIKE_RTOL * peak.

    Points already ``known`` to be bad are interpolated over from the start and stay flagged.
    """
    flags = known.copy()
    work = series.copy()
    if np.any(flags):
        work[flags] = np.interp(omega[flags], omega[~flags], series[~flags])
    for _ in range(series.size):
        err = np.abs(_loo_error(omega, work))
        err[flags] = 0.0
        worst = int(np.argmax(err))
        if err[worst] <= SPIKE_RTOL * peak:
            break
        flags[worst] = True
        work = series.copy()
        work[flags] = np.interp(omega[flags], omega[~flags], series[~flags])
    return flags


def _flags(ds: xr.Dataset) -> np.ndarray:
    """Boolean (omega, dof): points of each diagonal damping entry that look like artefacts."""
    diag = np.diagonal(ds.radiation_damping.values, axis1=1, axis2=2)
    peak = np.max(np.abs(diag), axis=0)
    peak = np.where(peak > 0, peak, 1.0)
    flags = diag < -NEGATIVE_RTOL * peak
    skip = negligible_dofs(ds)
    flags[:, skip] = False
    if diag.shape[0] >= 5:
        for j in np.flatnonzero(~skip):
            flags[:, j] = _spikes(ds.omega.values, diag[:, j], float(peak[j]), flags[:, j])
    return flags


def _bands(mask: np.ndarray) -> list[tuple[int, int]]:
    """Contiguous runs of True in a 1-D mask, as (first, last) indices."""
    out: list[tuple[int, int]] = []
    idx = np.flatnonzero(mask)
    if idx.size == 0:
        return out
    start = prev = int(idx[0])
    for i in idx[1:]:
        if i != prev + 1:
            out.append((start, prev))
            start = int(i)
        prev = int(i)
    out.append((start, prev))
    return out


def find_irregular_frequencies(ds: xr.Dataset) -> list[tuple[str, float, float]]:
    """Return the suspicious bands as ``(dof, omega_low, omega_high)`` [rad/s] (empty if none)."""
    flags = _flags(ds)
    omega = ds.omega.values
    result = []
    for j, dof in enumerate(ds.radiating_dof.values):
        for lo, hi in _bands(flags[:, j]):
            result.append((str(dof), float(omega[lo]), float(omega[hi])))
    return result


def describe_bands(bands: tuple[tuple[str, float, float], ...] | list[tuple[str, float, float]], limit: int = 8) -> str:
    """Short text of flagged bands, DOFs grouped by band: ``"17.6 rad/s: a__Surge, a__Heave; ..."``."""
    grouped: dict[tuple[float, float], list[str]] = {}
    for dof, lo, hi in bands:
        grouped.setdefault((lo, hi), []).append(dof)
    parts = []
    for (lo, hi), dofs in sorted(grouped.items()):
        span = f"{lo:.4g} rad/s" if lo == hi else f"{lo:.4g}-{hi:.4g} rad/s"
        parts.append(f"{span}: {', '.join(dofs)}")
    if len(parts) > limit:
        parts = [*parts[:limit], f"... ({len(parts)} bands in all)"]
    return "; ".join(parts)


@dataclass(frozen=True)
class IrregularFrequencyReport:
    """What :func:`remove_irregular_frequencies` changed.

    Attributes
    ----------
    method : str
        ``"interpolate"`` or ``"drop"``.
    omega : tuple of float
        Frequencies [rad/s] whose values were replaced or dropped.
    bands : tuple of (str, float, float)
        The flagged bands per DOF, as found by :func:`find_irregular_frequencies`.
    dropped_at_ends : tuple of float
        Flagged frequencies [rad/s] beyond the last (or before the first) clean one, which cannot be
        interpolated and were dropped.
    """

    method: str
    omega: tuple[float, ...]
    bands: tuple[tuple[str, float, float], ...]
    dropped_at_ends: tuple[float, ...] = ()

    def __str__(self) -> str:
        if not self.omega:
            return "no irregular-frequency artefacts found; nothing changed"
        bands = describe_bands(self.bands)
        if self.method == "drop":
            return f"dropped {len(self.omega)} frequencies ({bands})"
        text = f"replaced {len(self.omega) - len(self.dropped_at_ends)} frequencies by interpolation"
        if self.dropped_at_ends:
            text += (
                f" and dropped {len(self.dropped_at_ends)} at the ends of the range "
                f"({min(self.dropped_at_ends):.4g}-{max(self.dropped_at_ends):.4g} rad/s)"
            )
        return f"{text} ({bands})"


def remove_irregular_frequencies(
    ds: xr.Dataset, *, method: str = "interpolate"
) -> tuple[xr.Dataset, IrregularFrequencyReport]:
    """Remove irregular-frequency artefacts from every frequency-dependent variable.

    Parameters
    ----------
    ds : xarray.Dataset
        A hydrodynamic dataset (it need not pass validation: this is how one repairs it).
    method : {"interpolate", "drop"}
        ``"interpolate"`` replaces the flagged frequencies, for all DOFs at once, by cubic interpolation
        in omega from the unflagged ones (PCHIP, which does not overshoot), and drops flagged frequencies
        at the ends of the range, which would need extrapolation; ``"drop"`` removes them all.

    Returns
    -------
    (xarray.Dataset, IrregularFrequencyReport)
        The cleaned dataset and what changed.

    Raises
    ------
    ValueError
        For an unknown method, or when too few frequencies are left to interpolate from.
    """
    if method not in ("interpolate", "drop"):
        raise ValueError(f"method must be 'interpolate' or 'drop'; got {method!r}")
    bands = tuple(find_irregular_frequencies(ds))
    original = ds.omega.values
    # the flags are relative to each entry's peak over the frequencies kept: dropping a band that held the peak
    # (a wide negative band at the top of the range) can expose more, so repeat until nothing more is dropped
    flagged: set[float] = set()
    dropped: list[float] = []
    for _ in range(original.size):
        bad = np.any(_flags(ds), axis=1)
        flagged.update(float(w) for w in ds.omega.values[bad])
        if not np.any(bad):
            break
        good_index = np.flatnonzero(~bad)
        if good_index.size < 2:
            raise ValueError(
                f"fewer than two of {original.size} frequencies are free of artefacts; cannot clean this dataset"
            )
        # "drop" removes every flagged frequency; "interpolate" only those beyond the last (before the first)
        # clean one, which would need extrapolation
        keep = good_index if method == "drop" else np.arange(good_index[0], good_index[-1] + 1)
        if keep.size == bad.size:
            break
        dropped.extend(float(w) for w in np.delete(ds.omega.values, keep))
        ds = ds.isel(omega=keep)
    omega = tuple(w for w in original if float(w) in flagged or float(w) in set(dropped))
    if method == "drop":
        return ds.copy(), IrregularFrequencyReport(method, tuple(float(w) for w in omega), bands)
    report = IrregularFrequencyReport(method, tuple(float(w) for w in omega), bands, tuple(sorted(dropped)))
    if not np.any(bad):
        return ds.copy(), report
    good_omega = ds.omega.values[~bad]
    from scipy.interpolate import PchipInterpolator

    out = ds.copy()
    for name in _FREQUENCY_VARIABLES:
        if name not in ds:
            continue
        da = ds[name]
        axis = da.dims.index("omega")
        values = np.array(da.values)
        good = np.take(values, np.flatnonzero(~bad), axis=axis)
        if np.iscomplexobj(values):
            fill = PchipInterpolator(good_omega, good.real, axis=axis)(ds.omega.values[bad]) + 1j * PchipInterpolator(
                good_omega, good.imag, axis=axis
            )(ds.omega.values[bad])
        else:
            fill = PchipInterpolator(good_omega, good, axis=axis)(ds.omega.values[bad])
        index = [slice(None)] * values.ndim
        index[axis] = np.flatnonzero(bad)  # type: ignore[call-overload]
        values[tuple(index)] = fill
        out[name] = da.copy(data=values)
    return out, report
