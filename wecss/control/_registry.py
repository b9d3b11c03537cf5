"""Controllers by name: the ``wecss.controllers`` entry-point group, where the built-ins of the ``wecss_controllers``
package and third-party packages register theirs (wecss itself never imports a plugin)."""

from __future__ import annotations

import inspect
from typing import Any

from ..plugins import entry_points
from ._protocol import Controller

ENTRY_POINT_GROUP = "wecss.controllers"


def available() -> list[str]:
    """Names registered under the ``wecss.controllers`` entry-point group."""
    return sorted(ep.name for ep in entry_points(ENTRY_POINT_GROUP))


def create(name: str, **parameters: Any) -> Controller:
    """Build a registered controller by name with its parameters.

    Raises
    ------
    ValueError
        For an unknown name (the message lists the known ones).
    TypeError
        For parameters the controller does not take, or a registered class that is not a :class:`Controller`.
    """
    for ep in entry_points(ENTRY_POINT_GROUP):
        if ep.name == name:
            cls = ep.load()
            try:
                controller = cls(**parameters)
            except TypeError as err:  # a typo in a parameter: say which ones the controller takes
                accepted = [
                    f"{p.name}" + ("" if p.default is inspect.Parameter.empty else f" (default {p.default!r})")
                    for p in inspect.signature(cls).parameters.values()
                    if p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY)
                ]
                raise TypeError(f"{err}; {name!r} accepts: {', '.join(accepted) or 'no parameters'}") from None
            check_controller(controller)
            return controller
    raise ValueError(f"unknown controller {name!r}; available: {', '.join(available()) or 'none'}")


def check_controller(controller: object) -> Controller:
    """``controller`` if it is a :class:`Controller` with well-formed declarations.

    Raises
    ------
    TypeError
        If it is not a :class:`Controller` (subclass ``wecss.control.Controller``) or declares needs of the
        wrong type.
    """
    if not isinstance(controller, Controller):
        raise TypeError(
            f"{type(controller).__name__} is not a wecss controller: subclass wecss.control.Controller "
            "(setup(context), compute(t, measurement), optionally linear_gains())"
        )
    if not isinstance(controller.needs_state, bool):
        raise TypeError(f"needs_state must be True or False; got {controller.needs_state!r}")
    horizon = controller.preview_horizon
    if horizon is not None and not (isinstance(horizon, int | float) and horizon > 0):
        raise TypeError(f"preview_horizon must be None or a positive time [s]; got {horizon!r}")
    point = controller.elevation_at
    if point is not None and not (isinstance(point, tuple | list) and len(point) == 2):
        raise TypeError(f"elevation_at must be None or a point (x, y) [m]; got {point!r}")
    return controller
