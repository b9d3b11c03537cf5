"""A convex quadratic programme over the Fourier coefficients of a periodic PTO force, with constraints and penalties
at the sample points of the period, solved exactly by a dual active-set method whose every step costs FFTs and one
dense factorisation of the active rows.

The programme (:class:`SpectralProgramme`): over the force amplitudes F_m (m = 1 ... M, n_pto each; module
``_periodic``),

    minimise  1/2 sum_m F_m^H H_m F_m - Re sum_m gamma_m^H F_m + sum_{r in penalties} w_r e_r(F)^2 / 2
    subject to  lower_a <= u^a(t_j) <= upper_a  for every constrained signal a, PTO and sample j,

with H_m Hermitian positive definite and the signals u^a(t) = u^a_free(t) + Re sum_m T^a_m F_m exp(i omega_m t)
(the force itself: T = I; the stroke: T = Y / (i omega); the stroke rate: T = Y; the force rate: T = i omega), each
penalty e_r a combination of signals at one sample. Its dual over the multipliers y (>= 0 for constraints, free for
penalties) is the quadratic programme

    minimise  1/2 y' (G + W^-1) y - y' c,     G_rs = sum_m Re(c_r,m^H H_m^-1 c_s,m),

where c_r,m is row r's functional on F_m and c the rows' values at the unconstrained optimum. G depends on two rows'
samples only through their distance in time, so it is read from a few kernels (one inverse FFT each) and never
multiplied out; the primal force follows from y by one FFT per signal, and every constraint's slack at every sample
by one inverse FFT per signal. The active set is found by the primal-dual active-set iteration (Hintermueller, Ito
and Kunisch 2002: rows whose multiplier stays positive, plus rows violated, until the set repeats), with a
monotone fallback (add the violated rows, drop the negative multipliers) if it cycles. Started from the
unconstrained optimum's violations it can cycle where many limits bind together (the Wavestar's SS3 and SS6, and a
one-DOF body with force and stroke limits); ``_admm.solve_robust`` therefore starts it from the
active set ADMM finds (``_admm``: FFTs and per-harmonic solves only), from which it settles in one iteration in
every case tried.

Where that iteration does not settle (it can cycle when several limits bind together), ``_admm.solve_robust``
solves the same programme by an interior-point method instead (cvxpy with Clarabel, in the real and
imaginary parts of the F_m, the signals as dense matrices: for programmes of up to CONIC_ENTRIES entries).

Certificate: for any y >= 0 on the constraints the dual value D(y) bounds the programme's minimum from below, and the
primal value at F(y) from above when F(y) is feasible; the solution reports both, their gap (the sum of the
active rows' slack times multiplier, and the penalties' stationarity residual) and the largest violation.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ._periodic import PeriodicResponse

FEASIBILITY: float = 1e-9
"""A constraint counts as violated beyond this share of its bound's size."""

MAX_ITERATIONS: int = 80
"""Most active-set iterations."""

PDAS_ITERATIONS: int = 40
"""Primal-dual active-set iterations before the monotone fallback."""

CONIC_ENTRIES: float = 2e7
"""Largest dense problem (signals x samples x coefficients) the interior-point fallback takes on."""


@dataclass(frozen=True)
class Signal:
    """A signal of the programme: u(t) = ``free`` + Re sum_m ``operator``_m F_m exp(i omega_m t).

    Attributes
    ----------
    operator : complex ndarray (M, n_pto, n_pto)
    free : ndarray (N, n_pto)
        Its value with no PTO force, at the samples.
    lower, upper : ndarray (n_pto,) or None
        Its bounds per PTO (+-inf: none); None: not constrained (only in penalties).
    """

    operator: np.ndarray
    free: np.ndarray
    lower: np.ndarray | None = None
    upper: np.ndarray | None = None


