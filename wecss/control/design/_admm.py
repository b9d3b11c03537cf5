"""The spectral programme by the alternating direction method of multipliers (ADMM): a first guess of its active set
for the exact dual active-set solve, and, for programmes with many penalty rows (the electrical objective's
majorants), its solution with a certified duality gap.

The programme (``_spectral_qp``) with every signal that is limited or penalised split off as its own variable z_k
(at the samples, divided by a scale s_k per PTO so that all rows weigh alike):

    minimise  1/2 sum_m F_m^H H_m F_m - Re sum_m gamma_m^H F_m + g(z)    subject to  z_k = (S T^k F + u^k_free) / s_k,

with g the limits (0 in the box, inf outside) and the penalties w_r (c_1 u^a + c_2 u^b)^2 / 2 at their samples;
S maps harmonic amplitudes to the N samples (S c = Re sum_m c_m exp(i omega_m t_j)). Because the samples cover the
period evenly and the harmonics lie strictly between 0 and N / 2, S^* S = (N / 2) I: the force's step of ADMM is
one n_pto x n_pto solve per harmonic,

    (H_m + rho N / 2 sum_k T^k_m^H T^k_m / s_k^2) F_m = gamma_m - rho sum_k T^k_m^H (S^* r_k)_m / s_k,

with r_k the scaled residual, and the z step is a clip per sample, or for a penalised pair (its second signal free)
a 2 x 2 solve and a clip. The penalty parameter rho is adapted to balance the primal and dual residuals (Boyd et
al. 2011, section 3.4.1), and the iteration is over-relaxed (1.6, section 3.4.3).

Certificate: for multipliers y of the splitting, the Lagrangian's minimum over F and z is a lower bound on the
programme's minimum (a closed form: a per-harmonic quadratic in F, a linear or quadratic function per sample in z);
the multipliers are first made such that it is finite (zero on a free side, the penalised pair's balance), so the
bound holds for any iterate. The primal value at the force F of the last iterate bounds the minimum from above when
F is feasible; the solution reports both, their gap and F's largest violation.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ._spectral_qp import SpectralProgramme, SpectralSolution

RELAXATION: float = 1.6
"""Over-relaxation of the z step."""


class PenaltiesNotSeparable(ValueError):
    """The penalties are not of the form ADMM takes here (each penalised pair's second signal free, at most one
    penalty per signal, sample and PTO)."""


@dataclass
class AdmmState:
    """Where an ADMM run ended, to start a similar programme from: the penalty parameter, the split variables and
    the scaled multipliers (used signals x N x n_pto), and the split signals and their scales (a start is used only
    for a programme with the same)."""

    rho: float
    z: np.ndarray
    w: np.ndarray
    used: tuple[int, ...] = ()
    scale: np.ndarray | None = None


@dataclass
class AdmmResult:
    """The force of the last iterate, its multipliers and the certified lower bound."""

    force: np.ndarray
    dual: float
    iterations: int
    state: AdmmState
    active: np.ndarray


class Splitting:
    """The splitting of a :class:`SpectralProgramme` (module docstring): which signals are split, their scales,
    boxes and operators, and the penalty rows in scaled variables (none with ``with_penalties`` false: the
    programme's limits alone); the signals ``extra`` are split too (free unless limited).

    Raises
    ------
    PenaltiesNotSeparable
        If a penalty's second signal is limited, both its signals are the same, or two penalties share a sample.
    """

    def __init__(self, programme: SpectralProgramme, with_penalties: bool = True, extra: tuple[int, ...] = ()) -> None:
        periodic = programme.periodic
        n, n_pto = periodic.points, periodic.n_pto
        self.programme = programme
        pen = programme.penalties if with_penalties and programme.penalties is not None else None
        has_penalties = pen is not None and pen.size > 0
        penalised = set(np.unique(pen.signal).tolist()) if pen is not None and has_penalties else set()
        used = sorted(set(programme.constrained) | penalised | set(extra))
        self.used = used
        position = {k: i for i, k in enumerate(used)}
        start = [programme.signals[k].free + periodic.samples(
            np.einsum("mpq,mq->mp", programme.signals[k].operator, programme.unconstrained)) for k in used]  # fmt: skip
        lower = np.full((len(used), n_pto), -np.inf)
        upper = np.full((len(used), n_pto), np.inf)
        scale = np.ones((len(used), n_pto))
        for i in range(len(used)):  # by default its RMS at the unconstrained optimum
            rms = np.sqrt(np.mean(start[i] ** 2, axis=0))
            scale[i] = np.where(rms > 0, rms, 1.0)
        for c, k in enumerate(programme.constrained):  # a limited signal: its bound's size, where it has a bound
            i = position[k]
            lower[i] = -programme._bound[c, :, 0]
            upper[i] = programme._bound[c, :, 1]
            bounded = np.any(np.isfinite(programme._bound[c]), axis=-1)
            scale[i] = np.where(bounded, programme._size[c, :, 0], scale[i])
        self.scale, self.lower, self.upper = scale, lower / scale, upper / scale
        self.operators = [programme.signals[k].operator / scale[i][None, :, None] for i, k in enumerate(used)]
        self.free = np.stack([programme.signals[k].free / scale[i][None] for i, k in enumerate(used)])
        self.gram = sum(np.einsum("mqp,mqr->mpr", np.conj(t), t) for t in self.operators)
        self.start = np.stack(start) / scale[:, None, :]
        # penalty rows: first (a) and second (b) signal, cell, scaled coefficients C1, C2 and weight
        self.rows = None
        if has_penalties:
            assert pen is not None
            a = np.array([position[int(k)] for k in pen.signal[:, 0]])
            b = np.array([position[int(k)] for k in pen.signal[:, 1]])
            c1 = pen.coefficient[:, 0] * scale[a, pen.pto]
            c2 = pen.coefficient[:, 1] * scale[b, pen.pto]
            free_b = ~np.isfinite(self.lower[b, pen.pto]) & ~np.isfinite(self.upper[b, pen.pto])
            cells = np.concatenate([a * n * n_pto + pen.point * n_pto + pen.pto, b * n * n_pto + pen.point * n_pto
                                    + pen.pto])  # fmt: skip
            if np.any(a == b) or not np.all(free_b) or np.any(c2 == 0) or np.unique(cells).size != cells.size:
                raise PenaltiesNotSeparable("ADMM takes penalties on two different signals, the second one free")
            self.rows = (a, b, pen.point, pen.pto, c1, c2, np.asarray(pen.weight, float))

    def values(self, force: np.ndarray) -> np.ndarray:
        """The split signals at the samples, scaled (used, N, n_pto)."""
        samples = self.programme.periodic.samples
        return self.free + np.stack([samples(np.einsum("mpq,mq->mp", t, force)) for t in self.operators])

    def adjoint(self, r: np.ndarray) -> np.ndarray:
        """sum_k T^k^H S^* r_k (M, n_pto)."""
        spectrum = self.programme.periodic.spectrum
        return sum(np.einsum("mqp,mq->mp", np.conj(t), spectrum(rk)) for t, rk in zip(self.operators, r, strict=True))

    def project(self, target: np.ndarray, rho: float) -> np.ndarray:
        """The z step: argmin g(z) + rho / 2 |z - target|^2."""
        z = np.clip(target, self.lower[:, None, :], self.upper[:, None, :])
        if self.rows is not None:
            a, b, j, p, c1, c2, weight = self.rows
            ta, tb = target[a, j, p], target[b, j, p]
            # [W c1^2 + rho, W c1 c2; W c1 c2, W c2^2 + rho] [x; v] = rho [ta; tb]
            d11, d12, d22 = weight * c1**2 + rho, weight * c1 * c2, weight * c2**2 + rho
            det = d11 * d22 - d12**2
            x = rho * (d22 * ta - d12 * tb) / det
            x = np.clip(x, self.lower[a, p], self.upper[a, p])
            z[a, j, p] = x
            z[b, j, p] = (rho * tb - d12 * x) / d22
        return z

    def dual_bound(self, y: np.ndarray) -> float:
        """The Lagrangian's minimum over F and z at multipliers ``y`` (used, N, n_pto) on z = u / s, made finite
        first (module docstring): a lower bound on the programme's minimum [the objective's units]."""
        y = y.copy()
        lower, upper = self.lower[:, None, :], self.upper[:, None, :]
        in_row = np.zeros(y.shape, dtype=bool)
        if self.rows is not None:
            a, b, j, p, c1, c2, weight = self.rows
            in_row[a, j, p] = True
            in_row[b, j, p] = True
        y = np.where(~in_row & (((y > 0) & ~np.isfinite(upper)) | ((y < 0) & ~np.isfinite(lower))), 0.0, y)
        z_part = 0.0
        if self.rows is not None:
            # min over x in [l, u], v free of W/2 (c1 x + c2 v)^2 - y_a x - y_b v
            ya, yb = y[a, j, p], y[b, j, p]
            slope = yb * c1 / c2 - ya  # the remaining linear term in x
            lo, hi = self.lower[a, p], self.upper[a, p]
            unbounded = ((slope > 0) & ~np.isfinite(lo)) | ((slope < 0) & ~np.isfinite(hi))
            ya = np.where(unbounded, yb * c1 / c2, ya)
            y[a, j, p] = ya
            slope = np.where(unbounded, 0.0, slope)
            at = np.where(slope > 0, lo, hi)
            at = np.where(np.isfinite(at), at, 0.0)
            z_part += float(np.sum(-((yb / c2) ** 2) / (2 * weight) + slope * at))
        at = np.where(y > 0, upper, lower)
        z_part += float(np.sum(np.where(~in_row & (y != 0), -y * np.where(np.isfinite(at), at, 0.0), 0.0)))
        programme = self.programme
        g = programme.linear - self.adjoint(y)
        f_part = float(np.sum(y * self.free)) - 0.5 * float(
            np.real(np.einsum("mp,mpq,mq->", np.conj(g), programme.inverse, g))
        )
        return f_part + z_part


def admm(
    programme: SpectralProgramme,
    tolerance: float = 1e-6,
    max_iterations: int = 5000,
    state: AdmmState | None = None,
    certify_every: int = 0,
    with_penalties: bool = True,
) -> AdmmResult:
    """ADMM on ``programme`` (module docstring).

    Parameters
    ----------
    programme : SpectralProgramme
    tolerance : float
        Stop when the primal and dual residuals are below this share of their scales [-], and, with
        ``certify_every``, the duality gap below this share of the objective.
    max_iterations : int
    state : AdmmState or None
        Start from here (a similar programme's end) instead of the unconstrained optimum.
    certify_every : int
        Evaluate the certificate every this many iterations (0: never; then ``dual`` is evaluated once at the end).
    with_penalties : bool
        False: the programme's limits alone (its penalties left out; ``dual`` then bounds that programme).

    Raises
    ------
    PenaltiesNotSeparable
        See :class:`Splitting`.
    """
    if certify_every and not with_penalties:
        raise ValueError("certify_every needs the programme's penalties (with_penalties=True)")
    split = Splitting(programme, with_penalties)
    n = programme.periodic.points
    hessian = programme.hessian
    if (
        state is not None
        and state.used == tuple(split.used)
        and state.scale is not None
        and state.scale.shape == split.scale.shape
        and np.allclose(state.scale, split.scale, rtol=1e-12, atol=0.0)
    ):
        rho, z, w = state.rho, state.z.copy(), state.w.copy()
    else:
        rho = _initial_rho(hessian, split.gram, n)
        z, w = split.project(split.start, rho), np.zeros_like(split.start)

    def certified(force: np.ndarray, y: np.ndarray) -> bool:
        return _gap_small(programme, split, force, y, tolerance)

    force, z, w, rho, iteration = iterate(
        split, split.project, rho, z, w, tolerance, max_iterations, RELAXATION,
        certify=certified if certify_every else None, certify_every=max(certify_every, 1),
    )  # fmt: skip
    y = rho * w
    at_upper = (z >= split.upper[:, None, :] - 1e-9) & (y > 0)
    at_lower = (z <= split.lower[:, None, :] + 1e-9) & (y < 0)
    index = [split.used.index(k) for k in programme.constrained]
    active = np.stack([at_lower[index], at_upper[index]], axis=-1)  # (n_c, N, n_pto, 2)
    state_end = AdmmState(rho, z, w, tuple(split.used), split.scale)
    return AdmmResult(
        force=force, dual=split.dual_bound(y), iterations=iteration, state=state_end,
        active=np.ascontiguousarray(np.swapaxes(active, 1, 2)),
    )  # fmt: skip


def iterate(
    split: Splitting,
    project: Callable[[np.ndarray, float], np.ndarray],
    rho: float,
    z: np.ndarray,
    w: np.ndarray,
    tolerance: float,
    max_iterations: int,
    relaxation: float,
    floor: float = 0.0,
    certify: Callable[[np.ndarray, np.ndarray], bool] | None = None,
    certify_every: int = 1,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, float, int]:
    """The scaled ADMM iteration of the module docstring from (rho, z, w): the force's step, the z step
    ``project(target, rho)``, the multipliers' step, over-relaxed by ``relaxation``; rho rebalanced every 25
    iterations (never below ``floor``). It stops when the primal and dual residuals are below ``tolerance`` of their
    scales and, with ``certify``, when ``certify(force, rho w)`` says so (asked every ``certify_every`` iterations).

    Returns
    -------
    force, z, w, rho, iterations
    """
    programme = split.programme
    n = programme.periodic.points
    hessian, linear = programme.hessian, programme.linear
    factor = np.linalg.inv(hessian + rho * 0.5 * n * split.gram)
    iteration, force = 0, programme.unconstrained
    for iteration in range(1, max_iterations + 1):
        force = np.einsum("mpq,mq->mp", factor, linear - rho * split.adjoint(split.free - z + w))
        u = split.values(force)
        relaxed = relaxation * u + (1.0 - relaxation) * z
        z_old = z
        z = project(relaxed + w, rho)
        w = w + relaxed - z
        primal = float(np.max(np.abs(u - z)))
        dual = rho * float(np.max(np.abs(z - z_old)))
        scale_primal = max(float(np.max(np.abs(u))), float(np.max(np.abs(z))), 1e-300)
        scale_dual = max(rho * float(np.max(np.abs(w))), 1e-300)
        if primal <= tolerance * scale_primal and dual <= tolerance * scale_dual:
            if certify is None:
                break
            if iteration % certify_every == 0 and certify(force, rho * w):
                break
        if iteration % 25 == 0:  # keep the residuals balanced: rescale rho and the scaled multipliers with it
            ratio = (primal / scale_primal) / max(dual / scale_dual, 1e-300)
            if ratio > 10.0 or ratio < 0.1:
                new = max(rho * float(np.clip(np.sqrt(ratio), 0.1, 10.0)), floor)
                w *= rho / new
                rho = new
                factor = np.linalg.inv(hessian + rho * 0.5 * n * split.gram)
    return force, z, w, rho, iteration


def admm_active_set(
    programme: SpectralProgramme, tolerance: float = 1e-6, max_iterations: int = 5000
) -> tuple[np.ndarray, int]:
    """The rows at their bound after ADMM on ``programme``'s limits alone (its penalties left out), in the layout
    of ``SpectralProgramme.solve``'s ``active`` (n_constrained, n_pto, N, 2; side 0: lower, 1: upper), and the ADMM
    iterations made (0 where the unconstrained optimum is feasible: nothing binds)."""
    periodic = programme.periodic
    split = Splitting(programme, with_penalties=False)
    if np.array_equal(split.project(split.start, 1.0), split.start):
        return np.zeros((len(programme.constrained), periodic.n_pto, periodic.points, 2), dtype=bool), 0
    result = admm(programme, tolerance, max_iterations, with_penalties=False)
    return result.active, result.iterations


def _gap_small(programme: SpectralProgramme, split: Splitting, force: np.ndarray, y: np.ndarray, tol: float) -> bool:
    primal, _ = programme.objective(force)
    return primal - split.dual_bound(y) <= tol * max(abs(primal), 1e-300)


def _initial_rho(hessian: np.ndarray, gram: np.ndarray, n: int) -> float:
    """rho that makes the splitting's term as large as the Hessian on the average harmonic."""
    h = float(np.mean(np.abs(np.trace(hessian, axis1=1, axis2=2))))
    g = 0.5 * n * float(np.mean(np.abs(np.trace(gram, axis1=1, axis2=2))))
    return h / g if g > 0 and h > 0 else 1.0


def solve_robust(
    programme: SpectralProgramme, active: np.ndarray | None = None
) -> tuple[SpectralSolution, np.ndarray | None]:
    """``programme.solve`` from ``active``, or when none is given from the active set ADMM finds
    (:func:`admm_active_set`: the dual active-set iteration started from the unconstrained optimum's violations
    cycles where many limits bind together), or ``programme.solve_conic`` where the active-set iteration does not
    settle (then no active set is returned)."""
    if active is None and programme.constrained:
        active, _ = admm_active_set(programme)
    try:
        return programme.solve(active)
    except RuntimeError:
        return programme.solve_conic(), None


def solve_admm(
    programme: SpectralProgramme, state: AdmmState | None = None, tolerance: float = 1e-7, max_iterations: int = 20000
) -> tuple[SpectralSolution, AdmmState]:
    """``programme`` solved by ADMM (module docstring): every iteration FFTs and per-harmonic solves, however many
    penalty rows (where the exact solve factors a dense matrix of them all); certified by the Lagrangian dual value
    of its multipliers. The force may violate a limit by about ``tolerance`` of the limit (reported).

    Parameters
    ----------
    programme : SpectralProgramme
    state : AdmmState or None
        Start from the end of a similar programme's solve.
    tolerance : float
        The residuals' and the duality gap's share at which it stops [-].
    max_iterations : int

    Returns
    -------
    SpectralSolution, AdmmState
        The solution (method "ADMM") and where ADMM ended.

    Raises
    ------
    PenaltiesNotSeparable
        If the penalties are not of the form ADMM takes (see :class:`Splitting`).
    """
    result = admm(programme, tolerance, max_iterations, state, certify_every=25)
    values = programme.values(result.force)
    primal, e = programme.objective(result.force, values)
    violation = float(max(0.0, -float(np.min(programme._slacks(values), initial=0.0))))
    solution = SpectralSolution(
        result.force, primal, result.dual, primal - result.dual, violation, int(np.sum(result.active)),
        result.iterations, False, values, e, "ADMM",
    )  # fmt: skip
    return solution, result.state
