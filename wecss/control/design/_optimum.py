"""The non-causal optimum: the best PTO force trajectory over a periodic wave record on the linear model, all PTOs
together, within force, stroke and force-rate limits, for the mean absorbed (mechanical) power, the mechanical power
less a copper loss R f^2, or the electrical power of an asymmetric conversion efficiency (P_elec = eta P when
absorbing, P / eta when supplying, per PTO). It knows the whole record (no causal controller can do better on the
same record and model, within its force basis) and is the ceiling a controller's power is judged by, beside the
unconstrained complex-conjugate bound; its trajectory is a design target.

Formulation (pseudo-spectral): the force is a Fourier series on the record's harmonics 1 ... M (``_periodic``; M a
``basis`` multiple of the waves' highest harmonic, wider than the waves' own so that a saturated force can take its
shape), the limits hold at the N > 2 M sample points of the period, and the mean mechanical power is exact (Parseval).
The electrical objective's instantaneous power f v has harmonics up to 2 M, which N > 2 M samples hold only in the
mean: there the procedure below finds trajectories whose power is positive at the samples and negative between them,
so its value is reported between them (ELECTRICAL_OVERSAMPLING), and ``points`` > 4 M makes the programme see it (the
Wavestar's SS1: 0.0201 W at the samples and 0.0185 W between them at the default N; 0.02002 and 0.01999 W at N > 4 M,
where perfect-preview MPC converted 0.0199 W, but in 35 s against 2.4 s on a shared machine; in SS5 the limits' active
set at N > 4 M took minutes). Mechanical power and copper loss make a convex quadratic programme (``_spectral_qp``),
solved exactly by a dual active-set method started from the active set ADMM finds (``_admm``), with a certificate: the
dual value bounds the optimum from above, the primal value from below, and their gap is reported. The electrical
objective of the asymmetric efficiency is not convex: it is
P_elec = eta P - (1 / eta - eta) max(-P, 0), and max(f v, 0) <= (alpha f + v / alpha)^2 / 4 for any alpha > 0,
with equality at a point (f_0, v_0) for alpha^2 = |v_0 / f_0|. A stationary point of the whole objective is found
first by nonconvex ADMM (``_electrical_admm``: the exact proximal step of max(f v, 0) per sample), and taken as the
start where it keeps the limits (to GUESS_VIOLATION) and beats the mechanical optimum; then each step of a
convex-concave procedure solves the convex programme with that majorant at the samples where the present trajectory
supplies power and where the last step had it (where the new one supplies power elsewhere and the step did not gain,
with the majorant there too, solved again: then it cannot lose; the majorant is tight at a sample that absorbs, 0
there, so keeping the last step's samples loses nothing and saves most of the solves again: on SS1 8 solves and
61,000 ADMM iterations in all, against 19 and 150,000, the same optimum), by ADMM (``_admm``: the penalty rows cost
nothing per iteration, where the exact solve factors a dense matrix of them all), each programme to a tenth of the
last step's relative gain (from ADMM_LOOSE down to ADMM_TIGHT), certified by its duality gap; a step that loses is
refused and solved again 100 times tighter. It stops when a step gains less than CCP_TOLERANCE (a local optimum),
evaluated at the samples, when a refused step solved tighter ends where it did (to CCP_TOLERANCE: stationary), or
after CCP_ITERATIONS steps: the procedure's gains shrink slowly (alone from the mechanical optimum, SS5 of the
Wavestar gained 2.8e-6 W per step after 60 steps, in 80 s; from ADMM's start 4 steps, 8 s). eta times the mechanical
optimum bounds it from above (P_elec <= eta P pointwise).
"""

from __future__ import annotations

import dataclasses
import time as _time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from ._admm import solve_admm, solve_robust
from ._electrical_admm import electrical_admm
from ._periodic import PeriodicResponse, periodic_response
from ._spectral_qp import FEASIBILITY, Penalties, Signal, SpectralProgramme, SpectralSolution

if TYPE_CHECKING:
    import xarray as xr

    from ...linear import LinearModel

