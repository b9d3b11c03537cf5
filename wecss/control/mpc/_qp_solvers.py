"""Two ways to solve a :class:`PowerQP` step after step, both set up once and then given only the new linear term
and bounds: OSQP directly (``update`` and warm start: the fast path) and cvxpy with Parameters (disciplined
parametrised programming, so the problem is canonicalised once), with OSQP or any other QP solver cvxpy has."""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from ._power_qp import PowerQP

TOLERANCE: float = 1e-9
"""Absolute and relative tolerance given to the solvers (the programme is scaled to order one). At 1e-7 OSQP's
forces were up to 1.7e-3 N m from Clarabel's on an m4-111 run with its limits binding; at 1e-9 within 4e-4."""


@dataclass(frozen=True)
class Solution:
    """One solve: ``x`` the solution (None when the solver did not solve the programme), ``status`` the solver's
    word for it and ``seconds`` the solve's wall time [s]."""

    x: np.ndarray | None
    status: str
    seconds: float


class OsqpPath:
    """The programme in OSQP, set up once (``osqp.OSQP.setup``); :meth:`solve` updates q, l, u and warm starts
    from the last solution.

    Parameters
    ----------
    qp : PowerQP
    max_iter : int
        Most ADMM iterations per solve.
    """

    name = "osqp"

    def __init__(self, qp: PowerQP, *, max_iter: int = 20_000) -> None:
        import osqp

        self.qp = qp
        self._solver = osqp.OSQP()
        n = qp.n_variables
        q0, l0, u0 = np.zeros(n), *_placeholder_bounds(qp)
        self._solver.setup(
            qp.hessian, q0, qp.constraints, l0, u0, verbose=False, eps_abs=TOLERANCE, eps_rel=TOLERANCE,
            polishing=False, warm_starting=True, max_iter=max_iter,
        )  # fmt: skip

    def solve(self, q: np.ndarray, lower: np.ndarray, upper: np.ndarray, loss: np.ndarray | None = None) -> Solution:
        """Solve with the linear term ``q``, the bounds ``lower`` <= A z <= ``upper`` and, for a programme with
        loss rows, their coefficients ``loss`` (``PowerQP.loss_coefficients``)."""
        start = time.perf_counter()
        if loss is not None:
            self._solver.update(Ax=loss, Ax_idx=self.qp.loss_index)
        if lower.size:
            self._solver.update(q=q, l=_finite(lower), u=_finite(upper))
        else:
            self._solver.update(q=q)
        result = self._solver.solve(raise_error=False)
        seconds = time.perf_counter() - start
        status = str(result.info.status)
        solved = status == "solved" and result.x is not None and np.all(np.isfinite(result.x))
        return Solution(np.array(result.x) if solved else None, status, seconds)


class ClarabelPath:
    """The programme in Clarabel (an interior-point method) directly, set up once: each :meth:`solve` updates q,
    the bounds and the loss rows' coefficients in place (Clarabel's data updates; the sparsity stays). Slower
    than OSQP on the absorbed-power programme (about 1.5 ms against 0.2 ms on the Wavestar, N = 30), it is the
    robust path for the electrical one, whose loss slacks sit at their kink in much of the horizon: a degenerate
    programme on which OSQP's ADMM needed about 800 iterations at a tolerance of 1e-4 and often did not settle at
    1e-9.

    The rows l <= A z <= u become A z <= u and -A z <= -l for the rows with a finite bound (the same rows at
    every step), in Clarabel's nonnegative cone.
    """

    name = "clarabel"

    def __init__(self, qp: PowerQP, *, max_iter: int = 200) -> None:
        import clarabel
        import scipy.sparse as sp

        self.qp = qp
        lower, upper = _placeholder_bounds(qp)
        self._upper_rows = np.flatnonzero(np.isfinite(upper))
        self._lower_rows = np.flatnonzero(np.isfinite(lower))
        # where each entry of the stacked matrix comes from in the constraints' CSC data, and its sign
        marked = qp.constraints.copy()
        marked.data = np.arange(1, marked.nnz + 1, dtype=float)
        stacked = sp.vstack([marked[self._upper_rows], -marked[self._lower_rows]]).tocsc()
        stacked.sort_indices()
        self._source = np.abs(stacked.data).astype(np.int64) - 1
        self._sign = np.sign(stacked.data)
        self._data = qp.constraints.data.copy()
        stacked.data = self._sign * self._data[self._source]
        settings = clarabel.DefaultSettings()
        settings.verbose = False
        settings.max_iter = max_iter
        settings.presolve_enable = False  # keep the rows (the data updates need the same structure)
        bounds = np.concatenate([_finite(upper[self._upper_rows]), -_finite(lower[self._lower_rows])])
        self._solver = clarabel.DefaultSolver(
            sp.csc_matrix(qp.hessian), np.zeros(qp.n_variables), stacked, bounds,
            [clarabel.NonnegativeConeT(bounds.size)], settings,
        )  # fmt: skip

    def solve(self, q: np.ndarray, lower: np.ndarray, upper: np.ndarray, loss: np.ndarray | None = None) -> Solution:
        """Solve with the linear term ``q``, the bounds ``lower`` <= A z <= ``upper`` and, for a programme with
        loss rows, their coefficients ``loss`` (``PowerQP.loss_coefficients``)."""
        start = time.perf_counter()
        bounds = np.concatenate([_finite(upper[self._upper_rows]), -_finite(lower[self._lower_rows])])
        if loss is not None:
            self._data[self.qp.loss_index] = loss
            self._solver.update(q=q, b=bounds, A=self._sign * self._data[self._source])
        else:
            self._solver.update(q=q, b=bounds)
        result = self._solver.solve()
        seconds = time.perf_counter() - start
        status = str(result.status)
        x = np.array(result.x)
        solved = status == "Solved" and x.size == self.qp.n_variables and np.all(np.isfinite(x))
        return Solution(x if solved else None, status, seconds)


