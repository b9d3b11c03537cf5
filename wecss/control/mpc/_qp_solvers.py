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

    def solve(self, q: np.ndarray, lower: np.ndarray, upper: np.ndarray) -> Solution:
        """Solve with the linear term ``q`` and the bounds ``lower`` <= A z <= ``upper``."""
        start = time.perf_counter()
        if lower.size:
            self._solver.update(q=q, l=_finite(lower), u=_finite(upper))
        else:
            self._solver.update(q=q)
        result = self._solver.solve(raise_error=False)
        seconds = time.perf_counter() - start
        status = str(result.info.status)
        solved = status == "solved" and result.x is not None and np.all(np.isfinite(result.x))
        return Solution(np.array(result.x) if solved else None, status, seconds)


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
        self._upper_rows = np.flatnonzero(np.isfinite(upper))
        self._lower_rows = np.flatnonzero(np.isfinite(lower))
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
        objective = cp.Minimize(0.5 * cp.quad_form(self._z, cp.psd_wrap(hessian)) + self._q @ self._z)
        self._problem = cp.Problem(objective, constraints)
        if not self._problem.is_dpp():
            raise AssertionError("the MPC programme is not DPP")  # a programming error, not a user's

    def solve(self, q: np.ndarray, lower: np.ndarray, upper: np.ndarray) -> Solution:
        """Solve with the linear term ``q`` and the bounds ``lower`` <= A z <= ``upper``."""
        import cvxpy as cp

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
