"""Annual energy of a device at a site: a power matrix (mean power over significant height and period) weighted by
the site's scatter diagram (occurrence of each sea state), and the power matrix of a sweep's combined dataset."""

from __future__ import annotations

import json
import math

import numpy as np
import xarray as xr

HOURS_PER_YEAR = 8766.0
"""Hours in a year of 365.25 days [h]."""

JOULES_PER_MWH = 3.6e9
"""[J / MWh]."""

OCCURRENCES = ("hours", "probability")
"""How a scatter diagram gives each sea state's occurrence: hours per year [h] or probability (summing to 1)."""

OCCURRENCE_UNITS = {"h": "hours", "hours": "hours", "hour": "hours", "1": "probability", "probability": "probability"}
"""The ``units`` attributes of a scatter diagram that say its occurrence kind."""

PROBABILITY_SUM_TOLERANCE = 1e-6
"""How far from 1 the probabilities of a scatter diagram may sum (rounding of published tables)."""

INTERPOLATION = (
    "bilinear on the power matrix's grid (a bin on a node takes the node's value; a NaN node makes only the bins "
    "that lean on it unknown); no extrapolation"
)
"""How the power matrix is brought onto the scatter diagram's grid."""


def _check_grid(da: xr.DataArray, label: str) -> None:
    if da.ndim != 2:
        raise ValueError(f"the {label} must have 2 dimensions (height, period); got {da.ndim}: {da.dims}")
    for dim in da.dims:
        if dim not in da.coords:
            raise ValueError(f"the {label}'s dimension {dim!r} has no coordinate values; give them (assign_coords)")
        values = np.asarray(da[dim].values, dtype=float)
        if not np.all(np.isfinite(values)) or np.any(np.diff(values) <= 0):
            raise ValueError(
                f"the {label}'s coordinate {dim!r} must be finite and strictly increasing; got {values.tolist()}"
            )


def _occurrence_kind(scatter: xr.DataArray, occurrence: str | None) -> str:
    units = scatter.attrs.get("units")
    from_units = OCCURRENCE_UNITS.get(str(units).strip().lower()) if units is not None else None
    if units is not None and from_units is None:
        raise ValueError(
            f"the scatter diagram's units {units!r} are not an occurrence; accepted: 'h' (hours per year) or "
            "'1' (probability)"
        )
    if occurrence is not None and occurrence not in OCCURRENCES:
        raise ValueError(f"occurrence must be one of {OCCURRENCES}; got {occurrence!r}")
    if occurrence is not None and from_units is not None and occurrence != from_units:
        raise ValueError(
            f"occurrence={occurrence!r} contradicts the scatter diagram's units {units!r} ({from_units}); "
            "give one or make them agree"
        )
    kind = occurrence or from_units
    if kind is None:
        raise ValueError(
            "the scatter diagram does not say whether it holds hours per year or probabilities: give "
            "occurrence='hours' or occurrence='probability', or set its units attribute to 'h' or '1'"
        )
    return kind


def _occurrence_hours(scatter: xr.DataArray, kind: str, hours_per_year: float) -> xr.DataArray:
    values = np.asarray(scatter.values, dtype=float)
    if not np.all(np.isfinite(values)):
        raise ValueError(f"the scatter diagram holds {int(np.sum(~np.isfinite(values)))} NaN or infinite values")
    if np.any(values < 0):
        raise ValueError(f"the scatter diagram holds negative occurrence (least {values.min():g}); accepted: >= 0")
    total = float(values.sum())
    if kind == "probability":
        if abs(total - 1.0) > PROBABILITY_SUM_TOLERANCE:
            raise ValueError(
                f"the scatter diagram's probabilities sum to {total:.9g}, not 1 (tolerance "
                f"{PROBABILITY_SUM_TOLERANCE:g}); for hours per year give occurrence='hours'"
            )
        return (scatter.astype(float) * hours_per_year).assign_attrs(units="h")
    if total > hours_per_year * (1 + 1e-9):
        raise ValueError(
            f"the scatter diagram's hours sum to {total:.6g} h, more than the year's {hours_per_year:g} h; "
            "for probabilities give occurrence='probability'"
        )
    return scatter.astype(float).assign_attrs(units="h")