class CvxpyPath:
    """The programme in cvxpy with Parameters for q and the finite bounds (canonicalised once, DPP), solved by
    ``solver`` (a cvxpy solver name: "OSQP" by default, "CLARABEL", ...) with warm start.

    Raises
    ------
    ValueError
        If cvxpy does not have ``solver``.
    """

    name = "cvxpy"

    def __init__(self, qp: PowerQP, *, solver: str = "OSQP") -> None:
        import cvxpy as cp

        if solver.upper() not in cp.installed_solvers():
            raise ValueError(
                f"cvxpy solver {solver!r} is not installed; installed: {', '.join(cp.installed_solvers())}"
            )
        self.qp = qp
        self.solver = solver.upper()
        n = qp.n_variables
        lower, upper = _placeholder_bounds(qp)
        fixed = np.ones(lower.size, dtype=bool)
        loss_rows = np.arange(lower.size)[qp.loss_rows]
        fixed[loss_rows] = False  # the loss rows' coefficients are a Parameter (they change with the plan)
        self._upper_rows = np.flatnonzero(np.isfinite(upper) & fixed)
        self._lower_rows = np.flatnonzero(np.isfinite(lower) & fixed)
        self._loss_rows = loss_rows
        a = qp.constraints.tocsr()
        self._z = cp.Variable(n)
        self._q = cp.Parameter(n)
        self._u = cp.Parameter(self._upper_rows.size)
        self._l = cp.Parameter(self._lower_rows.size)
        hessian = qp.hessian.toarray()
        hessian = hessian + np.triu(hessian, 1).T  # the full symmetric matrix of the upper triangle
        constraints = []
        if self._upper_rows.size:
            constraints.append(a[self._upper_rows] @ self._z <= self._u)
        if self._lower_rows.size:
            constraints.append(a[self._lower_rows] @ self._z >= self._l)
        if loss_rows.size:
            m = loss_rows.size  # one per planned force; sigma the last m variables
            self._loss = cp.Parameter((m, m))
            self._loss_bound = cp.Parameter(m)
            constraints.append(self._loss @ self._z[:m] - self._z[n - m :] <= self._loss_bound)
        objective = cp.Minimize(0.5 * cp.quad_form(self._z, cp.psd_wrap(hessian)) + self._q @ self._z)
        self._problem = cp.Problem(objective, constraints)
        if not self._problem.is_dpp():
            raise AssertionError("the MPC programme is not DPP")  # a programming error, not a user's

    def solve(self, q: np.ndarray, lower: np.ndarray, upper: np.ndarray, loss: np.ndarray | None = None) -> Solution:
        """Solve with the linear term ``q``, the bounds ``lower`` <= A z <= ``upper`` and, for a programme with
        loss rows, their coefficients ``loss`` (``PowerQP.loss_coefficients``)."""
        import cvxpy as cp

        if self._loss_rows.size:
            if loss is None:
                raise ValueError("the programme has loss rows: give their coefficients (PowerQP.loss_coefficients)")
            assert self.qp.loss_pattern is not None
            matrix = np.zeros((self._loss_rows.size, self._loss_rows.size))
            matrix[self.qp.loss_pattern] = loss
            self._loss.value = matrix
            self._loss_bound.value = upper[self._loss_rows]
        self._q.value = q
        if self._upper_rows.size:
            self._u.value = upper[self._upper_rows]
        if self._lower_rows.size:
            self._l.value = lower[self._lower_rows]
        options: dict[str, object] = {}
        if self.solver == "OSQP":
            options = {"eps_abs": TOLERANCE, "eps_rel": TOLERANCE, "polishing": False, "max_iter": 20_000}
        start = time.perf_counter()
        try:
            self._problem.solve(solver=self.solver, warm_start=True, **options)
        except cp.error.SolverError as err:
            return Solution(None, f"solver error: {err}", time.perf_counter() - start)
        seconds = time.perf_counter() - start
        status = str(self._problem.status)
        value = self._z.value
        solved = status == cp.OPTIMAL and value is not None and np.all(np.isfinite(value))
        return Solution(np.array(value) if solved else None, status, seconds)


def _placeholder_bounds(qp: PowerQP) -> tuple[np.ndarray, np.ndarray]:
    """Bounds with the programme's structure (which rows have a finite lower and upper bound) for the set-up."""
    n = qp.horizon.phi.shape[0]
    nv = qp.horizon.disturbance_now.shape[1]
    return qp.vectors(np.zeros(n), np.zeros((qp.horizon.steps + 1, nv)), np.zeros(qp.horizon.n_pto))[1:]


def _finite(bounds: np.ndarray) -> np.ndarray:
    """Bounds with +-inf replaced by OSQP's infinity."""
    return np.clip(bounds, -1e30, 1e30)
