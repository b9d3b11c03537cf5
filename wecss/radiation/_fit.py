"""Fitting state-space radiation models, with the order chosen by error targets, checks, repair and a report.

Targets (per fitted entry, DESIGN.md and the radiation issue): K(0) error and RMS error of K(t) within 1 % of
the entry's peak, B(omega) and A(omega) - A_inf reconstructed within 2 % of their peaks over the data band. The
order grows until every target holds (or the maximum order is reached; the report then shows the miss). Entries
that the coupling rule of ``wecss.radiation.significant_couplings`` drops are left out (per-entry fits) or not
judged (the MIMO fit realises the whole kernel), and listed.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import asdict, dataclass, field, replace
from typing import Literal

import numpy as np
import xarray as xr
from scipy.linalg import block_diag, null_space

from ..hydro import HydroData
from ._couplings import significant_couplings
from ._irf import ImpulseResponse, impulse_response
from ._modal import hankel_realisation, matrix_pencil, realise
from ._passivity import Passivation, PassivityCheck, damping_scale, enforce_passivity
from ._statespace import STABILITY_DAMPING, RadiationStateSpace

Method = Literal["prony", "era", "era-mimo"]

ORDER_SLACK: float = 0.1
"""When the targets are not reached, the lowest order within this relative margin of the best score is kept."""

MIN_FIT_DAMPING: float = 5e-3
"""Smallest damping ratio -Re(s)/|s| of the poles of a MIMO fit: lighter poles are given this damping before C is
fitted (on the m4-134 fit this changed the largest fit errors by less than 2e-3 of the peaks; the ERA poles of a
band-limited kernel reach 5e-4, below STABILITY_DAMPING)."""

FIT_VERSION: str = "passive-lift-1"
"""Part of the cache key: fits made by older code (not passive) are not reused."""

SUPPORT_FACTOR: float = 3.0
"""Kernel samples up to this multiple of an entry's truncation time are fitted and judged (the slow tail beyond
the 1 % truncation still shapes A(omega) at low frequency)."""


@dataclass(frozen=True)
class FitSettings:
    """How to fit.

    Attributes
    ----------
    method : {"prony", "era", "era-mimo"}
        Matrix-pencil Prony per entry, Hankel-SVD realisation per entry, or one Hankel-SVD realisation of the whole
        MIMO kernel (shared poles).
    coupling_threshold : float
        Entries whose kernel peak is below this share of sqrt(P_i P_j) (P the diagonal peaks; the rule of
        :func:`significant_couplings`, the same as the convolution's) are not fitted or judged (reported as
        dropped); the targets apply to the others. Scenes pass their ``radiation.coupling_threshold``.
    k0_tol, rms_tol, frequency_tol : float
        Targets: K(0) and RMS errors relative to the entry's peak; B and A - A_inf errors relative to their peaks.
    max_order : int
        Largest order per entry (per-entry methods).
    max_order_mimo : int
        Largest order of the whole model (MIMO realisation).
    samples : int
        Number of kernel samples per entry used by the fit.
    """

    method: Method = "prony"
    coupling_threshold: float = 1e-3
    k0_tol: float = 0.01
    rms_tol: float = 0.01
    frequency_tol: float = 0.02
    max_order: int = 24
    max_order_mimo: int = 400
    samples: int = 400

    def __post_init__(self) -> None:
        if self.method not in ("prony", "era", "era-mimo"):
            raise ValueError(f"method must be 'prony', 'era' or 'era-mimo'; got {self.method!r}")


@dataclass(frozen=True)
class RadiationFit:
    """A fitted radiation model with its report (an xarray Dataset) and what was repaired."""

    model: RadiationStateSpace
    report: xr.Dataset
    passivation: Passivation
    irf: ImpulseResponse = field(repr=False)


@dataclass(frozen=True)
class _Reference:
    """What a fit is judged against: kernel samples and frequency data per entry."""

    time: np.ndarray
    kernel: np.ndarray  # (t, i, j)
    omega: np.ndarray
    damping: np.ndarray  # (w, i, j)
    added: np.ndarray  # A(omega) - A_inf, (w, i, j)
    support: np.ndarray  # (i, j) time up to which the RMS error is measured

    def errors(self, i: int, j: int, kernel: np.ndarray, response: np.ndarray) -> tuple[float, float, float, float]:
        """(K(0), RMS K(t), B, A - A_inf) errors of one entry from the fitted kernel (t,) and response (w,)."""
        ref = self.kernel[:, i, j]
        peak = max(np.max(np.abs(ref)), 1e-300)
        window = self.time <= self.support[i, j]
        k0 = abs(kernel[0] - ref[0]) / peak
        rms = float(np.sqrt(np.mean((kernel[window] - ref[window]) ** 2)) / peak)
        b = self.damping[:, i, j]
        a = self.added[:, i, j]
        b_err = float(np.max(np.abs(response.real - b)) / max(np.max(np.abs(b)), 1e-300))
        a_err = float(np.max(np.abs(response.imag / self.omega - a)) / max(np.max(np.abs(a)), 1e-300))
        return float(k0), rms, b_err, a_err


def _reference(hydro: HydroData, irf: ImpulseResponse) -> _Reference:
    ds = hydro.dataset
    support = np.minimum(np.maximum(SUPPORT_FACTOR * irf.truncation_time, 20 * irf.dt), irf.time[-1])
    if irf.band is not None:
        # a band-limited kernel is judged against itself, below the roll-off: B and A - A_inf from its transform
        # (A_inf of a band-limited model differs from the database's by a constant the simulator corrects)
        omega = hydro.omega[hydro.omega <= irf.band[0]]
        weights = np.full(irf.time.size, irf.dt)
        weights[[0, -1]] *= 0.5
        phase = np.exp(-1j * np.outer(omega, irf.time)) * weights[None, :]
        n = len(irf.dofs)
        response = (phase @ irf.kernel.reshape(irf.time.size, n * n)).reshape(omega.size, n, n)
        return _Reference(irf.time, irf.kernel, omega, response.real, response.imag / omega[:, None, None], support)
    added = ds.added_mass.values - ds.added_mass_inf.values[None]
    return _Reference(irf.time, irf.kernel, hydro.omega, ds.radiation_damping.values, added, support)


def _siso(a: np.ndarray, b: np.ndarray, c: np.ndarray, time: np.ndarray, omega: np.ndarray):
    """Kernel (t,) and response (w,) of a small SISO realisation."""
    if a.size == 0:
        return np.zeros(time.size), np.zeros(omega.size, dtype=complex)
    lam, vec = np.linalg.eig(a)
    left = c @ vec
    right = np.linalg.solve(vec, b)
    weights = left * right
    kernel = np.real(np.exp(np.outer(time, lam)) @ weights)
    response = (1.0 / (1j * omega[:, None] - lam[None, :])) @ weights
    return kernel, response


def _entries(irf: ImpulseResponse, threshold: float) -> tuple[list[tuple[int, int]], list[tuple[int, int]]]:
    """Entries (i <= j) that :func:`significant_couplings` keeps, and the rest."""
    kept = significant_couplings(np.max(np.abs(irf.kernel), axis=0), threshold)
    n = kept.shape[0]
    fitted = [(i, j) for i in range(n) for j in range(i, n) if kept[i, j]]
    dropped = [(i, j) for i in range(n) for j in range(i, n) if not kept[i, j]]
    return fitted, dropped


def _score(errors: tuple[float, float, float, float], settings: FitSettings) -> float:
    """The largest ratio of an entry's (K(0), RMS K(t), B, A - A_inf) errors to their targets (1: on target)."""
    k0, rms, b, a = errors
    return max(k0 / settings.k0_tol, rms / settings.rms_tol, b / settings.frequency_tol, a / settings.frequency_tol)


