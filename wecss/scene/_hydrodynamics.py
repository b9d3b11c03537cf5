"""The scene's switches of the hydrodynamic forces beyond the linear ones (``[hydrodynamics]``), and its initial
state (``[initial]``, for free-decay tests)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from ._checks import check_choice, check_types
from ._errors import SceneError
from ._parameters import Parameters

MODELS = ("linear", "body-exact")
FREE_SURFACES = ("instantaneous", "mean")
FORMULATIONS = ("remainder", "replace")
DRAG_VELOCITIES = ("relative", "body")


@dataclass(frozen=True)
class Hydrodynamics:
    """Which hydrodynamic forces beyond the linear database act (all off by default: the linear hydrodynamics of
    the database, as in the M4 paper). A scene pays only for what it asks: with everything off the compiled plant
    carries empty arrays.

    Attributes
    ----------
    hydrostatics : {"linear", "body-exact"}
        "linear" (default): buoyancy at equilibrium and the database's hydrostatic stiffness. "body-exact": the
        pressure -rho g z integrated over each body's surface mesh below the free surface at every evaluation.
    froude_krylov : {"linear", "body-exact"}
        "linear" (default): the database's excitation. "body-exact": the incident-wave pressure (Airy,
        Wheeler-stretched, zero above the surface) integrated over the mesh below the free surface.
    free_surface : {"instantaneous", "mean"} or None
        Where the meshes are clipped for the body-exact forces: at the incident wave's surface (the default with
        the body-exact Froude-Krylov force, which it needs) or at the still water level z = 0 (the default without
        it). Only with a body-exact force.
    formulation : {"remainder", "replace"} or None
        "remainder" (default): the body-exact forces minus their own value, tangent and linear Froude-Krylov force
        at the equilibrium are added to the linear forces, so that the equilibrium, the linear model and small
        waves are today's. "replace": the database's diffraction with the mesh's Froude-Krylov force and
        hydrostatics in place of the database's excitation and hydrostatic stiffness (the database must hold
        ``froude_krylov``). Only with a body-exact force.
    drag : bool
        The device's viscous forces (``[[bodies]]`` ``drag`` and ``linear_damping``, ``[[morison]]`` elements):
        quadratic drag, linear damping and Morison elements (default False).
    drag_velocity : {"relative", "body"} or None
        The velocity the drag acts on: relative to the undisturbed fluid (default) or the body's own. Only with
        ``drag``.
    """

    hydrostatics: str = "linear"
    froude_krylov: str = "linear"
    free_surface: str | None = None
    formulation: str | None = None
    drag: bool = False
    drag_velocity: str | None = None

    def __post_init__(self) -> None:
        check_types(
            "hydrodynamics",
            {
                "hydrostatics": (self.hydrostatics, str),
                "froude_krylov": (self.froude_krylov, str),
                "drag": (self.drag, bool),
            },
        )
        check_choice("hydrodynamics.hydrostatics", self.hydrostatics, MODELS)
        check_choice("hydrodynamics.froude_krylov", self.froude_krylov, MODELS)
        for name, value, accepted in (
            ("free_surface", self.free_surface, FREE_SURFACES),
            ("formulation", self.formulation, FORMULATIONS),
        ):
            if value is not None:
                check_choice(f"hydrodynamics.{name}", value, accepted)
                if not self.body_exact:
                    raise SceneError(
                        f"hydrodynamics.{name} = {value!r} applies to body-exact forces; set "
                        "hydrodynamics.hydrostatics or froude_krylov to 'body-exact' (or leave it out)"
                    )
        if self.free_surface == "instantaneous" and self.froude_krylov != "body-exact":
            raise SceneError(
                "hydrodynamics.free_surface = 'instantaneous' clips the meshes at the incident wave, whose pressure "
                "acts on them only with froude_krylov = 'body-exact'; set it, or free_surface = 'mean'"
            )
        if self.drag_velocity is not None:
            check_choice("hydrodynamics.drag_velocity", self.drag_velocity, DRAG_VELOCITIES)
            if not self.drag:
                raise SceneError(
                    f"hydrodynamics.drag_velocity = {self.drag_velocity!r} applies to the drag; set hydrodynamics.drag "
                    "= true (or leave it out)"
                )

    @property
    def body_exact(self) -> bool:
        """A force integrated over the meshes is on."""
        return "body-exact" in (self.hydrostatics, self.froude_krylov)

    @property
    def nonlinear(self) -> bool:
        """Anything beyond the linear hydrodynamics is on."""
        return self.body_exact or self.drag

    @property
    def surface(self) -> str:
        """Where the meshes are clipped: ``free_surface`` when given, else "instantaneous" with the body-exact
        Froude-Krylov force and "mean" (z = 0) without it."""
        return self.free_surface or ("instantaneous" if self.froude_krylov == "body-exact" else "mean")

    @property
    def form(self) -> str:
        """The formulation ("remainder" unless ``formulation`` says otherwise)."""
        return self.formulation or "remainder"

    @property
    def relative_drag(self) -> bool:
        """The drag acts on the velocity relative to the undisturbed fluid."""
        return (self.drag_velocity or "relative") == "relative"


@dataclass(frozen=True)
class Initial:
    """The initial state, as a departure from the static equilibrium (default: at rest in it).

    Attributes
    ----------
    displacement : dict
        Generalised-coordinate increments by velocity name (``wecss.devices.Device.model.velocity_names``, e.g.
        ``{"float__heave": 0.1}``) [m, rad or 1]; applied on the configuration manifold (a free base's rotation as a
        rotation vector).
    velocity : dict
        Generalised velocities by name [m/s, rad/s or 1/s].
    """

    displacement: dict[str, Any] = field(default_factory=dict)
    velocity: dict[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        for name in ("displacement", "velocity"):
            values = getattr(self, name)
            check_types("initial", {name: (values, dict)})
            for key, value in values.items():
                if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
                    raise SceneError(f"initial.{name}.{key} must be a finite number; got {value!r}")
            object.__setattr__(self, name, Parameters(values))

    @property
    def at_rest(self) -> bool:
        """At rest in the equilibrium (nothing given)."""
        return not any(self.displacement.values()) and not any(self.velocity.values())
