"""Causal estimation of the wave excitation from PTO measurements: a Kalman filter on the linear model augmented with
excitation states.

The plant is the device's linear model without controller (``context.linear_model()``): x' = A x + M^-1 (D w + G' f) in
the rate rows, with w the excitation estimated along the directions D (nv, n_d) of generalised force and f the PTO
forces, measured y = [PTO strokes, PTO stroke rates] (from the equilibrium). By default D = G': the PTO forces w that
move the PTOs as the generalised excitation e = Bw' F_exc does. In the frequency domain that is w* = (G Z^-1 G')^-1 G
Z^-1 e with Z(omega) the dynamic stiffness (:func:`pto_equivalent`), the one combination the PTO measurements identify;
:meth:`ExcitationEstimator.for_sea` takes its prior from it. The static w = (G M^-1 G')^-1 G M^-1 e
(:func:`pto_referred`) is another quantity on a device with more coordinates than PTOs (50-70 % RMS apart on m4-134),
which the PTOs alone cannot give (see :mod:`._wave_estimation`). With D the identity every generalised component is
estimated, but as independent processes the PTOs cannot tell them apart. Each excitation component is the output of a
bank of lightly damped oscillators at the sea state's frequencies driven by white noise, e_j = sum_i eta_ij, eta'' + 2
zeta w_i eta' + w_i^2 eta = noise, whose stationary variance is the component's expected variance split over the bank.
The augmented system is discretised exactly at the control period with the PTO force held (zero-order hold, as the
simulators apply it) and the excitation's noise integrated exactly (Van Loan); the steady-state Kalman gain comes from
the discrete algebraic Riccati equation. Components the PTOs cannot see (with one PTO on m4-111, most of the base's
surge and heave) keep their prior uncertainty: :attr:`ExcitationEstimator.observed` says how much of each component's
variance the filter resolves. The filter's model decays at LEAK times the lowest oscillator frequency on top of the
plant's own damping, so that modes at zero frequency (a free surge) do not leave the Riccati equation without a
solution. Optionally the measured strokes carry slowly varying offsets, estimated with the rest (``bias_std``).
"""

from __future__ import annotations

import numpy as np

from ...linear import LinearModel
from ._kalman import LEAK as LEAK
from ._kalman import RunningFilter, pto_measure, steady_kalman