def _lowest_near_best(candidates: list[tuple[float, int, object]]) -> object:
    """The lowest-order candidate whose score is within ORDER_SLACK of the best one (the targets decide the order;
    when they cannot be met, no states are spent on improvements smaller than the slack)."""
    best = min(score for score, _, _ in candidates)
    return min((c for c in candidates if c[0] <= best * (1 + ORDER_SLACK)), key=lambda c: c[1])[2]


def _fit_entry(
    ref: _Reference,
    i: int,
    j: int,
    settings: FitSettings,
    method: Callable[[np.ndarray, float], Callable[[int], np.ndarray]],
):
    """Lowest order meeting the targets (or the best one), as (a, b, c, order, errors)."""
    window = ref.time <= ref.support[i, j]
    stride = max(1, int(np.ceil(window.sum() / settings.samples)))
    t = ref.time[window][::stride]
    y = ref.kernel[window, i, j][::stride]
    poles_of = method(y, float(t[1] - t[0]))
    candidates: list[tuple[float, int, object]] = []
    for order in range(1, settings.max_order + 1):
        try:
            a, b, c = realise(poles_of(order), t, y)
        except np.linalg.LinAlgError:
            continue
        kernel, response = _siso(a, b, c, ref.time, ref.omega)
        errors = ref.errors(i, j, kernel, response)
        score = _score(errors, settings)
        candidates.append((score, a.shape[0], (a, b, c, a.shape[0], errors)))
        if score <= 1.0:
            return a, b, c, a.shape[0], errors
    return _lowest_near_best(candidates)


