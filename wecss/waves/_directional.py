"""Directional seas: a spreading function D(theta) over the directions of propagation, its weights on the
headings of a hydrodynamic database, and the components of a short-crested sea that sit on those headings.

D integrates to 1 over the circle. Two forms, about the mean direction theta_m:

- ``cos-2s`` (Longuet-Higgins): D = G(s) cos^(2 s)((theta - theta_m) / 2) on the whole circle, with
  G(s) = Gamma(s + 1) / (2 sqrt(pi) Gamma(s + 1/2));
- ``cos-n``: D = cos^n(theta - theta_m) / B(1/2, (n + 1) / 2) for |theta - theta_m| < pi / 2, zero behind.

Its integral from theta_m to theta_m + phi is (sign phi / 2) I_x(1/2, p + 1/2) with I the regularised incomplete
beta function, p = s and x = sin^2(phi / 2) for cos-2s, p = n / 2 and x = sin^2(phi) for cos-n (|phi| <= pi / 2).

Each database heading beta_j takes the energy of the directions nearer to it than to its neighbours (its bin,
from half-way to the previous heading to half-way to the next); where the headings leave a gap wider than twice
any other (a database that covers part of the circle), the headings on its edges reach into it by half their
other gap only, and the spreading's mass left in it is reported (and refused above :data:`MAX_UNCOVERED_SHARE`).
The weights w_j are D's integrals over the bins, scaled to sum to 1, so the variance of the sea is unchanged:
each frequency's component A_k becomes components sqrt(w_j) |A_k| exp(i phi_kj) on every heading with weight,
with independent uniform phases (those of the heading whose bin holds the mean direction are the unidirectional
phases, so that a narrow spreading gives the unidirectional sea).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ._elevation import DEFAULT_ENERGY_THRESHOLD, DroppedComponents, WaveComponents, drop_negligible

SPREADING_TYPES: tuple[str, ...] = ("cos-2s", "cos-n")
"""The spreading functions: their exponent is ``s`` for cos-2s and ``n`` for cos-n."""

MAX_UNCOVERED_SHARE: float = 0.01
"""Largest share of the spreading's mass that may lie in a gap of the database's headings (left out, reported)."""

TWO_PI = 2 * math.pi


@dataclass(frozen=True)
class Spreading:
    """A directional spreading function (see the module docstring).

    Attributes
    ----------
    kind : {"cos-2s", "cos-n"}
    exponent : float
        s (cos-2s) or n (cos-n) [-], positive.
    mean : float
        Mean direction of propagation theta_m [rad] (0: along +x).

    Raises
    ------
    ValueError
        On an unknown kind or an exponent that is not a positive finite number.
    """

    kind: str
    exponent: float
    mean: float = 0.0

    def __post_init__(self) -> None:
        if self.kind not in SPREADING_TYPES:
            raise ValueError(f"spreading type {self.kind!r} is unknown; accepted: {', '.join(SPREADING_TYPES)}")
        if isinstance(self.exponent, bool) or not (
            isinstance(self.exponent, int | float) and 0 < self.exponent < math.inf
        ):
            name = "s" if self.kind == "cos-2s" else "n"
            raise ValueError(f"spreading {name} of {self.kind} must be a positive finite number; got {self.exponent!r}")

    def density(self, theta: np.ndarray) -> np.ndarray:
        """D(theta) [1/rad] at the directions ``theta`` [rad]."""
        from scipy.special import beta

        phi = _wrap(np.asarray(theta, dtype=float) - self.mean)
        if self.kind == "cos-2s":
            s = float(self.exponent)
            return np.cos(phi / 2) ** (2 * s) / (2 * beta(0.5, s + 0.5))
        n = float(self.exponent)
        return np.where(np.abs(phi) < math.pi / 2, np.abs(np.cos(phi)) ** n, 0.0) / beta(0.5, (n + 1) / 2)

    def cumulative(self, theta: np.ndarray) -> np.ndarray:
        """The integral of D from theta_m - pi to ``theta`` [rad] along the unwrapped angle [-] (it grows by 1 per
        turn), so that the integral over an arc [a, b] is cumulative(b) - cumulative(a)."""
        from scipy.special import betainc

        theta = np.asarray(theta, dtype=float)
        turns = np.floor((theta - self.mean + math.pi) / TWO_PI)
        phi = theta - self.mean - turns * TWO_PI  # in [-pi, pi)
        if self.kind == "cos-2s":
            half = 0.5 * betainc(0.5, float(self.exponent) + 0.5, np.sin(phi / 2) ** 2)
        else:
            inside = np.abs(phi) <= math.pi / 2
            x = np.where(inside, np.sin(phi) ** 2, 1.0)
            half = 0.5 * betainc(0.5, (float(self.exponent) + 1) / 2, x)
        return turns + 0.5 + np.sign(phi) * half

    def integral(self, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
        """The integral of D over the arcs from ``lo`` to ``hi`` [rad] (hi >= lo, at most a turn apart) [-]."""
        return self.cumulative(hi) - self.cumulative(lo)


@dataclass(frozen=True)
class HeadingWeights:
    """A spreading's weights on a database's headings.

    Attributes
    ----------
    headings : ndarray (m,)
        The database's headings [rad], as the database gives them, in increasing order of angle on [0, 2 pi).
    lower, upper : ndarray (m,)
        Each heading's bin, from ``lower`` to ``upper`` [rad] (unwrapped: upper > lower).
    weights : ndarray (m,)
        D's integral over each bin, scaled so that they sum to 1 [-].
    uncovered : float
        D's mass outside every bin (in a gap of the headings), which the scaling spreads over the bins [-].
    """

    headings: np.ndarray
    lower: np.ndarray
    upper: np.ndarray
    weights: np.ndarray
    uncovered: float


def heading_bins(headings: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The headings [rad] sorted by angle on [0, 2 pi) and their bins' edges (lower, upper) [rad] (see the module
    docstring).

    Raises
    ------
    ValueError
        For fewer than two distinct headings.
    """
    given = np.asarray(headings, dtype=float).ravel()
    order = np.argsort(np.mod(given, TWO_PI), kind="stable")
    given = given[order]
    angle = np.mod(given, TWO_PI)
    if given.size < 2 or np.any(np.diff(angle) < 1e-9) or angle[0] + TWO_PI - angle[-1] < 1e-9:
        raise ValueError(
            f"a spreading needs at least two distinct headings; got {np.rad2deg(given).round(6).tolist()} degrees"
        )
    gaps = np.diff(np.append(angle, angle[0] + TWO_PI))  # gaps[j]: from heading j to the next
    before = np.roll(gaps, 1)  # gap from the previous heading to heading j
    half_after, half_before = gaps / 2, before / 2
    widest = int(np.argmax(gaps))
    others = np.delete(gaps, widest)
    if gaps[widest] > 2 * others.max() + 1e-12:  # a gap the database does not cover
        nxt = (widest + 1) % gaps.size
        half_after[widest] = before[widest] / 2
        half_before[nxt] = gaps[nxt] / 2
    return given, angle - half_before, angle + half_after


