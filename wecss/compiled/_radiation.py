"""Radiation memory as flat arrays for the time loop: a discretised state-space model or a sparse convolution.

Both give the memory force at the end of a step as ``history + newest @ u_new``: a part fixed by the past
(computed once per step) plus a constant matrix on the new hydro velocity, so a corrector only repeats the
small product (DESIGN.md, "Radiation memory").

State space, in complex modal form (one state per real pole or conjugate pair): z_dot = lambda z + b u,
F = -Re(c z). Over a step the velocity is taken linear in time (first-order hold), which the exponential
integrates exactly: z1 = e^{lambda h} z0 + h (phi1 - phi2) b u0 + h phi2 b u1, phi1 = (e - 1)/(lambda h),
phi2 = (e - 1 - lambda h)/(lambda h)^2. Unconditionally stable and second order, like the Beeman scheme.
The time loop applies these maps in real form, on the real and imaginary parts of z side by side
(``z.view(float)``): the hydro velocities are real, so a complex product with them wastes half its
multiplications, and the part of the force fixed at the start of a step, -Re(c (e^{lambda h} z0 + h (phi1 - phi2)
b u0)), is one real product with z0 and one with u0.

Convolution, by the trapezoidal rule on the simulation step, entry by entry: each kernel entry that
``wecss.radiation.significant_couplings`` keeps has its own memory (MEMORY_FACTOR times its 1 % truncation
time); the others are dropped (reported).
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import IntEnum
from typing import NamedTuple

import numpy as np

from ..radiation import MEMORY_FACTOR, ImpulseResponse, RadiationStateSpace, significant_couplings
from ._linalg import complex_columns, real_part_rows
from ._phi import phi_functions

FINE_MEMORY: float = 3.0
"""Convolution lags up to this time [s] use every simulation step (the kernel changes fast near t = 0)."""

COARSE_STEP: float = 0.06
"""Step [s] of the trapezoidal rule for older lags, where the kernel is smooth. On the default scene (M4 134, Tp
1.2 s, dt 6 ms) the hinge angles differ from the every-step rule by 4.4e-4 of their RMS (0.03 s: 1.1e-4), at a
fifth of the cost."""


class RadiationKind(IntEnum):
    """How the memory force is computed (the ``kind`` of :class:`RadiationArrays`; numba compares the members).
    The scene's ``radiation.method`` names it (:meth:`from_method`, :attr:`method`)."""

    NONE = 0
    STATE_SPACE = 1
    CONVOLUTION = 2

    @classmethod
    def from_method(cls, method: str) -> RadiationKind:
        """The kind a scene's ``radiation.method`` ("none", "state_space", "convolution") names.

        Raises
        ------
        ValueError
            For another name.
        """
        try:
            return cls[method.upper()]
        except KeyError:
            raise ValueError(
                f"unknown radiation method {method!r}; accepted: {', '.join(k.method for k in cls)}"
            ) from None

    @property
    def method(self) -> str:
        """The scene's name of this kind (``radiation.method``)."""
        return self.name.lower()


