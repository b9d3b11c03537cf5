"""Compile a scene into flat arrays once: the plant, the radiation memory, the wave components. The controller is
attached afterwards (``wecss.control.compile_scene`` makes a ``ControlledScene``), its linear gains folded in by
:func:`with_linear_gains`.

Everything that can fail on bad input fails here, before the time loop, with a message that says what to change.
Whatever is dropped to save time (wave components, radiation couplings, components outside the database's
frequencies) is written into ``notes`` and ends up in the result's attributes.
"""

from __future__ import annotations

import dataclasses
import functools
import hashlib
import json
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .. import waves as wv
from ..devices import Device, DeviceSpecError, check_against_database
from ..devices import available as available_devices
from ..devices import load as load_device
from ..hydro import HydroData, without_body_interactions
from ..multibody import HydroCoupling, JointPTO, StaticModel
from ..radiation import FitSettings, RadiationFit
from ..scene import Radiation, Scene, SceneError, SeaState
from ._body_exact import PressureArrays
from ._inputs import device_inputs
from ._kernels import integrate_configuration
from ._plant import Plant, build_plant
from ._pto_law import pto_gains
from ._radiation import (
    RadiationArrays,
    RadiationKind,
    RadiationSummary,
    added_mass_correction,
    from_impulse_response,
    from_state_space,
    no_radiation,
)
from ._terms import pressure_arrays, viscous_arrays, wave_arrays
from ._viscous import ViscousArrays
from ._wave_kinematics import no_waves


