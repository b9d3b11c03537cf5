"""Causal estimation of the generalised wave excitation on every coordinate of a device from its PTO measurements,
with the excitation modelled as ONE wave process per frequency band (a Kalman filter on the linear model augmented
with it).

A long-crested sea drives every excitation component through one elevation: e(t) = Re sum_k X(omega_k) A_k
e^{i omega_k t} with X (nv,) the generalised excitation per unit wave. Within a narrow band of frequencies around
omega_b, X is nearly one complex vector u_b, and the band's excitation is e_b = Re(u_b c_b(t)) with c_b a scalar
narrow-band process: with p_b = Re c_b an oscillator of the bank (p'' + 2 zeta omega_b p' + omega_b^2 p = white
noise), e_b = Re(u_b) p_b + Im(u_b) / omega_b p_b' (exact at omega_b). The shape u_b is the band's principal
direction: the leading eigenvector of the cross-spectral matrix sum_k E_k E_k^H of the wave components in the band
(each coordinate scaled by its RMS), and the oscillator's variance the share of the band's energy along it. So the
whole generalised excitation costs two states per band, whatever the number of coordinates, and the components
are tied together as the waves tie them: the few PTO measurements resolve all of them where a model with
independent components (:class:`._estimation.ExcitationEstimator` with the identity as directions) cannot tell them
apart.

Referring the excitation to the PTOs by the static formula w = (G M^-1 G')^-1 G M^-1 e is what the PTO
measurements of a multi-coordinate device do NOT determine: the PTO strokes respond to
(G Z^-1 G')^-1 G Z^-1 e with Z(omega) the dynamic stiffness, which differs from the static formula by 50 % of its
RMS on m4-134 in the default sea (30 % on m4-111). Estimating e itself and referring it afterwards gives both.
"""

from __future__ import annotations

import numpy as np

from ...linear import LinearModel
from ._estimation import measured_rms, pto_referred
from ._kalman import RunningFilter, pto_measure, steady_kalman


