"""A passive or reactive spring-damper on every PTO stroke: f = -c x_dot - k x (a PI controller of the stroke
rate), reactive when the stiffness is negative."""

from __future__ import annotations

from ._damping import LinearDamping


class SpringDamper(LinearDamping):
    """Linear damping and stiffness per PTO, both given (no device default).

    Parameters
    ----------
    damping : float or sequence of float
        c [N s/m or N m s/rad], one value for all PTOs or one per PTO; >= 0.
    stiffness : float or sequence of float
        k [N/m or N m/rad], one value for all PTOs or one per PTO; negative for reactive control (the PTO then
        returns power to the device over part of each cycle; the simulators check nothing about it but the
        statics, so a too negative k gives no equilibrium: ``SceneError``).

    Raises
    ------
    ValueError
        On negative or non-finite damping, non-finite stiffness, or a number of gains that does not match the PTOs.
    """

    def __init__(self, damping: float | list[float], stiffness: float | list[float]) -> None:
        super().__init__(damping=damping, stiffness=stiffness)