class RadiationArrays(NamedTuple):
    """Arrays of the radiation memory read by the integrators (``kind``: a :class:`RadiationKind`, stored as int).

    State space: ``poles`` (nz,), ``input`` (nz, n_h), ``output`` (n_h, nz) complex (F = -Re(output z)),
    ``decay`` e^{lambda h}, ``hold0``, ``hold1`` (nz, n_h) the first-order-hold input matrices.
    Convolution, grouped by the radiating DOF (column) c, whose kept entries have rows ``row[col[c]:col[c + 1]]``:
    a fine part (lags 1 ... ``fine_length[c]``) stored from ``fine_start[c]`` as a (lag, row) block, oldest lag
    first, and a coarse tail (every ``stride``-th lag after the fine part, ``coarse_length[c]`` lags) stored the same
    way in ``coarse``; values carry the quadrature weights and the sign (force = sum of value * velocity), and
    entries with a shorter memory are padded with zeros. ``depth``: length of the velocity ring buffer.
    Both: ``newest`` (n_h, n_h), the memory force per unit new velocity, and ``dt`` the step [s] the arrays were
    made for (0.0 for no memory: no step baked in).
    State space in real form, on the interleaved real and imaginary parts ``z.view(float)`` (2 nz,):
    ``output_real`` (n_h, 2 nz) with F = output_real @ z.view(float) = -Re(output z); ``input_real`` (2 nz, n_h)
    the rows of ``input`` (b u); ``history_state`` (n_h, 2 nz) and ``history_input`` (n_h, n_h), the force at the
    end of a step without its newest-velocity term, history_state @ z0.view(float) + history_input @ u0; and
    ``hold_real`` (2 nz, 2 n_h), the step's input [hold0, hold1] @ [u0, u1].
    """

    kind: int
    poles: np.ndarray
    input: np.ndarray
    output: np.ndarray
    decay: np.ndarray
    hold0: np.ndarray
    hold1: np.ndarray
    row: np.ndarray
    col: np.ndarray
    fine_start: np.ndarray
    fine_length: np.ndarray
    coarse_start: np.ndarray
    coarse_length: np.ndarray
    fine: np.ndarray
    coarse: np.ndarray
    stride: int
    depth: int
    dt: float
    newest: np.ndarray
    output_real: np.ndarray
    input_real: np.ndarray
    history_state: np.ndarray
    history_input: np.ndarray
    hold_real: np.ndarray


@dataclass(frozen=True)
class RadiationSummary:
    """What a radiation model kept: its kind, states or memory steps, and the dropped couplings."""

    kind: RadiationKind
    states: int = 0
    entries: int = 0
    dropped_entries: tuple[str, ...] = ()
    memory: float = 0.0
    max_pole: float = 0.0
    multiply_adds: int = 0
    stride: int = 1
    fine_memory: float = 0.0

    def __str__(self) -> str:
        if self.kind == RadiationKind.NONE:
            return "no radiation memory"
        if self.kind == RadiationKind.STATE_SPACE:
            return f"state space, {self.states} complex modal states, fastest pole at {self.max_pole:.4g} rad/s"
        dropped = f"; dropped {len(self.dropped_entries)} couplings below the threshold" if self.dropped_entries else ""
        return (
            f"convolution, {self.entries} kernel entries, longest memory {self.memory:.4g} s, every {self.stride}-th "
            f"step beyond the first {self.fine_memory:.4g} s, {self.multiply_adds} multiply-adds per step{dropped}"
        )


def _empty(n_h: int, kind: RadiationKind, newest: np.ndarray, dt: float = 0.0) -> dict:
    c0 = np.zeros((0, n_h), dtype=complex)
    return {
        "kind": int(kind),
        "dt": float(dt),
        "poles": np.zeros(0, dtype=complex),
        "input": c0,
        "output": np.zeros((n_h, 0), dtype=complex),
        "decay": np.zeros(0, dtype=complex),
        "hold0": c0,
        "hold1": c0,
        "row": np.zeros(0, dtype=np.int64),
        "col": np.zeros(0, dtype=np.int64),
        "fine_start": np.zeros(0, dtype=np.int64),
        "fine_length": np.zeros(0, dtype=np.int64),
        "coarse_start": np.zeros(0, dtype=np.int64),
        "coarse_length": np.zeros(0, dtype=np.int64),
        "fine": np.zeros(0),
        "coarse": np.zeros(0),
        "stride": 1,
        "depth": 1,
        "newest": newest,
        "output_real": np.zeros((n_h, 0)),
        "input_real": np.zeros((0, n_h)),
        "history_state": np.zeros((n_h, 0)),
        "history_input": np.zeros((n_h, n_h)),
        "hold_real": np.zeros((0, 2 * n_h)),
    }


def no_radiation(n_h: int) -> tuple[RadiationArrays, RadiationSummary]:
    """No memory force (for tests of the mechanics alone)."""
    return RadiationArrays(**_empty(n_h, RadiationKind.NONE, np.zeros((n_h, n_h)))), RadiationSummary(
        RadiationKind.NONE
    )


