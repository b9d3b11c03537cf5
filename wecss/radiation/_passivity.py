"""Passivity of a state-space radiation model K_hat(omega) = C (i omega I - A)^-1 B: the check and its enforcement.

The model is passive when H(omega) = (K_hat + K_hat^H) / 2, the damping matrix it implies, is positive
semi-definite at every omega >= 0: the radiation memory then never gives energy to the bodies. Everything here works
on the scaled model S K_hat S with S = diag(scale)^-1/2 and ``scale`` each DOF's peak radiation damping, so that
surge forces and pitch moments weigh alike (H >= 0 if and only if S H S >= 0).

The check covers the whole half-line in two parts:

- a grid (:func:`passivity_grid`): 0, dense up to 1.5 times the largest of the highest data frequency and the
  poles' moduli, eleven points across every resonance, then logarithmic up past ``omega_tail``;
- above ``omega_tail``, a bound (:func:`tail_bound`). Exactly, 1 / (i w - s) = 1 / (i w) + s / (i w)^2 +
  s^2 / ((i w)^2 (i w - s)), so K_hat = C B / (i w) + C A B / (i w)^2 + E(w) / (i w)^2 with ||E(w)|| <= r / (w - rho)
  for w > rho; r = sum over the modes of ||R_k|| |s_k|^2 (R_k the rank-one residues), rho = max |Im s_k|. The
  first term's Hermitian part is -i skew(C B) / w, the second's -sym(C A B) / w^2, so with C B symmetric and
  mu = lambda_min(-sym(C A B)) > 0, H is positive definite above omega_tail = rho + 2 r / mu (up to
  mu / (2 ||skew(C B)||), which rounding alone puts at 1e12 rad/s or more).

A fitted model is not passive in general: near-null directions of the damping matrix (combinations of DOFs that
radiate little at that frequency) come out slightly negative by the fit's error, at every frequency, and the
fitted modes hardly couple to those directions, so a change of the output matrix C alone would have to be large.
:func:`enforce_passivity` therefore makes two changes:

1. the least (Frobenius) change of C that makes K_hat(0) = C (-A)^-1 B zero (the damping of a floating body vanishes
   at omega = 0) and C B and C A^-2 B symmetric (the kernel at t = 0 and the low-frequency slope of the added mass,
   both symmetric in the data), so that H vanishes at 0 like omega^2 and the tail bound can hold;
2. a passive lift: for each DOF i and each of a few frequency sections (a1, a2) (:data:`LIFT_CORNERS`), a damping
   d_ik scale_i T(s) on the DOF's own velocity with T(s) = a2 s / ((s + a1)(s + a2)), whose real part
   omega^2 a2 (a1 + a2) / ((omega^2 + a1^2)(omega^2 + a2^2)) is non-negative at every frequency (T is positive
   real), about 1 between a1 and a2, zero at 0 and decaying like 1 / omega^2. Two real states per (DOF, section)
   with d_ik > 0 realise it. The weights d >= 0 minimise the added damping over the data band (a linear programme)
   subject to v^H (S H S + D(omega)) v >= 0 for the eigenvectors v of the negative eigenvalues at the grid's worst
   frequencies: cutting planes of the semidefinite condition, added round by round until the grid passes. Each cut
   is necessary, and lifting never lowers the margin anywhere, so the rounds converge.

The lift changes the damping in the data band by the fit's own error (about 1e-3 of the peak damping for the
shipped M4 fits); the fit report states it.
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import pairwise

import numpy as np
from scipy.linalg import block_diag

from ._statespace import RadiationStateSpace

MAX_ENFORCE_STATES: int = 800
"""Above this many states no enforcement is attempted (the report says so): fit fewer states instead."""

LIFT_CORNERS: tuple[float, ...] = (0.01, 0.14, 0.55, 1.8)
"""Corner frequencies of the lift's sections as multiples of the highest data frequency: a section between each
consecutive pair. The highest pole of the lift is 1.8 times the highest data frequency (explicit integrators'
steps resolve it wherever they resolve the fit's own poles)."""

ROUNDING: float = 1e-12
"""A scaled margin above -ROUNDING x the largest scaled eigenvalue on the grid passes (H vanishes at omega = 0
exactly, and rounding puts it on either side)."""

CUT_OVERSHOOT: float = 0.05
"""Each cut asks for this share more than the violation it removes, so that the next round's eigenvectors (which
differ slightly) are covered too [-]."""

MAX_SYMMETRY_CHANGE: float = 0.25
"""Largest change of C (relative, Frobenius) the symmetry correction may make: more would not be a correction."""

MAX_ROUNDS: int = 80
"""Most rounds of cutting planes."""

FREQUENCIES_PER_ROUND: int = 300
"""Most frequencies given cuts per round: the violated local minima of the margin and points spread over the
violated ranges."""

VECTORS_PER_FREQUENCY: int = 12
"""Most eigenvectors (the most negative first) given a cut per frequency and round."""


@dataclass(frozen=True)
class Tail:
    """The high-frequency passivity bound of a model (module docstring).

    Attributes
    ----------
    mu : float
        lambda_min(-sym(C A B)) of the scaled model: the damping tends to mu / omega^2 [1/s^2].
    skew : float
        ||skew(C B)||_2 of the scaled model (zero up to rounding for a symmetric K(0)) [1/s].
    omega_tail : float
        rho + 2 r / mu [rad/s]: above it (up to ``omega_upper``) the model is passive; inf when mu <= 0.
    omega_upper : float
        mu / (2 skew) [rad/s], inf for an exactly symmetric K(0) (0 when mu <= 0).
    """

    mu: float
    skew: float
    omega_tail: float
    omega_upper: float

    @property
    def holds(self) -> bool:
        """The bound proves passivity over a non-empty range [omega_tail, omega_upper]."""
        return bool(np.isfinite(self.omega_tail) and self.omega_upper > self.omega_tail)


def scaled(model: RadiationStateSpace, scale: np.ndarray) -> RadiationStateSpace:
    """The model of S K_hat S with S = diag(scale)^-1/2 (``scale`` > 0 per DOF)."""
    root = 1.0 / np.sqrt(_checked_scale(model, scale))
    return model.with_matrices(B=model.B * root[None, :], C=model.C * root[:, None])


def damping_scale(damping: np.ndarray) -> np.ndarray:
    """Each DOF's peak |B_ii(omega)| from a damping array (omega, n, n), floored at 1e-9 of the largest."""
    peaks = np.max(np.abs(np.diagonal(np.asarray(damping, dtype=float), axis1=1, axis2=2)), axis=0)
    return np.maximum(peaks, 1e-9 * max(float(peaks.max()), 1e-300))


def tail_bound(model: RadiationStateSpace, scale: np.ndarray) -> Tail:
    """The high-frequency passivity bound of the scaled ``model`` (module docstring)."""
    if model.n_states == 0:
        return Tail(0.0, 0.0, 0.0, float("inf"))
    m = scaled(model, scale)
    lam, left, right = m.modal()
    cb = m.C @ m.B
    cab = m.C @ (m.A @ m.B)
    mu = float(np.linalg.eigvalsh(-0.5 * (cab + cab.T))[0])
    skew = float(np.linalg.norm(0.5 * (cb - cb.T), 2))
    r = float(np.sum(np.linalg.norm(left, axis=0) * np.linalg.norm(right, axis=1) * np.abs(lam) ** 2))
    rho = float(np.max(np.abs(lam.imag)))
    if mu <= 0:
        return Tail(mu, skew, float("inf"), 0.0)
    return Tail(mu, skew, rho + 2 * r / mu, mu / (2 * skew) if skew > 0 else float("inf"))


def passivity_grid(
    model: RadiationStateSpace, omega_data: np.ndarray, scale: np.ndarray, n: int = 4000, tail: Tail | None = None
) -> np.ndarray:
    """Frequencies [rad/s] on which the passivity of ``model`` is checked (module docstring).

    0; ``n`` points (linear and geometric from 1 % of the lowest data frequency) up to 1.5 times the largest of the
    highest data frequency and the poles' moduli; eleven points across every resonance (w + k sigma,
    k in 0, +-0.25, +-0.5, +-1, +-2, +-4); 100 per decade beyond, up to 1.1 x the larger of ten times that top and
    ``omega_tail`` of :func:`tail_bound` (capped at 1e9 rad/s; ``tail``: the bound when already known).
    """
    omega_data = np.asarray(omega_data, dtype=float)
    if omega_data.size == 0 or not np.any(omega_data > 0):
        raise ValueError(f"omega_data needs a positive frequency; got {omega_data!r}")
    low = 0.01 * float(omega_data[omega_data > 0].min())
    lam = model.poles()
    top = 1.5 * max(float(np.max(omega_data)), float(np.max(np.abs(lam))) if lam.size else 0.0)
    omega_tail = (tail or tail_bound(model, scale)).omega_tail
    far = 1.1 * min(max(omega_tail, 10 * top), 1e9) if np.isfinite(omega_tail) else 10 * top
    steps = np.array([0.0, 0.25, 0.5, 1.0, 2.0, 4.0])
    steps = np.concatenate([-steps[1:], steps])
    upper = lam[lam.imag > 0]
    resonances = (upper.imag[:, None] + np.abs(upper.real)[:, None] * steps[None, :]).ravel()
    parts = [
        [0.0],
        np.linspace(low, top, n // 2),
        np.geomspace(low, top, n // 2),
        resonances[(resonances > low) & (resonances < top)],
        np.geomspace(top, far, max(2, int(100 * np.log10(far / top)))),
    ]
    return np.unique(np.concatenate(parts))


def scaled_damping_eigh(
    model: RadiationStateSpace, omega: np.ndarray, scale: np.ndarray, chunk: int = 1000
) -> tuple[np.ndarray, np.ndarray]:
    """Eigenvalues (ascending) and eigenvectors of S H(omega) S at every ``omega``."""
    m = scaled(model, scale)
    values, vectors = [], []
    for start in range(0, omega.size, chunk):
        h = m.frequency_response(omega[start : start + chunk])
        v, u = np.linalg.eigh(0.5 * (h + np.conj(np.swapaxes(h, 1, 2))))
        values.append(v)
        vectors.append(u)
    return np.concatenate(values), np.concatenate(vectors)


@dataclass(frozen=True)
class PassivityCheck:
    """The passivity check of a model on its grid and beyond (module docstring).

    Attributes
    ----------
    margin : float
        Smallest eigenvalue of S H S over the grid [-] (a share of each DOF's peak damping).
    omega_worst : float
        Where it is [rad/s].
    tail : Tail
    grid_end : float
        Highest grid frequency [rad/s].
    passive : bool
        The margin is non-negative to rounding on the grid and the tail bound covers the rest.
    """

    margin: float
    omega_worst: float
    tail: Tail
    grid_end: float
    passive: bool


def check_passivity(model: RadiationStateSpace, omega_data: np.ndarray, scale: np.ndarray) -> PassivityCheck:
    """Check ``model`` on :func:`passivity_grid` and with :func:`tail_bound` (module docstring)."""
    tail = tail_bound(model, scale)
    grid = passivity_grid(model, omega_data, scale, tail=tail)
    if model.n_states == 0:
        return PassivityCheck(0.0, 0.0, tail, float(grid[-1]), True)
    values = scaled_damping_eigh(model, grid, scale)[0]
    worst = int(np.argmin(values[:, 0]))
    on_grid = float(values[worst, 0]) >= -ROUNDING * float(np.max(np.abs(values)))
    passive = on_grid and tail.holds and float(grid[-1]) >= tail.omega_tail
    return PassivityCheck(float(values[worst, 0]), float(grid[worst]), tail, float(grid[-1]), bool(passive))


@dataclass(frozen=True)
class Passivation:
    """What :func:`enforce_passivity` did.

    Attributes
    ----------
    before, after : PassivityCheck or None
        The checks of the fitted and of the returned model (None when nothing was attempted).
    symmetry_change : float
        ||dC|| / ||C|| of the equality step (K_hat(0) = 0, C B and C A^-2 B symmetric) [-].
    lift_states : int
        States added by the lift.
    lift_in_band : float
        Largest added damping over the data band, as a share of the DOF's peak damping [-].
    rounds : int
        Rounds of cutting planes.
    conditions : str
        What the change of C imposed (:func:`symmetry_correction`).
    skipped : str
        Why no enforcement was attempted ("" when it was).
    """

    before: PassivityCheck | None = None
    after: PassivityCheck | None = None
    symmetry_change: float = 0.0
    lift_states: int = 0
    lift_in_band: float = 0.0
    rounds: int = 0
    conditions: str = ""
    skipped: str = ""

    def __str__(self) -> str:
        if self.skipped:
            return f"NOT PASSIVE: {self.skipped}"
        if self.before is None or self.after is None:
            return "no enforcement"
        state = "passive" if self.after.passive else "NOT PASSIVE"
        return (
            f"{state}: scaled margin {self.before.margin:.3g} -> {self.after.margin:.3g} on the grid to "
            f"{self.after.grid_end:.3g} rad/s, tail bound from {self.after.tail.omega_tail:.3g} rad/s; C changed by "
            f"{self.symmetry_change:.2e} relative ({self.conditions}); lift of "
            f"{self.lift_states} states, at most {self.lift_in_band:.2e} of a DOF's peak damping over the data band, "
            f"{self.rounds} rounds"
        )


def _checked_scale(model: RadiationStateSpace, scale: np.ndarray) -> np.ndarray:
    scale = np.asarray(scale, dtype=float)
    if scale.shape != (len(model.dofs),) or not np.all(scale > 0):
        raise ValueError(f"scale must hold one positive value per DOF ({len(model.dofs)}); got {scale!r}")
    return scale


CONDITIONS: dict[str, str] = {
    "zero": "zero damping at omega = 0",
    "k0": "K(0) symmetric",
    "slope": "C A^-2 B symmetric",
}
"""The conditions :func:`symmetry_correction` imposes on C, by key."""


def symmetry_correction(model: RadiationStateSpace) -> tuple[RadiationStateSpace, tuple[str, ...]]:
    """The least (Frobenius) change of C making C A^-1 B zero and C B and C A^-2 B symmetric (module docstring).

    A model with few states may not have enough freedom in C for all three (the equations outnumber C's entries or
    are dependent), or only at the price of a large change: then the largest of the sets (zero, k0), (k0,) that C
    satisfies exactly with a change of at most MAX_SYMMETRY_CHANGE of its norm is imposed, K(0) symmetric first
    (the tail bound needs it), or none. Returns the model and the keys of :data:`CONDITIONS` imposed.
    """
    n, nx = len(model.dofs), model.n_states
    a_inv_b = np.linalg.solve(model.A, model.B)
    a_inv2_b = np.linalg.solve(model.A, a_inv_b)
    upper = np.triu_indices(n, 1)

    def product_rows(m: np.ndarray) -> np.ndarray:
        """The linear map vec(C) -> vec(C m) (C row-major), (n * n, n * nx)."""
        return np.kron(np.eye(n), m.T)

    def skew_rows(m: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        rows = product_rows(m).reshape(n, n, n * nx)
        value = model.C @ m
        return rows[upper] - rows[upper[1], upper[0]], -(value[upper] - value.T[upper])

    equations = {
        "zero": (product_rows(a_inv_b), -(model.C @ a_inv_b).ravel()),
        "k0": skew_rows(model.B),
        "slope": skew_rows(a_inv2_b),
    }
    for keys in (("zero", "k0", "slope"), ("zero", "k0"), ("k0",)):
        rows = np.vstack([equations[k][0] for k in keys])
        rhs = np.concatenate([equations[k][1] for k in keys])
        if rows.shape[0] == 0:
            return model, keys  # nothing to impose (one DOF: C B and C A^-2 B are symmetric)
        if rows.shape[0] > rows.shape[1]:
            continue
        delta, _, rank, _ = np.linalg.lstsq(rows, rhs, rcond=None)
        small = np.linalg.norm(delta) <= MAX_SYMMETRY_CHANGE * np.linalg.norm(model.C)
        if rank == rows.shape[0] and small:  # every equation satisfied exactly (to rounding), C barely changed
            return model.with_matrices(C=model.C + delta.reshape(n, nx)), keys
    return model, ()


def lift_sections(omega_top: float) -> list[tuple[float, float]]:
    """The lift's sections (a1, a2) [rad/s] for data up to ``omega_top`` (:data:`LIFT_CORNERS`)."""
    corners = [c * omega_top for c in LIFT_CORNERS]
    return list(pairwise(corners))


def lift_response(a1: float, a2: float, omega: np.ndarray) -> np.ndarray:
    """Re T(i omega) of the section T(s) = a2 s / ((s + a1)(s + a2)) (module docstring)."""
    w2 = np.asarray(omega, dtype=float) ** 2
    return w2 * a2 * (a1 + a2) / ((w2 + a1**2) * (w2 + a2**2))


def _lift_weights(
    model: RadiationStateSpace,
    grid: np.ndarray,
    scale: np.ndarray,
    sections: list[tuple[float, float]],
    omega_band: np.ndarray,
) -> tuple[np.ndarray, int]:
    """The weights d (section, DOF) of the least lift over the band that makes S H S + D >= 0 on ``grid``."""
    from scipy.optimize import linprog

    n = len(model.dofs)
    base = scaled(model, scale)
    response = np.array([lift_response(a1, a2, grid) for a1, a2 in sections])  # (section, w)
    cost = np.repeat([lift_response(a1, a2, omega_band).mean() for a1, a2 in sections], n)
    weights = np.zeros((len(sections), n))
    rows: list[np.ndarray] = []
    needs: list[float] = []
    h = base.frequency_response(grid)
    herm = 0.5 * (h + np.conj(np.swapaxes(h, 1, 2)))
    diagonal = np.arange(n)
    for rounds in range(1, MAX_ROUNDS + 1):
        lifted = herm.copy()
        lifted[:, diagonal, diagonal] += np.einsum("kw,ki->wi", response, weights)
        values, vectors = np.linalg.eigh(lifted)
        floor = -ROUNDING * float(np.max(np.abs(values)))
        bad = np.flatnonzero((values[:, 0] < floor) & (grid > 0))
        if bad.size == 0:
            return weights, rounds - 1
        margin = values[:, 0]
        last = margin.size - 1
        local = [k for k in bad if (k == 0 or margin[k] <= margin[k - 1]) and (k == last or margin[k] <= margin[k + 1])]
        picks = sorted({*local, *bad[:: max(1, bad.size // FREQUENCIES_PER_ROUND)].tolist()})
        for k in picks:
            for j in np.flatnonzero(values[k] < floor)[:VECTORS_PER_FREQUENCY]:
                v = vectors[k][:, j]
                violation = -float(np.real(np.conj(v) @ herm[k] @ v))
                rows.append((response[:, k][:, None] * (np.abs(v) ** 2)[None, :]).ravel())
                needs.append((1 + CUT_OVERSHOOT) * max(violation, 0.0))
        a = np.array(rows)
        norm = np.maximum(np.abs(a).max(axis=1), 1e-300)
        result = linprog(
            cost / cost.max(), A_ub=-a / norm[:, None], b_ub=-np.array(needs) / norm, bounds=(0, None), method="highs"
        )
        if result.status != 0:
            raise RuntimeError(f"the passivity lift's linear programme failed: {result.message}")
        weights = result.x.reshape(len(sections), n)
    return weights, MAX_ROUNDS


def _with_lift(
    model: RadiationStateSpace, weights: np.ndarray, scale: np.ndarray, sections: list[tuple[float, float]]
) -> RadiationStateSpace:
    """``model`` with the lift's states appended (two real states per non-zero weight)."""
    n = len(model.dofs)
    blocks_a, rows_b, cols_c = [], [], []
    for (a1, a2), per_dof in zip(sections, weights, strict=True):
        for i in np.flatnonzero(per_dof > 1e-9 * max(float(weights.max()), 1e-300)):
            gain = per_dof[i] * scale[i] * a2 / (a2 - a1)
            blocks_a.append(np.diag([-a2, -a1]))
            b = np.zeros((2, n))
            b[:, i] = 1.0
            rows_b.append(b)
            c = np.zeros((n, 2))
            c[i] = [gain * a2, -gain * a1]
            cols_c.append(c)
    if not blocks_a:
        return model
    return model.with_matrices(
        A=block_diag(model.A, *blocks_a), B=np.vstack([model.B, *rows_b]), C=np.hstack([model.C, *cols_c])
    )


def enforce_passivity(
    model: RadiationStateSpace, omega_data: np.ndarray, scale: np.ndarray, omega_band: np.ndarray | None = None
) -> tuple[RadiationStateSpace, Passivation]:
    """Make ``model`` passive (module docstring): the symmetry correction of C, then the least passive lift.

    Parameters
    ----------
    model : RadiationStateSpace
        A stable model with A in real modal form or any other form.
    omega_data : ndarray
        The data's frequencies [rad/s]: the grid and the lift's sections are placed from them.
    scale : ndarray (n_dof,)
        Each DOF's peak radiation damping (:func:`damping_scale`) [N s/m, N m s/rad].
    omega_band : ndarray, optional
        Frequencies over which the lift's added damping is minimised [rad/s] (default ``omega_data``).

    Returns
    -------
    (model, Passivation)
        The passive model (or, when the enforcement is not attempted or fails, the given one: the report says
        which) and what was done.
    """
    scale = _checked_scale(model, scale)
    omega_data = np.asarray(omega_data, dtype=float)
    before = check_passivity(model, omega_data, scale)
    if before.passive:
        return model, Passivation(before, before)
    if model.n_states > MAX_ENFORCE_STATES:
        why = f"enforcement not attempted ({model.n_states} states > MAX_ENFORCE_STATES = {MAX_ENFORCE_STATES})"
        return model, Passivation(before, before, skipped=why)
    corrected, conditions = symmetry_correction(model)
    change = float(np.linalg.norm(corrected.C - model.C) / max(float(np.linalg.norm(model.C)), 1e-300))
    at_zero = scaled_damping_eigh(corrected, np.array([0.0]), scale)[0][0]
    if at_zero[0] < -ROUNDING:  # scaled: each DOF's peak damping is 1; the lift vanishes at omega = 0
        why = (
            f"enforcement failed: the damping at omega = 0 has a negative eigenvalue ({at_zero[0]:.3g}, scaled) that "
            "C could not remove with its few states and no lift reaches; the fitted model is kept"
        )
        return model, Passivation(before, before, skipped=why)
    sections = lift_sections(float(omega_data.max()))
    band = omega_data if omega_band is None else np.asarray(omega_band, dtype=float)
    grid = passivity_grid(corrected, omega_data, scale)
    for _ in range(4):  # the lifted model's grid reaches further (its tail bound): cut there too if needed
        try:
            weights, rounds = _lift_weights(corrected, grid, scale, sections, band)
        except RuntimeError as err:  # the linear programme failed
            return model, Passivation(before, before, skipped=f"enforcement failed ({err}); the fitted model is kept")
        lifted = _with_lift(corrected, weights, scale, sections)
        after = check_passivity(lifted, omega_data, scale)
        if after.passive:
            break
        grid = np.union1d(grid, passivity_grid(lifted, omega_data, scale))
    if not after.passive:  # never hand back a model changed without reaching passivity
        why = (
            f"enforcement failed (scaled margin {after.margin:.3g} after {rounds} rounds of the lift); the fitted "
            "model is kept"
        )
        return model, Passivation(before, before, skipped=why)
    added = sum(np.outer(lift_response(a1, a2, band), w) for (a1, a2), w in zip(sections, weights, strict=True))
    in_band = float(np.max(added))
    imposed = ", ".join(CONDITIONS[k] for k in conditions) or "none"
    return lifted, Passivation(before, after, change, lifted.n_states - model.n_states, in_band, rounds, imposed)
