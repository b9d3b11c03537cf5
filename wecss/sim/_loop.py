"""What the fixed-step integrators share: the state they advance in place (:class:`LoopState`), the settings fixed
over a run (:class:`StepSettings`), where they record a run (:class:`Store`, allocated from the output table's
channels by :func:`new_store`), the one recording kernel (:func:`record_step`), and how a chunk of steps ends
(:class:`LoopStatus`)."""

from __future__ import annotations

from enum import IntEnum
from typing import NamedTuple

import numpy as np

from ..compiled import Plant, RadiationArrays
from ..compiled.kernels import Workspace, kernel
from ..outputs import CHANNEL_NAMES, CHANNELS

ACCELERATION_FLOOR: float = 1e-11
"""Absolute floor [m/s^2 or rad/s^2] of the corrector's convergence test: changes of the accelerations below it are
round-off (static loads of order m g cancel in them), so a body at rest converges too."""

_X, _XD, _F = (CHANNEL_NAMES.index(name) for name in ("x", "xd", "f"))


class LoopStatus(IntEnum):
    """How a chunk of steps ended (numba returns the members)."""

    OK = 0
    NOT_FINITE = 1
    """The state became non-finite."""
    OUT_OF_BOUNDS = 2
    """A bounded coordinate (revolute angle) passed its bound."""
    CORRECTOR_FAILED = 3
    """The corrector (fixed point and Newton, or the explicit added-mass iteration) did not converge."""
    STROKE_LIMIT = 4
    """A PTO stroke passed its limit where the PTO has no end stop."""


class Store(NamedTuple):
    """Where the integrators record a run.

    Every ``every``-th step (0: none) the arrays the step hands over (one per channel of ``wecss.outputs.CHANNELS``,
    in that order) go into the rows ``save_index[0]`` of ``series``, column c of channel s taken from entry
    ``columns[s][c]`` of its source (the hydro DOFs stored grouped by kind, see ``_layout``); an array of
    ``series`` may have a single row instead of one per saved step: a scratch row, overwritten, for what no output
    of the run reads. Running sums over the steps from ``stats_start`` on go into ``stats`` (absorbed power,
    stroke^2, count, stroke per PTO), [corrector evaluations, largest per step, Newton steps] into
    ``evaluations``, and per PTO into ``limits`` (4, n_pto): the steps with the force at its limit, the episodes
    of it (steps where it starts), the steps with the stroke beyond its limit (the end stop engaged), the episodes
    of that (``limit_last``: the last step each was active).

    The absorbed PTO power of each step (the channel ``p``, made here: ``power``) is the work of the force over the
    step divided by the step ``h``: for a sampled controller (``sampled``) the force ``held`` over the step (the
    loop sets it at each command: the command saturated at the force limit) times the stroke's change since the
    last step (``last_stroke``), exact for a held force; for a continuous force law (linear gains, or no
    controller force) its power at the step's end, -(f + k_spring x) x_dot, whose sum over the window is the
    rectangle rule."""

    every: int
    stats_start: int
    series: tuple[np.ndarray, ...]
    columns: tuple[np.ndarray, ...]
    save_index: np.ndarray
    stats: np.ndarray
    evaluations: np.ndarray
    limits: np.ndarray
    limit_last: np.ndarray
    sampled: bool
    h: float
    held: np.ndarray
    last_stroke: np.ndarray
    power: np.ndarray


def new_store(
    every: int,
    stats_start: int,
    n_rows: int,
    sizes: dict[str, int],
    groups: tuple[str, ...],
    columns: dict[str, np.ndarray],
    *,
    sampled: bool = False,
    h: float = 1.0,
) -> Store:
    """A :class:`Store` with ``n_rows`` saved rows (0: none) for the channels the output ``groups`` read (and
    those always kept), one scratch row for the others. ``sizes``: columns per size name of the channels ("nq",
    "nv", "n_pto", "n_h"); ``columns``: the stored column order of a channel where it is not the natural one;
    ``sampled``: the PTO force is a sampled controller's, held over each step ``h`` [s] (its power is its work;
    set ``held`` and ``last_stroke`` before the first step)."""
    series, maps = [], []
    for channel in CHANNELS:
        width = sizes[channel.size]
        wanted = channel.kept or any(group in groups for group in channel.groups)
        rows = n_rows if (channel.kept or (n_rows and wanted)) else 1
        series.append(np.zeros((rows, width)))
        maps.append(np.ascontiguousarray(columns.get(channel.name, np.arange(width)), dtype=np.int64))
    n_pto = sizes["n_pto"]
    return Store(
        every=every,
        stats_start=stats_start,
        series=tuple(series),
        columns=tuple(maps),
        save_index=np.zeros(1, dtype=np.int64),
        stats=np.zeros((4, n_pto)),
        evaluations=np.zeros(3, dtype=np.int64),
        limits=np.zeros((4, n_pto), dtype=np.int64),
        limit_last=np.full((2, n_pto), -2, dtype=np.int64),
        sampled=bool(sampled),
        h=float(h),
        held=np.zeros(n_pto),
        last_stroke=np.zeros(n_pto),
        power=np.zeros(n_pto),
    )