@dataclass(frozen=True, eq=False)
class CompiledScene:
    """A scene as arrays and ready objects (see the module docstring).

    Attributes
    ----------
    scene : Scene
    device : Device
    coupling : HydroCoupling
        The database mapped onto the model, about the bodies' centres of mass.
    plant : Plant
    radiation : RadiationArrays
    radiation_summary : RadiationSummary
    radiation_fit : RadiationFit or None
        The state-space fit the radiation arrays were made from (None for other methods); the linear model uses
        the same fit.
    waves : WaveComponents or None
        None in calm water.
    spectrum : Spectrum or None
        The sea state's spectrum (None for regular waves, measured elevations and calm water).
    excitation : ExcitationModel or None
    linear_controller : bool
        A controller's linear gains act inside the equations of motion (:func:`with_linear_gains`; else a
        controller's force is held over each control period). The controller itself comes with the scene it is
        attached to (``wecss.control.ControlledScene``).
    statics : StaticModel
        Gravity, hydrostatics and the PTO springs (device springs plus the controller's linear stiffness).
    q0 : ndarray
        Static equilibrium, the initial configuration.
    stiffness : ndarray (nv, nv)
        Static stiffness K* at q0 with its geometric part and the controller's linear stiffness [SI].
    dt : float
        Step [s], the scene's, read once; the radiation arrays were made for it (checked).
    n_steps : int
    bounded : ndarray of int
        Coordinates (revolute joint angles) checked against ``solver.angle_bound``.
    notes : list of str
        What was dropped or assumed.
    """

    scene: Scene
    device: Device
    coupling: HydroCoupling
    plant: Plant
    radiation: RadiationArrays
    radiation_summary: RadiationSummary
    radiation_fit: RadiationFit | None
    waves: wv.WaveComponents | None
    spectrum: wv.Spectrum | None
    excitation: wv.ExcitationModel | None
    linear_controller: bool
    statics: StaticModel
    q0: np.ndarray
    stiffness: np.ndarray
    dt: float
    n_steps: int
    bounded: np.ndarray
    notes: list[str] = field(default_factory=list)

    def __post_init__(self) -> None:
        if self.dt != self.scene.dt:
            raise ValueError(f"compiled step {self.dt!r} s differs from the scene's {self.scene.dt!r} s")
        if self.radiation.dt not in (0.0, self.dt):
            raise ValueError(
                f"the radiation memory was discretised for a step of {self.radiation.dt!r} s, the scene's is "
                f"{self.dt!r} s"
            )

    def initial_state(self) -> tuple[np.ndarray, np.ndarray]:
        """The run's initial configuration and generalised velocities: the equilibrium ``q0`` moved by the scene's
        ``initial.displacement`` (velocity-space increments, on the configuration manifold) and its
        ``initial.velocity`` (zero by default).

        Raises
        ------
        SceneError
            If ``initial.velocity`` gives a rate to a modal coordinate held quasi-static (it has none).
        """
        delta, velocity = initial_increments(self.scene, self.device)
        model = self.device.model
        held = model.quasi_static_velocities
        if np.any(velocity[held]):
            names = [n for n, h, x in zip(model.velocity_names, held, velocity, strict=True) if h and x]
            raise SceneError(
                f"initial.velocity gives {names} a rate, and they are held quasi-static (flexible.quasi_static_above): "
                "they have none; leave them out"
            )
        if not np.any(delta):
            return self.q0.copy(), velocity
        return integrate_configuration(self.plant, self.q0, delta), velocity

    @property
    def hydro(self) -> HydroData:
        """The hydrodynamic database (about the centres of mass)."""
        return self.coupling.hydro

    @property
    def time(self) -> np.ndarray:
        """Times of every step [s]."""
        return np.arange(self.n_steps + 1) * self.dt

    def excitation_at(self, times: np.ndarray) -> np.ndarray:
        """The scene's excitation on the hydrodynamic DOFs at ``times`` (n_t, n_h) [N, N m], ramp included (zero
        in calm water)."""
        if self.excitation is None:
            return np.zeros((np.size(times), len(self.hydro.dofs)))
        return np.ascontiguousarray(self.excitation.force(np.asarray(times, dtype=float)).T)

    @property
    def pto_kinds(self) -> tuple[str, ...]:
        """Per PTO "rotary" (a joint PTO on a revolute joint: torque [N m], stroke [rad]) or "linear"."""
        model = self.device.model
        return tuple(
            "rotary" if isinstance(p, JointPTO) and model.joint(p.joint).kind == "revolute" else "linear"
            for p in self.device.ptos
        )

    @property
    def fingerprint(self) -> str:
        """SHA-256 (32 hex digits) of everything a model of this scene depends on: the scene without its outputs,
        the device spec, the hydrodynamic data, the wave components and the wecss version. Two compilations
        with one fingerprint give the same linear model."""
        cached = self.__dict__.get("_fingerprint")
        if cached is None:
            from .. import __version__

            h = hashlib.sha256()
            scene = self.scene.to_dict()
            scene.pop("outputs")
            h.update(json.dumps(scene, sort_keys=True, default=str).encode())
            h.update(json.dumps(self.device.spec, sort_keys=True, default=str).encode())
            ds = self.hydro.dataset
            for name in sorted(str(v) for v in ds.data_vars):
                h.update(name.encode())
                h.update(np.ascontiguousarray(ds[name].values).tobytes())
            if self.waves is not None:
                h.update(self.waves.omega.tobytes())
                h.update(self.waves.amplitude.tobytes())
            h.update(__version__.encode())
            cached = h.hexdigest()[:32]
            object.__setattr__(self, "_fingerprint", cached)
        return cached


def initial_increments(scene: Scene, device: Device) -> tuple[np.ndarray, np.ndarray]:
    """The scene's ``[initial]`` displacement and velocity as generalised-velocity vectors (nv,).

    Raises
    ------
    SceneError
        For a name that is not one of the device's generalised velocities (the message lists them).
    """
    names = list(device.model.velocity_names)
    out = []
    for label, values in (("displacement", scene.initial.displacement), ("velocity", scene.initial.velocity)):
        vector = np.zeros(len(names))
        for name, value in values.items():
            if name not in names:
                raise SceneError(
                    f"initial.{label}: {name!r} is no generalised coordinate of {device.name}; known: {names}"
                )
            vector[names.index(name)] = float(value)
        out.append(vector)
    return out[0], out[1]