def _assemble(blocks: list[tuple[int, int, np.ndarray, np.ndarray, np.ndarray]], n: int):
    a = block_diag(*[blk[2] for blk in blocks]) if blocks else np.zeros((0, 0))
    nx = a.shape[0]
    b = np.zeros((nx, n))
    c = np.zeros((n, nx))
    k = 0
    for i, j, ae, be, ce in blocks:
        m = ae.shape[0]
        b[k : k + m, j] = be
        c[i, k : k + m] = ce
        k += m
    return a, b, c


def _fit_per_entry(hydro: HydroData, irf: ImpulseResponse, settings: FitSettings):
    ref = _reference(hydro, irf)
    method = matrix_pencil if settings.method == "prony" else hankel_realisation
    fitted, dropped = _entries(irf, settings.coupling_threshold)
    blocks = []
    rows = []
    for i, j in fitted:
        a, b, c, order, errors = _fit_entry(ref, i, j, settings, method)
        blocks.append((i, j, a, b, c))
        if i != j:
            blocks.append((j, i, a, b, c))
        rows.append((i, j, order, *errors))
    a, b, c = _assemble(blocks, len(irf.dofs))
    return RadiationStateSpace(a, b, c, irf.dofs, settings.method), rows, dropped, ref


def _real_modes(a: np.ndarray, b: np.ndarray, time: np.ndarray) -> np.ndarray:
    """exp(A t) B for every t (n_t, n_x, n_in), through the eigen-decomposition of A."""
    lam, vec = np.linalg.eig(a)
    right = np.linalg.solve(vec, b)
    return np.real(np.einsum("ak,tk,kj->taj", vec, np.exp(np.outer(time, lam)), right))


