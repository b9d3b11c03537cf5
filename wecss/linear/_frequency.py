"""The exact frequency-domain steady state of the linearised MFM equations on a scene's waves (the reference the
nonlinear simulator must reproduce in small waves: same hydro data, same record), as a Dataset."""

from __future__ import annotations

import numpy as np
import xarray as xr

from ..attributes import apply_attrs, by_pto_kind
from ..compiled import CompiledScene
from ..hydro import dof_kinds
from ..waves import ExcitationModel, evaluate
from ._model import LinearModel, linearize


def response_amplitudes(model: LinearModel, omega: np.ndarray, coefficients: np.ndarray) -> np.ndarray:
    """Complex amplitudes xi_hat (nv, n_w) of the generalised displacements from the equilibrium, Re[xi_hat
    e^{i omega t}], for excitation amplitudes ``coefficients`` (n_h, n_w) [N, N m, J] at ``omega`` (n_w,) [rad/s]
    on the hydro DOFs: the exact frequency response of ``model`` [m, rad, 1]; with the model's linearised drag
    (``model.drag``) its forcing by the fluid's velocity too (the components must be those it was linearised on).

    Raises
    ------
    ValueError
        If the model carries a linearised drag of other wave components.
    """
    omega = np.asarray(omega, dtype=float)
    if omega.size == 0:
        return np.zeros((model.mass.shape[0], 0), dtype=complex)
    out = np.einsum("wvj,jw->vw", model.frequency_response(omega), coefficients)
    if model.drag is not None and model.drag.forcing.size:
        if not np.array_equal(omega, model.drag.omega):
            raise ValueError(
                "the linear model's drag was linearised in its scene's sea state: evaluate it on that scene's wave "
                "components (or linearise a scene with these waves)"
            )
        z = model.dynamic_stiffness(omega)
        out = out + np.linalg.solve(z, model.drag.forcing.T[:, :, None])[:, :, 0].T
    return out


def steady_state(compiled: CompiledScene, time: np.ndarray | None = None) -> xr.Dataset:
    """Steady-state linear response to the scene's wave components (no ramp, no transient), exact from the
    database's A(omega) and B(omega), with the scene's linear PTO gains.

    Parameters
    ----------
    compiled : CompiledScene
        A scene in waves whose controller has linear gains (such as "damping").
    time : array, optional
        Times [s] at which to also give the time series (absolute values, laid out as a result's:
        ``displacement``, ``angle``, ``pto_angle``, ``pto_displacement`` and their rates); without it, only the
        amplitudes.

    Returns
    -------
    Dataset
        Dimensions ``omega`` (the wave components), ``dof_linear`` / ``dof_angular`` / ``dof_generalised`` (the
        kinds of ``Multibody.velocity_kinds``; a kind no coordinate has gives no dimension), ``pto`` (with
        ``pto_kind``) and ``time`` when given. Complex amplitudes, Re[X e^{+i omega t}] about the equilibrium:
        ``displacement_amplitude`` [m], ``angle_amplitude`` [rad] and ``generalised_coordinate_amplitude`` [1] (the
        bodies' generalised modes) of the generalised coordinates (those held quasi-static, ``flexible.
        quasi_static_above``, condensed: no rate, no acceleration; their rates in the time series zero, as a run
        records them),
        ``pto_angle_amplitude`` [rad] and ``pto_displacement_amplitude`` [m] of the PTO strokes (NaN for PTOs of
        the other kind, absent for a kind no PTO has), ``excitation_force_amplitude`` [N],
        ``excitation_moment_amplitude`` [N m] and ``excitation_generalised_force_amplitude`` [J] on the hydro DOFs
        (``hydro_dof_linear`` / ``hydro_dof_angular`` / ``hydro_dof_generalised``),
        ``wave_amplitude`` of the undisturbed elevation at the origin [m]; ``mean_pto_power`` [W], the exact mean
        absorbed power of each PTO's linear damping c, sum over components of c omega^2 |x_hat|^2 / 2 (x_hat
        without the held coordinates' part, which has no rate).
        Attributes ``rho`` and ``g`` of the data.

    Raises
    ------
    ValueError
        In calm water, for a controller without linear gains, or for time series of a device with a free base.
    TypeError
        If ``compiled`` is not a CompiledScene.
    """
    exc = frequency_domain_waves(compiled, "steady_state")
    model = linearize(compiled)
    device = compiled.device.model
    amplitudes = response_amplitudes(model, exc.omega, exc.coefficients)  # (nv, n_w)
    stroke = model.pto_jacobian @ amplitudes  # (n_pto, n_w)
    moving = stroke if model.held is None else model.pto_jacobian @ _moving(model, amplitudes)  # rate / i omega
    velocity_kinds = np.array(device.velocity_kinds)
    names = np.array(device.velocity_names)
    ptos = [p.name for p in compiled.device.ptos]
    rotary = np.array([kind == "rotary" for kind in compiled.pto_kinds], dtype=bool)
    data: dict[str, tuple] = {"wave_amplitude": (("omega",), _wave_amplitudes(compiled, exc.omega))}
    coords: dict[str, object] = {"omega": exc.omega}
    hydro_kinds = np.array(dof_kinds(exc.dofs))
    for mask, name, dim in (
        (hydro_kinds == "linear", "excitation_force_amplitude", "hydro_dof_linear"),
        (hydro_kinds == "angular", "excitation_moment_amplitude", "hydro_dof_angular"),
        (hydro_kinds == "generalised", "excitation_generalised_force_amplitude", "hydro_dof_generalised"),
    ):
        if mask.any():
            data[name] = (("omega", dim), exc.coefficients[mask].T)
            coords[dim] = [d for d, m in zip(exc.dofs, mask, strict=True) if m]
    for mask, name, dim in (
        (velocity_kinds == "linear", "displacement_amplitude", "dof_linear"),
        (velocity_kinds == "angular", "angle_amplitude", "dof_angular"),
        (velocity_kinds == "generalised", "generalised_coordinate_amplitude", "dof_generalised"),
    ):
        if mask.any():
            data[name] = (("omega", dim), amplitudes[mask].T)
            coords[dim] = list(names[mask])
    if ptos:
        kinds = ("pto_angle_amplitude", "pto_displacement_amplitude")
        data.update(by_pto_kind(stroke.T, rotary, kinds, ("omega", "pto")))
        power = 0.5 * model.pto_damping * np.sum((exc.omega * np.abs(moving)) ** 2, axis=1)
        data["mean_pto_power"] = (("pto",), power)
        coords["pto"] = ptos
        coords["pto_kind"] = ("pto", ["rotary" if r else "linear" for r in rotary])
    if time is not None:
        _add_time_series(data, coords, compiled, model, amplitudes, np.atleast_1d(np.asarray(time, dtype=float)))
    ds = apply_attrs(
        xr.Dataset(
            data,
            coords=coords,
            attrs={
                "title": f"steady state of {compiled.device.name} (exact frequency domain)",
                "convention": "complex amplitudes X of Re[X exp(+i omega t)], about the static equilibrium",
                "rho": compiled.hydro.rho,
                "g": compiled.hydro.g,
            },
        )
    )
    if "mean_pto_power" in ds:
        ds.mean_pto_power.attrs["long_name"] = "mean absorbed power of the PTO's linear damping (exact, long-time)"
    return ds


