"""Complex load amplitudes per wave frequency for frequency-domain runs (``solver.method = "frequency"``).

The loads of a run are a function L(z) of the record at a step, z = (q, v, v_dot, PTO stroke, rate and force,
excitation plus radiation memory on the hydro DOFs) (:func:`wecss.sim._loads.recover_loads`). Linearised about the
equilibrium z0 (q0, v = 0, v_dot = 0, the rest stroke and its spring force, no wave load), L(z0 + dz) = L(z0) + J dz.
The frequency-domain solution gives every entry of dz as Re[dz_hat_k exp(+i omega_k t)] on the wave components, so
the loads are L(z0) + Re[sum_k (J dz_hat_k) exp(+i omega_k t)]: the equilibrium loads and the complex amplitudes
J dz_hat_k, in the wave's e^{+i omega t} convention and with its amplitudes and phases (not per unit wave).

J is found by central differences of the exact recovery: L is affine in v_dot, the PTO force and the hydro loads at
v = 0 and quadratic in v (gyroscopic and Bdot terms), where central differences are exact to round-off; in q
(rotations) the step 1e-5 [m or rad] leaves a relative error of order 1e-10.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..compiled import CompiledScene
from ._loads import Loads, recover_loads

_STEP = {"q": 1e-5, "v": 1e-3, "a": 1.0, "x": 1e-6, "xd": 1e-6, "f": 1.0, "h": 1.0}
"""Central-difference steps per input block [SI units of the block]."""


@dataclass
class Spectral:
    """The record of a frequency-domain run as amplitudes: the equilibrium ``z0`` and the complex amplitudes
    ``z_hat`` (n_w columns) of each input block (keys ``q, v, a, x, xd, f, h`` as in :data:`_STEP`) on the wave
    frequencies ``omega`` [rad/s]."""

    omega: np.ndarray
    z0: dict[str, np.ndarray]
    z_hat: dict[str, np.ndarray]


_FIELDS = (
    "joint_force",
    "joint_moment",
    "joint_force_local",
    "joint_moment_local",
    "pto_body_force",
    "pto_body_moment",
    "section",
)


def _loads_of(compiled: CompiledScene, rows: dict[str, np.ndarray]) -> Loads:
    return recover_loads(compiled, rows["q"], rows["v"], rows["a"], (rows["x"], rows["xd"], rows["f"]), rows["h"])


def load_amplitudes(compiled: CompiledScene, spectral: Spectral) -> tuple[Loads, Loads]:
    """The equilibrium loads (n_t = 1) and the complex load amplitudes (n_t = n_w: one row per wave frequency) as
    :class:`Loads` (their ``closure`` is not meaningful here and is 0)."""
    keys = list(_STEP)
    sizes = [spectral.z0[k].size for k in keys]
    n_in = sum(sizes)
    rows = {k: np.repeat(spectral.z0[k][None], 2 * n_in + 1, axis=0) for k in keys}
    steps = np.zeros(n_in)
    col = 0
    for k, size in zip(keys, sizes, strict=True):
        for j in range(size):
            rows[k][1 + 2 * col, j] += _STEP[k]
            rows[k][2 + 2 * col, j] -= _STEP[k]
            steps[col] = _STEP[k]
            col += 1
    loads = _loads_of(compiled, rows)
    equilibrium = Loads(**{f: getattr(loads, f)[:1] for f in _FIELDS}, closure=0.0)
    z_hat = np.concatenate([spectral.z_hat[k] for k in keys], axis=0)  # (n_in, n_w)
    out: dict[str, Any] = {}
    for f in _FIELDS:
        values = getattr(loads, f)
        jac = (values[1::2] - values[2::2]) / (2 * steps.reshape((-1,) + (1,) * (values.ndim - 1)))
        out[f] = np.tensordot(z_hat.T, jac, axes=1)  # (n_w, ...)
    amplitudes = Loads(**out, closure=0.0)
    return equilibrium, amplitudes