@dataclass(frozen=True)
class Penalties:
    """Penalty rows w_r e_r^2 / 2, e_r = sum_k coefficient_rk u^{signal_rk}_{pto_r}(t_{point_r}) (two terms each;
    a zero coefficient for one).

    Attributes
    ----------
    signal : ndarray of int (P, 2)
        Indices into the programme's signals.
    coefficient : ndarray (P, 2)
    pto, point : ndarray of int (P,)
    weight : ndarray (P,)
        w_r > 0.
    """

    signal: np.ndarray
    coefficient: np.ndarray
    pto: np.ndarray
    point: np.ndarray
    weight: np.ndarray

    @property
    def size(self) -> int:
        return int(self.weight.size)


@dataclass
class SpectralSolution:
    """The solution of a :class:`SpectralProgramme`.

    Attributes
    ----------
    force : complex ndarray (M, n_pto)
        F_m [N or N m].
    primal, dual : float
        The programme's objective at ``force`` and the dual value of the multipliers (a lower bound on the
        programme's minimum) [the objective's units].
    gap : float
        primal - dual.
    violation : float
        Largest constraint violation relative to its bound's size [-] (<= FEASIBILITY when solved).
    active : int
        Constraint rows at their bound.
    iterations : int
        Active-set iterations.
    fallback : bool
        The monotone fallback was used (the primal-dual iteration cycled).
    values : list of ndarray (N, n_pto)
        Every signal at the samples.
    penalty_values : ndarray (P,)
        e_r at the solution.
    method : str
        "active set" (:meth:`SpectralProgramme.solve`), "ADMM" (``_admm.solve_admm``) or "interior
        point" (:meth:`SpectralProgramme.solve_conic`).
    """

    force: np.ndarray
    primal: float
    dual: float
    gap: float
    violation: float
    active: int
    iterations: int
    fallback: bool
    values: list[np.ndarray] = field(repr=False)
    penalty_values: np.ndarray = field(repr=False)
    method: str = "active set"


