"""A scene: everything one simulation needs (device, sea state, controller, solver, radiation, outputs).

Declarative: a TOML file (``Scene.from_toml``) or frozen dataclasses with the same fields, validated on
construction. Durations and steps may be given in seconds or relative to the sea state's period: ``"100 Tp"``,
``"Tp/200"`` (``T`` for regular waves means the same). A scene round-trips through a plain dict
(``to_dict`` / ``from_dict``), which every result stores as JSON in its ``scene`` attribute.

Example (the embedded default, ``wecss/data/scenes/default.toml``)::

    [device]
    name = "m4-134"

    [sea]
    kind = "jonswap"
    height = 0.04        # Hs [m]
    period = 1.2         # Tp [s]
    gamma = 3.3
    duration = "100 Tp"
    seed = 1

    [solver]
    method = "beeman"
    dt = "Tp/200"
"""

from __future__ import annotations

import json
import math
import re
import tomllib
from dataclasses import asdict, dataclass, field, fields
from functools import cached_property
from pathlib import Path
from typing import Any, cast

from ..outputs import DEFAULT_GROUPS, GROUP_NAMES
from ..tomlfile import read_toml
from ._checks import check_choice, check_keys, check_types
from ._errors import SceneError
from ._hydrodynamics import Hydrodynamics, Initial
from ._parameters import Parameters
from ._paths import plain_copy, set_path
from ._runners import RADIATION_METHODS, Runner, runner, tolerance_runners

SEA_KINDS = ("regular", "jonswap", "pierson-moskowitz", "tabulated", "elevation", "calm")
LINEAR_HOLDS = ("foh", "zoh")
ADDED_MASS_TREATMENTS = ("implicit", "explicit")
EXPLICIT_RUNNER = "beeman-explicit"
"""The runner of the M4 paper's explicit added mass; ``solver.added_mass = "explicit"`` with ``method = "beeman"``
is read as this method."""
OUTPUT_GROUPS = GROUP_NAMES
DEFAULT_OUTPUTS = DEFAULT_GROUPS


DEFAULT_METHOD: str = "beeman"
"""``solver.method`` when a scene gives neither a method nor a tolerance."""

DEFAULT_DT: str = "Tp/200"
"""``solver.dt`` when a scene gives neither a step nor a tolerance."""

MAX_TOLERANCE: float = 0.1
"""Largest ``solver.tolerance`` (a relative error of the statistics)."""

TOLERANCE_CANDIDATES: tuple[str, ...] = ("rk4", "beeman")
"""The runners ``solver.tolerance`` chooses from when the scene names no ``solver.method``."""

_NOT_CHOSEN = (
    "{what} of this scene is chosen from solver.tolerance when the run starts: simulate(scene) chooses it, "
    "wecss.sim.choose_step(scene).scene is the scene it runs"
)

MAX_STEPS: float = 1e9
"""Most steps a scene may ask for."""

BYTES_PER_SAVED_STEP: int = 2000
"""Upper estimate of the memory one saved step takes: m4-134 with the default outputs took 1.0 kB per saved step
(1.28 GB peak for 10^6 saved steps, 0.26 GB of it the interpreter and the compiled scene; the Dataset's variables
are views of the loop's arrays); the radiation and loads groups take more."""

MAX_SAVED_BYTES: float = 8e9
"""Most memory the saved time series of a scene may take (estimated; this machine class has 24 GiB)."""


_RELATIVE = re.compile(r"^\s*(?:([0-9.eE+-]+)\s*\*?\s*)?(Tp|T)\s*(?:/\s*([0-9.eE+-]+))?\s*$")


def resolve_time(value: float | str, period: float | None, name: str) -> float:
    """Seconds from a number [s] or a string relative to the period: ``"100 Tp"``, ``"Tp/200"``, ``"2.5 T"``.

    Raises
    ------
    SceneError
        On a malformed string, a relative value without a period, or a non-positive result.
    """
    if isinstance(value, bool):
        raise SceneError(f"{name}: expected seconds or a multiple of Tp such as '100 Tp'; got {value!r}")
    if isinstance(value, int | float):
        seconds = float(value)
    elif isinstance(value, str):
        match = _RELATIVE.match(value)
        if match is None:
            raise SceneError(f"{name}: cannot read {value!r}; use seconds, 'x Tp' or 'Tp/n'")
        if period is None:
            raise SceneError(f"{name}: {value!r} is relative to the period, but this sea state has none; give seconds")
        try:
            factor = float(match.group(1)) if match.group(1) else 1.0
            divisor = float(match.group(3)) if match.group(3) else 1.0
        except ValueError:
            raise SceneError(f"{name}: cannot read {value!r}; use seconds, 'x Tp' or 'Tp/n'") from None
        if divisor == 0:
            raise SceneError(f"{name}: {value!r} divides by zero")
        seconds = factor * period / divisor
    else:
        raise SceneError(f"{name}: expected seconds or a string such as '100 Tp'; got {value!r}")
    if not (math.isfinite(seconds) and seconds > 0):
        raise SceneError(f"{name} must be positive; got {value!r} ({seconds} s)")
    return seconds


