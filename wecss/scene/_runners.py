"""Runners: the integrators and solvers a scene's ``solver.method`` names, as objects in one registry.

A runner declares what it needs and supports (:class:`Capabilities`), checks a scene against that (:meth:`Runner.check`,
called when the scene is built, so a scene it cannot run is refused before any work), and runs a compiled scene
with its controller into a record of raw arrays (:meth:`Runner.run`; the result Dataset is built from it by
``wecss.sim``). The built-ins (``beeman``, ``rk4``, ``beeman-explicit``, ``reference``, ``linear``, ``frequency``)
live in ``wecss.sim`` and are registered under the entry-point group ``wecss.runners``, as a third-party package
registers its own; :func:`register_runner` adds one at run time (a test's toy integrator, a notebook's experiment).

The registry sits below the simulator (a scene validates its method here) and never imports it: the entry points
are loaded on the first look-up.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass
from typing import Any

from ..outputs import GROUPS
from ..plugins import entry_points
from ._errors import SceneError

ENTRY_POINT_GROUP = "wecss.runners"

RADIATION_METHODS = ("state_space", "convolution", "none")


@dataclass(frozen=True)
class Capabilities:
    """What a runner needs and supports.

    Attributes
    ----------
    radiation : tuple of str
        The ``radiation.method`` values it runs with.
    memory_model : bool
        It steps a time-domain radiation memory (the compilation builds one; False: the runner takes A(omega) and
        B(omega) from the database and ``radiation`` settings are not used).
    sampled_controllers : bool
        It can call a controller without linear gains once per control period and hold its force (False: only
        controllers whose linear gains fold into the equations).
    streaming : bool
        ``simulate(scene, path=...)`` can append its time series to the file as it runs (else the result is built
        whole, then written).
    free_base : bool
        It runs devices with a free (6-DOF, quaternion) base.
    options : tuple of str
        Optional ``solver`` fields (default None) it reads; another runner refuses a scene that sets them.
    transient : bool
        It starts from rest at the equilibrium and applies the sea's start ramp (False: a steady state, no ramp).
    initial_state : bool
        It starts from the scene's ``[initial]`` state (a departure from the equilibrium) when one is given.
    terms : bool
        It records the hydrodynamic terms' forces (the output group ``hydrodynamics``).
    hydrodynamics : tuple of str
        The forces beyond the linear database it computes (``[hydrodynamics]``): "body-exact" (the meshes'
        hydrostatics and Froude-Krylov force), "drag" (the viscous forces: exactly, or linearised by a linear
        runner).
    order : int
        Order of accuracy in the step (0: not a time stepper, e.g. an exact solution).
    tolerance : bool
        Its step may be chosen from ``solver.tolerance`` (a fixed-step runner whose error shrinks as the step to
        its ``order``; ``wecss.sim.choose_step``).
    quasi_static : bool
        It solves the algebraic equations of modal coordinates held quasi-static
        (``flexible.quasi_static_above``).
    """

    radiation: tuple[str, ...] = RADIATION_METHODS
    memory_model: bool = True
    sampled_controllers: bool = True
    streaming: bool = False
    free_base: bool = True
    options: tuple[str, ...] = ()
    transient: bool = True
    initial_state: bool = False
    terms: bool = False
    hydrodynamics: tuple[str, ...] = ()
    order: int = 2
    tolerance: bool = False
    quasi_static: bool = False

    def __post_init__(self) -> None:
        unknown = sorted(set(self.radiation) - set(RADIATION_METHODS))
        if unknown:
            raise ValueError(
                f"capabilities: unknown radiation methods {unknown}; known: {', '.join(RADIATION_METHODS)}"
            )


OPTIONAL_SOLVER_FIELDS = ("hold", "allow_large")
"""``solver`` fields that only some runners read (default None); a scene that sets one for a runner that does not
declare it in :attr:`Capabilities.options` is refused."""


class Runner(ABC):
    """An integrator or solver of scenes (see the module docstring).

    Subclasses set :attr:`name`, :attr:`description` and :attr:`capabilities`, and implement :meth:`run`.
    (The arguments are typed loosely here because this registry sits below the scene and the simulator; the
    built-in runners in ``wecss.sim`` annotate them exactly.)
    """

    name: str = ""
    description: str = ""
    capabilities: Capabilities = Capabilities()
    radiation_reason: str = ""
    """Why the runner takes only the radiation methods it declares (said when it refuses another)."""
    tolerance_reason: str = ""
    """Why the runner takes no ``solver.tolerance`` (said when it refuses one: ": ..." or empty)."""

    def check(self, scene: Any) -> None:
        """Refuse a scene (a ``wecss.scene.Scene``) this runner cannot run.

        The default checks the radiation method and the optional solver fields against :attr:`capabilities`;
        subclasses add their own and call this one.

        Raises
        ------
        SceneError
            Naming the field, the value and what this runner accepts.
        """
        caps = self.capabilities
        if caps.memory_model and scene.radiation.method not in caps.radiation:
            reason = f" ({self.radiation_reason})" if self.radiation_reason else ""
            raise SceneError(
                f"solver.method {self.name!r} needs radiation.method {' or '.join(map(repr, caps.radiation))}{reason}; "
                f"got {scene.radiation.method!r}"
            )
        hydro = scene.hydrodynamics
        for wanted, on in (("body-exact", hydro.body_exact), ("drag", hydro.drag)):
            if on and wanted not in caps.hydrodynamics:
                takers = [name for name in available_runners() if wanted in runner(name).capabilities.hydrodynamics]
                raise SceneError(
                    f"solver.method {self.name!r} does not compute the {wanted} hydrodynamics the scene asks for "
                    f"([hydrodynamics]); these do: {', '.join(takers) or 'none'}"
                )
        for group in GROUPS:
            if group.name in scene.outputs.variables and group.needs and not getattr(caps, group.needs):
                takers = [name for name in available_runners() if getattr(runner(name).capabilities, group.needs)]
                raise SceneError(
                    f"outputs.variables: solver.method {self.name!r} does not fill the group {group.name!r}; these "
                    f"do: {', '.join(takers) or 'none'}"
                )
        if "hydrodynamics" in scene.outputs.variables and not hydro.nonlinear:
            raise SceneError(
                "outputs.variables: 'hydrodynamics' holds the forces [hydrodynamics] switches on, and the scene "
                "switches none on (hydrostatics, froude_krylov = 'body-exact' or drag = true)"
            )
        if not scene.initial.at_rest and not caps.initial_state:
            takers = [name for name in available_runners() if runner(name).capabilities.initial_state]
            raise SceneError(
                f"solver.method {self.name!r} starts from the equilibrium at rest; [initial] needs one of "
                f"{', '.join(takers) or 'none'}"
            )
        for option in OPTIONAL_SOLVER_FIELDS:
            if getattr(scene.solver, option) is not None and option not in caps.options:
                takers = [name for name in available_runners() if option in runner(name).capabilities.options]
                raise SceneError(
                    f"solver.{option} applies to solver.method {' or '.join(map(repr, takers))} only; got method "
                    f"{self.name!r}"
                )

    def check_compiled(self, compiled: Any) -> None:
        """Refuse a compiled plant (a ``wecss.compiled.CompiledScene``) this runner cannot run, once its arrays are
        known (a state-space fit too fast for the step, say). The default checks the device's base against
        :attr:`Capabilities.free_base`; subclasses add their own and call this one.

        Raises
        ------
        SceneError
        """
        model = compiled.device.model
        if compiled.scene.solver.method is not None:  # an unnamed one may still be chosen (``wecss.simulate``)
            self.refuse_quasi_static(compiled)
        if not self.capabilities.free_base and model.nq != model.nv:
            raise SceneError(
                f"solver.method {self.name!r} needs joint coordinates; device {compiled.device.name!r} has a free "
                "base (its quaternion coordinates are not linear): use a nonlinear runner such as 'beeman'"
            )

    def refuse_quasi_static(self, compiled: Any) -> None:
        """Refuse a device with modal coordinates held quasi-static (``flexible.quasi_static_above``) unless
        :attr:`Capabilities.quasi_static`.

        Raises
        ------
        SceneError
            Naming the coordinates and the runners that solve them.
        """
        model = compiled.device.model
        held = [name for name, q in zip(model.velocity_names, model.quasi_static_velocities, strict=True) if q]
        if held and not self.capabilities.quasi_static:
            takers = [name for name in available_runners() if runner(name).capabilities.quasi_static]
            raise SceneError(
                f"solver.method {self.name!r} does not solve the equations of the modal coordinates held "
                f"quasi-static ({', '.join(held)}: flexible.quasi_static_above of device {compiled.device.name!r}); "
                f"these do: {', '.join(takers) or 'none'}"
            )

    @abstractmethod
    def run(self, controlled: Any, *, progress: bool = False, stream: Any = None) -> Any:
        """Run a compiled scene with its controller (a ``wecss.control.ControlledScene``) and return its
        ``wecss.sim.Record``; with ``stream`` (``capabilities.streaming`` only) the saved rows go to it as the run
        goes. ``progress``: print a progress bar on standard error."""

    def __repr__(self) -> str:
        return f"<runner {self.name!r}: {self.description}>"


_REGISTERED: dict[str, Runner] = {}
_LOADED: list[bool] = []


def _load_entry_points() -> None:
    if _LOADED:
        return
    _LOADED.append(True)
    for ep in entry_points(ENTRY_POINT_GROUP):
        if ep.name not in _REGISTERED:
            register_runner(ep.load(), name=ep.name)


def register_runner(runner_: Runner, *, name: str | None = None, replace: bool = False) -> Runner:
    """Add a runner to the registry under ``name`` (default ``runner_.name``); returns it.

    Raises
    ------
    TypeError
        If ``runner_`` is not a :class:`Runner`.
    ValueError
        If the name is taken (unless ``replace``) or empty.
    """
    if not isinstance(runner_, Runner):
        raise TypeError(f"{type(runner_).__name__} is not a wecss runner: subclass wecss.scene.Runner")
    key = name or runner_.name
    if not key:
        raise ValueError(f"{type(runner_).__name__}: a runner needs a name")
    if key != runner_.name:
        raise ValueError(f"runner {runner_.name!r} registered under another name {key!r}")
    if key in _REGISTERED and not replace and _REGISTERED[key] is not runner_:
        raise ValueError(f"a runner {key!r} is registered already ({_REGISTERED[key]!r}); pass replace=True")
    _REGISTERED[key] = runner_
    return runner_


def unregister_runner(name: str) -> None:
    """Remove the runner ``name`` (one added with :func:`register_runner`; a built-in comes back with the entry
    points only in a new process). Unknown names are ignored."""
    _REGISTERED.pop(name, None)


def available_runners() -> list[str]:
    """Names of the registered runners."""
    _load_entry_points()
    return sorted(_REGISTERED)


def tolerance_runners() -> list[str]:
    """Names of the registered runners whose step ``solver.tolerance`` may choose."""
    return [name for name in available_runners() if runner(name).capabilities.tolerance]


def runner(name: str) -> Runner:
    """The runner registered as ``name``.

    Raises
    ------
    SceneError
        For an unknown name (the message lists the known ones).
    """
    _load_entry_points()
    found = _REGISTERED.get(name) if isinstance(name, str) else None
    if found is None:
        raise SceneError(f"solver.method: unknown {name!r}; accepted: {', '.join(available_runners())}")
    return found