def _device(name: str) -> Device:
    if name.endswith(".toml"):
        if not Path(name).is_file():
            raise SceneError(f"device.name: no device spec at {name!r}")
        return Device.from_spec(name)
    if name not in available_devices():
        raise SceneError(f"device.name: unknown device {name!r}; known: {', '.join(available_devices())}")
    return load_device(name)


def _read_columns(path: str, what: str) -> tuple[np.ndarray, np.ndarray]:
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", UserWarning)  # "input contained no data": said below
            table = np.loadtxt(path, delimiter="," if path.endswith(".csv") else None, ndmin=2)
    except (ValueError, UnicodeDecodeError) as err:
        raise SceneError(f"sea.file {path!r}: cannot read two columns of numbers ({err})") from None
    if table.size == 0:
        raise SceneError(f"sea.file {path!r}: holds no numbers; needs two columns ({what})")
    if table.shape[1] != 2:
        raise SceneError(f"sea.file {path!r}: needs two columns ({what}); found {table.shape[1]}")
    return table[:, 0], table[:, 1]


def _measured(sea: SeaState) -> wv.WaveComponents:
    """The components of the scene's measured elevation record (``sea.file``).

    Raises
    ------
    SceneError
        Naming the file, for records that are not finite, uniformly sampled, at least 4 samples long, or
        that are shorter than the run (their components would repeat the record).
    """
    assert sea.file is not None
    t, eta = _read_columns(sea.file, "time [s], elevation [m]")
    try:
        waves = wv.from_elevation(t, eta, energy_threshold=sea.energy_threshold)
    except ValueError as err:
        raise SceneError(f"sea.file {sea.file!r} (time [s], elevation [m]): {err}") from None
    span = t.size * (t[1] - t[0])  # the record's repeat period
    if sea.duration_s > span * (1 + 1e-9):
        raise SceneError(
            f"sea.file {sea.file!r}: the record spans {span:.6g} s ({t.size} samples every {t[1] - t[0]:.6g} s) but "
            f"sea.duration is {sea.duration_s:.6g} s; a record at least as long as the run is accepted (it is not "
            f"repeated): give sea.duration <= {span:.6g} s or a longer record"
        )
    return waves


def make_waves(scene: Scene, hydro: HydroData) -> tuple[wv.WaveComponents | None, wv.Spectrum | None]:
    """The wave components of the scene's sea state (None in calm water) and its spectrum (None for regular
    waves and measured elevations).

    Raises
    ------
    SceneError
        If the period lies outside the database's frequency range.
    """
    sea = scene.sea
    lo, hi = float(hydro.omega[0]), float(hydro.omega[-1])
    if sea.kind == "calm":
        return None, None
    if sea.period is not None and sea.kind in ("regular", "jonswap", "pierson-moskowitz"):
        omega = 2 * np.pi / sea.period
        if not lo <= omega <= hi:
            raise SceneError(
                f"sea.period {sea.period} s (omega {omega:.4g} rad/s) lies outside the hydrodynamic database's "
                f"{lo:.4g}-{hi:.4g} rad/s (periods {2 * np.pi / hi:.4g}-{2 * np.pi / lo:.4g} s)"
            )
    if sea.kind == "regular":
        return _spread(scene, hydro, wv.regular(sea.height, sea.period, direction=sea.direction)), None  # type: ignore[arg-type]
    if sea.kind == "elevation":
        assert sea.file is not None
        return dataclasses.replace(_measured(sea), direction=sea.direction), None  # travelling along sea.direction
    spectrum: wv.Spectrum
    if sea.kind == "tabulated":
        assert sea.file is not None
        frequencies, values = _read_columns(sea.file, "omega [rad/s], S [m^2 s/rad]")
        spectrum = wv.TabulatedSpectrum(frequencies, values)
    else:
        gamma = 1.0 if sea.kind == "pierson-moskowitz" else sea.gamma
        spectrum = wv.Jonswap(sea.height, sea.period, gamma)  # type: ignore[arg-type]
    d_omega = sea.d_omega if sea.d_omega is not None else 2 * np.pi / sea.duration_s
    waves = wv.irregular(
        spectrum,
        d_omega=d_omega,
        omega_max=hi,
        seed=sea.seed,
        periodic=sea.periodic,
        energy_threshold=sea.energy_threshold,
        direction=sea.direction,
    )
    return _spread(scene, hydro, waves), spectrum