class ExcitationEstimator(RunningFilter):
    """Kalman filter of the plant state and the generalised excitation force (module docstring).

    Parameters
    ----------
    model : LinearModel
        The device's linear model with a state-space system (``context.linear_model()``: no controller folded
        in; the PTO forces are known inputs).
    dt : float
        Control period [s]: one :meth:`update` per period, the PTO force held over it.
    frequencies : array_like
        Centre frequencies of the oscillator bank [rad/s] (e.g. spread over the spectrum's band).
    variance : array_like (n_d,)
        Expected variance of each estimated excitation component [N^2 or (N m)^2] (0: a component not estimated).
    measurement_std : array_like (2 n_pto,)
        Standard deviation of the measurement noise of the strokes, then the rates [m or rad; m/s or rad/s].
    damping_ratio : float
        Damping ratio of the oscillators [-] (light: the excitation is narrow-banded around each).
    directions : array_like (nv, n_d) or None
        The generalised-force directions of the estimated components (default G': one per PTO).
    bias_std : array_like (n_pto,) or None
        Standard deviation of a slowly varying offset of each measured stroke [m or rad], estimated with the rest
        (default None: no offset). The nonlinear simulator's strokes carry one that the linear model has not: a
        mean shift second order in the motion (1.6 % of the stroke's RMS on the Wavestar, 1.0 % on m4-111 under
        damping), which a filter without it can only explain as excitation.
    bias_time : float
        Correlation time of that offset [s] (a first-order Gauss-Markov process; default 5).

    Raises
    ------
    ValueError
        On shapes that disagree, non-positive noise or frequencies, a model without state space, or one with
        coordinates held quasi-static (``LinearModel.refuse_held``).
    """

    def __init__(
        self,
        model: LinearModel,
        dt: float,
        frequencies: np.ndarray,
        variance: np.ndarray,
        measurement_std: np.ndarray,
        *,
        damping_ratio: float = 0.05,
        directions: np.ndarray | None = None,
        bias_std: np.ndarray | None = None,
        bias_time: float = 5.0,
    ) -> None:
        model.refuse_held("the excitation estimator")
        n = model.n_states
        nv, n_pto = model.mass.shape[0], model.pto_jacobian.shape[0]
        directions = model.pto_jacobian.T if directions is None else np.asarray(directions, dtype=float)
        if directions.ndim != 2 or directions.shape[0] != nv:
            raise ValueError(f"directions must be (nv, n_d) with nv = {nv}; got shape {directions.shape}")
        n_d = directions.shape[1]
        frequencies = np.atleast_1d(np.asarray(frequencies, dtype=float))
        variance = np.asarray(variance, dtype=float)
        measurement_std = np.asarray(measurement_std, dtype=float)
        if not dt > 0:
            raise ValueError(f"dt must be positive [s]; got {dt!r}")
        if frequencies.ndim != 1 or frequencies.size == 0 or not np.all(frequencies > 0):
            raise ValueError(f"frequencies must be positive [rad/s], at least one; got {frequencies!r}")
        if variance.shape != (n_d,) or not np.all(variance >= 0) or not np.any(variance > 0):
            raise ValueError(f"variance: expected {n_d} non-negative values, some positive; got {variance!r}")
        if measurement_std.shape != (2 * n_pto,) or not np.all(measurement_std > 0):
            raise ValueError(f"measurement_std: expected {2 * n_pto} positive values; got {measurement_std!r}")
        if not 0 < damping_ratio < 1:
            raise ValueError(f"damping_ratio must lie in (0, 1); got {damping_ratio!r}")
        if bias_std is not None:
            bias_std = np.asarray(bias_std, dtype=float)
            if bias_std.shape != (n_pto,) or not np.all(bias_std > 0):
                raise ValueError(f"bias_std: expected {n_pto} positive values or None; got {bias_std!r}")
        if not bias_time > 0:
            raise ValueError(f"bias_time must be positive [s]; got {bias_time!r}")
        estimated = np.flatnonzero(variance > 0)
        n_osc = frequencies.size
        m = 2 * n_osc * estimated.size  # oscillator states: (position, rate) per frequency per component
        # the oscillator bank: e_j = sum_i eta_ij; eta'' + 2 zeta w eta' + w^2 eta = q_ij white noise
        a_osc = np.zeros((m, m))
        out_osc = np.zeros((n_d, m))
        noise = np.zeros(m)
        for c, j in enumerate(estimated):
            for i, w in enumerate(frequencies):
                k = 2 * (c * n_osc + i)
                a_osc[k, k + 1] = 1.0
                a_osc[k + 1, k] = -(w**2)
                a_osc[k + 1, k + 1] = -2 * damping_ratio * w
                out_osc[j, k] = 1.0
                # stationary variance of eta is q / (4 zeta w^3): the component's variance split over the bank
                noise[k + 1] = 4 * damping_ratio * w**3 * variance[j] / n_osc
        measure = pto_measure(model)
        if bias_std is not None:  # a slowly varying offset of each measured stroke (first-order Gauss-Markov)
            m0 = m
            m += n_pto
            grow = np.zeros((m, m))
            grow[:m0, :m0] = a_osc
            grow[m0:, m0:] = -np.eye(n_pto) / bias_time
            a_osc = grow
            noise = np.concatenate([noise, 2 * bias_std**2 / bias_time])
            out_osc = np.hstack([out_osc, np.zeros((n_d, n_pto))])
            whole = np.zeros((2 * n_pto, n + m))
            whole[:, :n] = measure
            whole[:n_pto, n + m0 :] = np.eye(n_pto)
            measure = whole
        kalman = steady_kalman(
            model, dt, a_osc, noise, directions @ out_osc, measure, measurement_std,
            float(np.min(frequencies)),
        )  # fmt: skip
        prior = np.diag(out_osc @ kalman.predicted[n:, n:] @ out_osc.T)
        after = np.diag(out_osc @ kalman.corrected[n:, n:] @ out_osc.T)
        self.observed = np.where(prior > 0, 1.0 - after / np.where(prior > 0, prior, 1.0), 0.0)
        """Share of each component's predicted variance one update resolves [-] (0: the PTOs do not see it)."""
        self.output = out_osc
        self._start(kalman, model)

    @classmethod
    def for_sea(
        cls,
        model: LinearModel,
        dt: float,
        omega: np.ndarray,
        coefficients: np.ndarray,
        *,
        n_frequencies: int = 8,
        relative_noise: float = 1e-3,
        damping_ratio: float = 0.05,
        equivalent: bool = True,
        relative_bias: float = 0.0,
    ) -> ExcitationEstimator:
        """An estimator of the PTO-equivalent excitation (``equivalent``, default; else the static
        :func:`pto_referred` for the prior), tuned to a sea state's wave components (``context.excitation.omega``
        and ``.coefficients``): oscillators at ``n_frequencies`` quantiles of the excitation's energy, each
        component's variance from the spectrum, and measurement noise ``relative_noise`` times the measured
        signals' RMS in the open plant's steady state. With ``relative_bias`` > 0 each stroke has an offset state of
        that many times the stroke's RMS, correlated over four periods of the lowest oscillator.

        Raises
        ------
        ValueError
            On bad wave data or settings.
        """
        omega = np.asarray(omega, dtype=float)
        generalised = model.hydro_jacobian.T @ np.asarray(coefficients, dtype=complex)
        referred = pto_equivalent(model, omega, generalised) if equivalent else pto_referred(model, generalised)
        energy = 0.5 * np.abs(referred) ** 2
        variance = np.sum(energy, axis=1)
        weights = np.cumsum(np.sum(energy, axis=0))
        if not n_frequencies >= 1 or weights[-1] <= 0:
            raise ValueError(f"n_frequencies must be >= 1 and the waves must carry energy; got {n_frequencies!r}")
        quantiles = (np.arange(n_frequencies) + 0.5) / n_frequencies * weights[-1]
        frequencies = np.interp(quantiles, weights, omega)
        if not relative_noise > 0:
            raise ValueError(f"relative_noise must be positive; got {relative_noise!r}")
        if not relative_bias >= 0:
            raise ValueError(f"relative_bias must be >= 0; got {relative_bias!r}")
        rms = measured_rms(model, omega, coefficients)
        bias = relative_bias * rms[: model.pto_jacobian.shape[0]] if relative_bias > 0 else None
        return cls(
            model,
            dt,
            frequencies,
            variance,
            relative_noise * rms,
            damping_ratio=damping_ratio,
            bias_std=bias,
            bias_time=4 * 2 * np.pi / float(np.min(frequencies)),
        )

    def update(self, stroke: np.ndarray, rate: np.ndarray, force: np.ndarray | None) -> np.ndarray:
        """One control period: predict over it with the PTO force held since the last update, then correct with
        the measured PTO strokes (from their rest positions) and rates; returns the estimated excitation
        components (n_d,) now [N or N m]. ``force`` [N or N m] is the force applied from now on (None: give it
        with :meth:`hold` once known)."""
        self._correct(stroke, rate)
        if force is not None:
            self.hold(force)
        return self.excitation

    @property
    def excitation(self) -> np.ndarray:
        """The estimated excitation components (n_d,) [N or N m]: referred to the PTOs by default."""
        return self.output @ self.x[self.n_plant :]


