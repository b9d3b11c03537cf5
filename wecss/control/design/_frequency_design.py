"""Control design in the frequency domain, on the exact linear model and the wave components of a sea state: the
complex-conjugate power bound, the mean power of a linear PTO controller, and the optimal passive damping and
spring-damper (reactive) gains.

Per wave component k (frequency omega_k, excitation amplitudes F_k on the hydrodynamic DOFs, Re[. exp(i omega t)]),
the open plant (no PTO gains) answers the PTO forces f with the PTO stroke rates

    v = v_e + Y f,   v_e = i omega G Z^-1 Bw' F,   Y = i omega G Z^-1 G',

Z(omega) the model's dynamic stiffness, Bw the hydro-DOF Jacobian and G the PTO transmissions. The mean absorbed
power of component k is P = -Re(f^H v) / 2 (summed over PTOs), so with Yh = (Y + Y^H)/2, P = -Re(f^H v_e)/2 -
f^H Yh f / 2: a concave quadratic in f (Yh is positive definite for a passive, damped plant). Its maximum, the
complex-conjugate bound, is at f* = -Yh^-1 v_e / 2 with P* = v_e^H Yh^-1 v_e / 8; for one PTO on one DOF with
intrinsic impedance Z_i = B + iX (v_e = F / Z_i, Y = -1 / Z_i) it is |F|^2 / (8 B). Components add (they are
orthogonal over the record).

A linear PTO controller f = -c v - k x = -(c + k / (i omega)) v closes the loop: v = (I + Y D)^-1 v_e with
D = diag(c + k / (i omega)), and each PTO absorbs c_p |v_p|^2 / 2 per component.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...compiled import pto_gains
from ...linear import LinearModel


@dataclass(frozen=True)
class PowerBound:
    """The complex-conjugate bound of a sea state's wave components (see the module docstring).

    Attributes
    ----------
    per_pto : ndarray (n_pto,)
        Mean absorbed power of each PTO at the optimum [W].
    total : float
        Their sum [W].
    force, velocity : complex ndarray (n_pto, n_w)
        Optimal PTO force amplitudes [N or N m] and the stroke-rate amplitudes they give [m/s or rad/s].
    """

    per_pto: np.ndarray
    total: float
    force: np.ndarray
    velocity: np.ndarray


@dataclass(frozen=True)
class LinearGains:
    """Gains of a linear PTO controller f = -c x_dot - k x and the mean power they absorb.

    Attributes
    ----------
    damping, stiffness : ndarray (n_pto,)
        c [N s/m or N m s/rad] and k [N/m or N m/rad].
    power : ndarray (n_pto,)
        Mean absorbed power per PTO [W].
    force_rms : ndarray (n_pto,)
        RMS PTO force [N or N m].
    """

    damping: np.ndarray
    stiffness: np.ndarray
    power: np.ndarray
    force_rms: np.ndarray

    @property
    def total(self) -> float:
        """Total mean absorbed power [W]."""
        return float(np.sum(self.power))


def _check_waves(model: LinearModel, omega: np.ndarray, coefficients: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    omega = np.atleast_1d(np.asarray(omega, dtype=float))
    coefficients = np.asarray(coefficients, dtype=complex)
    n_h = model.hydro_jacobian.shape[0]
    if coefficients.ndim == 1:
        coefficients = coefficients[:, None]
    if coefficients.shape != (n_h, omega.size):
        raise ValueError(
            f"coefficients must be the (n_h, n_omega) = ({n_h}, {omega.size}) excitation amplitudes; "
            f"got shape {coefficients.shape}"
        )
    if not (np.all(np.isfinite(omega)) and np.all(omega > 0) and np.all(np.isfinite(coefficients))):
        raise ValueError("omega must be positive and finite [rad/s] and the coefficients finite")
    return omega, coefficients


def pto_response(model: LinearModel, omega: np.ndarray, coefficients: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The PTO stroke-rate amplitudes v_e (n_pto, n_w) the waves drive with no PTO force, and the PTO admittance Y
    (n_w, n_pto, n_pto) [m/s per N or rad/s per N m] of ``model`` (pass the open plant: ``model.with_pto_gains()``).
    Modal coordinates held quasi-static (``model.held``) have no rate: their part of a stroke moves it, not its rate
    (as in a run, whose PTO force and power see the kept coordinates' rates).

    Raises
    ------
    ValueError
        If the coefficients are not (n_h, n_omega) or not finite, or a frequency is not positive.
    """
    omega, coefficients = _check_waves(model, omega, coefficients)
    g = model.pto_jacobian
    moving = g if model.held is None else g * ~model.held  # the stroke rates: a held coordinate has no rate
    rate = np.empty((omega.size, g.shape[0], 1 + g.shape[0]), dtype=complex)  # (n_w, n_pto, 1 + n_pto)
    for start in range(0, omega.size, RESPONSE_BLOCK):  # the database's matrices per frequency, a block at a time
        w = slice(start, start + RESPONSE_BLOCK)
        z = model.dynamic_stiffness(omega[w])  # (n_w, nv, nv)
        forcing = (model.hydro_jacobian.T @ coefficients[:, w]).T[:, :, None]  # Bw' F per component (n_w, nv, 1)
        inputs = np.broadcast_to(g.T.astype(complex), (z.shape[0], *g.T.shape))
        solved = np.linalg.solve(z, np.concatenate([forcing, inputs], axis=2))
        rate[w] = 1j * omega[w, None, None] * (moving @ solved)
    return rate[:, :, 0].T, rate[:, :, 1:]