def _spread(scene: Scene, hydro: HydroData, waves: wv.WaveComponents) -> wv.WaveComponents:
    """The scene's waves spread over the database's headings by ``sea.spreading`` (unchanged without one).

    Raises
    ------
    SceneError
        Naming ``sea.spreading``, the database and its headings, when the database has one heading or when the
        spreading reaches directions its headings do not cover; for the terms that take one direction of waves
        (body-exact Froude-Krylov, drag with the waves' kinematics).
    """
    sea = scene.sea
    if sea.spreading is None:
        return waves
    database = (
        f"database {scene.device.hydro!r} (device.hydro)"
        if scene.device.hydro
        else f"database of device {scene.device.name!r}"
    )
    headings = np.asarray(hydro.dataset.wave_direction.values, dtype=float)
    listed = f"{np.rad2deg(headings).round(6).tolist()} degrees"
    if np.unique(np.round(np.mod(headings, 2 * np.pi), 9)).size < 2:
        raise SceneError(
            f"sea.spreading {dict(sea.spreading)} needs a database with several wave headings; the {database} has "
            f"one ({listed}): leave sea.spreading out (a long-crested sea along sea.direction) or give "
            "a database computed for several headings (device.hydro)"
        )
    hydrodynamics = scene.hydrodynamics
    for asked, field_name in (
        (hydrodynamics.froude_krylov == "body-exact", 'hydrodynamics.froude_krylov = "body-exact"'),
        (hydrodynamics.drag, "hydrodynamics.drag = true"),
    ):
        if asked:
            raise SceneError(
                f"sea.spreading with {field_name}: these terms take the incident wave of one direction of "
                "propagation; leave sea.spreading out or use the linear hydrodynamics alone"
            )
    exponent = "s" if sea.spreading["type"] == "cos-2s" else "n"
    spreading = wv.Spreading(sea.spreading["type"], sea.spreading[exponent], sea.direction)
    try:
        weights = wv.heading_weights(spreading, headings)
    except ValueError as err:
        raise SceneError(f"sea.spreading {dict(sea.spreading)} on the {database}: {err}") from None
    return wv.spread(waves, weights, seed=sea.seed, energy_threshold=sea.energy_threshold)


def make_radiation(
    radiation: Radiation, coupling: HydroCoupling, dt: float, fit: RadiationFit | None = None
) -> tuple[RadiationArrays, RadiationSummary, RadiationFit | None]:
    """The radiation memory arrays of the ``radiation`` settings for the step ``dt`` [s] on the database of
    ``coupling``, and the state-space fit they were made from (None for the other methods). ``fit``: the
    state-space fit of these settings when the caller has it (:func:`make_fit`; it does not depend on the step),
    else it is made (or read from the disk cache) here."""
    from ..radiation import impulse_response

    kind = RadiationKind.from_method(radiation.method)
    n_h = len(coupling.hydro.dofs)
    if kind == RadiationKind.NONE:
        return (*no_radiation(n_h), None)
    if kind == RadiationKind.CONVOLUTION:
        arrays, summary = from_impulse_response(
            impulse_response(coupling.hydro), dt, coupling_threshold=radiation.coupling_threshold
        )
        return arrays, summary, None
    fit = fit if fit is not None else make_fit(radiation, coupling)
    return (*from_state_space(fit.model, dt), fit)


def make_fit(radiation: Radiation, coupling: HydroCoupling) -> RadiationFit:
    """The state-space fit of the ``radiation`` settings on the database of ``coupling`` (from the disk cache of
    fits when it holds it)."""
    from ..radiation import fit_radiation

    settings, band = fit_request(radiation, coupling.hydro)
    return fit_radiation(coupling.hydro, settings, cache=True, band=band)


MIN_STEPS_PER_PERIOD: int = 4
"""Fewest solver steps per period of the shortest wave component a scene may ask for (fewer do not resolve it)."""