def pto_referred(model: LinearModel, generalised: np.ndarray) -> np.ndarray:
    """The excitation referred to the PTOs, w = (G M^-1 G')^-1 G M^-1 e, of generalised excitation forces e
    (nv, ...) [N or N m]: the PTO forces that would give the PTO coordinates the same acceleration."""
    g, minv = model.pto_jacobian, np.linalg.inv(model.mass)
    return np.linalg.solve(g @ minv @ g.T, g @ minv @ generalised)


def pto_equivalent(model: LinearModel, omega: np.ndarray, generalised: np.ndarray) -> np.ndarray:
    """The PTO forces equivalent to generalised excitation amplitudes ``generalised`` (nv, n_w) [N or N m] at the
    frequencies ``omega`` (n_w,) [rad/s], (n_pto, n_w): w*(omega) = (G Z^-1 G')^-1 G Z^-1 e with Z(omega) the open
    plant's dynamic stiffness (exact, from the database). The PTO strokes respond to G' w* as to e whatever the PTO
    forces, so w* is what PTO measurements identify; the static :func:`pto_referred` (Z ~ -omega^2 M) is not (50 %
    RMS apart on m4-134 in its default sea, 30 % on m4-111; equal with one coordinate per PTO)."""
    omega = np.atleast_1d(np.asarray(omega, dtype=float))
    generalised = np.asarray(generalised, dtype=complex)
    z = model.with_pto_gains().dynamic_stiffness(omega)  # (n_w, nv, nv)
    g = model.pto_jacobian
    out = np.empty((g.shape[0], omega.size), dtype=complex)
    for k in range(omega.size):
        to_pto = g @ np.linalg.inv(z[k])  # G Z^-1 (n_pto, nv)
        out[:, k] = np.linalg.solve(to_pto @ g.T, to_pto @ generalised[:, k])
    return out


def measured_rms(model: LinearModel, omega: np.ndarray, coefficients: np.ndarray) -> np.ndarray:
    """RMS of the PTO strokes, then of their rates (2 n_pto,) [m or rad; m/s or rad/s], of ``model`` without
    PTO gains in the waves ``omega`` [rad/s], ``coefficients`` (n_h, n_w) [N or N m], from the exact frequency
    response."""
    omega = np.asarray(omega, dtype=float)
    h = model.with_pto_gains().frequency_response(omega)  # (n_w, nv, n_h)
    xi = np.einsum("wvj,jw->vw", h, np.asarray(coefficients, dtype=complex))
    strokes = model.pto_jacobian @ xi
    return np.sqrt(0.5 * np.concatenate([np.sum(np.abs(strokes) ** 2, 1), np.sum(np.abs(omega * strokes) ** 2, 1)]))