class SpectralProgramme:
    """The programme of the module docstring.

    Parameters
    ----------
    periodic : PeriodicResponse
        The harmonics and samples.
    hessian : complex ndarray (M, n_pto, n_pto)
        H_m, Hermitian positive definite.
    linear : complex ndarray (M, n_pto)
        gamma_m.
    signals : sequence of Signal
    penalties : Penalties or None

    Raises
    ------
    ValueError
        If a Hessian block is not positive definite, or shapes disagree.
    """

    def __init__(
        self,
        periodic: PeriodicResponse,
        hessian: np.ndarray,
        linear: np.ndarray,
        signals: list[Signal],
        penalties: Penalties | None = None,
    ) -> None:
        m, n_pto, n = periodic.n_harmonics, periodic.n_pto, periodic.points
        if hessian.shape != (m, n_pto, n_pto) or linear.shape != (m, n_pto):
            raise ValueError(f"hessian must be ({m}, {n_pto}, {n_pto}) and linear ({m}, {n_pto})")
        for s in signals:
            if s.operator.shape != (m, n_pto, n_pto) or s.free.shape != (n, n_pto):
                raise ValueError("a signal's operator must be (M, n_pto, n_pto) and its free part (N, n_pto)")
        self.periodic = periodic
        self.hessian = 0.5 * (hessian + np.conj(np.swapaxes(hessian, 1, 2)))
        try:
            np.linalg.cholesky(self.hessian)
        except np.linalg.LinAlgError:
            raise ValueError("the Hessian must be positive definite at every harmonic") from None
        self.inverse = np.linalg.inv(self.hessian)
        self.linear = np.asarray(linear, dtype=complex)
        self.signals = list(signals)
        self.penalties = penalties
        self.unconstrained = np.einsum("mpq,mq->mp", self.inverse, self.linear)
        self.constrained = [k for k, s in enumerate(signals) if s.lower is not None or s.upper is not None]
        bounds = []
        for k in self.constrained:
            s = signals[k]
            lower = np.full(n_pto, -np.inf) if s.lower is None else np.broadcast_to(s.lower, (n_pto,)).astype(float)
            upper = np.full(n_pto, np.inf) if s.upper is None else np.broadcast_to(s.upper, (n_pto,)).astype(float)
            if np.any(lower >= upper):
                raise ValueError("every constrained signal needs lower < upper")
            bounds.append(np.stack([-lower, upper], axis=-1))  # row u <= upper, row -u <= -lower
        # per candidate row (n_c, n_pto, side): its bound b (row: coefficient u <= b) and its size for the slack
        self._bound = np.array(bounds).reshape(len(bounds), n_pto, 2)
        finite = np.where(np.isfinite(self._bound), np.abs(self._bound), 0.0)
        self._size = np.maximum(np.max(finite, axis=-1, keepdims=True), 1e-300) * np.ones((1, 1, 2))
        # kernels kappa_ab[p, q](lag) = sum_m Re(T^a_m H_m^-1 T^b_m^H)[p, q] exp(i omega_m lag dt)
        n_s = len(signals)
        self._kernels = np.zeros((n_s, n_s, n_pto, n_pto, n))
        for a in range(n_s):
            left = np.einsum("mpq,mqr->mpr", signals[a].operator, self.inverse)
            for b in range(a, n_s):
                k = np.einsum("mpr,msr->mps", left, np.conj(signals[b].operator))
                values = periodic.samples(k.reshape(m, n_pto * n_pto)).reshape(n, n_pto, n_pto)
                self._kernels[a, b] = np.moveaxis(values, 0, 2)
                if b != a:  # kappa_ba[q, p](lag) = kappa_ab[p, q](-lag)
                    self._kernels[b, a] = np.moveaxis(np.roll(values[::-1], 1, axis=0), 0, 2).swapaxes(0, 1)

    # --- the signals at a force -----------------------------------------------------------------------------------
    def values(self, force: np.ndarray) -> list[np.ndarray]:
        """Every signal at the samples (N, n_pto) for force amplitudes ``force`` (M, n_pto)."""
        return [s.free + self.periodic.samples(np.einsum("mpq,mq->mp", s.operator, force)) for s in self.signals]

    def objective(self, force: np.ndarray, values: list[np.ndarray] | None = None) -> tuple[float, np.ndarray]:
        """The primal objective at ``force`` and the penalty rows' values e_r."""
        quad = 0.5 * float(np.real(np.einsum("mp,mpq,mq->", np.conj(force), self.hessian, force)))
        value = quad - float(np.real(np.sum(np.conj(self.linear) * force)))
        e = np.zeros(0)
        if self.penalties is not None and self.penalties.size:
            values = self.values(force) if values is None else values
            e = self._penalty_values(values)
            value += 0.5 * float(np.sum(self.penalties.weight * e**2))
        return value, e

    def _penalty_values(self, values: list[np.ndarray]) -> np.ndarray:
        pen = self.penalties
        assert pen is not None
        stacked = np.stack(values)  # (n_s, N, n_pto)
        out = np.zeros(pen.size)
        for k in range(2):
            out += pen.coefficient[:, k] * stacked[pen.signal[:, k], pen.point, pen.pto]
        return out

    # --- rows --------------------------------------------------------------------------------------------------
    def _rows(self, active: np.ndarray) -> tuple[np.ndarray, ...]:
        """Atoms of the active constraint rows then the penalty rows: signal (K, 2), pto (K,), point (K,),
        coefficient (K, 2)."""
        c, p, j, side = np.nonzero(active)
        sig = np.array(self.constrained, dtype=np.int64)[c]
        coef = np.where(side == 0, -1.0, 1.0)  # side 0: u >= lower (-u <= -lower); side 1: u <= upper
        signal = np.stack([sig, sig], axis=1)
        coefficient = np.stack([coef, np.zeros_like(coef)], axis=1)
        pto, point = p, j
        pen = self.penalties
        if pen is not None and pen.size:
            signal = np.concatenate([signal, pen.signal])
            coefficient = np.concatenate([coefficient, pen.coefficient])
            pto = np.concatenate([pto, pen.pto])
            point = np.concatenate([point, pen.point])
        return signal, pto, point, coefficient

    def _gram(self, signal: np.ndarray, pto: np.ndarray, point: np.ndarray, coefficient: np.ndarray) -> np.ndarray:
        n = self.periodic.points
        lag = (point[:, None] - point[None, :]) % n
        gram = np.zeros((point.size, point.size))
        for a in range(2):
            if not np.any(coefficient[:, a]):
                continue
            for b in range(2):
                if not np.any(coefficient[:, b]):
                    continue
                k = self._kernels[signal[:, a][:, None], signal[:, b][None, :], pto[:, None], pto[None, :], lag]
                gram += coefficient[:, a][:, None] * coefficient[:, b][None, :] * k
        return 0.5 * (gram + gram.T)

    def _force(self, y: np.ndarray, signal: np.ndarray, pto: np.ndarray, point: np.ndarray, coefficient: np.ndarray):
        """F(y) = H^-1 (gamma - sum_r y_r c_r)."""
        periodic = self.periodic
        n, n_pto, m = periodic.points, periodic.n_pto, periodic.n_harmonics
        scatter = np.zeros((len(self.signals), n, n_pto))
        for a in range(2):
            np.add.at(scatter, (signal[:, a], point, pto), y * coefficient[:, a])
        adjoint = np.zeros((m, n_pto), dtype=complex)
        for k, s in enumerate(self.signals):
            if np.any(scatter[k]):
                spectrum = periodic.spectrum(scatter[k])
                adjoint += np.einsum("mqp,mq->mp", np.conj(s.operator), spectrum)
        return self.unconstrained - np.einsum("mpq,mq->mp", self.inverse, adjoint)

    def _slacks(self, values: list[np.ndarray]) -> np.ndarray:
        """Slack b - coefficient u of every candidate constraint row (n_c, n_pto, N, 2), relative to its bound's size
        (inf: no bound)."""
        if not self.constrained:
            return np.zeros((0, self.periodic.n_pto, self.periodic.points, 2))
        u = np.stack([values[k].T for k in self.constrained])[..., None] * np.array([-1.0, 1.0])  # (n_c, n_pto, N, 2)
        return (self._bound[:, :, None, :] - u) / self._size[:, :, None, :]

    # --- the solve -------------------------------------------------------------------------------------------------
    def solve(self, active: np.ndarray | None = None) -> tuple[SpectralSolution, np.ndarray]:
        """The programme's solution and its active set (start the next, similar, programme from it).

        Raises
        ------
        RuntimeError
            If the active set is not found within MAX_ITERATIONS (not seen in tests).
        """
        periodic = self.periodic
        shape = (len(self.constrained), periodic.n_pto, periodic.points, 2)
        slack = self._slacks(self.values(self.unconstrained))
        if active is None:
            active = slack < -FEASIBILITY
        active = active.copy()
        n_pen = 0 if self.penalties is None else self.penalties.size
        inv_w = np.zeros(0) if self.penalties is None else 1.0 / self.penalties.weight
        at_unconstrained = np.stack(self.values(self.unconstrained))  # (n_s, N, n_pto)
        seen: set[bytes] = set()
        fallback = False
        for iteration in range(1, MAX_ITERATIONS + 1):
            rows = self._rows(active)
            k = rows[0].shape[0]
            n_con = k - n_pen
            y = np.zeros(k)
            if k:
                gram = self._gram(*rows)
                gram[n_con:, n_con:] += np.diag(inv_w)
                # the rows' values at the unconstrained optimum, less their bounds
                rhs = np.zeros(k)
                for a in range(2):
                    rhs += rows[3][:, a] * at_unconstrained[rows[0][:, a], rows[2], rows[1]]
                c, p, _, side = np.nonzero(active)
                rhs[:n_con] -= self._bound[c, p, side]
                y = _solve_psd(gram, rhs)
            force = self._force(y, *rows)
            values = self.values(force)
            slack = self._slacks(values)
            multipliers = np.zeros(shape)
            multipliers[active] = y[:n_con]
            keep = active & (multipliers > 0)
            violated = slack < -FEASIBILITY
            if not np.any(violated) and np.all(y[:n_con] >= 0):
                break
            if not fallback:
                new = keep | (violated & ~active)
                key = new.tobytes()
                if key in seen or iteration > PDAS_ITERATIONS:
                    fallback = True
                else:
                    seen.add(key)
                    active = new
                    continue
            # monotone fallback: drop the most negative multiplier if any, else add the violated rows
            if np.any(multipliers[active] < 0):
                worst = np.unravel_index(np.argmin(np.where(active, multipliers, np.inf)), shape)
                active[worst] = False
            else:
                active |= violated
        else:
            raise RuntimeError(f"the spectral programme's active set was not found in {MAX_ITERATIONS} iterations")
        primal, e = self.objective(force, values)
        dual = primal - self._gap(y, rows, n_con, slack, active, e)
        violation = float(max(0.0, -float(np.min(slack, initial=0.0))))
        solution = SpectralSolution(
            force, primal, dual, primal - dual, violation, int(np.sum(active)), iteration, fallback, values, e
        )
        return solution, active

    # --- the same programme by an interior-point method (cvxpy, Clarabel) ------------------------------------------
    def synthesis(self, k: int) -> np.ndarray:
        """Signal ``k`` at the samples as a real matrix (N n_pto, 2 M n_pto) on the real coordinates x, ordered
        (m, [Re, Im], q): u = ``free`` + this x."""
        periodic = self.periodic
        phase = np.exp(1j * np.outer(periodic.time, periodic.omega))  # (N, M)
        g = np.einsum("jm,mpq->jpmq", phase, self.signals[k].operator)
        out = np.stack([g.real, -g.imag], axis=3)  # (N, p, M, 2, q)
        return out.reshape(periodic.points * periodic.n_pto, -1)

    def solve_conic(self) -> SpectralSolution:
        """The programme solved by an interior-point method (cvxpy with Clarabel) in the real coordinates of the
        force amplitudes: robust where the active-set iteration is not, but dense (time and memory grow as
        N M n_pto^2); certified the same way, by the Lagrangian dual value of the solver's multipliers.

        Raises
        ------
        RuntimeError
            If the solver does not report an optimal solution.
        """
        import cvxpy as cp

        periodic = self.periodic
        m, n_pto = periodic.n_harmonics, periodic.n_pto
        entries = len(self.signals) * periodic.points * n_pto * 2 * m * n_pto
        if entries > CONIC_ENTRIES:
            raise RuntimeError(
                f"the interior-point solve would hold {entries:.3g} matrix entries (more than {CONIC_ENTRIES:.3g}): "
                f"{m} harmonics x {n_pto} PTOs on {periodic.points} samples; narrow the force basis (basis, "
                "harmonics) or drop wave components that carry no energy"
            )
        factor = np.linalg.cholesky(self.hessian)  # H = L L^H
        k = np.conj(np.swapaxes(factor, 1, 2))  # L^H
        blocks = [np.block([[b.real, -b.imag], [b.imag, b.real]]) for b in k]
        r = scipy_sparse().block_diag(blocks, format="csc")
        c = np.stack([self.linear.real, self.linear.imag], axis=1).ravel()  # Re(gamma^H F) = c' x
        matrices = {}

        def matrix(index: int) -> np.ndarray:
            if index not in matrices:
                matrices[index] = self.synthesis(index)
            return matrices[index]

        rows, bounds = [], []
        for index, (lower, upper) in zip(self.constrained, self._bound.transpose(0, 2, 1), strict=True):
            a = matrix(index)
            free = self.signals[index].free.ravel()
            for sign, bound in ((-1.0, lower), (1.0, upper)):  # rows sign u <= bound (lower is stored negated)
                limit = np.tile(bound, periodic.points)
                keep = np.isfinite(limit)
                if np.any(keep):
                    rows.append(sign * a[keep])
                    bounds.append(limit[keep] - sign * free[keep])
        g = np.concatenate(rows) if rows else np.zeros((0, 2 * m * n_pto))
        h = np.concatenate(bounds) if bounds else np.zeros(0)
        pen = self.penalties
        e_matrix, e_free, weight = np.zeros((0, g.shape[1])), np.zeros(0), np.zeros(0)
        if pen is not None and pen.size:
            e_matrix, e_free = np.zeros((pen.size, g.shape[1])), np.zeros(pen.size)
            for term in range(2):
                for index in np.unique(pen.signal[:, term]):
                    sel = pen.signal[:, term] == index
                    flat = pen.point[sel] * n_pto + pen.pto[sel]
                    coef = pen.coefficient[sel, term]
                    e_matrix[sel] += coef[:, None] * matrix(int(index))[flat]
                    e_free[sel] += coef * self.signals[int(index)].free.ravel()[flat]
            weight = np.asarray(pen.weight, dtype=float)
        # scaled: x = scale z, the objective over q, every row over its norm (the multipliers are scaled back)
        scale = float(np.max(np.abs(self.unconstrained), initial=0.0)) or 1.0
        q = scale**2 * float(np.max(np.abs(self.hessian), initial=1.0))
        norms = np.maximum(np.linalg.norm(g, axis=1) * scale, 1e-300)
        z = cp.Variable(g.shape[1])
        objective = 0.5 * cp.sum_squares((scale / np.sqrt(q)) * (r @ z)) - (scale / q) * c @ z
        if weight.size:
            root = np.sqrt(weight / q)
            objective = objective + 0.5 * cp.sum_squares((root * scale)[:, None] * e_matrix @ z + root * e_free)
        constraints = [(scale / norms)[:, None] * g @ z <= h / norms] if h.size else []
        problem = cp.Problem(cp.Minimize(objective), constraints)
        problem.solve(solver=cp.CLARABEL, tol_gap_abs=1e-11, tol_gap_rel=1e-11, tol_feas=1e-10)
        if problem.status not in (cp.OPTIMAL, cp.OPTIMAL_INACCURATE) or z.value is None:
            raise RuntimeError(f"the spectral programme's conic solve ended {problem.status!r}")
        x = scale * np.asarray(z.value)
        xs = x.reshape(m, 2, n_pto)
        force = xs[:, 0] + 1j * xs[:, 1]
        values = self.values(force)
        primal, e = self.objective(force, values)
        y = q * np.maximum(np.asarray(constraints[0].dual_value), 0.0) / norms if constraints else np.zeros(0)
        # the Lagrangian's minimum over x at the multipliers y: a lower bound on the programme's minimum
        quad = (r.T @ r).toarray() + e_matrix.T @ (weight[:, None] * e_matrix)
        lin = e_matrix.T @ (weight * e_free) - c + g.T @ y
        dual = 0.5 * float(np.sum(weight * e_free**2)) - float(y @ h) - 0.5 * float(lin @ np.linalg.solve(quad, lin))
        slack = self._slacks(values)
        violation = float(max(0.0, -float(np.min(slack, initial=0.0))))
        active = int(np.sum(slack <= 1e-7))
        return SpectralSolution(
            force, primal, dual, primal - dual, violation, active, 0, False, values, e, "interior point"
        )

    def _gap(self, y, rows, n_con, slack, active, e) -> float:
        """primal - dual at the multipliers y: the constraints' sum y s (their slack in its units) and the
        penalties' (w e - y)^2 / (2 w)."""
        gap = 0.0
        if n_con:
            c, p, _, side = np.nonzero(active)
            gap += float(np.sum(y[:n_con] * slack[active] * self._size[c, p, side]))
        if self.penalties is not None and self.penalties.size:
            w = self.penalties.weight
            gap += float(np.sum((w * e - y[n_con:]) ** 2 / (2 * w)))
        return gap


def scipy_sparse() -> Any:
    """scipy.sparse, imported on first use."""
    import scipy.sparse

    return scipy.sparse


def _solve_psd(matrix: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """matrix^-1 rhs for a symmetric positive semidefinite matrix (Cholesky, with the least diagonal shift that
    makes it succeed where rows are dependent)."""
    from scipy.linalg import cho_factor, cho_solve

    scale = float(np.max(np.abs(np.diag(matrix)), initial=1.0))
    shift = 0.0
    for _ in range(12):
        try:
            factor = cho_factor(matrix + shift * np.eye(matrix.shape[0]), lower=True, check_finite=False)
            return cho_solve(factor, rhs, check_finite=False)
        except np.linalg.LinAlgError:
            shift = 1e-14 * scale if shift == 0.0 else 10 * shift
    raise np.linalg.LinAlgError("the active rows' Gram matrix could not be factored")
