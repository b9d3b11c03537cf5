"""The generalised-alpha runner: the implicit scheme of ``_generalized_alpha`` (Chung and Hulbert 1993) as a
fixed-step integrator of the nonlinear MFM equations, for plants whose fastest modes (a flexible body's stiff modal
coordinates) no explicit step can carry at the wave step.

Per step, the accelerations v_dot1 at the step's end solve v_dot1 = a(q1, v1, t1), with q1 and v1 the scheme's
updates from v_dot1 (module docstring of ``_generalized_alpha``), by a modified Newton iteration with the matrix
J = S^-1 M*, S = M* + h gamma c C + h^2 beta c K (M* times the residual's derivative). S is made once per step,
at the configuration of its first evaluation (the predictor's): M*(q) and the PTOs' G(q)' diag(h gamma c c_pto +
h^2 beta c k_pto) G(q) there (the linear PTO gains of the scene's controller), the rest of C and K the linear
model's about the equilibrium. A motion far from the equilibrium changes M* (the bodies' relative angles) and the
PTOs' lever arms most: on the elastic NOTC arm in a JONSWAP sea of Hs 0.5 m the equilibrium's matrix contracted the
iteration by 0.06-0.16 per pass (spectral radius), the step's by 0.004-0.04. A step costs a few evaluations of the
equations (one per iteration) whatever the stiffness. The iteration stops when its step J r (r = v_dot1 - a) is
below ``solver.corrector_tol`` of the largest acceleration (plus ``ACCELERATION_FLOOR``): the step, not the
residual, since the residual of an unresolved stiff mode stays large (its round-off and its unresolved
oscillation) where its step is tiny. Where the iteration stops contracting all the same, the matrix is made again
from differences of the equations at the iterate (nv evaluations) for the rest of that step; the result's
``iteration_matrix_refreshes`` counts them (an iteration that ends on that pass evaluates the equations once more,
at the accepted state, for the values the step records). The radiation states (state-space memory) follow the
trapezoidal rule, A-stable like the scheme, with the iterate's hydro velocities (its velocities through the hydro
Jacobian of the last evaluation). With rho_inf = :data:`SPECTRAL_RADIUS` the modes far above 1/h lose 20 % of
their amplitude per step (numerical damping of what the step cannot resolve), and the wave-frequency motion is
second-order accurate.

Modal coordinates held quasi-static (``flexible.quasi_static_above``; ``Multibody.quasi_static_velocities``) have
no rate and no acceleration: their equations are algebraic. Their unknowns in the iteration are their values at the
step's end (:func:`_end_state`), their residuals the accelerations the equations give them there (zero at the
solution), their columns of S the linear model's K (M*^-1 K: the derivative of those accelerations), and their
predictor the parabola through their last three values (the other unknowns' predictor is the line through the
last two steps' accelerations).
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np

from ..compiled import Plant, RadiationArrays
from ..compiled.kernels import (
    Workspace,
    configure,
    inline_kernel,
    integrate_configuration,
    kernel,
    lu_factor,
    lu_solve,
    matvec,
    respond,
)
from ..control import ControlledScene
from ..linear import linearize
from ..scene import Capabilities, SceneError
from ._fixed_step import FixedStepRunner
from ._generalized_alpha import GeneralizedAlpha
from ._guards import BEEMAN_ELASTIC_LIMIT, fastest_mode
from ._loop import (
    ACCELERATION_FLOOR,
    Chunk,
    LoopState,
    LoopStatus,
    StepSettings,
    Store,
    out_of_bounds,
    passes_stroke_limit,
    record_step,
)

SPECTRAL_RADIUS: float = 0.8
"""rho_inf of the scheme: the amplification of the modes far above 1/h per step."""

REFRESH_AFTER: int = 6
"""Newton iterations of a step after which an iteration that stops contracting (its step above half the last one)
makes its matrix again."""


@kernel
def alpha_chunk(
    p: Plant,
    r: RadiationArrays,
    excitation: np.ndarray,
    command: np.ndarray,
    step0: int,
    settings: StepSettings,
    state: LoopState,
    out: Store,
    w: Workspace,
    coefficients: np.ndarray,
    fixed: np.ndarray,
    pto_weight: np.ndarray,
    held: np.ndarray,
    weight: np.ndarray,
    history: np.ndarray,
) -> tuple[int, int]:
    """Advance ``excitation.shape[0] - 1`` steps from global step ``step0`` (``state`` updated in place; its
    ``acc_prev`` holds the scheme's algorithmic acceleration). ``coefficients``: (alpha_m, alpha_f, gamma, beta);
    ``fixed`` (nv, nv) and ``pto_weight`` (n_pto,): the part of the iteration's matrix S that does not depend on
    the configuration and the PTOs' weights in the part that does (:func:`_iteration_matrix`); ``held`` (nv,): per
    generalised velocity, the index in q of a modal coordinate held quasi-static, else -1 (see
    :func:`_end_state`); ``weight`` (nv,): what turns an unknown's Newton step into an acceleration for the
    stopping test (1, or for a held coordinate 1 / (h^2 beta c), c = (1 - alpha_f) / (1 - alpha_m): the
    acceleration step that would move the configuration as much); ``history`` (3, nv): what the predictor needs of
    the steps before, carried from chunk to chunk (the accelerations of the step before the last, and the held
    coordinates' changes over the last two steps; set at the run's first step, or where it holds NaN). Returns
    (status, global step of the failure)."""
    h, tol, max_iter, bounded, bound = settings
    q, v, acc, a, z, u_now, _, _, pto_now, _ = state
    nv = v.shape[0]
    n_h = u_now.shape[0]
    n_steps = excitation.shape[0] - 1
    vd = np.empty(nv)
    a1 = np.empty(nv)
    v1 = np.empty(nv)
    residual = np.empty(nv)
    step = np.empty(nv)
    lu = np.empty((nv, nv))  # the step's iteration matrix S, factored
    pivots = np.empty(nv, dtype=np.int64)
    mass = np.empty((nv, nv))  # and its M* (the Newton step is S^-1 M* r)
    increment = np.empty(nv)
    u1 = np.empty(n_h)
    rad = np.empty(n_h)
    drive0 = np.zeros(z.shape[0], dtype=np.complex128)
    drive1 = np.zeros(z.shape[0], dtype=np.complex128)
    z1 = np.zeros(z.shape[0], dtype=np.complex128)
    none = np.zeros((n_h, n_h))
    half = 0.5 * h * r.poles
    for c in range(nv):
        if held[c] >= 0:  # a held coordinate has no rate and no acceleration
            v[c] = 0.0
            acc[c] = 0.0
            a[c] = 0.0
    if step0 == 0 or np.isnan(history[0, 0]):  # the run's first step (or a fresh history) extrapolates nothing
        history[0] = acc
        history[1:] = 0.0
    acc_before = history[0]  # the accelerations of the step before the last
    moved = history[1]  # a held coordinate's change over the last step
    moved_before = history[2]  # and over the one before (the predictor is the parabola through three values)
    for k in range(n_steps):
        n1 = step0 + k + 1
        t1 = n1 * h
        e1 = excitation[k + 1]
        for c in range(nv):  # predictor: the accelerations extrapolated from the last two steps
            vd[c] = 2.0 * acc[c] - acc_before[c]
        for c in range(nv):
            if held[c] >= 0:  # and the held coordinates' values extrapolated from the last three steps
                vd[c] = q[held[c]] + 2.0 * moved[c] - moved_before[c]
        matvec(r.input_real, u_now, drive0.view(np.float64))  # a real matrix onto the states' real/imag parts
        converged = False
        refreshed = False
        stale = False  # the workspace holds the differences' last (perturbed) evaluation, not the iterate's
        count = 0
        previous = np.inf
        q1 = q
        for iteration in range(max_iter):
            q1 = _end_state(p, q, v, a, acc, vd, held, coefficients, h, a1, v1, increment)
            if not (_finite(q1) and _finite(v1)):
                return LoopStatus.NOT_FINITE, n1
            # the iterate's hydro velocities, through the hydro Jacobian of the last evaluation (the workspace holds
            # the initial state's before the first step): a radiation force one iteration behind the velocities
            # would cost an iteration per step
            matvec(w.bh, v1, u1)
            matvec(r.input_real, u1, drive1.view(np.float64))
            for j in range(z.shape[0]):  # trapezoidal radiation states
                z1[j] = ((1.0 + half[j]) * z[j] + 0.5 * h * (drive0[j] + drive1[j])) / (1.0 - half[j])
            matvec(r.output_real, z1.view(np.float64), rad)
            count += 1
            if not configure(p, q1, e1 + rad, t1, w):
                return LoopStatus.NOT_FINITE, n1
            respond(p, v1, none, command, w)
            stale = False
            scale = 0.0
            for c in range(nv):
                residual[c] = (vd[c] if held[c] < 0 else 0.0) - w.acc[c]
                scale = max(scale, abs(w.acc[c]))
            if iteration == 0 and not _iteration_matrix(fixed, pto_weight, held, w.mass, w.gmat, mass, lu, pivots):
                return LoopStatus.CORRECTOR_FAILED, n1
            # the Newton step, not the residual, is tested: the stiff coordinates' round-off in the accelerations
            # (their static loads cancel) is far above the floor, and their step J r far below it
            if refreshed:  # lu holds the derivative from differences: the step is its inverse times the residual
                lu_solve(lu, pivots, residual, step)
            else:
                _newton_step(mass, lu, pivots, residual, increment, step)
            change = _weighted_max(step, weight)
            if iteration >= REFRESH_AFTER and change > 0.5 * previous and not refreshed:
                # slow or no contraction (the equations' derivative far from the matrix's model): the matrix made
                # again, here, from the equations' differences (nv evaluations; for the rest of this step)
                refreshed = True
                stale = True
                out.evaluations[2] += 1
                if not _refresh(p, q, v, a, acc, vd, residual, e1 + rad, t1, command, w, coefficients, h, held, lu):
                    return LoopStatus.NOT_FINITE, n1  # M* not positive definite at a perturbed iterate
                count += nv
                if not lu_factor(lu, pivots):
                    return LoopStatus.CORRECTOR_FAILED, n1
                lu_solve(lu, pivots, residual, step)
                change = _weighted_max(step, weight)
            previous = change
            if not np.isfinite(change):
                return LoopStatus.NOT_FINITE, n1
            vd -= step
            if change <= tol * scale + ACCELERATION_FLOOR:
                converged = True
                break
        if converged:
            # the state of the last iterate v_dot1 (its last Newton step applied: a change below the tolerance, so
            # the equations' loads, strokes and forces of the last evaluation stand for it); v_dot1, not the
            # evaluated accelerations, is the scheme's: an unresolved stiff mode's residual is large and its step
            # J r tiny
            q1 = _end_state(p, q, v, a, acc, vd, held, coefficients, h, a1, v1, increment)
            if stale:  # the last pass made the matrix again: the equations at the accepted state instead
                count += 1
                if not configure(p, q1, e1 + rad, t1, w):
                    return LoopStatus.NOT_FINITE, n1
                respond(p, v1, none, command, w)
        out.evaluations[0] += count
        out.evaluations[1] = max(out.evaluations[1], count)
        if not converged:
            return LoopStatus.CORRECTOR_FAILED, n1
        if out_of_bounds(q1, bounded, bound):
            return LoopStatus.OUT_OF_BOUNDS, n1
        acc_before[:] = acc
        acc[:] = vd
        for c in range(nv):
            if held[c] >= 0:  # vd held the coordinate's value
                acc[c] = 0.0
                moved_before[c] = moved[c]
                moved[c] = q1[held[c]] - q[held[c]]
        q[:] = q1
        v[:] = v1
        a[:] = a1
        z[:] = z1
        u_now[:] = w.u
        pto_now[0] = w.stroke
        pto_now[1] = w.xdot
        pto_now[2] = w.f
        if passes_stroke_limit(p, w.stroke):
            return LoopStatus.STROKE_LIMIT, n1
        record_step(out, n1, p, (q, v, acc, w.stroke, w.xdot, w.f, rad, e1, w.terms.out.reshape(-1)))
    return LoopStatus.OK, step0 + n_steps


@kernel
def _iteration_matrix(
    fixed: np.ndarray,
    pto_weight: np.ndarray,
    held: np.ndarray,
    mass_now: np.ndarray,
    gmat: np.ndarray,
    mass: np.ndarray,
    lu: np.ndarray,
    pivots: np.ndarray,
) -> bool:
    """The step's iteration matrix S = M*(q) + h gamma c C(q) + h^2 beta c K (module docstring) at the
    configuration of the workspace's M* (``mass_now``) and PTO transmissions (``gmat``, (n_pto, nv)): ``fixed``
    plus M*(q) plus G(q)' diag(``pto_weight``) G(q) on the columns of the accelerations (a held coordinate's column
    is ``fixed``'s alone), factored into ``lu``, ``pivots``; M*(q) copied into ``mass``. Returns False when S is
    singular."""
    nv = fixed.shape[0]
    for i in range(nv):
        for j in range(nv):
            mass[i, j] = mass_now[i, j]
            lu[i, j] = fixed[i, j]
            if held[j] < 0:
                s = mass_now[i, j]
                for k in range(gmat.shape[0]):
                    s += gmat[k, i] * pto_weight[k] * gmat[k, j]
                lu[i, j] += s
    return lu_factor(lu, pivots)


@inline_kernel
def _newton_step(
    mass: np.ndarray, lu: np.ndarray, pivots: np.ndarray, residual: np.ndarray, scratch: np.ndarray, step: np.ndarray
) -> None:
    """The Newton step J r = S^-1 M* r into ``step`` (``scratch`` (nv,) is overwritten)."""
    matvec(mass, residual, scratch)
    lu_solve(lu, pivots, scratch, step)


@kernel
def _finite(x: np.ndarray) -> bool:
    """Every entry of ``x`` finite (no temporaries, unlike ``np.all(np.isfinite(x))``)."""
    for c in range(x.shape[0]):
        if not np.isfinite(x[c]):
            return False
    return True


@kernel
def _weighted_max(step: np.ndarray, weight: np.ndarray) -> float:
    """max_c |step_c| weight_c; NaN if any of them is NaN (the caller's finiteness test catches it)."""
    largest = 0.0
    for c in range(step.shape[0]):
        value = abs(step[c]) * weight[c]
        if np.isnan(value):
            return value
        largest = max(largest, value)
    return largest


@inline_kernel
def _end_state(
    p: Plant,
    q: np.ndarray,
    v: np.ndarray,
    a: np.ndarray,
    acc: np.ndarray,
    x: np.ndarray,
    held: np.ndarray,
    coefficients: np.ndarray,
    h: float,
    a1: np.ndarray,
    v1: np.ndarray,
    increment: np.ndarray,
) -> np.ndarray:
    """The step's end from the iteration's unknowns ``x``: the configuration q1 (returned), the velocities ``v1``
    and the algorithmic accelerations ``a1`` (both filled; ``increment`` (nv,) is scratch). ``x`` holds the
    accelerations v_dot1 at the step's end, and for a coordinate held quasi-static (``held[c]``: its index in q,
    else -1) its value at the step's end instead (its rate and accelerations are zero). (Inlined: a call that
    passes the Plant costs about 1 us.)"""
    alpha_m, alpha_f, gamma, beta = coefficients[0], coefficients[1], coefficients[2], coefficients[3]
    nv = v.shape[0]
    for c in range(nv):
        a1[c] = ((1.0 - alpha_f) * x[c] + alpha_f * acc[c] - alpha_m * a[c]) / (1.0 - alpha_m)
        increment[c] = h * v[c] + h * h * ((0.5 - beta) * a[c] + beta * a1[c])
        v1[c] = v[c] + h * ((1.0 - gamma) * a[c] + gamma * a1[c])
    for c in range(nv):
        if held[c] >= 0:
            a1[c] = 0.0
            v1[c] = 0.0
            increment[c] = x[c] - q[held[c]]
    return integrate_configuration(p, q, increment)


@kernel
def _refresh(
    p: Plant,
    q: np.ndarray,
    v: np.ndarray,
    a: np.ndarray,
    acc: np.ndarray,
    vd: np.ndarray,
    residual: np.ndarray,
    hydro_force: np.ndarray,
    t1: float,
    command: np.ndarray,
    w: Workspace,
    coefficients: np.ndarray,
    h: float,
    held: np.ndarray,
    derivative: np.ndarray,
) -> bool:
    """The residual's derivative at the iterate ``vd`` (its residual ``residual``) by forward differences of
    the equations (their memory force held), into ``derivative`` (nv, nv). The workspace ``w`` is left with the
    last, perturbed evaluation: the caller evaluates again before it reads ``w``. Returns False when an
    evaluation fails (M* not positive definite)."""
    nv = vd.shape[0]
    trial = vd.copy()
    a1 = np.empty(nv)
    v1 = np.empty(nv)
    increment = np.empty(nv)
    none = np.zeros((hydro_force.shape[0], hydro_force.shape[0]))
    for col in range(nv):
        eps = 1e-7 * max(1.0, abs(vd[col]))
        trial[col] = vd[col] + eps
        q1 = _end_state(p, q, v, a, acc, trial, held, coefficients, h, a1, v1, increment)
        if not configure(p, q1, hydro_force, t1, w):
            return False
        respond(p, v1, none, command, w)
        for c in range(nv):
            derivative[c, col] = ((trial[c] if held[c] < 0 else 0.0) - w.acc[c] - residual[c]) / eps
        trial[col] = vd[col]
    return True


def _held(controlled: ControlledScene) -> np.ndarray:
    """Per generalised velocity: the index in q of a modal coordinate held quasi-static, else -1."""
    model = controlled.device.model
    held = np.full(model.nv, -1, dtype=np.int64)
    modes = model.quasi_static_velocities[model.mode_velocities]  # modal coordinates add: one q per v
    held[model.mode_velocities[modes]] = model.mode_coordinates[modes]
    return held


class GeneralizedAlphaRunner(FixedStepRunner):
    """Generalised-alpha (see the module docstring): second order, implicit, state-space radiation or none, every
    controller, streamed results."""

    name = "generalized-alpha"
    description = "implicit generalised-alpha (rho_inf 0.8) with a modified Newton iteration, its matrix made per step"
    capabilities = Capabilities(
        radiation=("state_space", "none"),
        streaming=True,
        initial_state=True,
        hydrodynamics=("body-exact", "drag"),
        terms=True,
        order=2,
        quasi_static=True,
    )
    radiation_reason = (
        "the scheme integrates the radiation states with the motion; a convolution's memory has no state to "
        "integrate: use 'beeman' for convolutions"
    )

    def prepare(self, controlled: ControlledScene) -> Any:
        scheme = GeneralizedAlpha(SPECTRAL_RADIUS)
        alpha_m, alpha_f, gamma, beta = scheme.coefficients
        model = linearize(controlled)
        h = controlled.dt
        c = (1 - alpha_f) / (1 - alpha_m)
        held = _held(controlled)
        columns = held >= 0
        # a held step weighs as the acceleration step that moves the configuration as much
        weight = np.where(columns, 1.0 / (h * h * beta * c), 1.0)
        # S at the equilibrium less the parts the steps make again at their configuration: M* and G' diag(w) G
        pto_weight = h * gamma * c * model.pto_damping + h * h * beta * c * model.pto_stiffness
        g = model.pto_jacobian
        fixed = h * gamma * c * model.damping + h * h * beta * c * model.stiffness - (g.T * pto_weight) @ g
        # a held coordinate's unknown is its value: its column of the derivative is M^-1 K's
        fixed[:, columns] = model.stiffness[:, columns]
        history = np.full((3, model.mass.shape[0]), np.nan)  # (filled by the run's first chunk)
        return np.array([alpha_m, alpha_f, gamma, beta]), np.ascontiguousarray(fixed), pto_weight, held, weight, history

    def advance(self, prepared: Any, chunk: Chunk) -> tuple[int, int]:
        return alpha_chunk(*chunk, *prepared)

    def solver_attrs(self, out: Store, prepared: Any, n_steps: int) -> dict[str, Any]:
        evaluations = out.evaluations
        return {
            "solver": "generalized-alpha",
            "spectral_radius": SPECTRAL_RADIUS,
            "evaluations_per_step": float(evaluations[0]) / max(1, n_steps),
            "max_evaluations_per_step": int(evaluations[1]),
            "iteration_matrix_refreshes": int(evaluations[2]),
        }

    def failure(self, status: LoopStatus, controlled: ControlledScene) -> str | None:
        if status == LoopStatus.CORRECTOR_FAILED:
            return (
                "the generalised-alpha Newton iteration did not converge (its matrix takes M* and the PTOs' lever "
                "arms at each step's configuration, the rest of the damping and stiffness from the linear model "
                "about the equilibrium: a motion far from it, or a smaller solver.dt, may need more iterations)"
            )
        return None


GENERALIZED_ALPHA = GeneralizedAlphaRunner()


def with_elastic_choice(controlled: ControlledScene) -> ControlledScene:
    """``controlled`` to run with generalised-alpha when its scene names no ``solver.method`` and no tolerance,
    its device has elastic bodies, and the default explicit runner (Beeman) cannot carry the plant's fastest
    undamped mode at the scene's step (:data:`BEEMAN_ELASTIC_LIMIT`) or some modal coordinates are held
    quasi-static; else itself. The result's notes say so.

    Raises
    ------
    SceneError
        If generalised-alpha cannot run the scene (a convolution memory: the message says what to do).
    """
    scene = controlled.scene
    model = controlled.device.model
    if scene.solver.method is not None or scene.solver.step_chosen or not model.elastic_bodies:
        return controlled
    held = int(np.count_nonzero(model.quasi_static_velocities))
    rate = 0.0 if held else fastest_mode(controlled, damped=False)  # with held coordinates it is chosen anyway
    if not held and rate * controlled.dt <= BEEMAN_ELASTIC_LIMIT:
        return controlled
    try:
        chosen = replace(scene, solver=replace(scene.solver, method=GENERALIZED_ALPHA.name))
        GENERALIZED_ALPHA.check(chosen)
        GENERALIZED_ALPHA.check_compiled(replace(controlled, scene=chosen))
    except SceneError as err:
        why = (
            f"hold {held} modal coordinates quasi-static (only generalised-alpha solves them)"
            if held
            else f"have modes up to |s| = {rate:.4g} rad/s, beyond the explicit runners' steps at dt = "
            f"{controlled.dt:.3g} s"
        )
        raise SceneError(
            f"the elastic bodies {list(controlled.device.elastic_bodies)} {why}, and generalised-alpha cannot run "
            f"this scene: {err}"
        ) from None
    if held:
        note = (
            f"solver.method: generalized-alpha chosen (no method named; {held} modal coordinates are held "
            "quasi-static, and it solves their equations)"
        )
    else:
        note = (
            f"solver.method: generalized-alpha chosen (no method named; the elastic bodies' fastest undamped mode, "
            f"{rate:.4g} rad/s, needs an explicit step below {BEEMAN_ELASTIC_LIMIT / rate:.3g} s)"
        )
    return replace(controlled, scene=chosen, notes=[*controlled.notes, note])