GOOD_STEPS_PER_PERIOD: int = 20
"""Fewer solver steps than this per period of the shortest wave component are allowed but noted in the result."""


def check_step(dt: float, waves: wv.WaveComponents) -> list[str]:
    """Notes on the step ``dt`` [s] against the shortest wave component (empty when it is fine).

    Raises
    ------
    SceneError
        For fewer than MIN_STEPS_PER_PERIOD steps per period of the shortest component.
    """
    shortest = 2 * np.pi / float(np.max(waves.omega))
    steps = shortest / dt
    if steps < MIN_STEPS_PER_PERIOD:
        raise SceneError(
            f"solver.dt ({dt:.4g} s) gives {steps:.3g} steps per period of the shortest wave component "
            f"({shortest:.4g} s); at least {MIN_STEPS_PER_PERIOD} are needed ({GOOD_STEPS_PER_PERIOD} or more "
            "recommended): give a smaller solver.dt, such as 'Tp/200'"
        )
    if steps < GOOD_STEPS_PER_PERIOD:
        return [
            f"solver.dt ({dt:.4g} s) resolves the shortest wave component ({shortest:.4g} s) with {steps:.3g} steps "
            f"per period; {GOOD_STEPS_PER_PERIOD} or more are recommended"
        ]
    return []


def fit_request(radiation: Radiation, hydro: HydroData) -> tuple[FitSettings, tuple[float, float] | None]:
    """The fit settings (with the coupling threshold) and band [rad/s] the ``radiation`` settings of a scene ask
    for on the database ``hydro``."""
    top = float(hydro.omega[-1])
    band = (radiation.band * top, top) if radiation.band > 0 else None
    settings = FitSettings(method=radiation.fit, coupling_threshold=radiation.coupling_threshold)  # type: ignore[arg-type]
    return settings, band


def _added_mass_correction(
    hydro: HydroData, radiation: RadiationArrays, dt: float, waves: wv.WaveComponents
) -> np.ndarray | None:
    inside = (waves.omega >= hydro.omega[0]) & (waves.omega <= hydro.omega[-1])
    if not inside.any():
        return None
    ds = hydro.dataset
    return added_mass_correction(
        radiation, dt, hydro.omega, ds.added_mass.values, ds.added_mass_inf.values,
        waves.omega[inside], np.abs(waves.amplitude[inside]) ** 2,
    )  # fmt: skip


PARTS_CACHE_SIZE: int = 8
"""Devices (with their hydrodynamic coupling and equilibrium) and radiation memories kept in memory per process by
:func:`compile_plant`, so that the cases of a sweep that change only the sea state, the controller or the outputs
build them once per worker."""


FileStamp = tuple[str, int, int]
"""A file's resolved path, modification time [ns] and size [bytes]."""


def _stamp(path: Path) -> FileStamp:
    stat = path.stat()
    return str(path.resolve()), stat.st_mtime_ns, stat.st_size


def _device_sources(name: str, hydro: str | None) -> tuple[FileStamp, ...]:
    """Stamps of the user's files a device's cached parts are read from (:func:`device_inputs`). A changed, moved or
    replaced file changes the key, so the cache builds the parts again."""
    return tuple(_stamp(f) for f in device_inputs(name, hydro).values())