def _fit_mimo(hydro: HydroData, irf: ImpulseResponse, settings: FitSettings):
    """One Hankel-SVD realisation of the whole kernel matrix (shared poles), order by the targets."""
    ref = _reference(hydro, irf)
    n = len(irf.dofs)
    block_rows = max(4, min(settings.samples // 2, 2400 // n))
    # samples fine enough for the data band (Nyquist 1.2 omega_max), as many as the Hankel matrix allows
    stride = max(1, int(np.floor(np.pi / (1.2 * float(hydro.omega[-1])) / irf.dt)))
    span = min(float(np.max(ref.support)), 2 * block_rows * stride * irf.dt)
    window = ref.time <= span
    t = ref.time[window][::stride]
    y = ref.kernel[window][::stride]  # (m, n, n)
    dt = float(t[1] - t[0])
    r = (t.size - 1) // 2
    h0 = np.block([[y[p + q] for q in range(r)] for p in range(r)])
    h1 = np.block([[y[p + q + 1] for q in range(r)] for p in range(r)])
    u, sv, vh = np.linalg.svd(h0)
    fitted, dropped = _entries(irf, settings.coupling_threshold)
    judge = np.arange(0, ref.time.size, max(1, ref.time.size // 2000))
    judged = replace(ref, time=ref.time[judge], kernel=ref.kernel[judge])
    candidates: list[tuple[float, int, object]] = []
    orders = sorted({*range(2, 40, 2), *range(40, 200, 8), *range(200, 1001, 25)})
    for order in [k for k in orders if k <= min(settings.max_order_mimo, sv.size)]:
        root = 1.0 / np.sqrt(sv[:order])
        a_d = (root[:, None] * (u[:, :order].T @ h1 @ vh[:order].T)) * root[None, :]
        lam = np.linalg.eigvals(a_d)
        if np.any((np.abs(lam.imag) < 1e-12) & (lam.real <= 0)):
            continue  # a mode at the Nyquist limit has no real continuous counterpart
        lam_c, vec = np.linalg.eig(a_d)
        s_c = np.log(lam_c.astype(complex)) / dt
        s_c = np.where(s_c.real > 0, -s_c.real + 1j * s_c.imag, s_c)  # reflect unstable poles
        floor = MIN_FIT_DAMPING * np.abs(s_c)  # and lift the lightest damping to the floor (C is fitted after)
        s_c = np.where(-s_c.real < floor, -floor + 1j * s_c.imag, s_c)
        a_c = np.real(vec @ np.diag(s_c) @ np.linalg.inv(vec))
        b_c = (np.sqrt(sv[:order])[:, None] * vh[:order])[:, :n]
        modes = _real_modes(a_c, b_c, t)  # (m, nx, n)
        design = np.transpose(modes, (0, 2, 1)).reshape(-1, order)
        target = np.transpose(y, (0, 2, 1)).reshape(-1, n)
        # C with a zero kernel integral, C (-A^-1 B) = 0 (B(0) = 0, see _modal.realise): C' in the null space
        free = null_space(np.linalg.solve(a_c, b_c).T)
        if free.shape[1] == 0:
            continue
        c_c = (free @ np.linalg.lstsq(design @ free, target, rcond=None)[0]).T
        model = RadiationStateSpace(a_c, b_c, c_c, irf.dofs, "era-mimo")
        kernel = model.kernel(judged.time)
        response = model.frequency_response(ref.omega)
        rows = [(i, j, order, *judged.errors(i, j, kernel[:, i, j], response[:, i, j])) for i, j in fitted]
        score = max(_score(e[3:], settings) for e in rows)
        candidates.append((score, order, (model, rows)))
        if score <= 1.0:
            break
    if not candidates:
        raise RuntimeError("no MIMO realisation could be formed (every order had modes at the Nyquist limit)")
    model, rows = _lowest_near_best(candidates)  # type: ignore[misc]
    return model, rows, dropped, ref


def fit_cache_key(hydro: HydroData, settings: FitSettings, band: tuple[float, float] | None = None) -> str:
    """Key of a fit in the radiation cache: a hash of the radiation data, the settings and the band."""
    from . import _cache

    kernel = "irf-default" if band is None else f"band-{band[0]:.12g}-{band[1]:.12g}"
    return _cache.cache_key(hydro, asdict(settings), kernel, FIT_VERSION)


def fit_radiation(
    hydro: HydroData,
    settings: FitSettings | None = None,
    *,
    irf: ImpulseResponse | None = None,
    cache: bool = False,
    band: tuple[float, float] | None = None,
) -> RadiationFit:
    """Fit a state-space model to the radiation kernel of ``hydro``, check it and repair it when needed.

    Checks: every pole stable with damping ratio >= STABILITY_DAMPING (unstable poles are reflected during the
    fit, and MIMO fits lift lighter poles to MIN_FIT_DAMPING); passive, the Hermitian part of K_hat(omega)
    positive semi-definite on a grid and, above it, by a proven bound (else :func:`enforce_passivity` makes it so:
    a least change of C and a passive lift, see ``wecss.radiation._passivity``).

    With ``cache`` the fit is stored in and reused from the disk cache (``wecss.radiation._cache``), keyed by a
    hash of the radiation data and the settings (only for impulse responses made here).

    ``band`` (rad/s): fit the band-limited kernel ``impulse_response(hydro, band=band, tail=False)`` instead,
    judged against itself below ``band[0]``. It needs far fewer states and fits the band the sea states use much
    better; its A_inf differs from the database's by a constant that ``wecss.sim`` corrects.

    Returns
    -------
    RadiationFit
        The model, the report Dataset (per entry: order, errors; attributes: states, margins, repair, dropped
        entries) and the impulse response used.
    """
    settings = settings or FitSettings()
    key = None
    if band is not None and irf is not None:
        raise ValueError("give either irf or band, not both")

    def make_irf() -> ImpulseResponse:
        return impulse_response(hydro) if band is None else impulse_response(hydro, band=band, tail=False)

    if cache and irf is None:
        from . import _cache

        key = fit_cache_key(hydro, settings, band)
        hit = _cache.load_cached_fit(key)
        if hit is not None:
            return RadiationFit(hit[0], hit[1], Passivation(), make_irf())
    irf = irf or make_irf()
    if settings.method == "era-mimo":
        model, rows, dropped, ref = _fit_mimo(hydro, irf, settings)
    else:
        model, rows, dropped, ref = _fit_per_entry(hydro, irf, settings)
    fitted = model
    model, passivation = enforce_passivity(model, hydro.omega, damping_scale(ref.damping), omega_band=ref.omega)
    assert passivation.after is not None  # enforce_passivity checks the model it returns
    if model is not fitted:  # the report judges the final (passive) model
        kernel = model.kernel(ref.time)
        response = model.frequency_response(ref.omega)
        rows = [(i, j, order, *ref.errors(i, j, kernel[:, i, j], response[:, i, j])) for i, j, order, *_ in rows]
    report = _report(model, rows, dropped, settings, passivation, passivation.after, irf)
    if key is not None:
        from . import _cache

        _cache.cache_fit(key, model, report)
    return RadiationFit(model, report, passivation, irf)


def _report(
    model, rows, dropped, settings: FitSettings, passivation: Passivation, check: PassivityCheck, irf: ImpulseResponse
) -> xr.Dataset:
    dofs = irf.dofs
    names = [f"{dofs[i]}|{dofs[j]}" for i, j, *_ in rows]
    data = np.array([r[2:] for r in rows], dtype=float).reshape(-1, 5)
    ds = xr.Dataset(
        {
            "order": ("entry", data[:, 0].astype(int), {"long_name": "number of states of the entry's fit"}),
            "k0_error": ("entry", data[:, 1], {"long_name": "|K_fit(0) - K(0)| / peak |K|"}),
            "rms_error": ("entry", data[:, 2], {"long_name": "RMS of K_fit - K over the support / peak |K|"}),
            "damping_error": ("entry", data[:, 3], {"long_name": "max |B_fit - B| over the data band / peak |B|"}),
            "added_mass_error": (
                "entry",
                data[:, 4],
                {"long_name": "max |A_fit - A| over the data band / peak |A - A_inf|"},
            ),
            "influenced_dof": ("entry", [dofs[r[0]] for r in rows]),
            "radiating_dof": ("entry", [dofs[r[1]] for r in rows]),
        },
        coords={"entry": names},
        attrs={
            "method": settings.method,
            "n_states": model.n_states,
            "passivity_margin": check.margin,
            "passive": int(check.passive),
            "passivity_grid_end": check.grid_end,
            "passivity_tail_from": check.tail.omega_tail,
            "min_damping_ratio": model.min_damping_ratio(),
            "stable": int(model.is_stable(STABILITY_DAMPING)),
            "repair": str(passivation),
            "dropped_entries": ", ".join(f"{dofs[i]}|{dofs[j]}" for i, j in dropped) or "none",
            "settings": repr(asdict(settings)),
            "k0_tol": settings.k0_tol,
            "rms_tol": settings.rms_tol,
            "frequency_tol": settings.frequency_tol,
            "targets_met": int(
                bool(
                    np.all(data[:, 1] <= settings.k0_tol)
                    and np.all(data[:, 2] <= settings.rms_tol)
                    and np.all(data[:, 3] <= settings.frequency_tol)
                    and np.all(data[:, 4] <= settings.frequency_tol)
                )
            ),
        },
    )
    return ds