class StepSettings(NamedTuple):
    """What stays fixed over a run's steps: the step ``h`` [s], the corrector's relative tolerance ``tol`` and
    ``max_iterations``, and the coordinates ``bounded`` whose size may not pass ``angle_bound`` [rad]."""

    h: float
    tol: float
    max_iterations: int
    bounded: np.ndarray
    angle_bound: float


class LoopState(NamedTuple):
    """The state the integrators advance in place: configuration ``q``, velocities ``v``, accelerations ``acc``
    and those of the step before ``acc_prev`` (Beeman), complex radiation states ``z``, the newest hydro velocity
    ``u_now`` and the convolution's velocity ring buffer ``buf`` with its position ``pos`` (1,), ``pto_now``
    (3, n_pto): PTO strokes, rates and forces at the current state (what controllers measure), and ``far`` the
    convolution's far sums of the current block (``wecss.sim._memory``; a block of ``far.shape[0]`` steps starts
    at every global step that is a multiple of it)."""

    q: np.ndarray
    v: np.ndarray
    acc: np.ndarray
    acc_prev: np.ndarray
    z: np.ndarray
    u_now: np.ndarray
    buf: np.ndarray
    pos: np.ndarray
    pto_now: np.ndarray
    far: np.ndarray


class Chunk(NamedTuple):
    """What the fixed-step loop hands an integrator for a chunk of steps (``FixedStepRunner.advance``), in the
    order of the built-in chunk kernels' arguments: the plant ``p``, the radiation arrays ``r``, the chunk's
    ``excitation`` rows (the steps' times, and the stages between them where the runner asks for them), the held
    PTO ``command`` [N or N m], the global step ``step0`` the chunk starts at, the ``settings``, the ``state``
    advanced in place, the store ``out`` each step is recorded into (:func:`record_step`) and the kernels'
    workspace ``work``."""

    p: Plant
    r: RadiationArrays
    excitation: np.ndarray
    command: np.ndarray
    step0: int
    settings: StepSettings
    state: LoopState
    out: Store
    work: Workspace


@kernel
def passes_stroke_limit(p: Plant, x: np.ndarray) -> bool:
    """A stroke beyond its limit on a PTO without an end stop (the run must stop)."""
    for k in range(x.shape[0]):
        if abs(x[k]) > p.pto_stroke_limit[k] and p.pto_stop_stiffness[k] == 0.0:
            return True
    return False


@kernel
def out_of_bounds(q: np.ndarray, bounded: np.ndarray, bound: float) -> bool:
    """A bounded coordinate (``bounded``: indices into ``q``) beyond ``bound`` [rad]."""
    for k in bounded:
        if abs(q[k]) > bound:
            return True
    return False


@kernel
def record_step(out: Store, n1: int, p: Plant, sources: tuple[np.ndarray, ...]) -> None:
    """Record global step ``n1``: ``sources`` the step's arrays, one per channel in ``wecss.outputs.CHANNELS``'s
    order but the recorder's own (configuration, velocities, accelerations, PTO strokes, rates, forces, memory
    force and excitation on the hydro DOFs in the database's order); the step's absorbed PTO power, the saved
    rows, the limits' counts and the window's sums (see :class:`Store`)."""
    x, xd, f = sources[_X], sources[_XD], sources[_F]
    spring = p.pto_spring
    power = out.power
    for k in range(x.shape[0]):
        if out.sampled:  # the held force's work over the step (the device spring is conservative, left out)
            power[k] = -out.held[k] * (x[k] - out.last_stroke[k]) / out.h
        else:  # a continuous force law: its power at the step's end
            power[k] = -(f[k] + spring[k] * x[k]) * xd[k]
        out.last_stroke[k] = x[k]
    series = out.series
    if out.every > 0 and n1 % out.every == 0 and out.save_index[0] < series[0].shape[0]:
        j = out.save_index[0]
        for s in range(len(series)):
            dest = series[s]
            source = sources[s] if s < len(sources) else power  # the recorder's own channel comes last
            order = out.columns[s]
            row = min(j, dest.shape[0] - 1)  # one scratch row where no output reads the channel
            for c in range(order.shape[0]):
                dest[row, c] = source[order[c]]
        out.save_index[0] = j + 1
    for k in range(x.shape[0]):
        saturated = abs(f[k] + p.pto_spring[k] * x[k]) >= p.pto_force_limit[k] * (1.0 - 1e-12)
        stopped = abs(x[k]) > p.pto_stroke_limit[k]
        for row, active in ((0, saturated), (2, stopped)):  # force at its limit; stroke beyond it (end stop)
            if active:
                if out.limit_last[row // 2, k] != n1 - 1:
                    out.limits[row + 1, k] += 1  # an episode starts
                out.limits[row, k] += 1
                out.limit_last[row // 2, k] = n1
    if n1 >= out.stats_start:
        out.stats[0] += power
        out.stats[1] += x * x
        out.stats[2] += 1.0
        out.stats[3] += x
