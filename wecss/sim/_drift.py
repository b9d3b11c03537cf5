"""The drift note (issue 31): a body whose horizontal mean position moves by more than :data:`DRIFT_LIMIT` times its
size V^(1/3) between the first and the last tenth of the saved record is noted as drifting; with a re-run at half
the step (:class:`DriftCheck`, made by ``wecss.sim._drift_check``) the note says which part of the drift is the
integrator's error and which is physical, with the advice that fits each (a smaller step or RK4; a mooring).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: A body whose horizontal mean position moves by more than this multiple of its size V^(1/3) between the first and
#: the last tenth of the saved record is noted as drifting.
DRIFT_LIMIT = 1.0


@dataclass(frozen=True)
class DriftCheck:
    """The drift of a re-run of a drifting run at half its step (``wecss.sim`` makes it when the drift note fires):
    with the run's own drift it splits the drift into the integrator's error and the physics (Richardson).

    Attributes
    ----------
    dt : float
        The run's step [s] (the re-run's is dt / 2).
    order : int
        The runner's order p: its drift error goes as dt^p.
    half : numpy.ndarray or None
        (n_body, 2) [m]: the re-run's drift (as :meth:`MotionSummary.drift`); None when it could not be made.
    reason : str
        Why there is no re-run (``half`` None): the run too long, the re-run diverged.
    """

    dt: float
    order: int
    half: np.ndarray | None
    reason: str = ""


def drifting(names: list[str], sizes: dict[str, float], drift: np.ndarray) -> bool:
    """Whether a body's ``drift`` (n_body, 2) [m] passes :data:`DRIFT_LIMIT` times its size (the drift note's
    criterion; ``names`` and ``sizes`` as :func:`drift_note`)."""
    norms = np.linalg.norm(drift, axis=-1)
    return any(n in sizes and d > DRIFT_LIMIT * sizes[n] for n, d in zip(names, norms, strict=True))


MOORING_ADVICE = (
    "nothing restores it: give the device a linear mooring ([[moorings]] in its spec, docs/byo-bem.md) or a "
    "solver.translation_bound"
)


def drift_note(names: list[str], sizes: dict[str, float], drift: np.ndarray, check: DriftCheck | None) -> str:
    """The drift note (empty when no body drifts past :data:`DRIFT_LIMIT` x its size; ``names`` the bodies,
    ``sizes`` their V^(1/3) [m] by name, ``drift`` (n_body, 2) [m] their drift): the bodies and their drift;
    with a re-run at half the step (``check``), its numerical part, Richardson's (d_h - d_h/2) 2^p / (2^p - 1) for
    a runner of order p, and its physical part, the rest (the mean wave force, or the start from rest, on a body
    nothing restores), each with the advice that fits it."""
    norms = np.linalg.norm(drift, axis=-1)
    far = [i for i, (n, d) in enumerate(zip(names, norms, strict=True)) if n in sizes and d > DRIFT_LIMIT * sizes[n]]
    if not far:
        return ""
    head = f"drift: the horizontal mean position moved by more than {DRIFT_LIMIT:g} x the body size over the run"
    moved = ", ".join(f"{names[i]} {norms[i]:.3g} m" for i in far)
    if check is None:
        return f"{head} ({moved}); {MOORING_ADVICE}"
    if check.half is None:
        return (
            f"{head} ({moved}); its numerical part was not estimated ({check.reason}): a run at half the step or "
            f"with solver.method 'rk4' tells it from the physics; if it is physical, {MOORING_ADVICE}"
        )
    factor = 2.0**check.order / (2.0**check.order - 1.0)
    numerical = (drift - check.half) * factor
    physical = drift - numerical
    parts = ", ".join(
        f"{names[i]} {norms[i]:.3g} m: numerical {np.linalg.norm(numerical[i]):.3g} m, physical "
        f"{np.linalg.norm(physical[i]):.3g} m"
        for i in far
    )
    text = (
        f"{head} ({parts}; split by a re-run at dt/2 = {check.dt / 2:.4g} s, whose drift is the physical part plus "
        f"the numerical one divided by 2^{check.order}: numerical = (d(dt) - d(dt/2)) x {factor:.4g})"
    )
    advice = []
    if any(np.linalg.norm(numerical[i]) > 0.5 * DRIFT_LIMIT * sizes[names[i]] for i in far):
        advice.append(
            f"the numerical part is the integrator's error at dt = {check.dt:.4g} s: give a smaller solver.dt "
            "(or solver.tolerance) or use solver.method 'rk4'"
        )
    if any(np.linalg.norm(physical[i]) > DRIFT_LIMIT * sizes[names[i]] for i in far):
        advice.append(f"the physical part is a drift of the body itself: {MOORING_ADVICE}")
    else:
        advice.append(f"the physical part is below {DRIFT_LIMIT:g} x the body size: no mooring is needed for it")
    return f"{text}; {'; '.join(advice)}"