def _is_zero(value: float | str) -> bool:
    if isinstance(value, str):
        match = _RELATIVE.match(value)
        try:
            return match is not None and match.group(1) is not None and float(match.group(1)) == 0.0
        except ValueError:
            return False
    return not isinstance(value, bool) and value == 0


@dataclass(frozen=True)
class DeviceChoice:
    """The device (catalogue name or spec TOML path) and, optionally, another hydrodynamic database."""

    name: str = "m4-134"
    hydro: str | None = None

    def __post_init__(self) -> None:
        check_types("device", {"name": (self.name, str)})
        if self.hydro is not None:
            check_types("device", {"hydro": (self.hydro, str)})


MAX_SEED: int = 2**64 - 1
"""Largest ``sea.seed``: results store the seed as an unsigned 64-bit netCDF attribute."""


@dataclass(frozen=True)
class SeaState:
    """The waves.

    Attributes
    ----------
    kind : {"regular", "jonswap", "pierson-moskowitz", "tabulated", "elevation", "calm"}
    height : float
        Wave height H (regular) or significant wave height Hs (spectra) [m].
    period : float
        Wave period T (regular) or peak period Tp [s]; for tabulated spectra and measured elevations it only
        serves durations such as "100 Tp" (optional).
    gamma : float
        JONSWAP peak enhancement [-].
    duration : float or str
        Simulated time [s] or relative ("100 Tp").
    ramp : float or str
        Length of the cosine ramp at the start [s] or relative ("2 Tp"); 0 for none.
    seed : int
        Seed of the random phases (numpy Generator), 0 to 2**64 - 1 (:data:`MAX_SEED`).
    periodic : bool
        Periodic irregular record (frequencies k d_omega, repeat period 2 pi / d_omega).
    d_omega : float or None
        Frequency step [rad/s]; default 2 pi / duration (the record repeats once over the run).
    direction : float
        Direction of propagation [rad].
    energy_threshold : float
        Share of the variance the dropped (smallest) components may carry together [-].
    file : str or None
        Two-column text file: omega [rad/s] and S [m^2 s/rad] (tabulated) or time [s] and elevation [m].
    spreading : dict or None
        A directional (short-crested) sea about the mean ``direction``: ``{type = "cos-2s", s = 10}`` or
        ``{type = "cos-n", n = 2}`` (exponents [-], positive), its energy split over the database's headings
        (``wecss.waves.spread``; docs/seas.md); None: long-crested. Not for measured elevations or calm water.
    """

    kind: str = "jonswap"
    height: float = 0.04
    period: float | None = 1.2
    gamma: float = 3.3
    duration: float | str = "100 Tp"
    ramp: float | str = "5 Tp"
    seed: int = 1
    periodic: bool = True
    d_omega: float | None = None
    direction: float = 0.0
    energy_threshold: float = 1e-4
    file: str | None = None
    spreading: dict[str, Any] | None = None

    def __post_init__(self) -> None:
        check_choice("sea.kind", self.kind, SEA_KINDS)
        if self.spreading is not None:
            object.__setattr__(self, "spreading", _spreading(self.spreading, self.kind))
        if self.kind in ("regular", "jonswap", "pierson-moskowitz"):
            if self.period is None or not 0 < self.period < math.inf:
                raise SceneError(
                    f"sea.period must be positive and finite [s] for {self.kind} waves; got {self.period!r}"
                )
            if not 0 < self.height < math.inf:
                raise SceneError(f"sea.height must be positive and finite [m]; got {self.height!r}")
        if self.kind in ("tabulated", "elevation") and not self.file:
            raise SceneError(f"sea.file is required for {self.kind!r} seas (two columns of numbers)")
        if self.file and not Path(self.file).is_file():
            raise SceneError(f"sea.file: no file at {self.file!r}")
        if self.kind == "jonswap" and not self.gamma >= 1:
            raise SceneError(f"sea.gamma must be >= 1; got {self.gamma!r}")
        if abs(self.direction) > 2 * math.pi:
            raise SceneError(f"sea.direction is in radians; got {self.direction!r}, which looks like degrees")
        if self.d_omega is not None and not 0 < self.d_omega < math.inf:
            raise SceneError(f"sea.d_omega must be positive and finite [rad/s] (or absent); got {self.d_omega!r}")
        if self.period is not None and not 0 < self.period < math.inf:
            raise SceneError(f"sea.period must be positive and finite [s] (or absent); got {self.period!r}")
        if not 0 <= self.energy_threshold < 1:
            raise SceneError(f"sea.energy_threshold is a share in [0, 1); got {self.energy_threshold!r}")
        check_types(
            "sea",
            {"kind": (self.kind, str), "seed": (self.seed, int), "periodic": (self.periodic, bool)},
        )
        if not 0 <= self.seed <= MAX_SEED:
            raise SceneError(
                f"sea.seed must be an integer from 0 to 2**64 - 1 (a result file stores it as a 64-bit integer); "
                f"got {self.seed!r}"
            )
        duration = self.duration_s
        if self.ramp_s >= duration:
            raise SceneError(f"sea.ramp ({self.ramp!r}) must be shorter than sea.duration ({self.duration!r})")

    @cached_property
    def duration_s(self) -> float:
        """Duration [s] (read once from ``duration``)."""
        return resolve_time(self.duration, self.period, "sea.duration")

    @cached_property
    def ramp_s(self) -> float:
        """Ramp length [s] (0: none)."""
        return 0.0 if _is_zero(self.ramp) else resolve_time(self.ramp, self.period, "sea.ramp")