def from_state_space(model: RadiationStateSpace, dt: float) -> tuple[RadiationArrays, RadiationSummary]:
    """Complex modal, first-order-hold discretisation of ``model`` for the step ``dt`` [s]."""
    n_h = len(model.dofs)
    lam, left, inp, pair = model.half_modal()  # one of each conjugate pair, and the real poles
    output = left * np.where(pair, 2.0, 1.0)[None, :]
    phi1, phi2, _ = phi_functions(lam * dt)
    hold1 = (dt * phi2)[:, None] * inp
    hold0 = (dt * (phi1 - phi2))[:, None] * inp
    arrays = _empty(n_h, RadiationKind.STATE_SPACE, -np.real(output @ hold1), dt)
    arrays.update(
        poles=lam.astype(complex),
        input=np.ascontiguousarray(inp, dtype=complex),
        output=np.ascontiguousarray(output, dtype=complex),
        decay=np.exp(lam * dt),
        hold0=np.ascontiguousarray(hold0),
        hold1=np.ascontiguousarray(hold1),
        output_real=np.ascontiguousarray(-real_part_rows(output.T).T),
        input_real=np.ascontiguousarray(complex_columns(inp.T).T),
        history_state=np.ascontiguousarray(-real_part_rows((output * np.exp(lam * dt)[None, :]).T).T),
        history_input=-np.real(output @ hold0),
        hold_real=np.ascontiguousarray(np.hstack([complex_columns(hold0.T).T, complex_columns(hold1.T).T])),
    )
    max_pole = float(np.max(np.abs(lam))) if lam.size else 0.0
    return RadiationArrays(**arrays), RadiationSummary(
        RadiationKind.STATE_SPACE, states=int(lam.size), max_pole=max_pole
    )


