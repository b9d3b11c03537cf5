"""Model predictive control that maximises the absorbed energy over a receding horizon, all PTOs of a device in
one quadratic programme (``wecss.control.mpc.PowerQP``), solved every control period by OSQP (directly or through
cvxpy)."""

from __future__ import annotations

from collections import deque
from typing import Any

import numpy as np

from wecss.control import ControlContext, Controller, Measurement
from wecss.control.design import optimal_damping
from wecss.control.mpc import (
    ARPredictor,
    ClarabelPath,
    CvxpyPath,
    ExcitationEstimator,
    HorizonModel,
    OsqpPath,
    PowerQP,
    Solution,
    StateObserver,
    measured_rms,
    pto_equivalent,
)
from wecss.limits import MPC_PLANNED_FORCES, LimitError, beyond
from wecss.linear import LinearModel
from wecss.radiation import truncate_to_error

PREVIEWS = ("perfect", "causal")
SOLVERS = ("osqp", "clarabel", "cvxpy")

ESTIMATOR_NOISE: float = 0.1
"""Measurement noise of the causal preview's excitation estimator, relative to the measured signals' RMS: the
loop of the causal preview closes through the excitation estimate, which has to explain the nonlinear simulator's
departure from the linear model (2-3 % of the measured RMS under damping on m4-111 and the Wavestar) as excitation;
the plan then acts on it over the horizon. With the true excitation's history instead (same state estimate) the
Wavestar's nonlinear run is within 0.7 % of its linear one. At 1e-2 m4-111 (JONSWAP Hs 0.04 m, force penalty 0.01)
still diverges in the nonlinear simulator, though the linear run gains 4 %."""

PREDICTOR_RIDGE: float = 1e-4
"""Ridge of the causal preview's AR predictor, relative to the record's energy: the same as fitting it on the record
with white noise of 1 % of its RMS added. Fitted on a clean record (1e-8) the predictor amplified 1 % of white
noise in its history (the estimate's error) into 8.7 times the signal's RMS ten steps ahead on m4-134."""

ESTIMATOR_BIAS: float = 0.5
"""Standard deviation of the slowly varying stroke offset the causal preview's estimator tracks, relative to the
strokes' RMS: the nonlinear simulator's strokes shift in the mean with the motion (second order), which a filter
without an offset takes for excitation and the plan then acts on. On the Wavestar in WECCCOMP sea state 5 (force
penalty 0.01, 20 Tp) the nonlinear run's power went from 27 % below the linear one's to 4 %."""

FORCE_PENALTY: dict[str, float] = {"perfect": 0.01, "causal": 0.1}
"""Default force penalty per preview. The causal loop is stable at 0.01 on m4-111 in the nonlinear simulator since
the predictor's ridge (it diverged within 2 s), but its mean power there is 3.3 % below the linear simulator's
(Hs 0.04 m, 20 Tp; 0.5 % at Hs 0.02 m) and 4.4 % on the Wavestar in WECCCOMP sea state 5, against 1 % sought:
the causal default stays 0.1."""


