"""S-N curves as data: piecewise-linear curves in log-log axes, log10 N = log10 a_k - m_k log10(Delta S).

Stress ranges are in pascals at the API (SI inside, DESIGN.md); the standards tabulate log10 a for Delta S in MPa,
so the curves keep their published MPa constants and convert at the edge.

The catalogue holds only curves whose constants can be cited: the two-slope curve of Wang et al. (paper 003, its
Table 5, "SN curve parameters", taken from DNVGL-RP-C203, 2016 edition, its reference [25]): m 3, log a 12.592 up to
10^7 cycles, m 5, log a 16.320 beyond. The paper does not name the detail category or the environment; the knee at
10^7 cycles is that of DNV's curves in air. The other DNV-RP-C203 curves (other detail categories, seawater with
cathodic protection, free corrosion, the thickness correction) are not shipped: their constants could not be checked
against the standard here. Build them from the standard's tables with :class:`SNCurve`, e.g.
``SNCurve("my-curve", (3.0, 5.0), (log_a1, log_a2), (1e7,), "DNV-RP-C203 (edition), Table ...")``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

PA_PER_MPA = 1.0e6


@dataclass(frozen=True)
class SNCurve:
    """A one- or two-slope S-N curve (DNV form).

    Parameters
    ----------
    name : str
        Label, e.g. ``"paper-003-table-5"``.
    slopes : tuple of float
        m_k, the negative inverse slope of each segment in log-log axes [-].
    log_a : tuple of float
        log10 a_k, the intercept of each segment for Delta S in MPa [-].
    knees : tuple of float
        Cycle numbers where segment k ends and k + 1 begins (one fewer than the segments) [-].
    source : str
        Where the numbers come from.

    Raises
    ------
    ValueError
        If the tuples disagree in length, a slope is not positive, or the knees do not increase.
    """

    name: str
    slopes: tuple[float, ...]
    log_a: tuple[float, ...]
    knees: tuple[float, ...] = ()
    source: str = ""

    def __post_init__(self) -> None:
        if len(self.slopes) == 0 or len(self.slopes) != len(self.log_a):
            raise ValueError(
                f"S-N curve {self.name!r}: got {len(self.slopes)} slopes and {len(self.log_a)} intercepts; "
                "give one intercept per slope (at least one)"
            )
        if len(self.knees) != len(self.slopes) - 1:
            raise ValueError(
                f"S-N curve {self.name!r}: {len(self.slopes)} segments need {len(self.slopes) - 1} knee cycle "
                f"numbers, got {len(self.knees)}"
            )
        if any(not m > 0 for m in self.slopes):
            raise ValueError(f"S-N curve {self.name!r}: slopes must be positive, got {self.slopes}")
        if any(not k > 0 for k in self.knees) or any(b <= a for a, b in zip(self.knees, self.knees[1:], strict=False)):
            raise ValueError(f"S-N curve {self.name!r}: knees must be positive and increasing, got {self.knees}")

    def knee_ranges(self) -> np.ndarray:
        """Stress range at each knee from the segment above it [Pa]."""
        return np.array(
            [
                10.0 ** ((la - np.log10(n)) / m) * PA_PER_MPA
                for la, m, n in zip(self.log_a, self.slopes, self.knees, strict=False)
            ]
        )

    def cycles_to_failure(self, stress_range: np.ndarray | float) -> np.ndarray:
        """Number of cycles of a constant stress range to failure, N [-].

        Parameters
        ----------
        stress_range : array_like
            Delta S [Pa]; must be positive (a zero range does no damage: handle it before calling).

        Raises
        ------
        ValueError
            If a range is not positive or not finite.
        """
        s = np.asarray(stress_range, dtype=float)
        if not np.all(np.isfinite(s)) or np.any(s <= 0.0):
            raise ValueError(f"S-N curve {self.name!r}: stress ranges must be positive and finite [Pa], got {s!r}")
        log_s = np.log10(s / PA_PER_MPA)
        segment = np.zeros(s.shape, dtype=int)
        for k, s_knee in enumerate(self.knee_ranges()):
            segment = np.where(s < s_knee, k + 1, segment)
        m = np.asarray(self.slopes)[segment]
        la = np.asarray(self.log_a)[segment]
        return np.asarray(10.0 ** (la - m * log_s))


SN_CURVES: dict[str, SNCurve] = {
    c.name: c
    for c in (
        SNCurve(
            "paper-003-table-5",
            (3.0, 5.0),
            (12.592, 16.320),
            (1e7,),
            "Wang et al. (paper 003), Table 5, from DNVGL-RP-C203 (2016); detail category not named by the paper",
        ),
    )
}
"""The catalogue of S-N curves by name (only curves whose constants can be cited; see the module docstring)."""


def sn_curve(curve: str | SNCurve) -> SNCurve:
    """The S-N curve of that name (or the curve itself).

    Raises
    ------
    ValueError
        If the name is not in :data:`SN_CURVES` (the message lists the names).
    """
    if isinstance(curve, SNCurve):
        return curve
    try:
        return SN_CURVES[curve]
    except (KeyError, TypeError):
        raise ValueError(
            f"unknown S-N curve {curve!r}; known curves: {sorted(SN_CURVES)}, or pass an SNCurve"
        ) from None