SPREADING_EXPONENTS: dict[str, str] = {"cos-2s": "s", "cos-n": "n"}
"""The spreading types of ``sea.spreading`` and the name of each one's exponent."""


def _spreading(value: Any, kind: str) -> Parameters:
    """``sea.spreading`` checked and frozen: a table with ``type`` and its exponent (see :class:`SeaState`)."""
    accepted = 'a table such as {type = "cos-2s", s = 10} or {type = "cos-n", n = 2}'
    if not isinstance(value, dict):
        raise SceneError(f"sea.spreading must be {accepted}; got {value!r}")
    kind_name = value.get("type")
    if kind_name not in SPREADING_EXPONENTS:
        raise SceneError(
            f"sea.spreading.type must be one of {', '.join(SPREADING_EXPONENTS)}; got {kind_name!r} ({accepted})"
        )
    exponent = SPREADING_EXPONENTS[kind_name]
    unknown = sorted(set(value) - {"type", exponent})
    if unknown:
        raise SceneError(f"sea.spreading: unknown keys {unknown} for {kind_name!r}; accepted: type, {exponent}")
    given = value.get(exponent)
    if isinstance(given, bool) or not isinstance(given, int | float) or not 0 < given < math.inf:
        raise SceneError(f"sea.spreading.{exponent} must be a positive finite number [-]; got {given!r}")
    if kind in ("elevation", "calm"):
        raise SceneError(
            f"sea.spreading is for seas made of components (regular, spectra); sea.kind = {kind!r} has "
            + ("no waves" if kind == "calm" else "a measured elevation at one point, which gives no directions")
        )
    return Parameters({"type": kind_name, exponent: float(given)})


@dataclass(frozen=True)
class ControllerChoice:
    """A controller registered under the ``wecss.controllers`` entry points, with its parameters.

    The controller owns the gains it applies; without a ``damping`` parameter, ``damping`` takes the device's
    default PTO damping (6 N m s/rad for the M4 devices) from the context it is set up with.

    Attributes
    ----------
    name : str
    parameters : dict
        Keyword arguments of the controller, frozen (:class:`Parameters`: read-only, lists as tuples) so that the
        scene is hashable.
    dt : float or str or None
        Control period [s] or relative ("Tp/20"): the controller is called every ``dt`` and its force held in
        between. A whole number of solver steps; None (default) calls it every step. Controllers with linear
        gains act continuously and ignore it.
    time_limit : float
        Wall time [s] one call of the controller's ``compute`` may take (default 60: some 300 times the median
        cvxpy MPC solve of ``docs/control.md``, 194 ms, yet a hung controller stops within a minute); a call
        past it stops the run with ``wecss.sim.ControllerTimeout``. ``inf``: no limit. Enforced in the main
        thread only (``wecss/sim/_watchdog.py``; elsewhere the result's notes say it was not).
    """

    name: str = "damping"
    parameters: dict[str, Any] = field(default_factory=dict)
    dt: float | str | None = None
    time_limit: float = 60.0

    def __post_init__(self) -> None:
        check_types("controller", {"name": (self.name, str), "parameters": (self.parameters, dict)})
        if not self.time_limit > 0:
            raise SceneError(
                f"controller.time_limit must be a positive time [s] (inf: no limit); got {self.time_limit!r}"
            )
        object.__setattr__(self, "parameters", Parameters(self.parameters))