RESPONSE_BLOCK: int = 1024
"""Frequencies per block in :func:`pto_response`: the added mass and damping at a frequency are n_h x n_h matrices
(2 x 4.6 kB on m4-134), so a long run's 36,000 wave components took about 0.6 GB at once."""


def power_bound(model: LinearModel, omega: np.ndarray, coefficients: np.ndarray) -> PowerBound:
    """The complex-conjugate (unconstrained optimal) mean absorbed power of the wave components, per PTO and in
    total [W], with the optimal force amplitudes (module docstring). ``model`` is taken as the plant: pass the open
    plant (``context.linear_model()`` or ``model.with_pto_gains()``).

    Raises
    ------
    ValueError
        On bad wave data, or where Yh is singular (a PTO that cannot move at some frequency).
    """
    driven, admittance = pto_response(model, omega, coefficients)
    hermitian = 0.5 * (admittance + np.conj(np.swapaxes(admittance, 1, 2)))
    try:
        force = -0.5 * np.linalg.solve(hermitian, driven.T[:, :, None])[:, :, 0].T
    except np.linalg.LinAlgError:
        raise ValueError(
            "the PTO admittance's Hermitian part is singular: a PTO cannot absorb at some frequency"
        ) from None
    velocity = driven + np.einsum("wpq,qw->pw", admittance, force)
    per_pto = np.sum(-0.5 * np.real(np.conj(force) * velocity), axis=1)
    return PowerBound(per_pto, float(np.sum(per_pto)), force, velocity)