def heading_weights(spreading: Spreading, headings: np.ndarray) -> HeadingWeights:
    """The weights of ``spreading`` on the database ``headings`` [rad] (see the module docstring).

    Raises
    ------
    ValueError
        For fewer than two distinct headings, or when more than :data:`MAX_UNCOVERED_SHARE` of D's mass lies in a
        gap of the headings (the message gives the headings and the share).
    """
    given, lower, upper = heading_bins(headings)
    mass = np.asarray(spreading.integral(lower, upper), dtype=float)
    total = float(mass.sum())
    uncovered = max(0.0, 1.0 - total)
    if uncovered > MAX_UNCOVERED_SHARE or total <= 0:
        raise ValueError(
            f"{uncovered:.1%} of the spreading's energy comes from directions the database's headings "
            f"{np.rad2deg(given).round(6).tolist()} degrees do not cover (accepted: {MAX_UNCOVERED_SHARE:.0%}): "
            "use a narrower spreading, another mean direction or a database with more headings"
        )
    return HeadingWeights(given, lower, upper, mass / total, uncovered)


def spread(
    waves: WaveComponents,
    weights: HeadingWeights,
    *,
    seed: int | None = None,
    energy_threshold: float = DEFAULT_ENERGY_THRESHOLD,
) -> WaveComponents:
    """The short-crested sea of unidirectional ``waves`` spread over the headings of ``weights``: component k on
    heading j has amplitude sqrt(w_j) |A_k| and an independent uniform phase (drawn from ``seed``), the heading
    whose bin holds the mean direction ``waves.direction`` keeping the phases of ``waves``; then the smallest
    components carrying together at most ``energy_threshold`` of the variance are dropped.

    Returns
    -------
    WaveComponents
        Frequencies repeated per heading, ``headings`` per component [rad], ``direction`` the mean.

    Raises
    ------
    ValueError
        If ``waves`` is already directional.
    """
    if waves.headings is not None:
        raise ValueError("the waves are already directional (they have headings per component)")
    n, m = waves.omega.size, weights.headings.size
    unwrapped = weights.lower + np.floor((waves.direction - weights.lower) / TWO_PI) * TWO_PI
    home = np.flatnonzero(waves.direction < unwrapped + (weights.upper - weights.lower))
    main = int(home[0]) if home.size else int(np.argmax(weights.weights))
    rng = np.random.default_rng(None if seed is None else [int(seed), 1])
    phases = rng.uniform(0.0, TWO_PI, size=(n, m))
    phasor = np.exp(1j * phases)
    phasor[:, main] = np.exp(1j * np.angle(waves.amplitude))
    amplitude = np.abs(waves.amplitude)[:, None] * np.sqrt(weights.weights)[None, :] * phasor
    keep = np.broadcast_to(weights.weights > 0, (n, m))
    directional = WaveComponents(
        np.broadcast_to(waves.omega[:, None], (n, m))[keep],
        amplitude[keep],
        waves.direction,
        waves.repeat_period,
        None,
        np.broadcast_to(weights.headings[None, :], (n, m))[keep],
    )
    out = drop_negligible(directional, energy_threshold)
    before = waves.dropped
    if before is not None and out.dropped is not None:
        report = DroppedComponents(
            before.count + out.dropped.count,
            out.dropped.kept,
            before.energy_share + (1 - before.energy_share) * out.dropped.energy_share,
            energy_threshold,
        )
        out = WaveComponents(out.omega, out.amplitude, out.direction, out.repeat_period, report, out.headings)
    return out


def _wrap(angle: np.ndarray) -> np.ndarray:
    """``angle`` [rad] wrapped to [-pi, pi)."""
    return np.mod(np.asarray(angle, dtype=float) + math.pi, TWO_PI) - math.pi