@dataclass(frozen=True)
class Solver:
    """Time stepping.

    Attributes
    ----------
    method : str or None
        A registered runner (``wecss.scene.available_runners()``); default (None) :data:`DEFAULT_METHOD`, unless
        ``tolerance`` chooses it. The built-ins: the nonlinear MFM equations by
        the Beeman predictor-corrector (paper Eq. 52, "beeman"), the same with the M4 paper's explicit added mass
        ("beeman-explicit", see ``added_mass``), classic RK4 ("rk4", state-space radiation only) or scipy's DOP853
        at tight tolerance ("reference": verification; state-space radiation only); or the equations linearised
        about the static equilibrium: "linear", the linear state-space model stepped exactly (state-space
        radiation only; ``wecss.linear``), or "frequency", the exact frequency-domain steady state from the
        database's A(omega) and B(omega) (no ramp, no transient; controllers with linear gains only).
    dt : float or str or None
        Step [s] or relative ("Tp/200"); default (None) :data:`DEFAULT_DT`, unless ``tolerance`` chooses it.
    tolerance : float or None
        Relative error [-] allowed on the statistics the run reports (mean PTO power, RMS PTO strokes), in
        (0, :data:`MAX_TOLERANCE`]: the step (and, without a ``method``, the integrator: ``rk4`` or ``beeman``) is
        chosen from an error estimate when the run starts (``wecss.sim.choose_step``), and the result records the
        choice and the estimate. Exclusive with ``dt`` (a scene that gives both is refused); only the fixed-step
        runners take it (``Capabilities.tolerance``: ``beeman``, ``rk4``, ``linear``).
    corrector_tol : float
        Beeman: the corrector stops when the change of the accelerations is below this share of their size.
    max_corrector_iterations : int
    angle_bound : float
        A revolute joint angle beyond this [rad] stops the run (SimulationDiverged).
    translation_bound : float or None
        A body's centre of mass further than this [m] from its equilibrium position stops a nonlinear run
        (SimulationDiverged), checked after each chunk of steps; default (None): 100 times the largest body size
        V^(1/3) of the database (no bound when it has no displaced volumes).
    reference_rtol : float
        Relative tolerance of the reference solver.
    hold : {"foh", "zoh"} or None
        "linear" only: the excitation taken linear in time over a step (first-order hold, second order; the
        default) or held (zero-order hold, first order).
    added_mass : {"implicit", "explicit"} or None
        "beeman" only. "implicit" (the default, None): the infinite-frequency added mass in the mass matrix,
        B' (M + A_inf) B, no iteration for it. "explicit" (the same as ``method = "beeman-explicit"``, which the
        scene then names): the M4 paper's own method (its section 5.2), a replication option: the
        rigid mass alone on the left, the added-mass force of the last accelerations on the right, iterated with
        the corrector until the accelerations change by less than ``corrector_tol`` (the paper: 0.01), with no
        implicit fallback. Slower, and it converges only where the added mass is smaller than the rigid mass in
        every mode (a run refuses to start otherwise; see ``wecss.sim`` docs, "the paper's method").
    allow_large : bool or None
        "reference" only: run it even when it needs more than ``wecss.limits.REFERENCE_EVALUATIONS`` evaluations
        (a stiff plant: an explicit method's step is bounded by the fastest mode); default None: refused.
    """

    method: str | None = None
    dt: float | str | None = None
    tolerance: float | None = None
    corrector_tol: float = 1e-6
    max_corrector_iterations: int = 30
    angle_bound: float = 1.5
    translation_bound: float | None = None
    reference_rtol: float = 1e-10
    hold: str | None = None
    added_mass: str | None = None
    allow_large: bool | None = None

    def __post_init__(self) -> None:
        self._check_tolerance()
        if self.method is not None:
            check_types("solver", {"method": (self.method, str)})
        if self.allow_large is not None and not isinstance(self.allow_large, bool):
            raise SceneError(f"solver.allow_large must be true or false; got {self.allow_large!r}")
        if self.added_mass is not None:
            check_choice("solver.added_mass", self.added_mass, ADDED_MASS_TREATMENTS)
        if self.added_mass == "explicit" or self.method == EXPLICIT_RUNNER:
            if self.method not in (None, "beeman", EXPLICIT_RUNNER):
                raise SceneError(
                    f"solver.added_mass 'explicit' (the M4 paper's iterated added mass) needs solver.method 'beeman' "
                    f"(or {EXPLICIT_RUNNER!r}); got method {self.method!r}"
                )
            if self.added_mass == "implicit":
                raise SceneError(
                    f"solver.method {EXPLICIT_RUNNER!r} is the explicit added mass; solver.added_mass 'implicit' "
                    "contradicts it (leave added_mass out, or use method 'beeman')"
                )
            object.__setattr__(self, "method", EXPLICIT_RUNNER)  # one name for the runner
            object.__setattr__(self, "added_mass", "explicit")
        if self.method is not None:
            found = runner(self.method)  # a registered runner (SceneError listing them otherwise)
            if self.tolerance is not None and not found.capabilities.tolerance:
                raise SceneError(
                    f"solver.tolerance chooses the step of a fixed-step runner ({', '.join(tolerance_runners())}); "
                    f"solver.method {self.method!r} does not take it{found.tolerance_reason}"
                )
        if self.hold is not None:
            check_choice("solver.hold", self.hold, LINEAR_HOLDS)
        if not 0 < self.corrector_tol < 1:
            raise SceneError(f"solver.corrector_tol must lie in (0, 1); got {self.corrector_tol!r}")
        if not (isinstance(self.max_corrector_iterations, int) and self.max_corrector_iterations >= 1):
            raise SceneError(
                f"solver.max_corrector_iterations must be an integer >= 1; got {self.max_corrector_iterations!r}"
            )
        if not 0 < self.angle_bound <= 2 * math.pi:
            raise SceneError(f"solver.angle_bound must lie in (0, 2 pi] rad; got {self.angle_bound!r}")
        bound = self.translation_bound
        if bound is not None and not (isinstance(bound, int | float) and not isinstance(bound, bool) and bound > 0):
            raise SceneError(f"solver.translation_bound must be a positive length [m] or absent; got {bound!r}")

    def _check_tolerance(self) -> None:
        tol = self.tolerance
        if tol is None:
            return
        if isinstance(tol, bool) or not isinstance(tol, int | float):
            raise SceneError(
                f"solver.tolerance is a relative error, a number in (0, {MAX_TOLERANCE:g}] such as 1e-3; got {tol!r} "
                f"({type(tol).__name__})"
            )
        if not (math.isfinite(tol) and 0 < tol <= MAX_TOLERANCE):
            raise SceneError(
                f"solver.tolerance is a relative error in (0, {MAX_TOLERANCE:g}], such as 1e-3; got {tol!r}"
            )
        if self.dt is not None:
            raise SceneError(
                f"solver.dt ({self.dt!r}) and solver.tolerance ({tol!r}) both given: the tolerance chooses the step; "
                "give one of them"
            )

    @property
    def runner_name(self) -> str | None:
        """The runner's name: ``method``, else :data:`DEFAULT_METHOD`, or None while ``tolerance`` is to choose
        it (a method left out stays left out, so that a tolerance set later may still choose it)."""
        if self.method is not None:
            return self.method
        return DEFAULT_METHOD if self.tolerance is None else None

    @property
    def step_chosen(self) -> bool:
        """The step is chosen from ``tolerance`` when the run starts (``wecss.sim.choose_step``)."""
        return self.tolerance is not None

    @property
    def linear_hold(self) -> str:
        """The hold of linear runs ("foh" unless ``hold`` says otherwise)."""
        return self.hold or "foh"


