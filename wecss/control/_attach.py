"""A scene compiled with its controller: the plant compiled once (``wecss.compiled.compile_plant``), the controller
set up with a context that offers the plant's linear model, and its linear gains, if it has any, folded into the
equations of motion."""

from __future__ import annotations

import dataclasses
import functools

import numpy as np

from ..compiled import CompiledScene, compile_plant, with_linear_gains
from ..linear import LinearModel, linearize
from ..scene import Scene, SceneError
from ._protocol import ControlContext, Controller
from ._registry import available, check_controller, create


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
        raise SceneError(f"controller {choice.name!r} with parameters {dict(choice.parameters)}: {err}") from None


def attach_controller(compiled: CompiledScene, controller: Controller) -> CompiledScene:
    """``compiled`` (a plant from ``compile_plant``) with ``controller`` set up and its linear gains folded in.

    Raises
    ------
    SceneError
        If the controller rejects the context, or its gains, or the scene's solver cannot run it (the frequency
        domain needs linear gains; controllers that need the state, a preview or the elevation need a time
        stepping run).
    TypeError
        If ``controller`` is not a :class:`Controller`.
    """
    if compiled.controller is not None:
        raise ValueError("this compiled scene has a controller already; attach to the plant from compile_plant")
    check_controller(controller)
    context = control_context(compiled)
    name = type(controller).__name__
    try:
        controller.setup(context)
        gains = controller.linear_gains()
    except (TypeError, ValueError) as err:
        raise SceneError(f"controller {name}: {err}") from None
    method = compiled.scene.solver.method
    if method == "frequency" and gains is None:
        raise SceneError(
            f"solver.method 'frequency' needs a controller with linear gains (such as 'damping'); {name} has none: "
            "use 'linear' or a time-domain solver"
        )
    if gains is not None:
        try:
            damping, stiffness = (np.broadcast_to(np.asarray(g, dtype=float), (context.n_pto,)) for g in gains)
            compiled = with_linear_gains(compiled, damping, stiffness)
        except ValueError as err:
            raise SceneError(f"controller {name}: linear_gains() gave {gains!r}: {err}") from None
    horizon = controller.preview_horizon
    if horizon is not None:
        periods = horizon / context.control_period
        if abs(periods - round(periods)) > 1e-9 * max(1.0, periods) or round(periods) < 1:
            raise SceneError(
                f"controller {name}: preview_horizon {horizon:.6g} s must be a whole number (>= 1) of control "
                f"periods ({context.control_period:.6g} s)"
            )
    return dataclasses.replace(compiled, controller=controller, control_context=context)


def compile_scene(scene: Scene, controller: Controller | None = None) -> CompiledScene:
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
        controller = _scene_controller(scene)
    else:
        check_controller(controller)
    return attach_controller(compile_plant(scene), controller)