def annual_energy(
    power_matrix: xr.DataArray,
    scatter: xr.DataArray,
    *,
    occurrence: str | None = None,
    outside: str = "refuse",
    hours_per_year: float = HOURS_PER_YEAR,
) -> xr.Dataset:
    """Annual energy of a device at a site.

    The power matrix [W] is interpolated bilinearly onto the centres of the scatter diagram's bins (both over the
    same two dimensions, e.g. ``(hs, tp)`` or ``(hs, te)``); each bin's energy is its power times its hours per
    year.

    Parameters
    ----------
    power_matrix : xarray.DataArray
        Mean power [W] over two dimensions with increasing coordinates (``units`` attribute, if any, "W"). NaN for
        unknown sea states (a failed case).
    scatter : xarray.DataArray
        Occurrence of each sea state over the same two dimensions: hours per year [h] or probability summing to 1.
    occurrence : {"hours", "probability"}, optional
        Which the scatter holds; default: read from its ``units`` attribute ("h" or "1"). One of the two is needed.
    outside : {"refuse", "unknown"}
        A bin with occurrence whose power is unknown (outside the matrix's range: no extrapolation; or next to a NaN
        of the matrix): "refuse" raises, "unknown" leaves its energy out and reports its share of the year.
    hours_per_year : float
        [h]; default 8766 (365.25 days).

    Returns
    -------
    xarray.Dataset
        ``power`` [W] and ``hours`` [h] and ``energy`` [J] per bin (NaN where unknown), ``known`` (bool per bin),
        ``power_matrix`` (the matrix given, on dimensions ``<dim>_matrix``), scalars ``annual_energy`` [J],
        ``annual_energy_mwh`` [MWh], ``covered_share`` (share of the year in bins of known power),
        ``unknown_share`` (share of the year in bins of unknown power), ``mean_power`` [W] over the known hours;
        attributes ``occurrence`` (which the scatter held) and ``interpolation``.

    Raises
    ------
    ValueError
        For mismatched dimensions or units, NaN or negative occurrence, probabilities not summing to 1, hours
        beyond a year, an ambiguous occurrence, or (``outside="refuse"``) bins of unknown power, naming them.
    """
    if outside not in ("refuse", "unknown"):
        raise ValueError(f"outside must be 'refuse' or 'unknown'; got {outside!r}")
    if not (math.isfinite(hours_per_year) and hours_per_year > 0):
        raise ValueError(f"hours_per_year must be a positive number; got {hours_per_year!r}")
    _check_grid(power_matrix, "power matrix")
    _check_grid(scatter, "scatter diagram")
    if set(power_matrix.dims) != set(scatter.dims):
        raise ValueError(
            f"the power matrix is over {power_matrix.dims} and the scatter diagram over {scatter.dims}; "
            "accepted: the same two dimensions (e.g. both ('hs', 'tp'))"
        )
    units = power_matrix.attrs.get("units")
    if units is not None and units != "W":
        raise ValueError(f"the power matrix's units are {units!r}; accepted: 'W' (convert it first)")
    kind = _occurrence_kind(scatter, occurrence)
    hours = _occurrence_hours(scatter, kind, hours_per_year)
    matrix = power_matrix.astype(float).transpose(*scatter.dims)
    if np.any(np.isinf(matrix.values)):
        raise ValueError("the power matrix holds infinite values")
    power = _bilinear(matrix, scatter)
    known = power.notnull()
    unknown = (~known) & (hours > 0)
    if outside == "refuse" and bool(unknown.any()):
        bins = [
            {d: float(scatter[d].values[i]) for d, i in zip(scatter.dims, index, strict=True)}
            for index in zip(*np.nonzero(unknown.values), strict=True)
        ]
        raise ValueError(
            f"{len(bins)} bins of the scatter diagram with occurrence have no power (outside the power matrix's "
            f"range {_ranges(matrix)}, or next to its NaN): {bins[:5]}{' ...' if len(bins) > 5 else ''}; "
            "give outside='unknown' to leave them out and report their share"
        )
    energy = (power * hours * 3600.0).where(known)
    total = float(energy.sum())
    known_hours = float(hours.where(known).sum())
    out = xr.Dataset(
        {
            "power": power.assign_attrs(units="W", long_name="mean power interpolated to the bin"),
            "hours": hours.assign_attrs(units="h", long_name="occurrence per year"),
            "energy": energy.assign_attrs(units="J", long_name="energy per year in the bin"),
            "known": known.assign_attrs(long_name="the bin's power is known (inside the matrix)"),
            "power_matrix": matrix.rename({d: f"{d}_matrix" for d in matrix.dims}).assign_attrs(units="W"),
            "annual_energy": xr.DataArray(total, attrs={"units": "J"}),
            "annual_energy_mwh": xr.DataArray(total / JOULES_PER_MWH, attrs={"units": "MWh"}),
            "covered_share": xr.DataArray(known_hours / hours_per_year, attrs={"units": "1"}),
            "unknown_share": xr.DataArray(float(hours.where(unknown).sum()) / hours_per_year, attrs={"units": "1"}),
            "mean_power": xr.DataArray(
                total / (known_hours * 3600.0) if known_hours > 0 else math.nan, attrs={"units": "W"}
            ),
        }
    )
    out.attrs = {
        "occurrence": "hours per year" if kind == "hours" else "probability",
        "interpolation": INTERPOLATION,
        "hours_per_year": hours_per_year,
    }
    return out


