"""The M4 paper's own treatment of the added mass, as a replication option: the runner ``beeman-explicit``
(``solver.method = "beeman-explicit"``, or ``solver.added_mass = "explicit"`` with Beeman).

wecss puts the infinite-frequency added mass in the mass matrix, M*_total = B' (M + A_inf) B (DESIGN.md), so a
step needs no iteration for it. The paper (Lande-Sudall et al., Eq. 47 inserted into F* of Eq. 46, section 5.2 and
its Fig. 3) keeps only the rigid mass on the left and the added-mass force on the right, evaluated with the
accelerations of the previous iteration, and iterates the Beeman corrector until the accelerations change by less
than 1 %. Derived from Eq. 47 in the MFM's Cartesian rows (B rows: centre-of-mass velocity, body angular velocity):

    B' M (B a + Bdot v) = B' F - B' A_inf (B a_k + Bdot v)          a_{k+1} from a_k

where a is the generalised acceleration and B a + Bdot v the Cartesian acceleration. At its fixed point this is
exactly wecss's equation B' (M + A_inf) (B a + Bdot v) = B' F, so both converge to the same solution; the
iteration itself converges only where the spectral radius of (B' M B)^-1 B' A_inf B is below one (the added mass
smaller than the rigid mass in every mode), and slowly near one. :func:`iteration_factor` gives that radius at the
equilibrium; a run refuses to start above :data:`MAX_ITERATION_FACTOR`.

(The paper's Eq. 52 as printed is the velocity-Verlet form; its text, its reference (Beeman 1976) and its stated
O(dt^3) error are Beeman's scheme, which ``wecss.sim._beeman`` implements and this module reuses.)
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..compiled import Plant, RadiationArrays
from ..compiled.kernels import accelerations, integrate_configuration, kernel, kinematics
from ..control import ControlledScene
from ..scene import Capabilities, SceneError
from ._beeman import Beeman
from ._guards import check_beeman_step
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
from ._memory import block_history, memory_advance

MAX_ITERATION_FACTOR: float = 0.95
"""Largest spectral radius of the added-mass iteration a run starts with: at 0.95 a 1 % tolerance takes about 90
iterations per step; at 1 and above the iteration diverges."""


def split_added_mass(p: Plant) -> tuple[Plant, np.ndarray]:
    """The plant with the rigid mass alone on its active rows, and the added mass A_inf on them (m, m) [kg, kg m,
    kg m^2] (the difference of the total and the rigid mass matrices)."""
    rows = np.ix_(p.active, p.active)
    rigid_active = np.ascontiguousarray(p.rigid_mass[rows])
    return p._replace(active_mass=rigid_active), np.ascontiguousarray(p.active_mass - rigid_active)


def iteration_factor(p: Plant, q: np.ndarray) -> float:
    """Spectral radius of the explicit added-mass iteration at configuration ``q``: of (B' M B)^-1 B' A_inf B, with
    the rigid mass M and the added mass A_inf on the plant's active rows [-]. Below one the iteration converges,
    each iteration shrinking the error by about this factor."""
    rigid, added = split_added_mass(p)
    _rot, _pos, b, _bdot, _omega = kinematics(p, q, np.zeros(p.twists.shape[0]))
    ba = b[p.active]
    mass = ba.T @ rigid.active_mass @ ba
    return float(np.max(np.abs(np.linalg.eigvals(np.linalg.solve(mass, ba.T @ added @ ba)))))


@kernel
def explicit_accelerations(
    p: Plant,
    added: np.ndarray,
    q: np.ndarray,
    v: np.ndarray,
    hydro_force: np.ndarray,
    newest: np.ndarray,
    command: np.ndarray,
    guess: np.ndarray,
    t: float,
):
    """Accelerations with the rigid mass on the left and the added-mass force of the accelerations ``guess`` on
    the right (``p``: the rigid plant of :func:`split_added_mass`, ``added`` its A_inf); the other arguments and
    the returns as ``wecss.compiled.kernels.accelerations``."""
    a, u, x, xd, f, mass = accelerations(p, q, v, hydro_force, newest, command, t)
    _rot, _pos, b, bdot, _omega = kinematics(p, q, v)
    act = p.active
    nv = v.shape[0]
    ba = np.empty((act.shape[0], nv))
    cartesian = bdot @ v  # B a + Bdot v on the active rows
    acc = np.empty(act.shape[0])
    for k in range(act.shape[0]):
        ba[k] = b[act[k]]
        acc[k] = cartesian[act[k]]
    acc += ba @ guess
    a = a - np.linalg.solve(0.5 * (mass + mass.T), ba.T @ (added @ acc))
    return a, u, x, xd, f, mass


@kernel
def beeman_explicit_chunk(
    p: Plant,
    added: np.ndarray,
    r: RadiationArrays,
    excitation: np.ndarray,
    command: np.ndarray,
    step0: int,
    settings: StepSettings,
    state: LoopState,
    out: Store,
    terms: np.ndarray,
) -> tuple[int, int]:
    """Beeman steps as ``beeman_chunk``, with the added mass explicit (see the module docstring): one fixed-point
    iteration updates the corrector velocity and the added-mass force from the last accelerations, until their
    change is below ``settings.tol`` of their size (the paper: 1 %). No implicit fallback: a step whose iteration
    does not converge within ``settings.max_iterations`` reports CORRECTOR_FAILED."""
    h, tol, max_iter, bounded, bound = settings
    q, v, acc, acc_prev, z, u_now, buf, pos, pto_now, far = state
    n_steps = excitation.shape[0] - 1
    for k in range(n_steps):
        n1 = step0 + k + 1
        t1 = n1 * h
        hist = block_history(r, z, u_now, buf, pos[0], far, (n1 - 1) % far.shape[0])
        base = excitation[k + 1] + hist
        q1 = integrate_configuration(p, q, h * v + h * h / 6.0 * (4.0 * acc - acc_prev))
        if not np.all(np.isfinite(q1)):
            return LoopStatus.NOT_FINITE, n1
        if out_of_bounds(q1, bounded, bound):
            return LoopStatus.OUT_OF_BOUNDS, n1
        known = v + h / 6.0 * (5.0 * acc - acc_prev)
        # first evaluation: the predicted velocity, and the added-mass force of the last step's accelerations
        vc = v + h / 2.0 * (3.0 * acc - acc_prev)
        a1, u1, x1, xd1, f1, _mass = explicit_accelerations(p, added, q1, vc, base, r.newest, command, acc, t1)
        converged = False
        count = 1
        for _ in range(max_iter):
            vc = known + h / 3.0 * a1
            a_new, u1, x1, xd1, f1, _mass = explicit_accelerations(p, added, q1, vc, base, r.newest, command, a1, t1)
            count += 1
            change = np.max(np.abs(a_new - a1))
            a1 = a_new
            if not np.isfinite(change):
                return LoopStatus.NOT_FINITE, n1
            if change <= tol * np.max(np.abs(a_new)) + ACCELERATION_FLOOR:
                converged = True
                break
        if not converged:
            return LoopStatus.CORRECTOR_FAILED, n1
        out.evaluations[0] += count
        out.evaluations[1] = max(out.evaluations[1], count)
        rad = hist + r.newest @ u1
        memory_advance(r, z, u_now, u1, buf, pos)
        u_now[:] = u1
        q[:] = q1
        v[:] = vc
        acc_prev[:] = acc
        acc[:] = a1
        pto_now[0] = x1
        pto_now[1] = xd1
        pto_now[2] = f1
        if passes_stroke_limit(p, x1):
            return LoopStatus.STROKE_LIMIT, n1
        record_step(out, n1, p, (q, v, acc, x1, xd1, f1, rad, excitation[k + 1], terms))
    return LoopStatus.OK, step0 + n_steps


class BeemanExplicit(Beeman):
    """Beeman with the M4 paper's explicit, iterated added mass (see the module docstring): a replication option,
    slower, and refused where the iteration cannot converge."""

    name = "beeman-explicit"
    description = "Beeman with the M4 paper's explicit added mass, iterated with the corrector (replication option)"
    tolerance_reason = ": it replicates the paper's method at the step it is given (give solver.dt)"
    capabilities = Capabilities(streaming=True, initial_state=True, order=2)

    def prepare(self, controlled: ControlledScene) -> Any:
        """The rigid plant, the added mass and the iteration's spectral radius at the equilibrium; refuses a scene
        where the iteration cannot converge."""
        check_beeman_step(controlled)
        factor = iteration_factor(controlled.plant, controlled.q0)
        if factor > MAX_ITERATION_FACTOR:
            raise SceneError(
                f"solver.added_mass 'explicit': the added-mass iteration cannot converge on {controlled.device.name}: "
                f"its spectral radius (B'MB)^-1 B'A_inf B at the equilibrium is {factor:.3g} (the added mass outweighs "
                f"the rigid mass in some mode; at most {MAX_ITERATION_FACTOR} is accepted); use solver.added_mass "
                "'implicit'"
            )
        rigid, added = split_added_mass(controlled.plant)
        return rigid, added, factor

    def advance(self, prepared: Any, chunk: Chunk) -> tuple[int, int]:
        rigid, added, _ = prepared
        c = chunk
        terms = c.work.terms.out.reshape(-1)  # the paper's method computes none (its capabilities say so)
        return beeman_explicit_chunk(
            rigid, added, c.r, c.excitation, c.command, c.step0, c.settings, c.state, c.out, terms
        )

    def solver_attrs(self, out: Store, prepared: Any, n_steps: int) -> dict[str, Any]:
        return {
            **super().solver_attrs(out, prepared, n_steps),
            "added_mass": "explicit",
            "added_mass_iteration_factor": prepared[2],
        }

    def failure(self, status: LoopStatus, controlled: ControlledScene) -> str | None:
        if status == LoopStatus.CORRECTOR_FAILED:
            solver = controlled.scene.solver
            return (
                "the explicit added-mass iteration (solver.added_mass 'explicit') did not reach solver.corrector_tol "
                f"in {solver.max_corrector_iterations} iterations (solver.max_corrector_iterations); 'implicit' needs "
                "no iteration"
            )
        return None


BEEMAN_EXPLICIT = BeemanExplicit()
