"""What every runner returns: the :class:`Record` of a run, raw arrays at its saved steps before they become a
Dataset, and the window statistics every run accumulates."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..compiled import TERM_COLUMNS, CompiledScene
from ..outputs import CHANNEL_NAMES


@dataclass(kw_only=True)
class Record:
    """Raw arrays of a run at its saved steps (build it by keyword).

    Attributes
    ----------
    time : ndarray (n_save,)
        Times of the saved steps [s].
    series : dict of str to ndarray
        The recorded arrays by channel name (``wecss.outputs.CHANNELS``: ``q`` configurations, ``v`` generalised
        velocities, ``a`` accelerations, PTO strokes ``x``, rates ``xd`` and forces ``f`` (n_save, n_pto), memory
        forces ``rad`` and excitation ``exc`` on the hydro DOFs), each (n_save, columns). The fixed-step runs keep
        an array no asked-for output group reads as a single scratch row.
    stats : ndarray (4, n_pto)
        Sums over the statistics window (see :func:`window_statistics`).
    run_time : float
        Time [s] of the run itself.
    solver : dict
        What the run says about itself in the result's attributes: at least ``solver`` (its name), and whatever
        else it measured (evaluations per step, its radiation model, ...).
    limits : ndarray (4, n_pto) or None
        Steps with the force at its limit, episodes of it, steps with the stroke beyond its limit, episodes of
        that (None: the run did not count them).
    spectral : object or None
        A frequency-domain run's equilibrium and complex amplitudes (``wecss.sim``'s ``Spectral``), for the loads'
        amplitudes per frequency; None for time-domain runs.
    hydro_order : ndarray or None
        The hydro DOFs of the columns of ``rad`` and ``exc``, as indices into the database's (None: its order).
    pressure_flags : int ndarray (n_body,) or None
        The body-exact forces' flags per body, ORed over the run (``wecss.compiled`` DRY, SUBMERGED,
        OUTSIDE_TABLE); None for runs without them.
    """

    time: np.ndarray
    series: dict[str, np.ndarray]
    stats: np.ndarray
    run_time: float
    solver: dict[str, Any] = field(default_factory=dict)
    limits: np.ndarray | None = None
    spectral: Any = None
    hydro_order: np.ndarray | None = None
    pressure_flags: np.ndarray | None = None

    def __post_init__(self) -> None:
        missing = sorted(set(CHANNEL_NAMES) - set(self.series))
        unknown = sorted(set(self.series) - set(CHANNEL_NAMES))
        if missing or unknown:
            raise ValueError(
                f"a record holds the channels {', '.join(CHANNEL_NAMES)}; missing {missing}, unknown {unknown}"
            )

    def __getitem__(self, channel: str) -> np.ndarray:
        """The recorded array of ``channel`` (``record["q"]``)."""
        return self.series[channel]


def no_terms(compiled: CompiledScene, n_rows: int) -> np.ndarray:
    """The ``terms`` channel of a run that computes no hydrodynamic terms: zeros (n_rows, n_terms)."""
    return np.zeros((n_rows, TERM_COLUMNS * len(compiled.device.model.bodies)))


def stats_start(compiled: CompiledScene) -> int:
    """First step of the statistics window (the last ``outputs.window`` share of the steps)."""
    n = compiled.n_steps
    return n - max(1, round(compiled.scene.outputs.window * n)) + 1


def continuous_power(compiled: CompiledScene, x: np.ndarray, xd: np.ndarray, f: np.ndarray) -> np.ndarray:
    """Absorbed power of a continuous PTO force law (linear gains) at the steps: -(f + k_spring x) x_dot for
    strokes ``x``, rates ``xd`` and forces ``f`` (the device spring included, as recorded) (n, n_pto) [W]; the
    device spring's force is conservative and left out."""
    return -(f + compiled.plant.pto_spring * x) * xd


def held_power(held: np.ndarray, x: np.ndarray, dt: float) -> np.ndarray:
    """Absorbed power of PTO forces ``held`` over each step (row k: the force over the step ending at step k),
    the work -f_k (x_k - x_{k-1}) over the step ``dt`` [s] divided by it, exact for a held force (n, n_pto) [W];
    0 at step 0."""
    out = np.zeros_like(x)
    out[1:] = -held[1:] * np.diff(x, axis=0) / dt
    return out


def window_statistics(compiled: CompiledScene, x: np.ndarray, power: np.ndarray) -> np.ndarray:
    """Sums over the statistics window of every-step PTO strokes ``x`` and the absorbed power of each step
    ``power`` (n_steps + 1, n_pto; :func:`continuous_power` or :func:`held_power`): absorbed power, stroke^2,
    count, stroke; what the fixed-step kernels accumulate as they go."""
    window = slice(stats_start(compiled), None)
    xs = x[window]
    return np.stack([power[window].sum(0), (xs**2).sum(0), np.full(x.shape[1], float(xs.shape[0])), xs.sum(0)])


def limit_counts(stroke: np.ndarray, control: np.ndarray, limits: tuple[np.ndarray, np.ndarray]) -> np.ndarray:
    """What the fixed-step kernels count of the PTO limits, from every-step strokes (from rest) and controller
    forces (n_steps, n_pto) of a run and the (force, stroke) limits per PTO: (4, n_pto) steps with the force at its
    limit, episodes of it, steps with the stroke beyond its limit, episodes of that."""
    force_limit, stroke_limit = limits
    rows = []
    for active in (np.abs(control) >= force_limit * (1.0 - 1e-12), np.abs(stroke) > stroke_limit):
        starts = active[0].astype(np.int64) + np.sum(active[1:] & ~active[:-1], axis=0)
        rows += [np.sum(active, axis=0), starts]
    return np.array(rows, dtype=np.int64).reshape(4, -1)