def from_impulse_response(
    irf: ImpulseResponse,
    dt: float,
    *,
    coupling_threshold: float = 1e-3,
    memory_factor: float = MEMORY_FACTOR,
    fine_memory: float = FINE_MEMORY,
    coarse_step: float = COARSE_STEP,
) -> tuple[RadiationArrays, RadiationSummary]:
    """Sparse trapezoidal convolution on the step ``dt`` [s] (see the module docstring).

    Parameters
    ----------
    coupling_threshold : float
        Entries that :func:`wecss.radiation.significant_couplings` drops at this threshold are left out [-].
    memory_factor : float
        Memory of each entry as a multiple of its 1 % truncation time (at most the kernel's length).
    fine_memory : float
        Lags up to this time [s] use every step; older lags use the trapezoidal rule on a coarser grid.
    coarse_step : float
        Step of that coarser grid [s] (rounded to a whole number of steps; 0 for no coarse tail).
    """
    if not dt > 0:
        raise ValueError(f"dt must be positive [s]; got {dt!r}")
    n_h = len(irf.dofs)
    kept = significant_couplings(np.max(np.abs(irf.kernel), axis=0), coupling_threshold)
    t_max = float(irf.time[-1])
    stride = max(1, round(coarse_step / dt))
    n_fine = max(1, int(np.ceil(fine_memory / dt / stride)) * stride)  # a multiple of the stride
    memory = np.minimum(memory_factor * irf.truncation_time, t_max)
    n_lags = np.maximum(1, np.ceil(memory / dt).astype(np.int64))
    # fine lags 1..min(n_lags, n_fine); coarse lags n_fine + stride * k, k = 1..K, up to the entry's memory
    n_coarse = np.where(n_lags > n_fine, np.ceil((n_lags - n_fine) / stride).astype(np.int64), 0)
    longest = int(np.max(np.where(kept, np.minimum(n_lags, n_fine) + stride * n_coarse, 1)))
    kernel = irf.at(np.arange(longest + 1) * dt)  # (lags, n_h, n_h), lag 0 first
    rows: list[int] = []
    col_ptr = [0]
    fine_start, fine_length, coarse_start, coarse_length = [], [], [], []
    fine_values: list[np.ndarray] = []
    coarse_values: list[np.ndarray] = []
    dropped: list[str] = []
    newest = np.zeros((n_h, n_h))
    f0 = c0 = 0
    for j in range(n_h):
        members = [i for i in range(n_h) if kept[i, j]]
        dropped.extend(f"{irf.dofs[i]}|{irf.dofs[j]}" for i in range(n_h) if not kept[i, j])
        nf = int(max((min(n_lags[i, j], n_fine) for i in members), default=0))
        nc = int(max((n_coarse[i, j] for i in members), default=0))
        fine = np.zeros((nf, len(members)))
        coarse = np.zeros((nc, len(members)))
        for k, i in enumerate(members):
            nf_i = int(min(n_lags[i, j], n_fine))
            nc_i = int(n_coarse[i, j])
            w_fine = np.full(nf_i, dt)
            w_coarse = np.full(nc_i, stride * dt)
            if nc_i:
                w_fine[-1] = 0.5 * dt + 0.5 * stride * dt  # junction of the two grids
                w_coarse[-1] = 0.5 * stride * dt
            else:
                w_fine[-1] = 0.5 * dt
            lag_coarse = n_fine + stride * np.arange(1, nc_i + 1)
            fine[nf - nf_i :, k] = (-w_fine * kernel[1 : nf_i + 1, i, j])[::-1]  # oldest first, newest last
            coarse[nc - nc_i :, k] = (-w_coarse * kernel[lag_coarse, i, j])[::-1]
            newest[i, j] = -0.5 * dt * kernel[0, i, j]
        rows.extend(members)
        col_ptr.append(len(rows))
        fine_start.append(f0)
        fine_length.append(nf)
        coarse_start.append(c0)
        coarse_length.append(nc)
        fine_values.append(fine.reshape(-1))
        coarse_values.append(coarse.reshape(-1))
        f0 += fine.size
        c0 += coarse.size
    arrays = _empty(n_h, RadiationKind.CONVOLUTION, newest, dt)
    ints = {k: np.asarray(v, dtype=np.int64) for k, v in (
        ("row", rows), ("col", col_ptr), ("fine_start", fine_start), ("fine_length", fine_length),
        ("coarse_start", coarse_start), ("coarse_length", coarse_length),
    )}  # fmt: skip
    arrays.update(
        ints,
        fine=np.concatenate(fine_values),
        coarse=np.concatenate(coarse_values),
        stride=stride,
        depth=longest + 1,
    )
    summary = RadiationSummary(
        RadiationKind.CONVOLUTION,
        entries=len(rows),
        dropped_entries=tuple(dropped),
        memory=longest * dt,
        multiply_adds=int(arrays["fine"].size + arrays["coarse"].size),
        stride=stride,
        fine_memory=n_fine * dt,
    )
    return RadiationArrays(**arrays), summary


def memory_response(arrays: RadiationArrays, omega: np.ndarray, dt: float) -> np.ndarray:
    """K_hat(omega) (n_omega, n_h, n_h) of the memory model as the simulator applies it, so that the memory force
    of a velocity Re[u e^{i omega t}] is -Re[K_hat u e^{i omega t}] (discrete sums for the convolution, the
    continuous response for the state space)."""
    omega = np.atleast_1d(np.asarray(omega, dtype=float))
    n_h = arrays.newest.shape[0]
    out = np.zeros((omega.size, n_h, n_h), dtype=complex)
    if arrays.kind == RadiationKind.STATE_SPACE:
        resolvent = 1.0 / (1j * omega[:, None] - arrays.poles[None, :])
        # C diag(resolvent) B as one batched matrix product (an unoptimised three-operand einsum took ~0.3 s)
        full = (arrays.output[None, :, :] * resolvent[:, None, :]) @ arrays.input
        # the kept states stand for conjugate pairs: Re(c z) = (c z + conj(c z)) / 2 per pair, exactly the real part
        # of the pair's response; this equals (full(omega) + conj(full(-omega))) / 2
        mirror_resolvent = 1.0 / (-1j * omega[:, None] - arrays.poles[None, :])
        mirror = (arrays.output[None, :, :] * mirror_resolvent[:, None, :]) @ arrays.input
        return 0.5 * (full + np.conj(mirror))
    if arrays.kind == RadiationKind.CONVOLUTION:
        out -= arrays.newest[None]
        _subtract_convolution_response(arrays, omega, dt, out)
    return out