class MPC(Controller):
    """Energy-maximising model predictive control of every PTO of a device.

    At every control period T (the scene's ``controller.dt``) it plans the PTO forces over the next ``horizon``
    periods on the scene's linear model (radiation states included, discretised exactly: the force held over each
    period) and applies the first. The objective is the exact absorbed energy of the held forces, less a force
    penalty (``force_penalty``; with ``efficiency`` also a loss model of the power conversion); the force limit is
    hard, the stroke limit soft (a slack, penalised, so the programme stays feasible), the rate limit optional
    (``wecss.control.mpc.PowerQP`` has the formulation). The state comes from a Kalman filter of the PTO strokes and
    rates; the excitation over the horizon either from the scene itself (``preview = "perfect"``: a benchmark, no
    real controller knows it) or from the excitation estimator and an autoregressive predictor fitted on the sea
    state's spectrum with random phases (``"causal"``: only the sea state's spectrum is known, not the record).

    Gains and scales come from the sea state: c_opt, the optimal passive damping per PTO (frequency domain), sets
    the force scale sqrt(P_opt c_opt), the energy scale (P_opt over the horizon) and the fallback.

    Parameters
    ----------
    horizon : int
        Periods planned ahead, N (default 30).
    preview : str
        "perfect" or "causal" (default).
    force_penalty : float or None
        Quadratic force penalty as a share of the absorbed power at the optimal damping: the programme subtracts
        force_penalty / c_opt f^2 [W] per PTO (default None: 0.01 with the perfect preview, 0.1 with the causal
        one, whose loop closes through the excitation estimate and needs the margin).
    efficiency : float or None
        Conversion efficiency eta in (0, 1] of the PTOs' electrical objective (default None: absorbed power). The
        programme then maximises the competition's electrical energy, eta W when the PTO absorbs the work W over a
        control period and W / eta when it supplies it, per PTO and period (``wecss.control.mpc.PowerQP``). The
        supplied energy is bilinear in the forces, so it is linearised about the last plan shifted by one period
        (sequential convex programming, one convex programme per period; the loss is exact at the plan and its
        error second order in the plan's change). On the Wavestar's WECCCOMP records (docs/control.md) the
        electrical power it converts is above the non-causal electrical optimum's (a local optimum) with perfect
        preview and near it causal.
    rate_limit : float, sequence of float or None
        Largest force rate per PTO [N/s or N m/s] (default None: none).
    stroke_weights : (float, float)
        Weights (w1, w2) of the stroke slack e (relative to the limit): E_ref (w1 e + w2 e^2) with E_ref the
        energy the optimal damping absorbs over the horizon (default (100, 1000)).
    solver : str or None
        "osqp" (OSQP directly, the fast path: about 0.2 ms per programme on the Wavestar, N = 30), "clarabel"
        (Clarabel directly, an interior-point method: about 1.4 ms) or "cvxpy" (cvxpy with Parameters). Default
        None: OSQP for absorbed power, Clarabel with an ``efficiency`` (the electrical programme's loss slacks sit
        at their kink much of the time, where OSQP needed hundreds of iterations and often did not settle).
    cvxpy_solver : str
        The solver cvxpy uses with ``solver = "cvxpy"`` (default "OSQP"; "CLARABEL" and others cvxpy has).
    sequential_solves : int
        Convex programmes per control period with an ``efficiency``, each linearised about the plan of the one
        before (default 1; on the Wavestar SS5 a second changed the electrical power by -4e-4 relative and doubled
        the time).
    ar_order : int
        Order of the autoregressive predictor of the causal preview (default 30).
    radiation_error : float
        Relative error allowed in the plan's radiation memory (default 1e-3): its states are reduced by balanced
        truncation (``wecss.radiation.truncate_to_error``) to the fewest whose memory transfer function K_hat
        stays within ``radiation_error`` of the full one's peak (largest singular values, measured on a frequency
        grid past the data and the control period's Nyquist frequency). 0 keeps every state. The plan's model
        only: the simulation keeps its own. On m4-111 (perfect preview, N = 20) the mean power moved by 0.05 %
        at 1e-3 (93 of 350 states) and 1.2 % at 1e-2 (60 states).
    allow_large : bool
        Plan more than ``wecss.limits.MPC_PLANNED_FORCES`` (2000) forces (``horizon`` x PTOs) all the same
        (default False: such a plan is refused, by the horizon alone when it passes the limit with one PTO, else at
        setup; its dense matrices grow as the square of the forces and a solve as up to their cube).

    Notes
    -----
    A failed or infeasible solve never stops the run: the controller applies the rest of its last plan, or the
    optimal damping when that is used up, and counts it. :meth:`report` (kept in the result's attributes and
    notes) gives the preview used, the solves, the fallbacks, the solve times and the largest stroke slack.

    Raises
    ------
    ValueError
        On bad parameters; at setup in calm water, with a scene whose radiation memory is a convolution (no
        state space: use radiation.method = "state_space"), or with a rate limit of the wrong size.
    wecss.limits.LimitError
        (a ValueError) For a plan of more than ``MPC_PLANNED_FORCES`` forces without ``allow_large``.
    """

    def __init__(
        self,
        horizon: int = 30,
        preview: str = "causal",
        force_penalty: float | None = None,
        efficiency: float | None = None,
        rate_limit: float | list[float] | None = None,
        stroke_weights: tuple[float, float] | list[float] = (100.0, 1000.0),
        solver: str | None = None,
        cvxpy_solver: str = "OSQP",
        sequential_solves: int = 1,
        ar_order: int = 30,
        radiation_error: float = 1e-3,
        allow_large: bool = False,
    ) -> None:
        if not (isinstance(horizon, int) and horizon >= 1):
            raise ValueError(f"horizon must be a whole number of control periods >= 1; got {horizon!r}")
        if not isinstance(allow_large, bool):
            raise ValueError(f"allow_large must be true or false; got {allow_large!r}")
        self.horizon, self.allow_large = horizon, allow_large
        self._check_size(1)
        if preview not in PREVIEWS:
            raise ValueError(f"preview must be one of {PREVIEWS}; got {preview!r}")
        if force_penalty is None:
            force_penalty = FORCE_PENALTY.get(preview, 0.0)
        if not (isinstance(force_penalty, int | float) and force_penalty > 0):
            raise ValueError(f"force_penalty must be positive; got {force_penalty!r}")
        if efficiency is not None and not (isinstance(efficiency, int | float) and 0 < efficiency <= 1):
            raise ValueError(f"efficiency must lie in (0, 1] or be None; got {efficiency!r}")
        rates = None if rate_limit is None else np.atleast_1d(np.asarray(rate_limit, dtype=float))
        if rates is not None and not np.all(rates > 0):
            raise ValueError(f"rate_limit must be positive [N/s or N m/s]; got {rate_limit!r}")
        if len(stroke_weights) != 2 or not min(stroke_weights) > 0:
            raise ValueError(f"stroke_weights must be two positive numbers; got {stroke_weights!r}")
        if solver is None:
            solver = "osqp" if efficiency is None else "clarabel"
        if solver not in SOLVERS:
            raise ValueError(f"solver must be one of {SOLVERS} or None; got {solver!r}")
        if not (isinstance(sequential_solves, int) and sequential_solves >= 1):
            raise ValueError(f"sequential_solves must be an integer >= 1; got {sequential_solves!r}")
        if sequential_solves != 1 and efficiency is None:
            raise ValueError(
                f"sequential_solves ({sequential_solves}) applies to the electrical objective only: give an efficiency "
                "too, or leave sequential_solves out"
            )
        if not (isinstance(ar_order, int) and ar_order >= 1):
            raise ValueError(f"ar_order must be an integer >= 1; got {ar_order!r}")
        if not (isinstance(radiation_error, int | float) and 0 <= radiation_error < 1):
            raise ValueError(f"radiation_error must lie in [0, 1) (a relative error bound); got {radiation_error!r}")
        self.horizon = horizon
        self.preview = preview
        self.force_penalty = float(force_penalty)
        self.efficiency = None if efficiency is None else float(efficiency)
        self.rate_limit = rates
        self.stroke_weights = (float(stroke_weights[0]), float(stroke_weights[1]))
        self.solver = solver
        self.cvxpy_solver = cvxpy_solver
        self.sequential_solves = sequential_solves
        self.ar_order = ar_order
        self.radiation_error = float(radiation_error)
        self.radiation_states = (0, 0)
        self.radiation_measured_error = 0.0
        self.solve_times: list[float] = []
        self.fallbacks = 0
        self.largest_slack = 0.0

    def _check_size(self, n_pto: int) -> None:
        """Refuse a plan of more than MPC_PLANNED_FORCES forces (``horizon`` x ``n_pto``) without allow_large."""
        forces = self.horizon * n_pto
        if forces > MPC_PLANNED_FORCES and not self.allow_large:
            pto = "PTO" if n_pto == 1 else "PTOs"
            raise LimitError(
                beyond(
                    "horizon",
                    f"{self.horizon} control periods (x {n_pto} {pto}: {forces} planned forces)",
                    f"{MPC_PLANNED_FORCES} planned forces (horizon <= {MPC_PLANNED_FORCES // n_pto} here)",
                    f"the plan's dense matrices grow as the square of its forces, {8 * forces**2 / 1e9:.3g} GB "
                    "each, and a solve as up to their cube",
                    "give allow_large = true among the controller's parameters",
                )
            )

    def setup(self, context: ControlContext) -> None:
        exc = context.excitation
        if exc is None or exc.omega.size == 0:
            raise ValueError("mpc plans with the sea state's excitation; the scene's sea is calm")
        self._check_size(context.n_pto)
        period, steps = context.control_period, self.horizon
        model = self._reduced(context.linear_model(), period)
        self.preview_horizon = steps * period if self.preview == "perfect" else None
        tuned = optimal_damping(model, exc.omega, exc.coefficients)
        c_opt = np.maximum(tuned.damping, 1e-12 * max(float(np.max(tuned.damping)), 1e-300))
        power = np.maximum(tuned.power, 1e-12 * max(float(np.sum(tuned.power)), 1e-300))
        penalty = self.force_penalty / c_opt
        loss_weight = 0.0 if self.efficiency is None else 1 / self.efficiency**2 - 1
        rate = None
        if self.rate_limit is not None:
            if self.rate_limit.size not in (1, context.n_pto):
                raise ValueError(f"rate_limit has {self.rate_limit.size} values; the device has {context.n_pto} PTOs")
            rate = np.broadcast_to(self.rate_limit, (context.n_pto,)).copy()
        self.model = HorizonModel.of(model, period, steps)
        self.qp = PowerQP.build(
            self.model, force_limit=np.asarray(context.force_limit), stroke_limit=np.asarray(context.stroke_limit),
            stroke_at_equilibrium=model.pto_stroke, force_penalty=penalty, force_scale=np.sqrt(power * c_opt),
            energy_scale=float(np.sum(power)) * steps * period, rate_limit=rate, slack_weights=self.stroke_weights,
            loss_weight=loss_weight,
        )  # fmt: skip
        self.fallback_damping = c_opt
        self.force_limit = np.asarray(context.force_limit, dtype=float)
        self.hydro_jacobian = model.hydro_jacobian
        self.pto_jacobian = model.pto_jacobian
        self.excitation = exc
        rms = measured_rms(model, exc.omega, exc.coefficients)
        if self.preview == "perfect":
            generalised = model.hydro_jacobian.T @ exc.coefficients  # (nv, n_w)
            std = np.sqrt(0.5 * np.sum(np.abs(generalised) ** 2, axis=1))
            self.observer = StateObserver(
                self.model, 1e-2 * np.maximum(std, 1e-6 * float(np.max(std))), 1e-3 * rms, model.pto_stroke,
                float(np.min(exc.omega)),
            )  # fmt: skip
        else:
            self.estimator = ExcitationEstimator.for_sea(
                model,
                period,
                exc.omega,
                exc.coefficients,
                relative_noise=ESTIMATOR_NOISE,
                relative_bias=ESTIMATOR_BIAS,
            )
            self.predictor = ARPredictor(self.ar_order, ridge=PREDICTOR_RIDGE).fit(
                _synthetic_record(model, exc.omega, exc.coefficients, period, self.ar_order)
            )
        self.reset()

    def _solver_path(self) -> OsqpPath | ClarabelPath | CvxpyPath:
        """A new solver of the built programme (OSQP or Clarabel directly, or cvxpy)."""
        if self.solver == "osqp":
            return OsqpPath(self.qp)
        if self.solver == "clarabel":
            return ClarabelPath(self.qp)
        return CvxpyPath(self.qp, solver=self.cvxpy_solver)

    def _reduced(self, model: LinearModel, period: float) -> LinearModel:
        """``model`` with its radiation states reduced by balanced truncation to ``radiation_error`` (class
        docstring), the error measured on 800 frequencies from 0 to 1.5 times the larger of the database's last
        frequency and the control period's Nyquist frequency; the states kept and the error are reported."""
        full = 0 if model.radiation is None else model.radiation.n_states
        self.radiation_states, self.radiation_measured_error = (full, full), 0.0
        if model.radiation is None or full == 0 or self.radiation_error == 0:
            return model
        top = 1.5 * max(float(np.max(model.hydro.omega)), np.pi / period)
        reduction, error = truncate_to_error(model.radiation, self.radiation_error, np.linspace(0.0, top, 800))
        self.radiation_states = (full, reduction.model.n_states)
        self.radiation_measured_error = error
        return model.with_radiation(reduction.model)

    def reset(self) -> None:
        """A fresh start for a run: a new solver (no warm start carried from an earlier run, so that every run is
        the same), no plan, the filter at rest."""
        self.path = self._solver_path()
        n_pto = self.model.n_pto
        self.applied = np.zeros(n_pto)
        self.plan: np.ndarray | None = None
        self.plan_step = 0
        self.known: tuple[np.ndarray, np.ndarray] | None = None
        self.history: deque[np.ndarray] = deque([np.zeros(n_pto)] * self.ar_order, maxlen=self.ar_order)
        self.solve_times = []
        self.fallbacks = 0
        self.largest_slack = 0.0
        if self.preview == "perfect":
            self.observer.reset()
        else:
            self.estimator.reset()

    def compute(self, t: float, measurement: Measurement) -> np.ndarray:
        if self.preview == "perfect":
            assert measurement.preview is not None
            if self.known is None:  # first call: the disturbance now, from the scene's excitation, as before it
                now = self.excitation.force(np.array([t]))[:, 0] @ self.hydro_jacobian
                before = now
            else:
                before, now = self.known  # at t - T and at t, from the last call's preview
            state = self.observer.update(measurement.displacement, measurement.velocity, self.applied, before, now)
            disturbance = np.vstack([now, measurement.preview @ self.hydro_jacobian])
            self.known = (now, disturbance[1])
        else:
            referred = self.estimator.update(measurement.displacement, measurement.velocity, None)
            state = self.estimator.state
            self.history.append(referred.copy())
            future = self.predictor.predict(np.array(self.history), self.horizon)
            disturbance = np.vstack([referred, future]) @ self.pto_jacobian
        solution = self._solve(state, disturbance)
        self.solve_times.append(solution.seconds)
        if solution.x is not None:
            self.plan, self.plan_step = self.qp.forces(solution.x), 0
            self.largest_slack = max(self.largest_slack, float(np.max(self.qp.slack(solution.x), initial=0.0)))
            force = self.plan[0]
        else:
            self.fallbacks += 1
            self.plan_step += 1
            if self.plan is not None and self.plan_step < self.plan.shape[0]:
                force = self.plan[self.plan_step]
            else:
                force = -self.fallback_damping * measurement.velocity
        force = np.clip(force, -self.force_limit, self.force_limit)
        self.applied = np.array(force, dtype=float)
        if self.preview == "causal":
            self.estimator.hold(self.applied)
        return self.applied.copy()

    def _solve(self, state: np.ndarray, disturbance: np.ndarray) -> Solution:
        """One programme now; with the electrical objective, its supplied energy linearised about the last plan
        shifted by one period (the last force held), ``sequential_solves`` times, each about the one before."""
        if self.qp.loss_weight == 0:
            return self.path.solve(*self.qp.vectors(state, disturbance, self.applied))
        plan = None
        if self.plan is not None:
            rest = self.plan[self.plan_step + 1 :]
            plan = np.vstack([rest, np.repeat(self.plan[-1:], self.horizon - rest.shape[0], axis=0)])
        seconds = 0.0
        for _ in range(self.sequential_solves):
            q, lower, upper = self.qp.vectors(state, disturbance, self.applied, plan)
            solution = self.path.solve(q, lower, upper, self.qp.loss_coefficients(q, plan))
            seconds += solution.seconds
            if solution.x is None:
                break
            plan = self.qp.forces(solution.x)
        return Solution(solution.x, solution.status, seconds)

    def report(self) -> dict[str, Any]:
        times = np.array(self.solve_times)
        source = (
            "perfect (the scene's own excitation)"
            if self.preview == "perfect"
            else "causal (Kalman excitation estimate and AR prediction)"
        )
        return {
            "preview": source,
            "horizon_steps": self.horizon,
            "solver": f"cvxpy/{self.cvxpy_solver}" if self.solver == "cvxpy" else self.solver,
            "solves": int(times.size),
            "fallbacks": self.fallbacks,
            "solve_time_median_ms": float(np.median(times) * 1e3) if times.size else 0.0,
            "solve_time_p99_ms": float(np.percentile(times, 99) * 1e3) if times.size else 0.0,
            "largest_stroke_slack": self.largest_slack,
            "convexity_shift": float(self.qp.convexity_shift) if hasattr(self, "qp") else 0.0,
            "radiation_states": f"{self.radiation_states[1]} of {self.radiation_states[0]} (balanced truncation)",
            "radiation_relative_error": self.radiation_measured_error,
        }


def _synthetic_record(
    model: LinearModel, omega: np.ndarray, coefficients: np.ndarray, period: float, order: int
) -> np.ndarray:
    """A record of the PTO-equivalent excitation (``pto_equivalent``: what the estimator estimates) (n_samples, n_pto)
    sampled at ``period`` [s], with the sea state's amplitudes and phases drawn afresh (seeded): what the AR predictor
    learns from is the spectrum, not the run's record."""
    referred = pto_equivalent(model, omega, model.hydro_jacobian.T @ np.asarray(coefficients, dtype=complex))
    phases = np.exp(2j * np.pi * np.random.default_rng(20261123).random(omega.size))
    n = max(4000, 100 * order)
    times = np.arange(n) * period
    return np.real(np.exp(1j * np.outer(times, omega)) @ (referred * phases).T)
