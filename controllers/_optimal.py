"""Controllers tuned to the scene's sea state in the frequency domain, on the exact linear model of the device:
the optimal passive damping and the best causal spring-damper (reactive control)."""

from __future__ import annotations

import numpy as np

from wecss.control import ControlContext, Controller, Measurement, pto_control_force
from wecss.control.design import optimal_damping, optimal_spring_damper


def _waves(context: ControlContext, name: str) -> tuple[np.ndarray, np.ndarray]:
    if context.excitation is None or context.excitation.omega.size == 0:
        raise ValueError(f"{name} tunes its gains to the sea state; the scene's sea is calm")
    return context.excitation.omega, context.excitation.coefficients


class _TunedLinear(Controller):
    """A linear feedback f = -c x_dot - k x whose gains :meth:`setup` tunes."""

    damping: np.ndarray
    stiffness: np.ndarray
    expected_power: np.ndarray

    def linear_gains(self) -> tuple[np.ndarray, np.ndarray]:
        return self.damping.copy(), self.stiffness.copy()

    def compute(self, t: float, measurement: Measurement) -> np.ndarray:
        return pto_control_force(0.0, self.damping, self.stiffness, measurement.displacement, measurement.velocity)


class OptimalDamping(_TunedLinear):
    """The passive damping per PTO [N s/m or N m s/rad] that maximises the total mean absorbed power in the
    scene's sea state, all PTOs together, from the exact frequency-domain model
    (:func:`wecss.control.design.optimal_damping`). No parameters. ``expected_power`` [W] holds the frequency domain's
    mean power per PTO after :meth:`setup`.

    Raises
    ------
    ValueError
        In calm water (at setup).
    """

    def setup(self, context: ControlContext) -> None:
        gains = optimal_damping(context.linear_model(), *_waves(context, "optimal-damping"))
        self.damping, self.stiffness, self.expected_power = gains.damping, gains.stiffness, gains.power


class Reactive(_TunedLinear):
    """The best causal spring-damper per PTO for the scene's sea state: damping c >= 0 [N s/m or N m s/rad] and
    stiffness k of any sign [N/m or N m/rad] (reactive when negative), all PTOs together, from the exact
    frequency-domain model (:func:`wecss.control.design.optimal_spring_damper`; the static stiffness stays positive
    definite, so the loop is stable).

    Parameters
    ----------
    within_force_limit : bool
        Keep ``force_margin`` times the RMS PTO force within the device's force limit, where it declares one
        (default True); the simulators saturate the force at the limit either way.
    force_margin : float
        See above (default 3).

    Raises
    ------
    ValueError
        In calm water (at setup), or for a non-positive margin.
    """

    def __init__(self, within_force_limit: bool = True, force_margin: float = 3.0) -> None:
        if not isinstance(within_force_limit, bool):
            raise ValueError(f"within_force_limit must be true or false; got {within_force_limit!r}")
        if not force_margin > 0:
            raise ValueError(f"force_margin must be positive; got {force_margin!r}")
        self.within_force_limit = within_force_limit
        self.force_margin = force_margin

    def setup(self, context: ControlContext) -> None:
        limit = np.asarray(context.force_limit, dtype=float)
        use_limit = self.within_force_limit and bool(np.all(np.isfinite(limit)))
        gains = optimal_spring_damper(
            context.linear_model(),
            *_waves(context, "reactive"),
            force_limit=limit if use_limit else None,
            force_margin=self.force_margin,
        )
        self.damping, self.stiffness, self.expected_power = gains.damping, gains.stiffness, gains.power