def _weights(nodes: np.ndarray, points: np.ndarray) -> list[list[tuple[int, float]]]:
    """Per point, the nodes it leans on and their linear weights (none outside the nodes' range)."""
    out: list[list[tuple[int, float]]] = []
    for x in points:
        if x < nodes[0] or x > nodes[-1]:
            out.append([])
            continue
        i = min(int(np.searchsorted(nodes, x, side="right")) - 1, len(nodes) - 1)
        w = 0.0 if i == len(nodes) - 1 else (x - nodes[i]) / (nodes[i + 1] - nodes[i])
        out.append([(k, wk) for k, wk in ((i, 1.0 - w), (i + 1, w)) if wk != 0.0])
    return out


def _bilinear(matrix: xr.DataArray, scatter: xr.DataArray) -> xr.DataArray:
    rows, cols = (_weights(np.asarray(matrix[d], float), np.asarray(scatter[d], float)) for d in scatter.dims)
    values = np.asarray(matrix.values)
    power = np.full((len(rows), len(cols)), np.nan)
    for i, row in enumerate(rows):
        for j, col in enumerate(cols):
            if row and col:
                power[i, j] = sum(wr * wc * values[r, c] for r, wr in row for c, wc in col)
    return xr.DataArray(power, coords={d: scatter[d].values for d in scatter.dims}, dims=scatter.dims)


def _ranges(matrix: xr.DataArray) -> str:
    return ", ".join(f"{d} {float(matrix[d].min()):g}..{float(matrix[d].max()):g}" for d in matrix.dims)


def power_matrix(
    combined: xr.Dataset,
    *,
    variable: str = "total_power",
    height: str = "sea.height",
    period: str = "sea.period",
) -> xr.DataArray:
    """The power matrix of a sweep's combined dataset (``wecss.sweep``): ``variable`` [W] over ``(hs, tp)`` from the
    sweep's axes ``height`` and ``period`` (a JONSWAP or Pierson-Moskowitz sea's period is its peak period); failed
    and pending cases are NaN.

    Raises
    ------
    ValueError
        For a missing variable or axis, a regular sea (no significant height), or other axes left (select them
        first: ``combined.sel(...)``).
    """
    if variable not in combined:
        raise ValueError(f"the combined dataset has no {variable!r}; it has {sorted(map(str, combined.data_vars))}")
    sea = json.loads(combined.attrs.get("base_scene", "{}")).get("sea", {})
    if sea.get("kind") == "regular":
        raise ValueError("the sweep's sea is regular (a height H, not Hs): a power matrix needs irregular seas")
    da = combined[variable]
    if "case" in da.dims:  # a list sweep: one coordinate per axis along case
        for axis in (height, period):
            if axis not in da.coords:
                raise ValueError(f"the sweep has no axis {axis!r}; its coordinates: {sorted(map(str, da.coords))}")
        da = da.set_index(case=[height, period]).unstack("case")
    for axis in (height, period):
        if axis not in da.dims:
            raise ValueError(f"the sweep has no axis {axis!r}; {variable} is over {da.dims}")
    rest = [d for d in da.dims if d not in (height, period)]
    if rest:
        raise ValueError(
            f"{variable} has more dimensions than {height} and {period}: {rest}; select or reduce them first "
            f"(e.g. combined.sel({{{rest[0]!r}: ...}}) or .mean({rest[0]!r}))"
        )
    matrix = da.transpose(height, period).rename({height: "hs", period: "tp"}).sortby(["hs", "tp"])
    return matrix.astype(float).assign_attrs(units="W", long_name=f"{variable} of the sweep")