class WaveExcitationEstimator(RunningFilter):
    """Kalman filter of the plant state and the generalised excitation (nv,) as the output of one scalar process
    per band (module docstring).

    Parameters
    ----------
    model : LinearModel
        The device's linear model with a state-space system (``context.linear_model()``, or a reduction of it: no
        controller folded in; the PTO forces are known inputs).
    dt : float
        Control period [s]: one :meth:`update` per period, the PTO force held over it.
    frequencies : array_like (n_b,)
        Centre frequency of each band's oscillator [rad/s].
    shapes : complex array_like (nv, n_b)
        The generalised excitation per unit of each band's process, u_b [N or N m per unit].
    variance : array_like (n_b,)
        Stationary variance of each band's process [unit^2] (positive).
    measurement_std : array_like (2 n_pto,)
        Standard deviation of the measurement noise of the PTO strokes, then the rates [m or rad; m/s or rad/s].
    damping_ratio : float
        Damping ratio of the oscillators [-] (light: each band is narrow).
    velocity_std : array_like (nv,) or None
        Standard deviation of the measurement noise of the generalised velocities (the bodies' motions: the rates
        of the model's coordinates) [m/s or rad/s], when they are measured too (default None: the PTOs only).

    Raises
    ------
    ValueError
        On shapes that disagree, non-positive frequencies, variances or noise, or a model without state space.
    """

    def __init__(
        self,
        model: LinearModel,
        dt: float,
        frequencies: np.ndarray,
        shapes: np.ndarray,
        variance: np.ndarray,
        measurement_std: np.ndarray,
        *,
        damping_ratio: float = 0.05,
        velocity_std: np.ndarray | None = None,
    ) -> None:
        model.refuse_held("the wave estimator")
        nv, n_pto = model.mass.shape[0], model.pto_jacobian.shape[0]
        frequencies = np.atleast_1d(np.asarray(frequencies, dtype=float))
        shapes = np.asarray(shapes, dtype=complex)
        variance = np.atleast_1d(np.asarray(variance, dtype=float))
        measurement_std = np.asarray(measurement_std, dtype=float)
        n_b = frequencies.size
        if not dt > 0:
            raise ValueError(f"dt must be positive [s]; got {dt!r}")
        if frequencies.ndim != 1 or n_b == 0 or not np.all(frequencies > 0):
            raise ValueError(f"frequencies must be positive [rad/s], at least one; got {frequencies!r}")
        if shapes.shape != (nv, n_b) or not np.all(np.isfinite(shapes)):
            raise ValueError(f"shapes: expected finite ({nv}, {n_b}) (coordinates, bands); got shape {shapes.shape}")
        if variance.shape != (n_b,) or not np.all(variance > 0):
            raise ValueError(f"variance: expected {n_b} positive values; got {variance!r}")
        if measurement_std.shape != (2 * n_pto,) or not np.all(measurement_std > 0):
            raise ValueError(f"measurement_std: expected {2 * n_pto} positive values; got {measurement_std!r}")
        if not 0 < damping_ratio < 1:
            raise ValueError(f"damping_ratio must lie in (0, 1); got {damping_ratio!r}")
        measure = pto_measure(model)
        if velocity_std is not None:
            velocity_std = np.asarray(velocity_std, dtype=float)
            if velocity_std.shape != (nv,) or not np.all(velocity_std > 0):
                raise ValueError(f"velocity_std: expected {nv} positive values or None; got {velocity_std!r}")
            rates = np.zeros((nv, model.n_states))
            rates[:, nv : 2 * nv] = np.eye(nv)
            measure = np.vstack([measure, rates])
            measurement_std = np.concatenate([measurement_std, velocity_std])
        m = 2 * n_b
        a_osc = np.zeros((m, m))
        forcing = np.zeros((nv, m))
        noise = np.zeros(m)
        stationary = np.zeros(m)
        for b, w in enumerate(frequencies):
            k = 2 * b
            a_osc[k, k + 1] = 1.0
            a_osc[k + 1, k] = -(w**2)
            a_osc[k + 1, k + 1] = -2 * damping_ratio * w
            forcing[:, k] = shapes[:, b].real
            forcing[:, k + 1] = shapes[:, b].imag / w
            # stationary variances: q / (4 zeta w^3) of p, q / (4 zeta w) of p' (uncorrelated)
            noise[k + 1] = 4 * damping_ratio * w**3 * variance[b]
            stationary[k], stationary[k + 1] = variance[b], w**2 * variance[b]
        kalman = steady_kalman(model, dt, a_osc, noise, forcing, measure, measurement_std, float(np.min(frequencies)))
        n = model.n_states
        prior = np.einsum("ij,j,ij->i", forcing, stationary, forcing)
        after = np.diag(forcing @ kalman.corrected[n:, n:] @ forcing.T)
        self.resolved = 1.0 - after / np.where(prior > 0, prior, 1.0)
        """Share of each coordinate's excitation variance the filter resolves in its steady state [-]: 1 - the
        error's variance after an update / the excitation's variance (1: known exactly; 0: nothing learnt)."""
        referred = pto_referred(model, forcing)  # (n_pto, m)
        prior = np.einsum("ij,j,ij->i", referred, stationary, referred)
        after = np.diag(referred @ kalman.corrected[n:, n:] @ referred.T)
        self.resolved_referred = 1.0 - after / np.where(prior > 0, prior, 1.0)
        """The same share for the excitation referred to the PTOs (n_pto,) [-]."""
        self.measures_velocity = velocity_std is not None
        self.forcing = forcing
        self.model = model
        self._start(kalman, model)

    @classmethod
    def for_sea(
        cls,
        model: LinearModel,
        dt: float,
        omega: np.ndarray,
        coefficients: np.ndarray,
        *,
        n_bands: int = 16,
        relative_noise: float = 1e-3,
        damping_ratio: float = 0.05,
        velocities: bool = False,
    ) -> WaveExcitationEstimator:
        """An estimator tuned to a sea state's wave components (``context.excitation.omega`` [rad/s] and
        ``.coefficients`` (n_h, n_w) [N or N m]): ``n_bands`` bands centred at quantiles of the excitation's energy
        (every coordinate's share counted alike), each wave component in the band of the nearest centre, each
        band's shape and variance from its components' cross-spectral matrix (module docstring), and measurement
        noise ``relative_noise`` times the measured signals' RMS in the open plant's steady state. With
        ``velocities`` the generalised velocities are measured too, with noise ``relative_noise`` times their RMS.

        Raises
        ------
        ValueError
            On bad wave data or settings.
        """
        omega = np.asarray(omega, dtype=float)
        generalised = model.hydro_jacobian.T @ np.asarray(coefficients, dtype=complex)  # (nv, n_w)
        if not (isinstance(n_bands, int) and n_bands >= 1):
            raise ValueError(f"n_bands must be an integer >= 1; got {n_bands!r}")
        if not relative_noise > 0:
            raise ValueError(f"relative_noise must be positive; got {relative_noise!r}")
        energy = 0.5 * np.abs(generalised) ** 2  # (nv, n_w)
        total = np.sum(energy, axis=1)
        if omega.ndim != 1 or omega.size != generalised.shape[1] or not np.any(total > 0):
            raise ValueError(
                f"the waves must carry energy, with one frequency per coefficient column; got {omega.size} "
                f"frequencies for coefficients of shape {np.shape(coefficients)}"
            )
        scale = np.sqrt(np.where(total > 0, total, 1.0))  # each coordinate's RMS [N or N m]
        weights = np.cumsum(np.sum(energy[total > 0] / total[total > 0, None], axis=0))
        quantiles = (np.arange(n_bands) + 0.5) / n_bands * weights[-1]
        centres = np.unique(np.interp(quantiles, weights, omega))
        band = np.argmin(np.abs(omega[:, None] - centres[None, :]), axis=1)
        frequencies, shapes, variance = [], [], []
        for b, w in enumerate(centres):
            scaled = generalised[:, band == b] / scale[:, None]
            values, vectors = np.linalg.eigh(scaled @ scaled.conj().T)
            if values[-1] <= 0:
                continue
            u = vectors[:, -1]
            # the phase that makes u as real as it can be: e_b = Re(u) p + Im(u) / w p' is exact only at w
            square = np.sum(u**2)
            u = u * np.exp(-0.5j * np.angle(square)) if abs(square) > 0 else u
            frequencies.append(w)
            shapes.append(scale * u)
            variance.append(0.5 * values[-1])
        rms = measured_rms(model, omega, coefficients)
        velocity_std = None
        if velocities:
            xi = np.einsum("wvj,jw->vw", model.with_pto_gains().frequency_response(omega), coefficients)
            velocity_rms = np.sqrt(0.5 * np.sum(np.abs(omega * xi) ** 2, axis=1))
            velocity_std = relative_noise * np.maximum(velocity_rms, 1e-9 * float(np.max(velocity_rms)))
        return cls(
            model, dt, np.array(frequencies), np.array(shapes).T, np.array(variance), relative_noise * rms,
            damping_ratio=damping_ratio, velocity_std=velocity_std,
        )  # fmt: skip

    def update(
        self, stroke: np.ndarray, rate: np.ndarray, force: np.ndarray | None, velocity: np.ndarray | None = None
    ) -> np.ndarray:
        """One control period: predict over it with the PTO force held since the last update, then correct with
        the measured PTO strokes (from their rest positions) and rates, and the generalised ``velocity`` (nv,)
        [m/s or rad/s] when the filter measures it; returns the estimated generalised excitation (nv,) now [N or
        N m]. ``force`` [N or N m] is the force applied from now on (None: give it with :meth:`hold` once known).

        Raises
        ------
        ValueError
            Without ``velocity`` when the filter measures it (or with it when it does not).
        """
        if (velocity is None) == self.measures_velocity:
            raise ValueError(
                "this estimator measures the generalised velocities: give velocity"
                if self.measures_velocity
                else "this estimator measures the PTOs only: velocity must be None"
            )
        self._correct(stroke, rate, *(() if velocity is None else (velocity,)))
        if force is not None:
            self.hold(force)
        return self.excitation

    @property
    def excitation(self) -> np.ndarray:
        """The estimated generalised excitation (nv,) [N or N m] (Bw' F_exc: on the model's coordinates)."""
        return self.forcing @ self.x[self.n_plant :]

    @property
    def referred(self) -> np.ndarray:
        """The estimated excitation referred to the PTOs (n_pto,) [N or N m] (:func:`pto_referred`)."""
        return pto_referred(self.model, self.excitation)