def _convolution_groups(arrays: RadiationArrays) -> list[tuple[np.ndarray, np.ndarray, list[tuple[np.ndarray, int]]]]:
    """The convolution's stored lags grouped by columns with the same lags (usually all of them): per group the lags
    [steps] (oldest first), the kernel values (n_lags, n_entries) side by side and per column its rows and index,
    in the order of the values' columns."""
    n_h = arrays.newest.shape[0]
    groups: dict[tuple[int, int], list[int]] = {}
    for c in range(n_h):
        groups.setdefault((int(arrays.fine_length[c]), int(arrays.coarse_length[c])), []).append(c)
    out = []
    for (nf, nc), columns in groups.items():
        lags = np.concatenate([np.arange(nf, 0, -1), nf + arrays.stride * np.arange(nc, 0, -1)])
        blocks, targets = [], []
        for c in columns:
            members = arrays.row[arrays.col[c] : arrays.col[c + 1]]
            size = members.size  # (an empty block, such as a coarse tail of no lags, keeps its shape)
            fine = arrays.fine[arrays.fine_start[c] : arrays.fine_start[c] + nf * size].reshape(nf, size)
            coarse = arrays.coarse[arrays.coarse_start[c] : arrays.coarse_start[c] + nc * size].reshape(nc, size)
            blocks.append(np.concatenate([fine, coarse]))
            targets.append((members, c))
        out.append((lags, np.concatenate(blocks, axis=1), targets))
    return out


def _subtract_convolution_response(arrays: RadiationArrays, omega: np.ndarray, dt: float, out: np.ndarray) -> None:
    """Subtract sum_k K_k exp(-i omega tau_k) of the convolution's stored lags from ``out`` (n_omega, n_h, n_h).

    Columns with the same lags share one cos/sin table of omega tau_k and one pair of real matrix products: the
    exponentials, not the products, dominated when each column built its own (0.28 s for m4-134 at 359
    frequencies)."""
    for lags, values, targets in _convolution_groups(arrays):
        phase = np.outer(omega, lags * dt)
        real, imag = np.cos(phase) @ values, np.sin(phase) @ values  # exp(-i x) = cos x - i sin x
        start = 0
        for members, c in targets:
            part = slice(start, start + members.size)
            out[:, members, c] -= real[:, part] - 1j * imag[:, part]
            start += members.size


def weighted_memory_response(arrays: RadiationArrays, omega: np.ndarray, weights: np.ndarray, dt: float) -> np.ndarray:
    """sum_k w_k K_hat(omega_k) (n_h, n_h) over frequencies ``omega`` [rad/s] with real weights ``weights``, where
    K_hat is :func:`memory_response`, without making K_hat at each frequency.

    The response is linear in the state-space resolvents 1 / (i omega - lambda) and in the convolution's phasors
    exp(-i omega tau), so the weights sum those first: the work is n_omega x n_states (or n_omega x n_lags) instead
    of n_omega x n_h^2 x n_states, the memory a block of WEIGHTED_BLOCK frequencies. Equal to the weighted sum of
    :func:`memory_response` to round-off.
    """
    omega = np.atleast_1d(np.asarray(omega, dtype=float))
    weights = np.broadcast_to(np.asarray(weights, dtype=float), omega.shape)
    n_h = arrays.newest.shape[0]
    blocks = [slice(start, start + WEIGHTED_BLOCK) for start in range(0, omega.size, WEIGHTED_BLOCK)]
    if arrays.kind == RadiationKind.STATE_SPACE:
        full = np.zeros(arrays.poles.size, dtype=complex)  # sum_k w_k / (i omega_k - lambda)
        mirror = np.zeros(arrays.poles.size, dtype=complex)  # sum_k w_k / (-i omega_k - lambda)
        for b in blocks:
            full += weights[b] @ (1.0 / (1j * omega[b, None] - arrays.poles[None, :]))
            mirror += weights[b] @ (1.0 / (-1j * omega[b, None] - arrays.poles[None, :]))
        # as in memory_response: the kept states stand for conjugate pairs
        return 0.5 * ((arrays.output * full) @ arrays.input + np.conj((arrays.output * mirror) @ arrays.input))
    out = np.zeros((n_h, n_h), dtype=complex)
    if arrays.kind == RadiationKind.CONVOLUTION:
        out -= arrays.newest * weights.sum()
        for lags, values, targets in _convolution_groups(arrays):
            phasor = np.zeros(lags.size, dtype=complex)  # sum_k w_k exp(-i omega_k tau)
            for b in blocks:
                phase = np.outer(omega[b], lags * dt)
                phasor += weights[b] @ np.cos(phase) - 1j * (weights[b] @ np.sin(phase))
            summed = phasor @ values
            start = 0
            for members, c in targets:
                out[members, c] -= summed[start : start + members.size]
                start += members.size
    return out


