"""The controller interface: what a controller declares it needs, what it is told once per run
(:class:`ControlContext`), what it is given at every control step (:class:`Measurement`) and what it returns
(one force or torque per PTO)."""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Self

import numpy as np

if TYPE_CHECKING:
    from ..linear import LinearModel
    from ..scene import SeaState
    from ..waves import ExcitationModel, Spectrum, WaveComponents


@dataclass(frozen=True)
class ControlContext:
    """What a controller learns once per run, before the first :meth:`Controller.compute`.

    Attributes
    ----------
    pto_names : tuple of str
        The device's PTOs, in the order of every force vector.
    control_period : float
        Time between two calls of :meth:`Controller.compute` [s]; the force is held in between.
    default_damping : tuple of float
        The device's default PTO damping per PTO [N s/m or N m s/rad] (its spec's ``damping``; the M4 paper's
        6 N m s/rad). The controller owns the gains it applies: this is only a default it may take.
    pto_kinds : tuple of str
        "rotary" (torque [N m], stroke [rad]) or "linear" (force [N], stroke [m]) per PTO.
    force_limit, stroke_limit : tuple of float
        The device's limits per PTO (inf: none) [N or N m; m or rad]. The simulators saturate the force at
        ``force_limit`` and apply the end stops beyond ``stroke_limit`` whatever the controller does.
    time_step : float
        The solver's step [s].
    duration : float
        Simulated time [s].
    sea : SeaState or None
        The scene's sea state.
    spectrum : Spectrum or None
        Its spectrum (None for regular waves, measured records and calm water).
    waves : WaveComponents or None
        The wave components (None in calm water).
    excitation : ExcitationModel or None
        The excitation on the hydrodynamic DOFs (``excitation.omega``, ``excitation.coefficients``; ramp
        included in ``excitation.force(t)``).
    hydro_dofs : tuple of str
        The hydrodynamic DOFs of the excitation and of a preview.
    """

    pto_names: tuple[str, ...]
    control_period: float
    default_damping: tuple[float, ...]
    pto_kinds: tuple[str, ...] = ()
    force_limit: tuple[float, ...] = ()
    stroke_limit: tuple[float, ...] = ()
    time_step: float = 0.0
    duration: float = 0.0
    sea: SeaState | None = None
    spectrum: Spectrum | None = None
    waves: WaveComponents | None = None
    excitation: ExcitationModel | None = None
    hydro_dofs: tuple[str, ...] = ()
    plant: Callable[[], LinearModel] | None = field(default=None, repr=False, compare=False)

    def __post_init__(self) -> None:
        n = len(self.pto_names)
        if len(self.default_damping) != n:
            raise ValueError(f"default_damping has {len(self.default_damping)} values for {n} PTOs")
        for label in ("pto_kinds", "force_limit", "stroke_limit"):
            values = getattr(self, label)
            if not values:
                object.__setattr__(self, label, ("rotary",) * n if label == "pto_kinds" else (np.inf,) * n)
            elif len(values) != n:
                raise ValueError(f"{label} has {len(values)} values for {n} PTOs")
        if not self.control_period > 0:
            raise ValueError(f"control_period must be positive [s]; got {self.control_period!r}")

    @property
    def n_pto(self) -> int:
        """Number of PTOs."""
        return len(self.pto_names)

    def linear_model(
        self, damping: np.ndarray | float | None = None, stiffness: np.ndarray | float | None = None
    ) -> LinearModel:
        """The scene's device linearised about its equilibrium (``wecss.linear.LinearModel``: state space with
        radiation states where the scene's radiation is a state-space fit, and the exact frequency response from
        A(omega) and B(omega)). Without arguments the open plant (no controller folded in: the PTO forces are
        inputs); with ``damping`` and ``stiffness`` (per PTO or one for all) [SI] a linear PTO controller folded in.
        Built on first use and cached.

        Raises
        ------
        ValueError
            If the run offers no linear model (a context made by hand without ``plant``).
        """
        if self.plant is None:
            raise ValueError("this context has no linear model (it was not made by wecss for a scene)")
        model = self.plant()
        if damping is None and stiffness is None:
            return model
        return model.with_pto_gains(0.0 if damping is None else damping, 0.0 if stiffness is None else stiffness)