OBJECTIVES = ("mechanical", "copper", "electrical")

CCP_TOLERANCE: float = 1e-5
"""The convex-concave procedure stops when an iteration raises the electrical power by less than this share (its
gains shrink slowly: 1e-7 took 60 steps and 3 minutes on the Wavestar's SS1)."""

CCP_ITERATIONS: int = 60
"""Most iterations of the convex-concave procedure."""

GUESS_VIOLATION: float = 1e-4
"""The largest limit violation (a share of the limit) at which the nonconvex ADMM's force is taken as the point the
procedure's first majorant is made at (kept as a result only within FEASIBILITY of the limits)."""

ELECTRICAL_ADMM_ITERATIONS: int = 5000
"""Most iterations of the nonconvex ADMM that finds the procedure's start. At N > 4 M it often does not settle: on
the test record of ``tests/control/test_optimum.py`` (15 procedure steps, a shared machine, before the procedure
kept its majorant's samples between steps) 20,000 iterations took 18 s and the optimum was 893.8 W, 5,000 took
2.4 s and gave 895.7 W, 2,000 876.9 W. At the default N the Wavestar's six starts took 1,400-8,100 iterations
(SS6 did not settle in 20,000); with this cap and the samples kept, the optima are unchanged, SS6's 0.15 %
higher."""

ADMM_LOOSE: float = 1e-4
ADMM_TIGHT: float = 1e-8
"""The range of the tolerance each convex programme of the procedure is solved to (by ADMM, ``_admm``)."""


