"""Wave excitation forces in time (M4 paper Eq. 49), vectorised over components and times.

F_j(t) = r(t) Re[sum_k X_j(omega_k) A_k exp(i omega_k t)] with X_j the database's excitation per unit wave
amplitude (referenced, as BEM codes do, to the incident wave at the global origin) and r the ramp. To interpolate
X between the database's frequencies without smearing the fast phase rotation of bodies far from the origin, the
incident-wave phase at each body's position, exp(-i k (x cos beta + y sin beta)), is taken out before
interpolating and put back after.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..hydro import HydroData, split_dof
from ._blocks import BlockSum
from ._elevation import Ramp, WaveComponents, evaluate
from ._spectra import wavenumber

MAX_OUTSIDE_SHARE: float = 0.01
"""Largest share of the wave variance that may lie outside the database's frequencies (dropped, reported)."""


@dataclass(frozen=True)
class ExcitationModel:
    """Excitation of a database's DOFs by a sea state.

    Attributes
    ----------
    dofs : tuple of str
        DOF names (rows).
    omega : ndarray (n,)
        Component frequencies used [rad/s].
    coefficients : complex ndarray (n_dof, n)
        X_j(omega_k) A_k [N, N m].
    ramp : Ramp or None
    outside_share : float
        Share of the wave variance in components outside the database's frequency range, which were left out.
    """

    dofs: tuple[str, ...]
    omega: np.ndarray
    coefficients: np.ndarray
    ramp: Ramp | None = None
    outside_share: float = 0.0

    def force(self, time: np.ndarray, *, chunk: int = 2_000_000) -> np.ndarray:
        """Excitation forces [N, N m], (n_dof, n_times), at ``time`` [s]."""
        time = np.atleast_1d(np.asarray(time, dtype=float))
        out = np.real(evaluate(self.coefficients, self.omega, time, chunk=chunk))
        if self.ramp is not None:
            out *= self.ramp(time)[None, :]
        return out

    def sampled(self, tau: float, block: int | None = None) -> SampledForce | None:
        """The forces at the times n tau [s] of a uniform grid, by blocks of ``block`` samples (see
        :class:`SampledForce`); None when the components do not repeat on that grid (a record that does not
        repeat: :meth:`force` evaluates it)."""
        sums = BlockSum.on_grid(self.coefficients, self.omega, tau, block)
        return None if sums is None else SampledForce(sums, tau, self.ramp)


@dataclass(frozen=True)
class SampledForce:
    """Excitation forces at the times n tau of a uniform grid, evaluated for blocks of consecutive samples n at a
    cost per sample and a memory that depend on neither the number of wave components nor n (a chirp-z transform
    per block: :class:`~wecss.waves._blocks.BlockSum`). Equal to :meth:`ExcitationModel.force` to round-off.

    Attributes
    ----------
    sums : BlockSum
    tau : float
        Step of the grid [s].
    ramp : Ramp or None
    """

    sums: BlockSum
    tau: float
    ramp: Ramp | None = None

    @property
    def block(self) -> int:
        """Samples per block (a call for more is made of several)."""
        return self.sums.block

    def __call__(self, n0: int, m: int) -> np.ndarray:
        """Forces at the times (n0 + j) tau, j = 0 ... m - 1 [N, N m], ramp included, time-major (m, n_dof) as the
        time loop reads them (:meth:`ExcitationModel.force` gives (n_dof, m))."""
        out = self.sums.real(n0, m)
        if self.ramp is not None:
            out *= self.ramp((n0 + np.arange(m)) * self.tau)[:, None]
        return out


def excitation_coefficients(hydro: HydroData, omega: np.ndarray, direction: float = 0.0) -> np.ndarray:
    """Excitation X (n_dof, n) at ``omega`` [rad/s] for one wave ``direction`` [rad], interpolated with the
    incident-wave phase of each body taken out (see the module docstring).

    Raises
    ------
    ValueError
        If the direction is not in the database, or a frequency lies outside its range.
    """
    ds = hydro.dataset
    directions = ds.wave_direction.values
    match = np.flatnonzero(np.isclose(directions, direction, atol=1e-6))
    if match.size == 0:
        raise ValueError(f"wave direction {direction!r} rad is not in the database; it has {directions.tolist()} rad")
    omega = np.asarray(omega, dtype=float)
    data_omega = hydro.omega
    if omega.size and (omega.min() < data_omega[0] * (1 - 1e-12) or omega.max() > data_omega[-1] * (1 + 1e-12)):
        raise ValueError(
            f"frequencies {omega.min():.4g}-{omega.max():.4g} rad/s reach outside the database's "
            f"{data_omega[0]:.4g}-{data_omega[-1]:.4g} rad/s"
        )
    x = ds.excitation.values[:, match[0], :]  # (omega, dof)
    com = {str(b): ds.center_of_mass.sel(body=b).values for b in ds.body.values}
    along = np.array([com[split_dof(d)[0]] @ [np.cos(direction), np.sin(direction), 0.0] for d in hydro.dofs])
    k_data = wavenumber(data_omega, hydro.water_depth, hydro.g)
    local = x * np.exp(1j * np.outer(k_data, along))
    out = np.empty((len(hydro.dofs), omega.size), dtype=complex)
    for j in range(len(hydro.dofs)):
        out[j] = np.interp(omega, data_omega, local[:, j].real) + 1j * np.interp(omega, data_omega, local[:, j].imag)
    k = wavenumber(omega, hydro.water_depth, hydro.g)
    return out * np.exp(-1j * np.outer(along, k))


def excitation_model(
    hydro: HydroData,
    waves: WaveComponents,
    *,
    ramp: Ramp | None = None,
    max_outside_share: float = MAX_OUTSIDE_SHARE,
) -> ExcitationModel:
    """Excitation of every DOF of ``hydro`` by ``waves`` (in a directional sea, each component by the database's
    excitation at its own heading, and the components of one frequency summed into one column).

    Components outside the database's frequency range are left out when together they carry at most
    ``max_outside_share`` of the wave variance (reported in ``outside_share``).

    Raises
    ------
    ValueError
        If more than that lies outside the database's frequencies.
    """
    inside = (waves.omega >= hydro.omega[0]) & (waves.omega <= hydro.omega[-1])
    energy = np.abs(waves.amplitude) ** 2
    share = float(energy[~inside].sum() / energy.sum()) if energy.sum() > 0 else 0.0
    if share > max_outside_share:
        raise ValueError(
            f"{share:.1%} of the wave variance lies outside the database's frequencies "
            f"{hydro.omega[0]:.4g}-{hydro.omega[-1]:.4g} rad/s (accepted: {max_outside_share:.1%}); "
            "use a database with a wider frequency range or a sea state inside it"
        )
    omega = waves.omega[inside]
    if waves.headings is None:
        x = excitation_coefficients(hydro, omega, waves.direction)
        return ExcitationModel(tuple(hydro.dofs), omega, x * waves.amplitude[inside][None, :], ramp, share)
    # a directional sea: each heading's components by the database's excitation at that heading, then the
    # components of one frequency (on every heading) summed into one column
    headings = waves.headings[inside]
    amplitude = waves.amplitude[inside]
    unique, column = np.unique(omega, return_inverse=True)
    coefficients = np.zeros((len(hydro.dofs), unique.size), dtype=complex)
    for heading in np.unique(headings):
        rows = np.flatnonzero(headings == heading)
        x = excitation_coefficients(hydro, omega[rows], float(heading))
        np.add.at(coefficients.T, column[rows], (x * amplitude[rows][None, :]).T)
    return ExcitationModel(tuple(hydro.dofs), unique, coefficients, ramp, share)