@functools.lru_cache(maxsize=PARTS_CACHE_SIZE)
def _device_parts(
    name: str, hydro: str | None, sources: tuple[FileStamp, ...], body_to_body: bool = True
) -> tuple[Device, HydroCoupling, StaticModel, np.ndarray, np.ndarray]:
    """The device, its coupling to the database (without the radiation between bodies unless ``body_to_body``),
    its statics, equilibrium and static stiffness (cached, keyed also by the stamps of the files read, ``sources``;
    the arrays are read-only)."""
    try:  # elastic bodies' modes in the model (a wetted elastic body is refused)
        device = _device(name).with_elastic_model()
    except ValueError as err:
        raise SceneError(str(err)) from None
    if device.model.nv == 0:
        raise SceneError(
            f"device {device.name!r} has no degree of freedom (joints: "
            f"{', '.join(f'{j.name} {j.kind}' for j in device.model.joints) or 'none'}); a run needs at least one "
            "joint that moves: planar or free to the ground, revolute or prismatic between bodies"
        )
    try:
        database = device.hydro(hydro)
    except FileNotFoundError as err:
        raise SceneError(f"device.hydro: {err}") from None
    coupling = device.coupling(database if body_to_body else without_body_interactions(database))
    try:
        check_against_database(device.name, list(device.model.bodies), database)
    except DeviceSpecError as err:
        raise SceneError(str(err)) from None
    statics = StaticModel(device.model, coupling.hydro.g, coupling, device.ptos)
    q0 = statics.equilibrium()
    stiffness = statics.stiffness(q0)
    q0.flags.writeable = False
    stiffness.flags.writeable = False
    return device, coupling, statics, q0, stiffness


@functools.lru_cache(maxsize=PARTS_CACHE_SIZE)
def _radiation_fit(name: str, hydro: str | None, sources: tuple[FileStamp, ...], radiation: Radiation) -> RadiationFit:
    """The state-space fit of a device's radiation memory, for every step (cached, keyed as :func:`_device_parts`):
    a sweep over periods changes the step with the period (dt = Tp/200) and discretises this one fit again, without
    reading it from the disk cache and decomposing it into modes again."""
    coupling = _device_parts(name, hydro, sources, radiation.body_to_body)[1]
    return make_fit(radiation, coupling)


@functools.lru_cache(maxsize=PARTS_CACHE_SIZE)
def _radiation_parts(
    name: str, hydro: str | None, sources: tuple[FileStamp, ...], radiation: Radiation, dt: float
) -> tuple[RadiationArrays, RadiationSummary, RadiationFit | None]:
    """The radiation memory of a device for a step (cached, keyed as :func:`_device_parts`)."""
    coupling = _device_parts(name, hydro, sources, radiation.body_to_body)[1]
    fit = None
    if RadiationKind.from_method(radiation.method) == RadiationKind.STATE_SPACE:
        fit = _radiation_fit(name, hydro, sources, radiation)
    return make_radiation(radiation, coupling, dt, fit)


def clear_compile_cache() -> None:
    """Forget the devices, radiation fits and radiation memories :func:`compile_plant` keeps in memory."""
    _device_parts.cache_clear()
    _radiation_fit.cache_clear()
    _radiation_parts.cache_clear()