WEIGHTED_BLOCK: int = 2048
"""Frequencies per block in :func:`weighted_memory_response` (a block holds n_states or n_lags complex values per
frequency)."""


def interpolate_matrices(omega_data: np.ndarray, values: np.ndarray, omega: np.ndarray) -> np.ndarray:
    """Linear interpolation of (n_omega, n, n) coefficient matrices to the frequencies ``omega`` [rad/s]."""
    omega = np.asarray(omega, dtype=float)
    flat = values.reshape(omega_data.size, -1)
    if omega_data.size == 1:
        return np.broadcast_to(values, (omega.size, *values.shape[1:])).copy()
    # as np.interp, on all entries at once: the interval's slope from its left end, the end values outside
    j = np.clip(np.searchsorted(omega_data, omega, side="right") - 1, 0, omega_data.size - 2)
    slope = (flat[j + 1] - flat[j]) / (omega_data[j + 1] - omega_data[j])[:, None]
    out = slope * (omega - omega_data[j])[:, None] + flat[j]
    out[omega <= omega_data[0]] = flat[0]
    out[omega >= omega_data[-1]] = flat[-1]
    return out.reshape(omega.size, *values.shape[1:])


def added_mass_correction(
    arrays: RadiationArrays,
    dt: float,
    omega_data: np.ndarray,
    added_mass: np.ndarray,
    added_mass_inf: np.ndarray,
    omega: np.ndarray,
    weights: np.ndarray,
) -> np.ndarray:
    """Correction dA to A_inf (n_h, n_h) so that A_inf + dA + Im K_hat(omega)/omega matches the database's A(omega)
    in the weighted least-squares sense over ``omega`` (the sea state's frequencies).

    BEM codes compute A_inf separately from A(omega); the memory model implies its own A(omega) - A_inf through the
    Kramers-Kronig relation of the damping (Ogilvie 1964), which with a finite frequency range and a fitted tail
    is not exactly the database's. Without the correction the time-domain added mass is off by that constant.
    """
    w = np.asarray(weights, dtype=float) / np.sum(weights)
    omega = np.asarray(omega, dtype=float)
    # sum_k w_k (A(omega_k) - A_inf - Im K_hat(omega_k) / omega_k), the memory's part summed over frequencies first
    correction = -np.imag(weighted_memory_response(arrays, omega, w / omega, dt)) - added_mass_inf * w.sum()
    for start in range(0, omega.size, RESPONSE_BLOCK):  # in blocks: long runs have 10^4 frequencies and more
        block = slice(start, start + RESPONSE_BLOCK)
        correction += np.einsum("w,wij->ij", w[block], interpolate_matrices(omega_data, added_mass, omega[block]))
    return 0.5 * (correction + correction.T)


RESPONSE_BLOCK: int = 256
"""Frequencies per block of the database's interpolated added mass in :func:`added_mass_correction` (n_h x n_h
values per frequency)."""