@dataclass
class NonCausalOptimum:
    """The non-causal optimum of a periodic record (module docstring).

    Attributes
    ----------
    objective : str
        "mechanical", "copper" or "electrical".
    value : float
        The optimum of the objective's mean power [W]: absorbed power, absorbed power less copper loss, or
        electrical power (of the trajectory, evaluated between the samples too: ``ELECTRICAL_OVERSAMPLING``).
    upper_bound : float
        A certified upper bound on the programme's optimum [W] (the dual value; for "electrical", efficiency times
        the mechanical optimum's bound).
    gap : float
        The final convex programme's duality gap [W].
    absorbed : ndarray (n_pto,)
        Mean absorbed mechanical power per PTO [W].
    electrical : ndarray (n_pto,) or None
        Mean electrical power per PTO [W] (with an efficiency), on a grid ``ELECTRICAL_OVERSAMPLING`` times finer
        than the samples: the procedure maximises it at the samples, where the force can keep the power from
        being negative while it is negative between them, so the samples alone overstate it (the Wavestar's SS2
        on a 60 s record: 0.2766 W at the samples, 0.2587 W in a run that plays the trajectory, 0.2588 W on the
        finer grid). ``settings["electrical_at_samples"]`` keeps the samples' value.
    force : complex ndarray (M, n_pto)
        The force's Fourier amplitudes [N or N m].
    time : ndarray (N,)
        Sample times [s].
    pto_force, stroke, rate : ndarray (N, n_pto)
        Force [N or N m], stroke from rest [m or rad] and stroke rate [m/s or rad/s] at the samples.
    violation : float
        Largest limit violation at the samples, relative to the limit [-].
    iterations : int
        Active-set iterations (summed over the convex-concave procedure).
    ccp_iterations : int
        Convex-concave iterations (0 for the convex objectives).
    seconds : float
        Wall time [s].
    method : str
        How the (last) convex programme was solved: "active set", "ADMM" (the electrical objective's programmes)
        or "interior point" (where the active set did not settle).
    periodic : PeriodicResponse
    settings : dict
        The limits, efficiency, copper loss and basis it was made with, and how many harmonics' admittance had an
        eigenvalue raised to the passivity floor (``floored_harmonics``, a count; see ``PASSIVITY_FLOOR``).
    """

    objective: str
    value: float
    upper_bound: float
    gap: float
    absorbed: np.ndarray
    electrical: np.ndarray | None
    force: np.ndarray
    time: np.ndarray
    pto_force: np.ndarray
    stroke: np.ndarray
    rate: np.ndarray
    violation: float
    iterations: int
    ccp_iterations: int
    seconds: float
    method: str
    periodic: PeriodicResponse = field(repr=False)
    settings: dict = field(default_factory=dict)

    @property
    def total_absorbed(self) -> float:
        """Total mean absorbed power [W]."""
        return float(np.sum(self.absorbed))

    def dataset(
        self, pto_names: tuple[str, ...] | list[str] | None = None, pto_kinds: tuple[str, ...] | list[str] | None = None
    ) -> xr.Dataset:
        """The optimal trajectory as a Dataset: force, stroke, stroke rate and instantaneous absorbed power at the
        samples (``time``, ``pto``), the force's amplitudes per harmonic (``omega``; complex as [re, im]), the mean
        powers, and the optimum, bound, gap and settings as attributes. As in a run's result, a per-PTO variable
        comes per PTO kind (``pto_torque`` [N m] for rotary PTOs, ``pto_force`` [N] for linear ones, NaN for the
        others), so that no variable mixes units.

        Parameters
        ----------
        pto_names : sequence of str or None
            The PTOs' names (default pto_0, pto_1, ...).
        pto_kinds : sequence of str or None
            "rotary" or "linear" per PTO (default: all linear).

        Raises
        ------
        ValueError
            If the names or kinds are not one per PTO, or a kind is unknown.
        """
        import xarray as xr

        from ...outputs import PTO_KINDS

        n_pto = self.absorbed.size
        names = list(pto_names) if pto_names is not None else [f"pto_{k}" for k in range(n_pto)]
        kinds = list(pto_kinds) if pto_kinds is not None else ["linear"] * n_pto
        if len(names) != n_pto or len(kinds) != n_pto or not set(kinds) <= set(PTO_KINDS):
            raise ValueError(
                f"pto_names and pto_kinds must give one name and one kind of {PTO_KINDS} per PTO ({n_pto}); "
                f"got {pto_names!r} and {pto_kinds!r}"
            )
        rotary = np.array([k == "rotary" for k in kinds])
        table = {  # name per kind (rotary, linear), long name, units per kind, values, dims
            "force": (("pto_torque", "pto_force"), "optimal PTO force", ("N m", "N"), self.pto_force, ("time", "pto")),
            "stroke": (("pto_angle", "pto_displacement"), "PTO stroke from rest", ("rad", "m"), self.stroke,
                       ("time", "pto")),
            "rate": (("pto_angular_velocity", "pto_velocity"), "PTO stroke rate", ("rad/s", "m/s"), self.rate,
                     ("time", "pto")),
        }  # fmt: skip
        data: dict = {}
        for kind_names, long_name, units, values, dims in table.values():
            for k, (name, unit) in enumerate(zip(kind_names, units, strict=True)):
                mask = rotary if k == 0 else ~rotary
                if np.any(mask):
                    data[name] = (dims, np.where(mask[None], values, np.nan), {"long_name": long_name, "units": unit})
        amplitude = np.stack([self.force.real, self.force.imag], axis=-1)
        for k, (name, unit) in enumerate(zip(("torque_amplitude", "force_amplitude"), ("N m", "N"), strict=True)):
            mask = rotary if k == 0 else ~rotary
            if np.any(mask):
                data[name] = (
                    ("omega", "pto", "complex"), np.where(mask[None, :, None], amplitude, np.nan),
                    {"long_name": "complex amplitude of the optimal PTO force, Re[F exp(i omega t)]", "units": unit},
                )  # fmt: skip
        data["pto_power"] = (
            ("time", "pto"), -self.pto_force * self.rate, {"long_name": "absorbed PTO power", "units": "W"},
        )  # fmt: skip
        data["mean_pto_power"] = (("pto",), self.absorbed, {"long_name": "mean absorbed PTO power", "units": "W"})
        if self.electrical is not None:
            data["mean_electrical_power"] = (
                ("pto",), self.electrical, {"long_name": "mean electrical PTO power at the samples", "units": "W"},
            )  # fmt: skip
        attrs = {
            "title": "wecss non-causal optimum",
            "objective": self.objective,
            "optimum_W": self.value,
            "upper_bound_W": self.upper_bound,
            "duality_gap_W": self.gap,
            "largest_violation": self.violation,
            "record_period_s": self.periodic.period,
            "harmonics": f"{self.periodic.harmonic[0]}-{self.periodic.harmonic[-1]}",
            "samples": self.periodic.points,
            "response": self.periodic.response,
            "solver": self.method,
            "iterations": self.iterations,
            "ccp_iterations": self.ccp_iterations,
            "run_time_s": self.seconds,
            **{k: (v if v is not None else "none") for k, v in self.settings.items()},
        }
        coords = {
            "time": ("time", self.time, {"long_name": "time within the period", "units": "s"}),
            "pto": ("pto", names, {"long_name": "PTO name"}),
            "pto_kind": ("pto", kinds, {"long_name": "PTO kind"}),
            "omega": ("omega", self.periodic.omega, {"long_name": "harmonic of the record", "units": "rad/s"}),
            "complex": ["re", "im"],
        }
        return xr.Dataset(data, coords=coords, attrs=_netcdf_attrs(attrs))


