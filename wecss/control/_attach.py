"""A scene compiled with its controller (:class:`ControlledScene`): the plant compiled once
(``wecss.compiled.compile_plant``), the controller set up once with a context that offers the plant's linear
model, and its linear gains, if it has any, folded into the equations of motion."""

from __future__ import annotations

import dataclasses
import functools
import traceback

from ..compiled import CompiledScene, compile_plant, with_linear_gains
from ..linear import LinearModel, linearize
from ..scene import Scene, SceneError, available_runners
from ..scene import runner as get_runner
from ._protocol import ControlContext, Controller
from ._registry import available, check_controller, create


@dataclasses.dataclass(frozen=True, eq=False, kw_only=True)
class ControlledScene(CompiledScene):
    """A :class:`~wecss.compiled.CompiledScene` with its controller attached: what a runner runs.

    Made by :func:`compile_scene` or :func:`attach_controller`. The plant carries the controller's linear gains
    where it has them (``linear_controller``); the controller was set up once, with ``control_context``; the
    runs call its ``reset()`` at their start.

    Attributes
    ----------
    controller : Controller
        The controller, set up with ``control_context``.
    control_context : ControlContext
        What the controller was told (PTOs, limits, periods, the sea state, the open plant's linear model).
    controller_given : bool
        True when the controller was given (``simulate(scene, controller=obj)``) instead of made from the scene's
        ``controller`` section, which then did not run (the result says so).
    """

    controller: Controller
    control_context: ControlContext
    controller_given: bool = False


def control_context(compiled: CompiledScene) -> ControlContext:
    """The context a controller of ``compiled`` (a plant without controller gains) is set up with; its linear model
    is the open plant's, made on first use."""
    scene = compiled.scene
    plant = compiled.plant

    @functools.cache
    def open_plant() -> LinearModel:
        return linearize(compiled)

    return ControlContext(
        pto_names=tuple(p.name for p in compiled.device.ptos),
        control_period=compiled.dt * scene.control_steps,
        default_damping=tuple(float(p.damping) for p in compiled.device.ptos),
        pto_kinds=compiled.pto_kinds,
        force_limit=tuple(float(x) for x in plant.pto_force_limit),
        stroke_limit=tuple(float(x) for x in plant.pto_stroke_limit),
        time_step=compiled.dt,
        duration=compiled.n_steps * compiled.dt,
        sea=scene.sea,
        spectrum=compiled.spectrum,
        waves=compiled.waves,
        excitation=compiled.excitation,
        hydro_dofs=tuple(compiled.hydro.dofs),
        plant=open_plant,
    )


def _scene_controller(scene: Scene) -> Controller:
    choice = scene.controller
    known = available()
    if choice.name not in known:
        raise SceneError(f"controller.name: unknown controller {choice.name!r}; available: {', '.join(known)}")
    try:
        return create(choice.name, **choice.parameters)
    except (TypeError, ValueError) as err:
        raise SceneError(f"controller {choice.name!r} with parameters {dict(choice.parameters)}: {err}") from err


def attach_controller(compiled: CompiledScene, controller: Controller | None = None) -> ControlledScene:
    """``compiled`` (a plant from ``compile_plant``) with ``controller`` (default: the scene's own) set up (once) and
    its linear gains folded in.

    Raises
    ------
    SceneError
        If the controller rejects the context, or its gains, or the scene's runner cannot run it (the frequency
        domain and the reference solver need linear gains; a preview horizon must be whole control periods).
    TypeError
        If ``controller`` is not a :class:`Controller`.
    ValueError
        If ``compiled`` has a controller already.
    """
    if isinstance(compiled, ControlledScene):
        raise ValueError("this compiled scene has a controller already; attach to the plant from compile_plant")
    if controller is None:
        return _attach(compiled, _scene_controller(compiled.scene), given=False)
    return _attach(compiled, controller, given=True)


def _attach(compiled: CompiledScene, controller: Controller, *, given: bool) -> ControlledScene:
    """:func:`attach_controller` of a controller made from the scene (``given`` False) or given by the caller."""
    check_controller(controller)
    context = control_context(compiled)
    name = type(controller).__name__
    try:
        controller.setup(context)
        gains = controller.linear_gains()
    except (TypeError, ValueError) as err:  # the controller's own error chained, with where it was raised
        raise SceneError(f"controller {name}: {err} ({raised_at(err)})") from err
    runner = compiled.scene.runner
    if gains is None and not runner.capabilities.sampled_controllers:
        calling = [n for n in available_runners() if get_runner(n).capabilities.sampled_controllers]
        raise SceneError(
            f"solver.method {runner.name!r} needs a controller with linear gains (a constant PTO damping and "
            f"stiffness, such as 'damping'): it never calls the controller during the run; {name} has none (it "
            f"computes its force every control period): use a runner that calls it, one of {', '.join(calling)} "
            "('linear' steps the same linearised equations in time)"
        )
    if gains is not None:
        try:
            compiled = with_linear_gains(compiled, *gains)
        except ValueError as err:
            raise SceneError(f"controller {name}: linear_gains() gave {gains!r}: {err}") from err
    horizon = controller.preview_horizon
    if horizon is not None:
        periods = horizon / context.control_period
        if abs(periods - round(periods)) > 1e-9 * max(1.0, periods) or round(periods) < 1:
            raise SceneError(
                f"controller {name}: preview_horizon {horizon:.6g} s must be a whole number (>= 1) of control "
                f"periods ({context.control_period:.6g} s)"
            )
    fields = {f.name: getattr(compiled, f.name) for f in dataclasses.fields(CompiledScene)}
    return ControlledScene(**fields, controller=controller, control_context=context, controller_given=given)


def raised_at(err: BaseException) -> str:
    """Where ``err`` was raised: "raised in FUNCTION at FILE:LINE" of its innermost frame."""
    frames = traceback.extract_tb(err.__traceback__)
    if not frames:
        return "raised outside a traceback"
    last = frames[-1]
    return f"raised in {last.name} at {last.filename}:{last.lineno}"


def compile_scene(scene: Scene, controller: Controller | None = None) -> ControlledScene:
    """Compile ``scene`` with its controller (or ``controller``, an instance, instead of the scene's).

    The controller is created first (so that bad parameters fail before any work), then the plant is compiled,
    the controller set up with its :class:`ControlContext` and its linear gains folded in.

    Raises
    ------
    SceneError
        On a malformed scene, a controller that rejects its parameters or context, or a solver that cannot run it.
    TypeError
        If ``controller`` is not a :class:`Controller`.
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"compile_scene takes a wecss.scene.Scene; got {type(scene).__name__}")
    if controller is None:
        return _attach(compile_plant(scene), _scene_controller(scene), given=False)
    check_controller(controller)
    return _attach(compile_plant(scene), controller, given=True)