def _closed_loop(
    driven: np.ndarray, admittance: np.ndarray, omega: np.ndarray, damping: np.ndarray, stiffness: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Stroke-rate and force amplitudes (n_pto, n_w) of f = -c v - k x."""
    impedance = damping[None, :] + stiffness[None, :] / (1j * omega[:, None])  # (n_w, n_pto)
    n_pto = damping.size
    system = np.eye(n_pto)[None] + admittance * impedance[:, None, :]
    velocity = np.linalg.solve(system, driven.T[:, :, None])[:, :, 0].T
    return velocity, -impedance.T * velocity


def gains_power(
    model: LinearModel,
    omega: np.ndarray,
    coefficients: np.ndarray,
    damping: np.ndarray | float,
    stiffness: np.ndarray | float = 0.0,
) -> LinearGains:
    """Mean absorbed power per PTO [W] of the linear controller f = -c x_dot - k x on the plant ``model`` (the open
    plant) in the wave components, with the RMS force.

    Raises
    ------
    ValueError
        On bad wave data or gains.
    """
    driven, admittance = pto_response(model, omega, coefficients)
    omega = np.atleast_1d(np.asarray(omega, dtype=float))
    n_pto = driven.shape[0]
    c, k = pto_gains(damping, stiffness, n_pto)
    velocity, force = _closed_loop(driven, admittance, omega, c, k)
    power = 0.5 * c * np.sum(np.abs(velocity) ** 2, axis=1)
    return LinearGains(c, k, power, np.sqrt(0.5 * np.sum(np.abs(force) ** 2, axis=1)))


def optimal_damping(model: LinearModel, omega: np.ndarray, coefficients: np.ndarray) -> LinearGains:
    """The passive damping per PTO (c >= 0, all PTOs together) that maximises the total mean absorbed power of the
    plant ``model`` (the open plant) in the wave components.

    Started from each PTO's optimum alone at the most energetic component, c_p = 1 / |Y_pp|, and refined by
    L-BFGS-B on log c (the optimum is interior: zero damping absorbs nothing).

    Raises
    ------
    ValueError
        On bad wave data.
    """
    driven, admittance = pto_response(model, omega, coefficients)
    omega = np.atleast_1d(np.asarray(omega, dtype=float))
    n_pto = driven.shape[0]
    zero = np.zeros(n_pto)

    def negative_power(log_c: np.ndarray) -> float:
        c = np.exp(log_c)
        velocity, _ = _closed_loop(driven, admittance, omega, c, zero)
        return -0.5 * float(np.sum(c * np.sum(np.abs(velocity) ** 2, axis=1)))

    strongest = int(np.argmax(np.sum(np.abs(driven) ** 2, axis=0)))
    start = np.log(1.0 / np.abs(np.diagonal(admittance[strongest])))
    from scipy.optimize import minimize  # lazy: importing scipy.optimize takes about 0.25 s

    result = minimize(negative_power, start, method="L-BFGS-B", options={"ftol": 1e-15, "gtol": 1e-12})
    return gains_power(model, omega, coefficients, np.exp(result.x))


def optimal_spring_damper(
    model: LinearModel,
    omega: np.ndarray,
    coefficients: np.ndarray,
    *,
    force_limit: np.ndarray | float | None = None,
    force_margin: float = 3.0,
) -> LinearGains:
    """The best causal spring-damper per PTO (c >= 0, k of any sign: reactive when negative; all PTOs together)
    for the total mean absorbed power of the plant ``model`` (the open plant) in the wave components.

    Stability: the gains keep the static stiffness K + G' diag(k) G positive definite. With a passive plant (its
    radiation passive), c >= 0 and a positive definite potential energy the closed loop is stable; a negative
    spring may take away only what that leaves.

    Force limit: with ``force_limit`` (per PTO or one value) [N or N m], ``force_margin`` times the RMS PTO force
    stays within it (3 by default: a Gaussian force passes 3 sigma in 0.27 % of the time; the simulators saturate
    the rest).

    Raises
    ------
    ValueError
        On bad wave data, limits or margin.
    """
    driven, admittance = pto_response(model, omega, coefficients)
    omega = np.atleast_1d(np.asarray(omega, dtype=float))
    n_pto = driven.shape[0]
    if not force_margin > 0:
        raise ValueError(f"force_margin must be positive; got {force_margin!r}")
    limit = None
    if force_limit is not None:
        limit = np.broadcast_to(np.asarray(force_limit, dtype=float), (n_pto,)).copy()
        if np.any(~(limit > 0)):
            raise ValueError(f"force_limit must be positive [N or N m], 1 or {n_pto} values; got {force_limit!r}")
    g = model.pto_jacobian
    stiffness0 = model.stiffness - g.T @ np.diag(model.pto_stiffness) @ g  # the plant's own
    start = optimal_damping(model, omega, coefficients)
    scale_c = np.maximum(start.damping, 1e-12)
    scale_k = scale_c * float(np.sum(omega * np.sum(np.abs(driven) ** 2, axis=0)) / np.sum(np.abs(driven) ** 2))

    def unpack(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return x[:n_pto] * scale_c, x[n_pto:] * scale_k

    def negative_power(x: np.ndarray) -> float:
        c, k = unpack(x)
        velocity, _ = _closed_loop(driven, admittance, omega, c, k)
        return -0.5 * float(np.sum(c * np.sum(np.abs(velocity) ** 2, axis=1)))

    def static_margin(x: np.ndarray) -> float:
        _, k = unpack(x)
        total = stiffness0 + g.T @ np.diag(k) @ g
        return float(np.min(np.linalg.eigvalsh(0.5 * (total + total.T)))) / max(1.0, float(np.max(np.abs(total))))

    constraints = [{"type": "ineq", "fun": lambda x: static_margin(x) - 1e-6}]
    if limit is not None:

        def force_room(x: np.ndarray) -> np.ndarray:
            c, k = unpack(x)
            _, force = _closed_loop(driven, admittance, omega, c, k)
            return 1.0 - force_margin * np.sqrt(0.5 * np.sum(np.abs(force) ** 2, axis=1)) / limit

        constraints.append({"type": "ineq", "fun": force_room})
    x0 = np.concatenate([np.ones(n_pto), np.zeros(n_pto)])
    if limit is not None and np.any(force_room(x0) < 0):  # the optimal damping itself is too strong: scale it down
        x0[:n_pto] *= float(np.min(1.0 / (1.0 - force_room(x0)).clip(1.0)))
    bounds = [(0.0, None)] * n_pto + [(None, None)] * n_pto
    from scipy.optimize import minimize

    result = minimize(
        negative_power, x0, method="SLSQP", bounds=bounds, constraints=constraints,
        options={"ftol": 1e-14, "maxiter": 500},
    )  # fmt: skip
    c, k = unpack(result.x)
    return gains_power(model, omega, coefficients, np.maximum(c, 0.0), k)