def _netcdf_attrs(attrs: dict) -> dict:
    out = {}
    for k, v in attrs.items():
        if isinstance(v, np.ndarray):
            v = v.tolist()
        if isinstance(v, list | tuple):
            v = ", ".join(str(x) for x in v)
        out[k] = v
    return out


def _per_pto(value: np.ndarray | float | None, n_pto: int, label: str) -> np.ndarray:
    if value is None:
        return np.full(n_pto, np.inf)
    out = np.broadcast_to(np.asarray(value, dtype=float), (n_pto,)).copy() if np.size(value) in (1, n_pto) else None
    if out is None or not np.all(out > 0):
        raise ValueError(f"{label} must be positive (inf: none), 1 or {n_pto} values; got {value!r}")
    return out


def noncausal_optimum(
    model: LinearModel,
    omega: np.ndarray,
    coefficients: np.ndarray,
    period: float,
    *,
    force_limit: np.ndarray | float | None = None,
    stroke_limit: np.ndarray | float | None = None,
    rate_limit: np.ndarray | float | None = None,
    objective: str = "mechanical",
    efficiency: float | None = None,
    copper_loss: np.ndarray | float | None = None,
    harmonics: int | None = None,
    basis: float = 2.0,
    lowest: int | None = None,
    points: int | None = None,
    response: str = "database",
) -> NonCausalOptimum:
    """The best PTO force trajectory over a periodic record (module docstring).

    Parameters
    ----------
    model : LinearModel
        The open plant (``context.linear_model()``).
    omega, coefficients : ndarray
        The record's wave components [rad/s] (whole multiples of 2 pi / ``period``) and their excitation on the hydro
        DOFs (n_h, n_w) [N, N m] (``context.excitation``).
    period : float
        The record's repeat period [s] (``waves.repeat_period``).
    force_limit, stroke_limit, rate_limit : float, array or None
        Per PTO (or one for all; None or inf: none) [N or N m; m or rad from rest; N/s or N m/s].
    objective : str
        "mechanical" (mean absorbed power), "copper" (absorbed power less ``copper_loss`` R f^2 per PTO [W per N^2
        or per (N m)^2]) or "electrical" (P_elec with ``efficiency`` eta in (0, 1]).
    efficiency : float or None
        eta: needed for "electrical"; with the other objectives the electrical power of their optimum is reported.
    harmonics, basis, lowest, points, response
        The force basis (its highest harmonic M, or ``basis`` times the waves' highest; its lowest: by default
        (None) the record's first, or the waves' lowest where the programme from the first does not settle, which
        ``method`` and ``settings["lowest"]`` then say), the samples N and the frequency response ("database" or
        "fit"): see ``periodic_response``. For the electrical objective, ``points`` above 4 M (twice the default)
        makes the programme see the power between the samples too (module docstring), at several times the cost.
        Where the force limit binds, the best force is a saturated one, and its
        harmonics below the waves' matter: on the Wavestar's WECCCOMP records (60 N / 0.08 m) the optimum from the
        waves' lowest harmonic was 1.304967 W in SS3 and 1.320950 W in SS6 and is 1.353284 and 1.363517 W from the
        first (SS2 and SS5 +0.1 %, SS1 and SS4 unchanged), and perfect-preview MPC, whose held force has them,
        absorbed 1.3497 W in SS3 on the same record: more than the narrower optimum.

    Returns
    -------
    NonCausalOptimum
        The optimum [W], its certified upper bound and duality gap [W], the trajectory at the samples and the
        force's amplitudes (``.dataset()`` for an xarray Dataset).

    Raises
    ------
    ValueError
        On bad settings (see ``periodic_response``), an objective without its efficiency or copper loss.
    RuntimeError
        If neither the active-set iteration nor the interior-point solve (for a programme small enough to hold
        densely) finds the optimum.
    """

    def solve(low: int | None) -> NonCausalOptimum:
        return _optimum(
            model, omega, coefficients, period, force_limit=force_limit, stroke_limit=stroke_limit,
            rate_limit=rate_limit, objective=objective, efficiency=efficiency, copper_loss=copper_loss,
            harmonics=harmonics, basis=basis, lowest=low, points=points, response=response,
        )  # fmt: skip

    if lowest is not None:
        return solve(lowest)
    start = _time.perf_counter()
    try:
        return solve(1)
    except RuntimeError as err:
        narrow = solve(None)
        return dataclasses.replace(
            narrow,
            method=f"{narrow.method}; from the waves' lowest harmonic (from the first: {err})",
            seconds=_time.perf_counter() - start,
        )


