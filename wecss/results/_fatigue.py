"""Fatigue from stress records: rainflow counting, Miner's sum, damage-equivalent range and life in years.

Conventions: stress and stress ranges in pascals; a cycle's range is peak to valley (twice the amplitude); half
cycles of the rainflow residue count 0.5 (ASTM E1049-85); no mean-stress correction (DNV-RP-C203 for welded steel
uses ranges only). Life follows paper 003, Eq. 55, generalised to the counted cycles of a record:
a record of duration T with Miner sum D lasts T / D, and a year is 365 days. Rainflow counting uses the ``rainflow``
package (the ``fatigue`` extra: ``pip install "wecss[fatigue]"``), imported only when called.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ._sn_curves import SNCurve, sn_curve

SECONDS_PER_YEAR = 365.0 * 24.0 * 3600.0
"""Paper 003, Eq. 55: 365 days of 24 h [s]."""


@dataclass(frozen=True)
class Cycles:
    """Counted cycles: ranges [Pa] (or any unit for loads) and counts (1 or 0.5 per rainflow cycle) [-]."""

    ranges: np.ndarray
    counts: np.ndarray

    def __post_init__(self) -> None:
        r = np.asarray(self.ranges, dtype=float)
        c = np.asarray(self.counts, dtype=float)
        if r.ndim != 1 or r.shape != c.shape:
            raise ValueError(f"cycle ranges and counts must be 1-D of one length, got shapes {r.shape} and {c.shape}")
        if not np.all(np.isfinite(r)) or np.any(r < 0.0):
            raise ValueError(f"cycle ranges must be finite and not negative, got {r!r}")
        if not np.all(np.isfinite(c)) or np.any(c < 0.0):
            raise ValueError(f"cycle counts must be finite and not negative, got {c!r}")
        object.__setattr__(self, "ranges", r)
        object.__setattr__(self, "counts", c)


def rainflow_cycles(signal: np.ndarray) -> Cycles:
    """Rainflow count of a record (ASTM E1049-85, through the ``rainflow`` package).

    Parameters
    ----------
    signal : array_like (n,)
        Stress [Pa] (or a load) at successive times; needs at least two samples and finite values.

    Returns
    -------
    Cycles
        One entry per counted full or half cycle, its range and count; ranges of zero are dropped.

    Raises
    ------
    ValueError
        If the record is empty, shorter than two samples, not 1-D or not finite.
    ImportError
        If ``rainflow`` is not installed (with the install hint).
    """
    x = np.asarray(signal, dtype=float)
    if x.ndim != 1 or x.size < 2:
        raise ValueError(f"a record to count needs a 1-D array of at least two samples, got shape {x.shape}")
    if not np.all(np.isfinite(x)):
        raise ValueError("the record to count holds NaN or infinite values")
    try:
        import rainflow
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise ImportError('rainflow counting needs the "rainflow" package: pip install "wecss[fatigue]"') from exc
    rows = [(rng, count) for rng, _mean, count, _i0, _i1 in rainflow.extract_cycles(x) if rng > 0.0]
    if not rows:
        return Cycles(np.zeros(0), np.zeros(0))
    arr = np.asarray(rows, dtype=float)
    return Cycles(arr[:, 0], arr[:, 1])


def miner_damage(cycles: Cycles, curve: str | SNCurve = "paper-003-table-5", scf: float = 1.0) -> float:
    """Palmgren-Miner sum D = sum n_i / N(SCF Delta S_i) [-].

    Parameters
    ----------
    cycles : Cycles
        Counted stress ranges [Pa] and counts.
    curve : str or SNCurve
        A name in :data:`SN_CURVES` (default ``"paper-003-table-5"``, the paper's Table 5) or a curve.
    scf : float
        Stress concentration factor applied to the ranges [-]; at least 1 in normal use, must be positive.

    Raises
    ------
    ValueError
        On an unknown curve or a non-positive SCF.
    """
    if not scf > 0.0:
        raise ValueError(f"the stress concentration factor must be positive, got {scf!r}")
    sn = sn_curve(curve)
    if cycles.ranges.size == 0:
        return 0.0
    return float(np.sum(cycles.counts / sn.cycles_to_failure(scf * cycles.ranges)))


def damage_equivalent_range(cycles: Cycles, slope: float, n_equivalent: float) -> float:
    """The constant range that does the same single-slope damage in ``n_equivalent`` cycles.

    Delta S_eq = (sum n_i Delta S_i^m / N_eq)^(1/m), in the unit of the ranges (a damage-equivalent load when the
    cycles are of a load).

    Raises
    ------
    ValueError
        If the slope or the number of equivalent cycles is not positive.
    """
    if not slope > 0.0:
        raise ValueError(f"the S-N slope m must be positive, got {slope!r}")
    if not n_equivalent > 0.0:
        raise ValueError(f"the number of equivalent cycles must be positive, got {n_equivalent!r}")
    if cycles.ranges.size == 0:
        return 0.0
    return float((np.sum(cycles.counts * cycles.ranges**slope) / n_equivalent) ** (1.0 / slope))


def life_years(damage: float, duration: float) -> float:
    """Fatigue life in years of a record of ``duration`` seconds that does ``damage`` (paper Eq. 55 generalised).

    Returns ``inf`` for zero damage.

    Raises
    ------
    ValueError
        If the duration is not positive or the damage is negative.
    """
    if not duration > 0.0:
        raise ValueError(f"the record's duration must be positive [s], got {duration!r}")
    if not damage >= 0.0:
        raise ValueError(f"the damage must be zero or positive, got {damage!r}")
    if damage == 0.0:
        return float("inf")
    return duration / damage / SECONDS_PER_YEAR


def fatigue_life(
    stress: np.ndarray, duration: float, curve: str | SNCurve = "paper-003-table-5", scf: float = 1.0
) -> tuple[float, float]:
    """Miner damage of a stress record and its life in years.

    Parameters
    ----------
    stress : array_like (n,)
        Stress at a hot spot [Pa] (e.g. the signed von Mises stress).
    duration : float
        The time the record represents [s] (for a regular wave, a whole number of periods).
    curve, scf
        As in :func:`miner_damage`.

    Returns
    -------
    (damage, years) : float, float
    """
    damage = miner_damage(rainflow_cycles(stress), curve, scf)
    return damage, life_years(damage, duration)


def long_term_life(damage_rates: np.ndarray, probabilities: np.ndarray) -> float:
    """Life in years over a scatter diagram: 1 / sum_j p_j d_j, d_j the damage per second in sea state j.

    Parameters
    ----------
    damage_rates : array_like (n,)
        Miner damage per second of each sea state [1/s] (its record's damage over its duration).
    probabilities : array_like (n,)
        Probability of occurrence of each sea state [-]; must sum to 1 (within 1e-6).

    Raises
    ------
    ValueError
        If the arrays differ in shape, are empty, hold negative values, or the probabilities do not sum to 1.
    """
    d = np.asarray(damage_rates, dtype=float)
    p = np.asarray(probabilities, dtype=float)
    if d.ndim != 1 or d.shape != p.shape or d.size == 0:
        raise ValueError(f"damage rates and probabilities must be 1-D of one non-zero length, got {d.shape}, {p.shape}")
    if not np.all(np.isfinite(d)) or np.any(d < 0.0) or not np.all(np.isfinite(p)) or np.any(p < 0.0):
        raise ValueError("damage rates and probabilities must be finite and not negative")
    if abs(p.sum() - 1.0) > 1e-6:
        raise ValueError(f"the sea-state probabilities must sum to 1, they sum to {p.sum()!r}")
    rate = float(np.dot(p, d))
    return float("inf") if rate == 0.0 else 1.0 / rate / SECONDS_PER_YEAR