@dataclass(frozen=True)
class Radiation:
    """Radiation memory.

    Attributes
    ----------
    method : {"state_space", "convolution", "none"}
        ``state_space`` (default): the fitted, passive state-space model (fits of the shipped databases ship with
        wecss; another database's first fit takes minutes and is cached). ``convolution``: the database's kernel
        itself, the reference (no fit).
    coupling_threshold : float
        Both methods: kernel entries whose peak is below this share of sqrt(peak_ii peak_jj) are dropped from the
        convolution and from the state-space fit's targets (reported) [-]; the rule is
        ``wecss.radiation.significant_couplings``.
    fit : {"era-mimo", "prony", "era"}
        State space: the fit method (``wecss.radiation.FitSettings``); fits are cached on disk.
    band : float
        State space: fit the kernel band-limited by a cosine roll-off from ``band`` times the database's highest
        frequency to that frequency (0: the full kernel with its fitted tail). Sea states have no energy up there;
        the band-limited kernel needs fewer states and is fitted far better in the band that matters.
    consistent_added_mass : bool
        Adjust A_inf so that the memory model reproduces the database's A(omega) over the sea state's frequencies
        (BEM's A_inf and the A(omega) implied by the damping through Kramers-Kronig differ by a constant; the
        result's notes give the change).
    body_to_body : bool
        Keep the radiation between bodies (added mass and damping between DOFs of different bodies; wecss's
        default). False drops them, each body radiating onto itself only (WEC-Sim's default, its ``body2body``
        off); the result's notes say so.
    """

    method: str = "state_space"
    coupling_threshold: float = 1e-3
    fit: str = "era-mimo"
    band: float = 0.6
    consistent_added_mass: bool = True
    body_to_body: bool = True

    def __post_init__(self) -> None:
        check_types(
            "radiation",
            {
                "consistent_added_mass": (self.consistent_added_mass, bool),
                "body_to_body": (self.body_to_body, bool),
            },
        )
        check_choice("radiation.method", self.method, RADIATION_METHODS)
        check_choice("radiation.fit", self.fit, ("era-mimo", "prony", "era"))
        if not 0 <= self.coupling_threshold < 1:
            raise SceneError(f"radiation.coupling_threshold is a share in [0, 1); got {self.coupling_threshold!r}")
        if not 0 <= self.band < 1:
            raise SceneError(f"radiation.band is a share of the highest data frequency in [0, 1); got {self.band!r}")