def _optimum(
    model: LinearModel,
    omega: np.ndarray,
    coefficients: np.ndarray,
    period: float,
    *,
    force_limit: np.ndarray | float | None,
    stroke_limit: np.ndarray | float | None,
    rate_limit: np.ndarray | float | None,
    objective: str,
    efficiency: float | None,
    copper_loss: np.ndarray | float | None,
    harmonics: int | None,
    basis: float,
    lowest: int | None,
    points: int | None,
    response: str,
) -> NonCausalOptimum:
    """:func:`noncausal_optimum` on one force basis (``lowest`` None: from the waves' lowest harmonic)."""
    start = _time.perf_counter()
    if objective not in OBJECTIVES:
        raise ValueError(f"objective must be one of {OBJECTIVES}; got {objective!r}")
    if efficiency is not None and not (isinstance(efficiency, int | float) and 0 < efficiency <= 1):
        raise ValueError(f"efficiency must lie in (0, 1]; got {efficiency!r}")
    if objective == "electrical" and efficiency is None:
        raise ValueError('objective "electrical" needs an efficiency')
    if objective == "copper" and copper_loss is None:
        raise ValueError('objective "copper" needs a copper_loss R [W per N^2]')
    periodic = periodic_response(
        model,
        omega,
        coefficients,
        period,
        harmonics=harmonics,
        basis=basis,
        lowest=lowest,
        points=points,
        response=response,
    )
    n_pto = periodic.n_pto
    limits = {
        "force_limit": _per_pto(force_limit, n_pto, "force_limit"),
        "stroke_limit": _per_pto(stroke_limit, n_pto, "stroke_limit"),
        "rate_limit": _per_pto(rate_limit, n_pto, "rate_limit"),
    }
    loss = np.zeros(n_pto) if copper_loss is None else np.broadcast_to(np.asarray(copper_loss, float), (n_pto,))
    if np.any(loss < 0):
        raise ValueError(f"copper_loss must be >= 0; got {copper_loss!r}")
    signals = _signals(periodic, limits)
    hermitian, floored = _passive(0.5 * (periodic.admittance + np.conj(np.swapaxes(periodic.admittance, 1, 2))))
    linear = -0.5 * periodic.free_rate
    if objective == "copper":
        programme = SpectralProgramme(periodic, hermitian + np.diag(loss)[None], linear, signals)
        solution, _ = solve_robust(programme)
        iterations, ccp = solution.iterations, 0
        value, bound = -solution.primal, -solution.dual
    else:
        mechanical = SpectralProgramme(periodic, hermitian, linear, signals)
        solution, _ = solve_robust(mechanical)
        iterations, ccp = solution.iterations, 0
        value, bound = -solution.primal, -solution.dual
        if objective == "electrical" and efficiency is not None and efficiency < 1:
            solution, value, iterations, ccp = _electrical(
                periodic, hermitian, linear, signals, solution, float(efficiency)
            )
            bound = float(efficiency) * bound
    force_samples, stroke, rate = solution.values[0], solution.values[1], solution.values[2]
    absorbed = _absorbed(periodic, solution.force)
    electrical, at_samples = None, None
    if efficiency is not None:
        at_samples = float(np.sum(np.mean(_electrical_power(-force_samples * rate, float(efficiency)), axis=0)))
        electrical = _electrical_between_samples(periodic, solution.force, float(efficiency))
    if objective == "electrical" and electrical is not None:
        value = float(np.sum(electrical))
    return NonCausalOptimum(
        objective=objective, value=float(value), upper_bound=float(bound), gap=float(solution.gap),
        absorbed=absorbed, electrical=electrical, force=solution.force, time=periodic.time,
        pto_force=force_samples, stroke=stroke, rate=rate, violation=solution.violation, iterations=iterations,
        ccp_iterations=ccp, seconds=_time.perf_counter() - start, method=solution.method, periodic=periodic,
        settings={
            **{k: v.tolist() for k, v in limits.items()}, "efficiency": efficiency, "copper_loss": loss.tolist(),
            "basis": float(periodic.harmonic[-1] / periodic.wave_harmonics.max()),
            "floored_harmonics": floored, "electrical_at_samples": at_samples,
            "lowest": int(periodic.harmonic[0]),
        },
    )  # fmt: skip