def frequency_domain_waves(compiled: CompiledScene, caller: str) -> ExcitationModel:
    """The scene's excitation (its wave components) for the frequency-domain solution, after checking that
    ``compiled`` is a CompiledScene in waves with a linear controller (``caller`` names the function in the message).

    Raises
    ------
    TypeError
        If ``compiled`` is not a CompiledScene.
    ValueError
        In calm water or for a controller without linear gains.
    """
    if not isinstance(compiled, CompiledScene):
        raise TypeError(f"{caller} takes a CompiledScene (wecss.sim.compile_scene); got {type(compiled).__name__}")
    if compiled.excitation is None:
        raise ValueError("calm water: the steady state is the equilibrium")
    if not compiled.linear_controller:
        raise ValueError("the frequency-domain solution needs a controller with linear gains (such as 'damping')")
    return compiled.excitation


def _moving(model: LinearModel, amplitudes: np.ndarray) -> np.ndarray:
    """``amplitudes`` (nv, ...) with a held coordinate's rows zero: the amplitudes whose rates and accelerations the
    equations see (a coordinate held quasi-static has none)."""
    if model.held is None:
        return amplitudes
    out = amplitudes.copy()
    out[model.held] = 0.0
    return out


def _wave_amplitudes(compiled: CompiledScene, omega: np.ndarray) -> np.ndarray:
    """The complex amplitudes of the wave components at ``omega`` [m] (the excitation keeps a subset)."""
    waves = compiled.waves
    out = np.full(omega.size, np.nan, dtype=complex)
    if waves is None:
        return out
    if waves.directional:
        raise ValueError(
            "a directional sea (sea.spreading) has several components per frequency, one per heading: the response "
            "per unit wave amplitude is not defined; leave sea.spreading out for this output"
        )
    index = {float(w): k for k, w in enumerate(waves.omega)}
    for k, w in enumerate(omega):
        if float(w) in index:
            out[k] = waves.amplitude[index[float(w)]]
    return out


def _add_time_series(
    data: dict[str, tuple],
    coords: dict[str, object],
    compiled: CompiledScene,
    model: LinearModel,
    amplitudes: np.ndarray,
    time: np.ndarray,
) -> None:
    """The steady state at ``time``: generalised coordinates and PTO strokes with their rates (absolute values)."""
    device = compiled.device.model
    if device.nq != device.nv:
        raise ValueError("time series of the steady state need joint coordinates (no free base); use the amplitudes")
    omega = compiled.excitation.omega if compiled.excitation is not None else np.zeros(0)
    xi = np.real(evaluate(amplitudes, omega, time)).T  # (n_t, nv)
    rate = np.real(evaluate(1j * omega * _moving(model, amplitudes), omega, time)).T
    kinds = np.array(device.velocity_kinds)
    q = compiled.q0[None] + xi
    for mask, (position, velocity), dim in (
        (kinds == "linear", ("displacement", "velocity"), "dof_linear"),
        (kinds == "angular", ("angle", "angular_velocity"), "dof_angular"),
        (kinds == "generalised", ("generalised_coordinate", "generalised_velocity"), "dof_generalised"),
    ):
        if mask.any():
            data[position] = (("time", dim), q[:, mask])
            data[velocity] = (("time", dim), rate[:, mask])
    rotary = np.array([kind == "rotary" for kind in compiled.pto_kinds], dtype=bool)
    stroke = model.pto_stroke[None] + xi @ model.pto_jacobian.T
    stroke_rate = rate @ model.pto_jacobian.T  # a held coordinate's rate is zero
    data.update(by_pto_kind(stroke, rotary, ("pto_angle", "pto_displacement"), ("time", "pto")))
    data.update(by_pto_kind(stroke_rate, rotary, ("pto_angular_velocity", "pto_velocity"), ("time", "pto")))
    coords["time"] = time