@dataclass(frozen=True)
class Outputs:
    """What to keep.

    Attributes
    ----------
    variables : sequence of {"motion", "pto", "excitation", "radiation", "elevation", "poses", "loads"}
        Groups of time series; empty or left out with ``statistics_only`` (other groups with it are refused).
        ``loads`` (not in the default) adds the joint
        reactions and the PTO loads on both ends, recovered from the record after the run.
    every : int
        Keep every k-th step.
    statistics_only : bool
        Keep no time series, only running statistics (mean PTO power and RMS stroke over the window).
    window : float
        Statistics over the final share of the run (0.5: the final half, as the paper) [-].
    probes : sequence of (x, y), or dict of name to (x, y)
        Points of the still water plane [m], earth frame, where the ``elevation`` group also keeps the undisturbed
        elevation (``wave_elevation_probe``, dims time and probe, coordinates probe_x and probe_y; the probe
        coordinate is the names of a table, else 0, 1, ...); needs the ``elevation`` group (so not with
        ``statistics_only``).
    """

    variables: tuple[str, ...] = DEFAULT_OUTPUTS
    every: int = 1
    statistics_only: bool = False
    window: float = 0.5
    probes: tuple[tuple[float, float], ...] | dict[str, tuple[float, float]] = ()

    def __post_init__(self) -> None:
        if isinstance(self.variables, str) or not isinstance(self.variables, list | tuple):
            raise SceneError(f"outputs.variables must be a list of groups; got {self.variables!r}")
        check_types("outputs", {"statistics_only": (self.statistics_only, bool)})
        object.__setattr__(self, "variables", tuple(self.variables))
        for v in self.variables:
            check_choice("outputs.variables", v, OUTPUT_GROUPS)
        if not self.variables and not self.statistics_only:
            raise SceneError("outputs.variables is empty: ask for at least one group or set statistics_only = true")
        if self.statistics_only and self.variables and self.variables != DEFAULT_OUTPUTS:
            raise SceneError(
                f"outputs.statistics_only = true keeps no time series, yet outputs.variables = {list(self.variables)} "
                "asks for some; accepted: statistics_only = false with the groups, or statistics_only = true with "
                "variables = [] (or left out)"
            )
        if not (isinstance(self.every, int) and self.every >= 1):
            raise SceneError(f"outputs.every must be an integer >= 1; got {self.every!r}")
        if not 0 < self.window <= 1:
            raise SceneError(f"outputs.window is a share of the run in (0, 1]; got {self.window!r}")
        object.__setattr__(self, "probes", _probes(self.probes))
        if self.probes and (self.statistics_only or "elevation" not in self.variables):
            raise SceneError(
                f"outputs.probes ({len(self.probes)} points) are kept by the 'elevation' group, and "
                + (
                    "outputs.statistics_only = true keeps no time series"
                    if self.statistics_only
                    else f"outputs.variables = {list(self.variables)} leaves it out"
                )
                + ": add 'elevation' to outputs.variables (statistics_only = false) or leave the probes out"
            )

    @property
    def probe_points(self) -> tuple[tuple[float, float], ...]:
        """The points (x, y) [m] of ``probes``, in order."""
        probes = self.probes
        return tuple(probes.values()) if isinstance(probes, dict) else tuple(probes)

    @property
    def probe_names(self) -> tuple[str, ...] | None:
        """The names of ``probes`` given as a table (None for a list)."""
        return tuple(self.probes) if isinstance(self.probes, dict) else None


def _probes(value: Any) -> tuple[tuple[float, float], ...] | Parameters:
    """``outputs.probes`` checked and frozen: a list of [x, y] points [m], or a table of them by name."""
    accepted = (
        "a list of [x, y] points in metres, such as [[0.0, 0.0], [10.0, 5.0]], or a table of them by name, such "
        "as {buoy = [10.0, 5.0]}"
    )
    named = isinstance(value, dict)
    if not named and (isinstance(value, str) or not isinstance(value, list | tuple)):
        raise SceneError(f"outputs.probes must be {accepted}; got {value!r}")
    items = list(value.items()) if named else list(enumerate(value))
    out = []
    for key, point in items:
        where = f"outputs.probes.{key}" if named else f"outputs.probes[{key}]"
        if named and not (isinstance(key, str) and key.strip()):
            raise SceneError(f"outputs.probes: a probe's name must be a non-empty string; got {key!r}")
        ok = isinstance(point, list | tuple) and len(point) == 2
        ok = ok and all(isinstance(c, int | float) and not isinstance(c, bool) and math.isfinite(c) for c in point)
        if not ok:
            raise SceneError(f"{where} must be [x, y], two finite numbers [m]; got {point!r} ({accepted})")
        out.append((key, (float(point[0]), float(point[1]))))
    return Parameters(dict(out)) if named else tuple(point for _, point in out)


_SECTIONS: dict[str, type] = {
    "device": DeviceChoice,
    "sea": SeaState,
    "controller": ControllerChoice,
    "solver": Solver,
    "radiation": Radiation,
    "outputs": Outputs,
    "hydrodynamics": Hydrodynamics,
    "initial": Initial,
}