PASSIVITY_FLOOR: float = 1e-9
"""The least eigenvalue of the admittance's Hermitian part, as a share of its largest over all harmonics, that the
programme keeps (a passive plant's is >= 0; a database's rounding leaves some at -1e-10 of the largest)."""


def _passive(hermitian: np.ndarray) -> tuple[np.ndarray, int]:
    """The Hermitian parts of the admittance (M, n_pto, n_pto) with every eigenvalue at least PASSIVITY_FLOOR of the
    largest, and how many harmonics needed it. A direction in which a PTO force moves the PTOs without radiating
    (no damping: at the record's lowest harmonics, well below the waves' band) would let the programme absorb any
    power there if its eigenvalue is rounded below zero, and the programme needs a positive definite Hessian."""
    values, vectors = np.linalg.eigh(hermitian)
    floor = PASSIVITY_FLOOR * float(np.max(values, initial=0.0))
    low = np.any(values < floor, axis=1)
    if not np.any(low):
        return hermitian, 0
    clipped = np.maximum(values[low], floor)
    out = hermitian.copy()
    out[low] = np.einsum("mpk,mk,mqk->mpq", vectors[low], clipped, np.conj(vectors[low]))
    return out, int(np.sum(low))


def _signals(periodic: PeriodicResponse, limits: dict[str, np.ndarray]) -> list[Signal]:
    """force, stroke, stroke rate and force rate, in that order, with their limits."""
    m, n_pto, n = periodic.n_harmonics, periodic.n_pto, periodic.points
    eye = np.broadcast_to(np.eye(n_pto, dtype=complex), (m, n_pto, n_pto))
    w = periodic.omega[:, None, None]
    free_stroke = periodic.stroke_at_equilibrium[None] + periodic.samples(
        periodic.free_rate / (1j * periodic.omega[:, None])
    )
    force, stroke, rate = limits["force_limit"], limits["stroke_limit"], limits["rate_limit"]
    out = [
        Signal(eye, np.zeros((n, n_pto)), -force, force),
        Signal(periodic.admittance / (1j * w), free_stroke, -stroke, stroke),
        Signal(periodic.admittance, periodic.samples(periodic.free_rate)),
    ]
    if np.any(np.isfinite(rate)):
        out.append(Signal(1j * w * eye, np.zeros((n, n_pto)), -rate, rate))
    return [s if s.upper is None or np.any(np.isfinite(s.upper)) else Signal(s.operator, s.free) for s in out]