@dataclass(frozen=True)
class Measurement:
    """What a controller is given at a control step.

    Attributes
    ----------
    displacement : ndarray (n_pto,)
        PTO strokes from their rest positions [m or rad].
    velocity : ndarray (n_pto,)
        PTO stroke rates [m/s or rad/s].
    state : ndarray or None
        The simulator's full state, for controllers that declare ``needs_state``: the generalised coordinates q
        (nq,), their rates v (nv,) and the radiation states where the run has them: the nonlinear simulator's
        complex modal states as real and imaginary parts (state-space radiation; none for a convolution), the
        linear model's real radiation states in linear runs (where q = q0 + xi).
    preview_times : ndarray or None
        Times of the excitation preview [s]: t + k control_period, k = 1 ... (``preview_horizon``).
    preview : ndarray (n_preview, n_h) or None
        The scene's own excitation on the hydrodynamic DOFs at ``preview_times`` [N, N m] (perfect knowledge).
    elevation : float or None
        The wave elevation at the point the controller asked for (``elevation_at``), ramp included [m].
    """

    displacement: np.ndarray
    velocity: np.ndarray
    state: np.ndarray | None = None
    preview_times: np.ndarray | None = None
    preview: np.ndarray | None = None
    elevation: float | None = None


class Controller(ABC):
    """A PTO controller: one force (or torque) per PTO, positive extending the stroke.

    :meth:`setup` is called once, when the controller is attached to a compiled scene
    (``wecss.control.compile_scene``); every run then calls :meth:`reset` at its start and :meth:`compute` once per
    control period, holding the force over the period. A controller declares what it needs beyond the PTO strokes
    and rates with class (or instance) attributes, and a run that cannot give it refuses before it starts:

    - ``needs_state`` (bool): the full state in every :class:`Measurement`;
    - ``preview_horizon`` (float or None): an excitation preview over this many seconds (a whole number of
      control periods);
    - ``elevation_at`` ((x, y) or None): the wave elevation at this point [m].

    A linear feedback on the PTO strokes offers its gains through :meth:`linear_gains`; the simulators then apply
    f = -c x_dot - k x continuously inside the equations of motion (and fold it into linear models) instead of
    sampling :meth:`compute`.
    """

    needs_state: bool = False
    preview_horizon: float | None = None
    elevation_at: tuple[float, float] | None = None
    _made_with: tuple[tuple[Any, ...], dict[str, Any]]

    def __new__(cls, *args: Any, **kwargs: Any) -> Self:
        # the arguments the instance was made with, kept for the result's provenance
        # (``wecss.control.controller_attrs``): any subclass has them without cooperating
        self = super().__new__(cls)
        self._made_with = (args, kwargs)
        return self

    @abstractmethod
    def setup(self, context: ControlContext) -> None:
        """Called once when the controller is attached to a compiled scene (see :class:`ControlContext`): build
        what depends on the device and the sea state here (gains, models, solvers)."""

    def reset(self) -> None:
        """Called at the start of every run, after :meth:`setup`: a controller with memory (filters, plans,
        warm starts) starts afresh here, so that every run of the same scene gives the same result. Default:
        nothing (a controller without memory)."""
        return None

    @abstractmethod
    def compute(self, t: float, measurement: Measurement) -> np.ndarray:
        """PTO forces [N or N m] at time ``t`` [s], one per PTO."""

    def linear_gains(self) -> tuple[np.ndarray, np.ndarray] | None:
        """(damping, stiffness) per PTO [N s/m or N m s/rad; N/m or N m/rad] when the controller is the linear
        feedback f = -c x_dot - k x (valid after :meth:`setup`), else None (the default)."""
        return None

    def report(self) -> dict[str, Any]:
        """What the controller has to say about its last run (numbers or short texts by name; empty by default).
        The result keeps each as the attribute ``controller_<name>`` and lists them in its notes."""
        return {}