@dataclass(frozen=True)
class Scene:
    """Everything one run needs. Build it from TOML (:meth:`from_toml`), a dict (:meth:`from_dict`) or directly.

    Raises
    ------
    SceneError
        On any malformed field (the message names it, says what was received and what is accepted).
    """

    device: DeviceChoice = field(default_factory=DeviceChoice)
    sea: SeaState = field(default_factory=SeaState)
    controller: ControllerChoice = field(default_factory=ControllerChoice)
    solver: Solver = field(default_factory=Solver)
    radiation: Radiation = field(default_factory=Radiation)
    outputs: Outputs = field(default_factory=Outputs)
    hydrodynamics: Hydrodynamics = field(default_factory=Hydrodynamics)
    initial: Initial = field(default_factory=Initial)

    def __post_init__(self) -> None:
        if self.solver.step_chosen:  # the step-dependent checks wait for the chosen step (``choose_step``)
            self._check_step_choice()
            return
        dt = self.dt
        if dt >= self.sea.duration_s:
            raise SceneError(f"solver.dt ({dt:.4g} s) must be shorter than sea.duration ({self.sea.duration_s:.4g} s)")
        self._check_size()
        self.control_steps  # noqa: B018 (validates controller.dt)
        self.runner.check(self)

    @property
    def runner(self) -> Runner:
        """The runner of ``solver.method`` (``wecss.scene.runner``).

        Raises
        ------
        SceneError
            For a scene whose method is chosen from ``solver.tolerance`` (not yet chosen).
        """
        name = self.solver.runner_name
        if name is None:
            raise SceneError(_NOT_CHOSEN.format(what="solver.method"))
        return runner(name)

    @property
    def candidates(self) -> tuple[str, ...]:
        """The runners ``solver.tolerance`` may choose from: the scene's ``solver.method`` when it names one, else
        those of :data:`TOLERANCE_CANDIDATES` that can run the scene (in that order)."""
        if self.solver.method is not None:
            return (self.solver.method,)
        found = []
        for name in TOLERANCE_CANDIDATES:
            try:
                runner(name).check(self)
            except SceneError:
                continue
            found.append(name)
        return tuple(found)

    def _check_step_choice(self) -> None:
        """A scene whose step ``solver.tolerance`` chooses: its runner (or one of the candidates) can run it, and
        ``controller.dt`` reads."""
        if self.controller.dt is not None:
            resolve_time(self.controller.dt, self.sea.period, "controller.dt")
        if self.solver.method is not None:
            self.runner.check(self)
        elif not self.candidates:
            runner(TOLERANCE_CANDIDATES[-1]).check(self)  # raises, naming what the most general one refuses
            raise SceneError(f"solver.tolerance: none of {', '.join(TOLERANCE_CANDIDATES)} can run this scene")

    def _check_size(self) -> None:
        """Refuse runs that keep fewer than two saved steps or a statistics window of fewer than two steps, and runs
        too long or too large to hold (with an estimate)."""
        n = self.sea.duration_s / self.dt
        if n > MAX_STEPS:
            raise SceneError(
                f"sea.duration / solver.dt gives {n:.3g} steps (at most {MAX_STEPS:.0e}); at 50 us per step that is "
                f"{n * 50e-6 / 3600:.3g} hours: shorten sea.duration or lengthen solver.dt"
            )
        steps = self.n_steps
        outputs = self.outputs
        window = round(outputs.window * steps)
        if window < 2:
            raise SceneError(
                f"outputs.window = {outputs.window!r} of {steps} steps leaves {window} steps for the statistics; it "
                "needs at least 2"
            )
        if outputs.statistics_only:
            return
        saved = steps // outputs.every + 1
        if saved < 2:
            raise SceneError(
                f"outputs.every = {outputs.every} keeps {saved} of the run's {steps + 1} steps; at least 2 are needed "
                f"(every <= {steps})"
            )
        size = saved * BYTES_PER_SAVED_STEP
        if size > MAX_SAVED_BYTES:
            raise SceneError(
                f"{saved:.3g} saved steps would take about {size / 1e9:.3g} GB (at {BYTES_PER_SAVED_STEP} bytes per "
                f"step; at most {MAX_SAVED_BYTES / 1e9:.0f} GB): raise outputs.every or set outputs.statistics_only"
            )

    @cached_property
    def dt(self) -> float:
        """Time step [s] (read once from ``solver.dt``, default :data:`DEFAULT_DT`).

        Raises
        ------
        SceneError
            For a scene whose step is chosen from ``solver.tolerance`` (not yet chosen).
        """
        if self.solver.step_chosen:
            raise SceneError(_NOT_CHOSEN.format(what="solver.dt"))
        given = self.solver.dt if self.solver.dt is not None else DEFAULT_DT
        return resolve_time(given, self.sea.period, "solver.dt")

    @cached_property
    def n_steps(self) -> int:
        """Number of steps (duration / dt, rounded to the nearest integer)."""
        return max(1, round(self.sea.duration_s / self.dt))

    @cached_property
    def control_steps(self) -> int:
        """Solver steps per control period (1 without ``controller.dt``)."""
        if self.controller.dt is None:
            return 1
        control = resolve_time(self.controller.dt, self.sea.period, "controller.dt")
        steps = round(control / self.dt)
        if steps < 1 or abs(control - steps * self.dt) > 1e-9 * control:
            raise SceneError(
                f"controller.dt ({control:.6g} s) must be a whole number of solver steps (solver.dt {self.dt:.6g} s)"
            )
        return steps

    @classmethod
    def from_dict(cls, data: dict[str, Any], *, base: Path | None = None) -> Scene:
        """Build a scene from nested dicts with the sections device, sea, controller, solver, radiation, outputs.

        ``base``: folder against which relative file paths are resolved.
        """
        if not isinstance(data, dict):
            raise SceneError(f"a scene is a table of sections; got {type(data).__name__}")
        unknown = sorted(set(data) - set(_SECTIONS))
        if unknown:
            raise SceneError(f"unknown sections {unknown}; accepted: {', '.join(_SECTIONS)}")
        parts: dict[str, Any] = {}
        for section, kind in _SECTIONS.items():
            if not isinstance(data.get(section, {}), dict):
                raise SceneError(f"[{section}] must be a table of keys; got {data[section]!r}")
            values = dict(data.get(section, {}))
            check_keys(section, values, kind)
            if base is not None:
                for key in ("file", "name", "hydro"):
                    value = values.get(key)
                    # sea.file is always a path; device names and databases only when they look like one
                    looks_like_path = key == "file" or (
                        isinstance(value, str) and ("/" in value or value.endswith((".toml", ".nc", ".out")))
                    )
                    if isinstance(value, str) and looks_like_path and not Path(value).is_absolute():
                        values[key] = str((base / value).resolve())
            _check_numbers(section, values, kind)
            try:
                parts[section] = kind(**values)
            except TypeError as err:  # wrong types reaching comparisons
                raise SceneError(f"[{section}]: {err}") from None
        return cls(**parts)

    @classmethod
    def from_toml(cls, path: str | Path) -> Scene:
        """Read a scene TOML file (relative file paths are taken from the file's folder).

        Raises
        ------
        FileNotFoundError
            If the file does not exist.
        SceneError
            On malformed TOML or fields.
        """
        path = Path(path)
        if not path.is_file():
            raise FileNotFoundError(f"no scene file at {str(path)!r}")
        try:
            data = read_toml(path)
        except tomllib.TOMLDecodeError as err:
            raise SceneError(f"{path}: not valid TOML: {err}") from None
        except UnicodeDecodeError:
            raise SceneError(f"{path}: not a text file (a scene is a UTF-8 TOML file)") from None
        return cls.from_dict(data, base=path.parent)

    def replace(self, **changes: Any) -> Scene:
        """A copy of the scene with ``changes``, validated as a new scene is.

        Each keyword is a dotted path, as ``wecss run --set`` takes (``"sea.period"``,
        ``"controller.parameters.damping"``; passed as ``**{"sea.period": 1.4}``), or a section's name with the
        section (``sea=SeaState(...)``) or a dict of the keys of the section to change (``sea={"period": 1.4}``:
        the other keys keep their values). Values are in the scene's units (SI; durations and steps also relative,
        ``"100 Tp"``). Changes apply in the order given.

        Example::

            steeper = scene.replace(sea={"height": 0.06, "period": 1.4})
            damped = scene.replace(**{"controller.parameters.damping": 8.0})

        Raises
        ------
        SceneError
            For an unknown section or key, a section of the wrong type, or a value the scene refuses (the message
            names the field, the value and what is accepted).
        """
        data = plain_copy(self.to_dict())
        for key, value in changes.items():
            if "." in key:
                data = set_path(data, key, value)
                continue
            kind = _SECTIONS.get(key)
            if kind is None:
                raise SceneError(
                    f"Scene.replace: unknown section or path {key!r}; accepted: a section ({', '.join(_SECTIONS)}) "
                    "or a dotted path such as 'sea.period'"
                )
            if isinstance(value, kind):
                data[key] = plain_copy(asdict(cast(Any, value)))  # a section: one of the dataclasses above
            elif isinstance(value, dict):
                for name, item in value.items():
                    data = set_path(data, f"{key}.{name}", item)
            else:
                raise SceneError(
                    f"Scene.replace: {key} takes a {kind.__name__} or a dict of its keys; got {value!r} "
                    f"({type(value).__name__})"
                )
        return Scene.from_dict(data)

    def to_dict(self) -> dict[str, Any]:
        """Nested plain dict (round-trips through :meth:`from_dict`)."""
        out = asdict(self)
        out["outputs"]["variables"] = list(out["outputs"]["variables"])
        probes = out["outputs"]["probes"]
        if isinstance(probes, dict):
            out["outputs"]["probes"] = {name: list(point) for name, point in probes.items()}
        else:
            out["outputs"]["probes"] = [list(point) for point in probes]
        if out["sea"]["spreading"] is not None:
            out["sea"]["spreading"] = dict(out["sea"]["spreading"])
        return out

    def to_json(self) -> str:
        """JSON text of :meth:`to_dict` (stored in results)."""
        return json.dumps(self.to_dict(), sort_keys=True)

    @classmethod
    def from_json(cls, text: str) -> Scene:
        """Inverse of :meth:`to_json`.

        Raises
        ------
        SceneError
            If ``text`` is not JSON (or not text), or on malformed fields.
        """
        try:
            data = json.loads(text)
        except (json.JSONDecodeError, TypeError) as err:
            shown = text[:60] if isinstance(text, str) else type(text).__name__
            raise SceneError(f"a scene's JSON could not be read ({err}); got {shown!r}") from None
        return cls.from_dict(data)


_NUMBER_FIELDS = {"float": False, "float | None": False, "int": True, "int | None": True}


def _check_numbers(section: str, values: dict[str, Any], kind: type) -> None:
    """Refuse a value of the wrong type for a field that takes only a number (a string height, a float seed), naming
    the field, the value and what is accepted."""
    for f in fields(kind):
        integer = _NUMBER_FIELDS.get(str(f.type))
        if integer is None or f.name not in values or (values[f.name] is None and "None" in str(f.type)):
            continue
        value = values[f.name]
        ok = isinstance(value, int) if integer else isinstance(value, int | float)
        if isinstance(value, bool) or not ok:
            accepted = "int" if integer else "a number"
            raise SceneError(f"{section}.{f.name} must be {accepted}; got {value!r} ({type(value).__name__})")


def default_scene_path() -> Path:
    """The embedded default scene (M4 134, JONSWAP Hs 0.04 m, Tp 1.2 s, 100 Tp, dt Tp/200, damping 6)."""
    return Path(__file__).resolve().parent.parent / "data" / "scenes" / "default.toml"