def compile_plant(scene: Scene) -> CompiledScene:
    """Build everything the time loop needs from ``scene`` but the controller: the plant without PTO gains (an open
    plant, the PTO forces its inputs). ``wecss.control.compile_scene`` attaches the scene's controller;
    ``wecss.linear.linearize`` of the result is the open plant's linear model (``docs/control_design.md``).

    Devices, radiation fits and radiation memories are kept in memory between calls (:func:`clear_compile_cache`),
    so compiling the same device again in another sea state or with another step costs little.

    Parameters
    ----------
    scene : Scene
        Any scene; its ``controller`` section is not read (nor the device's default PTO damping, which is the
        ``damping`` controller's default). Its step must be chosen: a scene with ``solver.tolerance`` is compiled
        after ``wecss.sim.choose_step``.

    Returns
    -------
    CompiledScene
        ``device`` (bodies, joints, ``ptos``), ``coupling`` (the hydrodynamic database about the bodies' centres of
        mass), ``plant`` (the arrays of the time loop, ``pto_damping`` and ``pto_stiffness`` zero), ``q0`` (the
        static equilibrium [m, rad]), ``stiffness`` (the static stiffness there [SI per generalised coordinate]),
        ``waves``, ``spectrum`` and ``excitation`` of the sea state (None in calm water), the radiation memory
        and its fit, ``dt`` [s], ``n_steps`` and ``notes`` (what was dropped or assumed).

    Raises
    ------
    TypeError
        If ``scene`` is not a :class:`~wecss.scene.Scene`.
    SceneError
        On unknown names, missing files, periods outside the database, a step not yet chosen.
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"compile_plant takes a wecss.scene.Scene; got {type(scene).__name__}")
    name, hydro_name = scene.device.name, scene.device.hydro
    sources = _device_sources(name, hydro_name)
    body_to_body = scene.radiation.body_to_body
    device, coupling, statics, q0, static_stiffness = _device_parts(name, hydro_name, sources, body_to_body)
    notes: list[str] = []
    if not body_to_body:
        notes.append("radiation between bodies left out (radiation.body_to_body = false)")
    hydro = coupling.hydro
    dt = scene.dt
    waves, spectrum = make_waves(scene, hydro)
    excitation = None
    if waves is not None:
        notes.extend(check_step(dt, waves))
        if waves.dropped is not None and waves.dropped.count:
            notes.append(f"wave components: {waves.dropped}")
        ramp = wv.Ramp(scene.sea.ramp_s) if scene.sea.ramp_s > 0 else None
        try:
            excitation = wv.excitation_model(hydro, waves, ramp=ramp)
        except ValueError as err:  # a direction or frequencies the database does not have
            raise SceneError(
                f"sea (kind {scene.sea.kind!r}, direction {scene.sea.direction!r} rad) on the database of device "
                f"{name!r}" + (f" (device.hydro {hydro_name!r})" if hydro_name else "") + f": {err}"
            ) from None
        if excitation.outside_share > 0:
            notes.append(
                "wave components outside the database's frequencies left out: "
                f"{excitation.outside_share:.2e} of the variance"
            )
    runner = scene.runner
    if runner.capabilities.memory_model:
        radiation, summary, fit = _radiation_parts(name, hydro_name, sources, scene.radiation, dt)
    else:
        radiation, summary = no_radiation(len(hydro.dofs))
        fit = None
        notes.append(  # a runner without a memory model works in the frequency domain
            "radiation memory not used: the frequency-domain solution takes A(omega) and B(omega) from the database"
        )
    correction = None
    if waves is not None and radiation.kind != RadiationKind.NONE and scene.radiation.consistent_added_mass:
        correction = _added_mass_correction(hydro, radiation, dt, waves)
        if correction is not None:
            a_inf = np.abs(np.diag(hydro.dataset.added_mass_inf.values))
            change = np.max(np.abs(np.diag(correction)) / np.where(a_inf > 0, a_inf, np.inf))
            notes.append(
                "A_inf adjusted so that the memory model reproduces the database's A(omega) over the sea state's "
                f"frequencies: largest change {change:.2%} of a diagonal A_inf"
            )
    viscous, extra_mass = _viscous_terms(scene, device, q0, waves, hydro, notes)
    pressure = _pressure_terms(scene, device, coupling, q0, waves, notes)
    plant = build_plant(
        device.model,
        coupling,
        device.ptos,
        hydro.g,
        added_mass_correction=correction,
        viscous=viscous,
        pressure=pressure,
        extra_mass=extra_mass,
    )
    if summary.dropped_entries:
        notes.append(
            f"radiation couplings below {scene.radiation.coupling_threshold:g} of sqrt(peak_ii peak_jj) "
            f"dropped: {len(summary.dropped_entries)} of {len(hydro.dofs) ** 2}"
        )
    model = device.model
    bounded = [
        model.coordinate_names.index(f"{j.name}__{j.labels[0]}") for j in model.ordered_joints if j.kind == "revolute"
    ]
    compiled = CompiledScene(
        scene=scene,
        device=device,
        coupling=coupling,
        plant=plant,
        radiation=radiation,
        radiation_summary=summary,
        radiation_fit=fit,
        waves=waves,
        spectrum=spectrum,
        excitation=excitation,
        linear_controller=False,
        statics=statics,
        q0=q0.copy(),
        stiffness=static_stiffness.copy(),
        dt=dt,
        n_steps=scene.n_steps,
        bounded=np.asarray(bounded, dtype=np.int64),
        notes=notes,
    )
    initial_increments(scene, device)  # names checked before the run
    runner.check_compiled(compiled)
    return compiled


def _viscous_terms(
    scene: Scene, device: Device, q0: np.ndarray, waves: wv.WaveComponents | None, hydro: HydroData, notes: list[str]
) -> tuple[ViscousArrays, np.ndarray | None]:
    """The scene's viscous terms (``hydrodynamics.drag``) and the Morison elements' added mass, with a note."""
    hydrodynamics = scene.hydrodynamics
    if not hydrodynamics.drag:
        return viscous_arrays(device, q0, hydrodynamics, no_waves(), hydro.rho)
    ramp = wv.Ramp(scene.sea.ramp_s) if scene.sea.ramp_s > 0 else None
    wave = wave_arrays(waves, hydro.water_depth, hydro.g, ramp)
    try:
        viscous, extra_mass = viscous_arrays(device, q0, hydrodynamics, wave, hydro.rho)
    except ValueError as err:
        raise SceneError(str(err)) from None
    velocity = "relative to the undisturbed fluid" if hydrodynamics.relative_drag else "on the bodies' own velocity"
    notes.append(
        f"viscous forces on ({len(device.drag)} body drag entries, {len(device.morison)} Morison elements), "
        f"{velocity}; Morison added mass taken at the equilibrium immersion"
    )
    return viscous, extra_mass


def _pressure_terms(
    scene: Scene,
    device: Device,
    coupling: HydroCoupling,
    q0: np.ndarray,
    waves: wv.WaveComponents | None,
    notes: list[str],
) -> PressureArrays:
    """The scene's body-exact pressure forces (``hydrodynamics.hydrostatics`` / ``froude_krylov``), with notes."""
    hydrodynamics = scene.hydrodynamics
    if not hydrodynamics.body_exact:
        return pressure_arrays(device, coupling, q0, hydrodynamics, None, None, notes)
    ramp = wv.Ramp(scene.sea.ramp_s) if scene.sea.ramp_s > 0 else None
    try:
        pressure = pressure_arrays(device, coupling, q0, hydrodynamics, waves, ramp, notes)
    except (ValueError, KeyError) as err:
        raise SceneError(f"hydrodynamics: {err}") from None
    forces = " and ".join(
        name for name, on in (("hydrostatics", hydrodynamics.hydrostatics == "body-exact"),
                              ("Froude-Krylov force", hydrodynamics.froude_krylov == "body-exact")) if on
    )  # fmt: skip
    surface = "the incident wave's surface" if pressure.settings[0] == 1 else "the still water level"
    notes.append(
        f"body-exact {forces} on {pressure.owner.size} meshes ({pressure.mesh.faces.shape[0]} triangles), clipped at "
        f"{surface}, {hydrodynamics.form} formulation"
    )
    return pressure


