"""The controller call, written once for every simulator: a fresh start per run (the controller's ``reset``),
the measurement a controller asked for (PTO strokes and rates always; the state, an excitation preview and the
wave elevation at a point when declared), and one checked force per call."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ..compiled import CompiledScene
from ..control import ControlledScene, Measurement
from ..waves import evaluate
from ._watchdog import Watchdog


@dataclass
class ControlLoop:
    """The scene's controller during one run (make it with :meth:`start`)."""

    compiled: ControlledScene
    n_pto: int
    preview_steps: int
    elevation_coefficients: np.ndarray | None
    watchdog: Watchdog

    @classmethod
    def start(cls, compiled: ControlledScene) -> ControlLoop:
        """Start the scene's controller afresh for a run (its ``reset``: a controller with memory starts from
        scratch; it was set up once, when attached) and prepare what it declared it needs."""
        controller, context = compiled.controller, compiled.control_context
        controller.reset()
        horizon = controller.preview_horizon
        steps = 0 if horizon is None else round(horizon / context.control_period)
        coefficients = None
        if controller.elevation_at is not None:
            coefficients = _elevation_coefficients(compiled, *controller.elevation_at)
        choice = compiled.scene.controller
        name = f"{choice.name!r} ({type(controller).__name__})"
        return cls(compiled, context.n_pto, steps, coefficients, Watchdog(choice.time_limit, name))

    @property
    def needs_state(self) -> bool:
        """The controller asked for the full state."""
        return bool(self.compiled.controller.needs_state)

    def force(
        self,
        t: float,
        displacement: np.ndarray,
        velocity: np.ndarray,
        state: Callable[[], np.ndarray] | None = None,
    ) -> np.ndarray:
        """The PTO forces [N or N m] the controller commands at time ``t`` [s] for the PTO strokes
        ``displacement`` (from their rest positions) and ``velocity``; ``state()`` gives the simulator's state
        when the controller asked for it.

        Raises
        ------
        ValueError
            If the controller returns anything but one finite force per PTO.
        """
        compiled = self.compiled
        preview_times = preview = elevation = None
        if self.preview_steps:
            preview_times = t + compiled.control_context.control_period * np.arange(1, self.preview_steps + 1)
            preview = compiled.excitation_at(preview_times)
        if self.elevation_coefficients is not None:
            elevation = _elevation(compiled, self.elevation_coefficients, t)
        measurement = Measurement(
            np.array(displacement, dtype=float),
            np.array(velocity, dtype=float),
            state() if (self.needs_state and state is not None) else None,
            preview_times,
            preview,
            elevation,
        )
        self.watchdog.enter(t)
        try:
            given = compiled.controller.compute(t, measurement)
        finally:
            self.watchdog.leave()
        return checked_force(given, self.n_pto, t)


def checked_force(given: object, n_pto: int, t: float) -> np.ndarray:
    """The controller's return value ``given`` at time ``t`` [s] as ``n_pto`` real finite forces [N or N m].

    Raises
    ------
    ValueError
        For a complex value (even with a zero imaginary part: a phasor is not a force), a value that is not a
        number, the wrong number of forces, NaN or inf; the message gives the value and what is accepted.
    """
    raw = np.asarray(given)
    expected = f"expected {n_pto} real finite forces [N or N m]"
    if raw.dtype.kind == "c":
        raise ValueError(
            f"controller returned complex forces {given!r} at t = {t:.6g} s; {expected} (a complex amplitude is not "
            "a force in time: take its real part on purpose if that is meant)"
        )
    out = raw
    if raw.dtype.kind != "f":
        try:
            out = raw.astype(float)
        except (TypeError, ValueError):
            raise ValueError(f"controller returned {given!r} at t = {t:.6g} s; {expected}") from None
    # element by element in Python: for a few PTOs 0.5 us, np.isfinite(out).all() 3 us (measured)
    if out.shape != (n_pto,) or not all(map(math.isfinite, out.tolist())):
        raise ValueError(f"controller returned {given!r} at t = {t:.6g} s; {expected}")
    return out


def _elevation_coefficients(compiled: CompiledScene, x: float, y: float) -> np.ndarray | None:
    """Complex amplitudes of the wave components at the point (x, y) [m] (None in calm water)."""
    waves = compiled.waves
    if waves is None:
        return None
    return waves.at_point(x, y, compiled.hydro.water_depth, compiled.hydro.g)


def _elevation(compiled: CompiledScene, coefficients: np.ndarray | None, t: float) -> float:
    """The elevation at the controller's point at time ``t`` [m], with the scene's ramp."""
    if coefficients is None or compiled.waves is None:
        return 0.0
    value = float(np.real(evaluate(coefficients[None, :], compiled.waves.omega, np.array([t])))[0, 0])
    excitation = compiled.excitation
    if excitation is not None and excitation.ramp is not None:
        value *= float(excitation.ramp(np.array([t]))[0])
    return value