def _absorbed(periodic: PeriodicResponse, force: np.ndarray) -> np.ndarray:
    """Mean absorbed power per PTO of force amplitudes (M, n_pto) (Parseval) [W]."""
    rate = periodic.free_rate + np.einsum("mpq,mq->mp", periodic.admittance, force)
    return np.sum(-0.5 * np.real(np.conj(force) * rate), axis=0)


def _electrical_power(power: np.ndarray, efficiency: float) -> np.ndarray:
    """eta P absorbing, P / eta supplying."""
    return np.where(power >= 0, efficiency * power, power / efficiency)


ELECTRICAL_OVERSAMPLING: int = 16
"""How much finer than the programme's samples the reported electrical power is evaluated (``NonCausalOptimum``)."""


def _electrical_between_samples(periodic: PeriodicResponse, force: np.ndarray, efficiency: float) -> np.ndarray:
    """Mean electrical power per PTO [W] of force amplitudes (M, n_pto), the force and the stroke rate synthesised
    on ``ELECTRICAL_OVERSAMPLING`` times the programme's samples."""
    n = ELECTRICAL_OVERSAMPLING * periodic.points
    rate = periodic.free_rate + np.einsum("mpq,mq->mp", periodic.admittance, force)

    def fine(amplitudes: np.ndarray) -> np.ndarray:
        spectrum = np.zeros((n // 2 + 1, amplitudes.shape[1]), dtype=complex)
        spectrum[periodic.harmonic] = 0.5 * n * amplitudes
        return np.fft.irfft(spectrum, n=n, axis=0)

    return np.mean(_electrical_power(-fine(force) * fine(rate), efficiency), axis=0)


def _mean_electrical(values: list[np.ndarray], efficiency: float) -> float:
    """Mean electrical power of all PTOs at the samples of the signals ``values`` (force first, rate third) [W]."""
    return float(np.sum(np.mean(_electrical_power(-values[0] * values[2], efficiency), axis=0)))


def _electrical(
    periodic: PeriodicResponse,
    hermitian: np.ndarray,
    linear: np.ndarray,
    signals: list[Signal],
    start: SpectralSolution,
    efficiency: float,
) -> tuple[SpectralSolution, float, int, int]:
    """The convex-concave procedure of the module docstring, from the mechanical optimum ``start``."""
    n = periodic.points
    supply = 1.0 / efficiency - efficiency
    weight = supply / (2.0 * n)  # w e^2 / 2 = supply e^2 / (4 N)
    # a stationary point of the whole electrical objective by nonconvex ADMM, kept where it beats the mechanical optimum
    plain = SpectralProgramme(periodic, efficiency * hermitian, efficiency * linear, signals)
    force, admm_iterations = electrical_admm(
        plain, supply / n, tolerance=1e-5, max_iterations=ELECTRICAL_ADMM_ITERATIONS
    )
    values = plain.values(force)
    primal, e = plain.objective(force, values)
    violation = float(max(0.0, -float(np.min(plain._slacks(values), initial=0.0))))
    guess = SpectralSolution(
        force, primal, np.nan, np.nan, violation, 0, admm_iterations, False, values, e, "ADMM (nonconvex)"
    )
    iterations = start.iterations + admm_iterations
    state = None  # where the last ADMM solve ended: the next, similar, programme starts there

    def electrical(values: list[np.ndarray]) -> float:
        return _mean_electrical(values, efficiency)

    # solution: the best trajectory kept; point: the one the majorant is made at
    solution, value = start, electrical(start.values)
    point = start
    if violation <= GUESS_VIOLATION:
        restored = _within_limits(periodic, efficiency * hermitian, signals, guess)
        if electrical(restored.values) > value:
            solution, value, point = restored, electrical(restored.values), restored
    force_rms = np.sqrt(np.mean(point.values[0] ** 2, axis=0)) + 1e-300
    rate_rms = np.sqrt(np.mean(point.values[2] ** 2, axis=0)) + 1e-300
    typical = rate_rms / force_rms  # |v / f| scale per PTO
    ccp = 0
    tolerance = ADMM_LOOSE  # each programme is solved to a tenth of the last step's gain, down to ADMM_TIGHT
    refused = None  # the value of the last step refused, solved to a looser tolerance
    carried = None  # the samples the last step's majorant was at
    for ccp in range(1, CCP_ITERATIONS + 1):  # noqa: B007 (the count is returned)
        f, v = point.values[0], point.values[2]
        alpha = np.sqrt(np.clip(np.abs(v) / np.maximum(np.abs(f), 1e-300), 1e-4 * typical, 1e4 * typical))
        rows = (f * v > 0) | (np.abs(f * v) <= 1e-9 * float(np.mean(np.abs(f * v))))  # supplying (or at zero)
        if carried is not None:  # and where an earlier step needed it
            rows |= carried
        while True:
            j, p = np.nonzero(rows)
            penalties = Penalties(
                signal=np.tile(np.array([0, 2]), (j.size, 1)),
                coefficient=np.stack([alpha[j, p], 1.0 / alpha[j, p]], axis=1),
                pto=p, point=j, weight=np.full(j.size, weight),
            )  # fmt: skip
            programme = SpectralProgramme(periodic, efficiency * hermitian, efficiency * linear, signals, penalties)
            trial, state = solve_admm(programme, state, tolerance)
            iterations += trial.iterations
            trial_value = electrical(trial.values)
            new = (trial.values[0] * trial.values[2] > 0) & ~rows  # supplying where the majorant is not
            if not np.any(new) or trial_value > value:  # a majorant everywhere it supplies, or a gain anyway
                break
            rows |= new  # add the majorant there and solve again: then the procedure cannot lose

        carried = rows
        improved = trial_value - value
        if not improved > 0:  # lost (the programme solved too loosely), stationary or NaN: tighter, or done
            if tolerance <= ADMM_TIGHT or (
                refused is not None and abs(trial_value - refused) <= CCP_TOLERANCE * max(abs(value), 1e-300)
            ):
                break  # solved tighter, the step ends where it did: the procedure is stationary at the point
            refused = trial_value
            tolerance = max(0.01 * tolerance, ADMM_TIGHT)
            continue
        refused = None
        solution, value = trial, trial_value
        point = trial
        if improved <= CCP_TOLERANCE * max(abs(value), 1e-300) and tolerance <= 0.1 * CCP_TOLERANCE:
            break
        tolerance = float(np.clip(0.1 * improved / max(abs(value), 1e-300), ADMM_TIGHT, ADMM_LOOSE))
    if solution.violation > FEASIBILITY:  # an ADMM solution a little past a limit (its tolerance): the nearest within
        solution = _within_limits(periodic, efficiency * hermitian, signals, solution)
        value = electrical(solution.values)
    return solution, value, iterations, ccp


def _within_limits(
    periodic: PeriodicResponse, hessian: np.ndarray, signals: list[Signal], near: SpectralSolution
) -> SpectralSolution:
    """The force within the limits nearest ``near``'s in the norm of ``hessian`` (the exact, certified solve of
    min 1/2 (F - G)^H H (F - G)): an ADMM solution's small violations removed at a cost of the same order in power;
    its gap is that of the projection, so reported as NaN."""
    if near.violation <= FEASIBILITY:
        return near
    target = np.einsum("mpq,mq->mp", hessian, near.force)
    projected, _ = solve_robust(SpectralProgramme(periodic, hessian, target, signals))
    return dataclasses.replace(
        projected, primal=np.nan, dual=np.nan, gap=np.nan, method=f"{near.method} (projected onto the limits)"
    )