def with_linear_gains(compiled: CompiledScene, damping: Any, stiffness: Any) -> CompiledScene:
    """``compiled`` with a linear PTO controller f = -c x_dot - k x (``wecss.compiled.pto_control_force``; one gain
    per PTO, or one for all) [SI] in its equations of motion: the plant's gains set, and, for a stiffness, the
    statics, equilibrium and static stiffness with it (the controller's stiffness acts about the same rest stroke as
    the device springs).

    Raises
    ------
    ValueError
        If the gains are not finite, a damping is negative, or they are neither one nor one per PTO.
    """
    damping, stiffness = pto_gains(damping, stiffness, compiled.plant.pto_kind.size)
    plant = compiled.plant._replace(pto_damping=damping.copy(), pto_stiffness=stiffness.copy())
    out = dataclasses.replace(compiled, plant=plant, linear_controller=True)
    if np.any(stiffness != 0):
        ptos = compiled.device.ptos
        springs = tuple(
            dataclasses.replace(pto, stiffness=pto.stiffness + float(k)) for pto, k in zip(ptos, stiffness, strict=True)
        )
        statics = StaticModel(compiled.device.model, compiled.hydro.g, compiled.coupling, springs)
        q0 = statics.equilibrium()
        out = dataclasses.replace(out, statics=statics, q0=q0, stiffness=statics.stiffness(q0))
    return out
