"""Validity guards of a run, with stated thresholds: the step against the fastest mode of the plant with its PTO
gains (RK4 refused outside its stability region, see ``_rk4_check``; a coarse step noted), the sea's steepness and
height against the bodies' size, the bodies' motion amplitudes against their size and a drift of unrestrained bodies
(notes in the result).

The body size is the cube root of its displaced volume V^(1/3) [m] (from the hydrodynamic database). Linear
hydrodynamics (the database's coefficients, computed for small motions about the equilibrium) lose accuracy for
steep waves and motions comparable to the bodies' size; the guards say so in the result's notes but do not stop a
run, which stays a valid solution of the equations it integrates.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from ..compiled import DRY, OUTSIDE_TABLE, SUBMERGED, CompiledScene
from ..compiled.kernels import poses
from ..linear import cartesian_mass, equilibrium_maps
from ..scene import EXPLICIT_RUNNER, SceneError
from ..waves import wavenumber
from ._drift import DRIFT_LIMIT as DRIFT_LIMIT
from ._drift import DriftCheck, drift_note
from ._rk4_check import check_rk4 as check_rk4_region

#: Fewer steps than this per period 2 pi / |s| of the fastest mode are noted (an accurate step resolves it).
GOOD_STEPS_PER_MODE = 20
#: Significant wave height over the deep-water wavelength at the peak period above which a note is written
#: (linear wave theory is a good model for Hs / lambda_p below about 1/25; waves break near 1/7).
STEEPNESS_LIMIT = 1 / 25
#: Wave height Hs above this multiple of the smallest body's size V^(1/3) is noted.
HEIGHT_LIMIT = 1.0
#: A body's largest vertical displacement from its equilibrium above this multiple of its size V^(1/3) is noted.
TRANSLATION_LIMIT = 0.5
#: A body's largest rotation from its equilibrium above this angle [rad] (20 degrees) is noted.
ROTATION_LIMIT = float(np.deg2rad(20.0))


def _modes(compiled: CompiledScene, damped: bool = True, pto_springs: bool = True) -> tuple[np.ndarray, np.ndarray]:
    """Eigenvalues s and eigenvectors (velocity part first) of the plant linearised about its equilibrium with the
    PTO gains in its equations (mass with A_inf, static stiffness, PTO damping and stiffness; radiation memory left
    out); without ``damped``, of the undamped plant: s = i omega; without ``pto_springs``, the PTO stiffness taken
    out of the static stiffness (at the same equilibrium)."""
    p = compiled.plant
    b, _, g, _ = equilibrium_maps(compiled)
    mass = b.T @ cartesian_mass(compiled, compiled.q0) @ b
    damping = g.T @ np.diag(p.pto_damping) @ g if damped else np.zeros_like(mass)
    stiffness = compiled.stiffness if pto_springs else compiled.stiffness - g.T @ np.diag(p.pto_stiffness) @ g
    nv = mass.shape[0]
    a = np.zeros((2 * nv, 2 * nv))
    a[:nv, nv:] = np.eye(nv)
    a[nv:, :nv] = -np.linalg.solve(mass, stiffness)
    a[nv:, nv:] = -np.linalg.solve(mass, damping)
    return np.linalg.eig(a)


def fastest_mode(compiled: CompiledScene, damped: bool = True, pto_springs: bool = True) -> float:
    """|s| [rad/s] of the fastest mode of the plant linearised about its equilibrium with the PTO gains in its
    equations (mass with A_inf, static stiffness, PTO damping and stiffness; radiation memory left out); without
    ``damped``: the largest undamped natural frequency; without ``pto_springs``: that of the plant without its PTO
    springs (its hydrostatics, moorings and joints)."""
    eig, _ = _modes(compiled, damped, pto_springs)
    return float(np.max(np.abs(eig))) if eig.size else 0.0


def elastic_cause(compiled: CompiledScene, damped: bool = True) -> str:
    """A sentence naming the elastic bodies when the plant's fastest mode (``damped`` as :func:`fastest_mode`) is
    mostly their modal coordinates (its displacement's share on them above one half), else empty."""
    model = compiled.device.model
    if not model.elastic_bodies:
        return ""
    eig, vectors = _modes(compiled, damped)
    k = int(np.argmax(np.abs(eig)))
    nv = model.nv
    shape = np.abs(vectors[:nv, k]) ** 2
    modal = np.zeros(nv, dtype=bool)
    names = []
    for i in model.elastic_bodies:
        modal[model.mode_velocity_start[i] : model.mode_velocity_start[i + 1]] = True
        names.append(model.bodies[i].name)
    if shape[modal].sum() <= 0.5 * shape.sum():
        return ""
    return (
        f"the elastic modes of {names} set it (the fastest, |s| = {abs(eig[k]):.4g} rad/s, is their modal "
        "coordinates'): give solver.dt at most the limit, use solver.method 'generalized-alpha' (implicit), or run "
        "them rigid (flexible.dynamics = 'frozen')"
    )


#: Beeman's position step is explicit: an undamped mode of omega dt above 2 grows (its stability limit, that of the
#: Stormer-Verlet scheme; damping acts through its implicit corrector, with the trapezoidal rule where that fails);
#: elastic modes are refused above this, with the margin of RK4's check.
BEEMAN_ELASTIC_LIMIT = 2.0 / 1.1


def check_beeman_elastic(compiled: CompiledScene) -> None:
    """Refuse Beeman's explicit position step when an elastic body's modes set the plant's largest undamped
    natural frequency beyond :data:`BEEMAN_ELASTIC_LIMIT` / dt (a rigid plant is not checked: its stiff PTO steps
    fall back on the trapezoidal rule).

    Raises
    ------
    SceneError
        Giving the largest stable step and the elastic bodies.
    """
    if not compiled.device.model.elastic_bodies:
        return
    rate = fastest_mode(compiled, damped=False)
    limit = BEEMAN_ELASTIC_LIMIT / rate if rate > 0 else np.inf
    cause = elastic_cause(compiled, damped=False)
    if compiled.dt > limit and cause:
        raise SceneError(
            f"Beeman's explicit position step is unstable for this plant: its fastest undamped mode needs dt <= "
            f"{limit:.3g} s (given {compiled.dt:.3g} s, with a margin of 1.1); {cause}"
        )


def beeman_step_limit(compiled: CompiledScene) -> tuple[float, float]:
    """(the largest step [s] Beeman's explicit position step takes stably, the plant's fastest undamped natural
    frequency omega [rad/s] that sets it): BEEMAN_ELASTIC_LIMIT / omega, omega of the plant without its PTO springs
    (hydrostatics, moorings, joints; a stiff PTO's steps fall back on the trapezoidal rule); inf without one."""
    rate = fastest_mode(compiled, damped=False, pto_springs=False)
    return (BEEMAN_ELASTIC_LIMIT / rate if rate > 0 else float("inf")), rate


def check_beeman_step(compiled: CompiledScene) -> None:
    """Refuse a step beyond Beeman's stability limit for the rigid plant's fastest undamped natural frequency
    (:func:`beeman_step_limit`), before the run: such a run (the M4 at dt = T/5: omega dt = 1.95) grows until a
    bound stops it late, as a drift or a divergence blamed on other causes.

    Raises
    ------
    SceneError
        Naming solver.dt, the limit and the frequency.
    """
    limit, rate = beeman_step_limit(compiled)
    if compiled.dt > limit:
        raise SceneError(
            f"solver.dt = {compiled.dt:.4g} s is beyond the stability limit of Beeman's explicit position step for "
            f"this plant: its fastest undamped natural frequency is {rate:.4g} rad/s (period {2 * np.pi / rate:.4g} "
            f"s), so dt <= {BEEMAN_ELASTIC_LIMIT:.3g} / omega = {limit:.4g} s (omega dt <= 2, with a margin of 1.1); "
            "give a smaller solver.dt (such as 'Tp/200') or solver.tolerance"
        )


def _gains(compiled: CompiledScene) -> str:
    p = compiled.plant
    parts = [
        f"{pto.name}: damping {c:.4g}, stiffness {k:.4g}"
        for pto, c, k in zip(compiled.device.ptos, p.pto_damping, p.pto_stiffness, strict=True)
        if c != 0 or k != 0
    ]
    return "; ".join(parts)


def check_rk4(compiled: CompiledScene) -> None:
    """Refuse RK4 when the step passes its stability limit for the plant over the configurations the run may
    reach (see ``_rk4_check``).

    Raises
    ------
    SceneError
        Naming the PTO gains when there are any.
    """
    check_rk4_region(compiled, _gains(compiled), elastic_cause(compiled))


def stiff_pto_hint(compiled: CompiledScene) -> str:
    """A sentence for a divergence message: the elastic bodies, or the PTO gains, when the fastest mode they give
    is coarsely stepped, else the step and the device."""
    gains = _gains(compiled)
    rate = fastest_mode(compiled)
    steps = 2 * np.pi / (rate * compiled.dt) if rate > 0 else np.inf
    undamped = fastest_mode(compiled, damped=False)
    if undamped * compiled.dt > BEEMAN_ELASTIC_LIMIT and compiled.scene.runner.name in ("beeman", EXPLICIT_RUNNER):
        return (
            f" solver.dt = {compiled.dt:.4g} s is beyond the stability limit of Beeman's explicit position step for "
            f"the plant's fastest undamped mode with its PTO springs ({undamped:.4g} rad/s: dt <= "
            f"{BEEMAN_ELASTIC_LIMIT / undamped:.4g} s): give a smaller solver.dt"
            + (f" or softer PTO springs ({gains})" if gains else "")
            + "."
        )
    if steps < GOOD_STEPS_PER_MODE and elastic_cause(compiled):
        return (
            f" The elastic bodies {list(compiled.device.elastic_bodies)} set the fastest mode (|s| = {rate:.4g} "
            "rad/s): with an explicit runner give a smaller solver.dt; with generalized-alpha, a motion far from the "
            "equilibrium (where its iteration matrix's damping and stiffness come from) may need a smaller solver.dt."
        )
    if gains and steps < GOOD_STEPS_PER_MODE:
        return (
            f" A stiff PTO is the likely cause: with the PTO gains ({gains} [SI]) the fastest mode |s| = {rate:.4g} "
            f"rad/s has {steps:.3g} steps per period; reduce the PTO gain or give solver.dt below "
            f"{2 * np.pi / (GOOD_STEPS_PER_MODE * rate):.3g} s."
        )
    if not compiled.linear_controller and compiled.device.ptos:
        return (
            " A stiff controller (large gains on the PTO velocity or stroke) is a likely cause: reduce its gains, "
            "or try a smaller solver.dt or check the device."
        )
    return " Try a smaller solver.dt or check the device and controller."


def step_notes(compiled: CompiledScene) -> list[str]:
    """A note when the step resolves the fastest mode (PTO gains included) with fewer than GOOD_STEPS_PER_MODE
    steps per period (with generalised-alpha and elastic bodies' modes the fastest: that the scheme damps them)."""
    rate = fastest_mode(compiled)
    if rate <= 0:
        return []
    steps = 2 * np.pi / (rate * compiled.dt)
    if steps >= GOOD_STEPS_PER_MODE:
        return []
    if elastic_cause(compiled) and compiled.scene.runner.name == "generalized-alpha":
        return [
            f"solver.dt ({compiled.dt:.4g} s) does not resolve the elastic bodies' fastest modes (|s| up to "
            f"{rate:.4g} rad/s, {steps:.3g} steps per period): generalised-alpha damps the modes far above 1/dt "
            "(their quasi-static response is kept, their vibration is not); a mode the results should carry "
            f"needs {GOOD_STEPS_PER_MODE} or more steps per period"
        ]
    return [
        f"solver.dt ({compiled.dt:.4g} s) resolves the fastest mode of the plant with its PTO gains (|s| = "
        f"{rate:.4g} rad/s) with {steps:.3g} steps per period; {GOOD_STEPS_PER_MODE} or more are recommended"
    ]


def body_sizes(compiled: CompiledScene) -> dict[str, float]:
    """Body name -> V^(1/3) [m] for the bodies the database has a positive displaced volume for."""
    ds = compiled.hydro.dataset
    if "displaced_volume" not in ds or "body" not in ds.displaced_volume.dims:
        return {}
    names = [str(b) for b in ds.displaced_volume["body"].values]
    return {n: float(v) ** (1 / 3) for n, v in zip(names, ds.displaced_volume.values, strict=True) if v > 0}


def wave_notes(compiled: CompiledScene) -> list[str]:
    """Notes on the sea's steepness H / lambda (H or Hs [m] and the wavelength at the period or peak period, at
    the database's depth) and its height against the smallest body."""
    waves, sea = compiled.waves, compiled.scene.sea
    if sea.kind == "calm":
        return calm_notes(compiled)
    if waves is None or not waves.omega.size:
        return []
    # the height the user gave (H of a regular wave, Hs of a spectrum), else that of the simulated components
    given = sea.kind in ("regular", "jonswap", "pierson-moskowitz")
    hs = float(sea.height) if given else 4 * float(np.sqrt(np.sum(np.abs(waves.amplitude) ** 2) / 2))
    notes = []
    if sea.period is not None and sea.period > 0:
        k = float(wavenumber(np.array([2 * np.pi / sea.period]), compiled.hydro.water_depth, compiled.hydro.g)[0])
        steepness = hs * k / (2 * np.pi)
        if steepness > STEEPNESS_LIMIT:
            notes.append(
                f"steep sea: height / wavelength at the (peak) period = {steepness:.3g} (above "
                f"{STEEPNESS_LIMIT:.3g}); linear wave theory and linear hydrodynamics lose accuracy"
            )
    sizes = body_sizes(compiled)
    if sizes:
        name, size = min(sizes.items(), key=lambda item: item[1])
        if hs > HEIGHT_LIMIT * size:
            notes.append(
                f"wave height {hs:.3g} m exceeds {HEIGHT_LIMIT:g} x the size V^(1/3) = {size:.3g} m of body "
                f"{name}; linear hydrodynamics lose accuracy"
            )
    return notes


BREAKING_STEEPNESS: float = 1 / 7
"""The largest wave height over wavelength a sea may have (waves break beyond it, Michell's H / lambda = 0.142): a
height or a record above it at its (peak) period is refused, not simulated."""


def check_sea(compiled: CompiledScene) -> None:
    """Refuse, before the run, a sea steeper than waves can be: its height (H of a regular wave, Hs of a spectrum;
    4 sqrt(m0) of a tabulated spectrum or a measured record's components) over the wavelength at its (peak) period
    (a record's: its largest component's) at the database's depth above :data:`BREAKING_STEEPNESS`. Such a sea is
    an input error (Hs 1e6 m; Hs 2.0 meant as 2 cm; a record in cm), which would otherwise end late as a "drift".

    Raises
    ------
    SceneError
        Naming the field, the value, the wavelength and the largest height accepted.
    """
    waves, sea = compiled.waves, compiled.scene.sea
    if sea.kind == "calm" or waves is None or not waves.omega.size:
        return
    amplitude = np.abs(np.asarray(waves.amplitude))
    given = sea.kind in ("regular", "jonswap", "pierson-moskowitz") and sea.period is not None
    if given:
        height, field = float(sea.height), "sea.height"
        omega = 2 * np.pi / float(sea.period or np.inf)
    else:
        height = 4 * float(np.sqrt(np.sum(amplitude**2) / 2))
        field = f"the {sea.kind} sea's significant height 4 sqrt(m0)" + (
            f" (sea.file {sea.file!r})" if sea.file else ""
        )
        frequencies = np.asarray(waves.omega).ravel()
        energy = amplitude**2
        if energy.size != frequencies.size:  # components spread over directions too: the energy per frequency
            if energy.size % frequencies.size:
                return
            energy = energy.reshape(-1, frequencies.size).sum(axis=0)
        omega = float(frequencies[int(np.argmax(energy.ravel()))])
    if not omega > 0:
        return
    k = float(wavenumber(np.array([omega]), compiled.hydro.water_depth, compiled.hydro.g)[0])
    wavelength = 2 * np.pi / k
    water = float(compiled.hydro.water_depth)
    depth = f"depth {water:.4g} m" if np.isfinite(water) else "deep water"
    if height > BREAKING_STEEPNESS * wavelength:
        hint = "a record in cm or mm instead of m?" if not given else "a height in the wrong unit? 2 cm is 0.02"
        raise SceneError(
            f"{field} = {height:.4g} m is {height / wavelength:.3g} times the wavelength {wavelength:.4g} m at the "
            f"(peak) period {2 * np.pi / omega:.4g} s ({depth}); accepted: at most "
            f"1/7 of it, {BREAKING_STEEPNESS * wavelength:.4g} m (waves break beyond H / lambda = 1/7): {hint}"
        )


def calm_notes(compiled: CompiledScene) -> list[str]:
    """A note when a calm sea's times are given relative to a period it does not have (``sea.duration = "20 Tp"``:
    resolved with ``sea.period``, the default 1.2 s unless given)."""
    scene = compiled.scene
    relative = [
        f"{name} = {value!r}"
        for name, value in (("sea.duration", scene.sea.duration), ("sea.ramp", scene.sea.ramp))
        if isinstance(value, str)
    ]
    if not relative:
        return []
    return [
        f"calm sea: {', '.join(relative)} resolved with sea.period = {scene.sea.period!r} s though a calm sea has no "
        "period; give seconds"
    ]


def pressure_notes(compiled: CompiledScene, flags: np.ndarray | None) -> list[str]:
    """Notes on what the body-exact forces met during a run (``flags``: per body, ORed over the run): a body out of
    the water, a body wholly under it (its top or deck submerged), points outside the incident field's table."""
    if flags is None or not np.any(flags):
        return []
    names = list(compiled.device.model.body_names)
    notes = []
    for bit, what in (
        (DRY, "left the water entirely at some instant (no pressure force then)"),
        (SUBMERGED, "went wholly under the incident surface at some instant (its top or deck submerged)"),
    ):
        which = [names[i] for i in np.flatnonzero(flags & bit)]
        if which:
            notes.append(f"body-exact hydrodynamics: {', '.join(which)} {what}")
    if np.any(flags & OUTSIDE_TABLE):
        notes.append(
            "body-exact hydrodynamics: points of the meshes left the incident field's table (evaluated by direct sums "
            "there: exact but slower); the motion reached beyond the regions the table was built for"
        )
    return notes


POSE_BLOCK: int = 100_000
"""Configurations per block when the notes evaluate the poses of a record."""


def motion_notes(
    compiled: CompiledScene,
    q: np.ndarray,
    known: tuple[np.ndarray, np.ndarray] | None = None,
    check: DriftCheck | None = None,
) -> list[str]:
    """Notes on the saved configurations ``q`` (n_t, nq): motion amplitudes against the bodies' size and a drift
    of the horizontal mean position. ``known``: the poses of ``q`` (positions, rotation vectors) when the caller
    has them already (else they are computed here, in blocks: a long record's poses would double its memory);
    ``check``: the drift of a re-run at half the step, which splits a drift into its numerical and physical parts
    (:func:`drift_note`)."""
    summary = MotionSummary(compiled, q.shape[0])
    summary.check = check
    for start in range(0, q.shape[0], POSE_BLOCK):
        rows = slice(start, start + POSE_BLOCK)
        summary.add(q[rows], None if known is None else (known[0][rows], known[1][rows]))
    return summary.notes()


class MotionSummary:
    """What :func:`motion_notes` reads of a record, gathered from its rows in order, block by block (a run
    streamed to its file never holds the whole record): the largest rotation and vertical shift of each body from
    its equilibrium, and the sums of its horizontal positions over the first and the last tenth of the
    ``n_rows`` saved rows."""

    def __init__(self, compiled: CompiledScene, n_rows: int) -> None:
        self.compiled, self.n_rows = compiled, n_rows
        self.tenth = max(1, n_rows // 10)
        self.seen = 0
        n_body = len(compiled.device.model.body_names)
        self.rest = poses(compiled.plant, np.ascontiguousarray(compiled.q0[None]))
        self.angle, self.shift = np.zeros(n_body), np.zeros(n_body)
        self.head, self.tail = np.zeros((n_body, 2)), np.zeros((n_body, 2))
        self.check: DriftCheck | None = None  # a re-run at half the step, for the drift note (set by the caller)

    def add(self, q: np.ndarray, known: tuple[np.ndarray, np.ndarray] | None = None) -> None:
        """The next rows ``q`` (k, nq) of the record, with their poses ``known`` when the caller has them."""
        if not q.shape[0]:
            return
        position, rotation = known if known is not None else poses(self.compiled.plant, np.ascontiguousarray(q))
        rest_pos, rest_rot = self.rest
        self.angle = np.maximum(self.angle, np.linalg.norm(rotation - rest_rot, axis=-1).max(axis=0))
        self.shift = np.maximum(self.shift, np.abs(position[..., 2] - rest_pos[..., 2]).max(axis=0))
        index = self.seen + np.arange(q.shape[0])
        self.head += position[index < self.tenth, :, :2].sum(axis=0)
        self.tail += position[index >= self.n_rows - self.tenth, :, :2].sum(axis=0)
        self.seen += q.shape[0]

    def notes(self) -> list[str]:
        """The notes (see :func:`motion_notes`) once every row was added."""
        if self.n_rows < 2:
            return []
        compiled = self.compiled
        names = list(compiled.device.model.body_names)
        sizes = body_sizes(compiled)
        angle, shift = self.angle, self.shift
        notes = []
        big = [f"{n} {np.rad2deg(a):.3g} deg" for n, a in zip(names, angle, strict=True) if a > ROTATION_LIMIT]
        if big:
            notes.append(
                f"large rotations from the equilibrium (above {np.rad2deg(ROTATION_LIMIT):.3g} deg): {', '.join(big)}; "
                "linear hydrodynamics lose accuracy"
            )
        # vertical only: horizontal motion of an unmoored body is mostly drift, noted below
        big = [
            f"{n} {s:.3g} m (size {sizes[n]:.3g} m)"
            for n, s in zip(names, shift, strict=True)
            if n in sizes and s > TRANSLATION_LIMIT * sizes[n]
        ]
        if big:
            notes.append(
                f"large vertical motions from the equilibrium (above {TRANSLATION_LIMIT:g} x the body size V^(1/3)): "
                f"{', '.join(big)}; linear hydrodynamics lose accuracy"
            )
        note = drift_note(names, sizes, self.drift(), self.check)
        return notes + ([note] if note else [])

    def drift(self) -> np.ndarray:
        """(n_body, 2) [m]: the move of each body's horizontal mean position from the first to the last tenth of the
        record, along the directions nothing restores (a mooring or a joint to the ground holds the others)."""
        if self.n_rows < 2:
            return np.zeros_like(self.head)
        return (self.tail - self.head) / self.tenth * unrestrained_directions(self.compiled)


#: Singular values of the static stiffness below this fraction of the largest are free directions.
FREE_DIRECTION_TOL = 1e-9


def unrestrained_directions(compiled: CompiledScene) -> np.ndarray:
    """(n_body, 2): 1.0 where a body's centre of mass can move along world x (column 0) or y (column 1) without a
    restoring force (along a null vector of the static stiffness, moorings and PTO springs included), else 0.0."""
    b, _, _, _ = equilibrium_maps(compiled)
    k = compiled.stiffness
    starts = compiled.plant.cart_start
    n = starts.size
    if k.size == 0:
        return np.zeros((n, 2))
    _, values, vt = np.linalg.svd(k)
    free = vt[values <= FREE_DIRECTION_TOL * max(float(values[0]), 1e-300)]
    motion = b @ free.T  # Cartesian motion along each free direction (n_cart, n_free)
    out = np.zeros((n, 2))
    for i in range(n):
        for axis in range(2):
            out[i, axis] = float(np.any(np.abs(motion[starts[i] + axis]) > 1e-9))
    return out


#: The default translation bound: this multiple of the largest body size V^(1/3).
TRANSLATION_BOUND_SIZES = 100.0


def translation_bound(compiled: CompiledScene) -> float:
    """The scene's ``solver.translation_bound`` [m], or by default TRANSLATION_BOUND_SIZES times the largest body
    size V^(1/3) (inf when the database has no displaced volumes)."""
    given = compiled.scene.solver.translation_bound
    if given is not None:
        return float(given)
    sizes = body_sizes(compiled)
    return TRANSLATION_BOUND_SIZES * max(sizes.values()) if sizes else float("inf")


def farthest_body(compiled: CompiledScene, q: np.ndarray) -> tuple[str, float]:
    """The body whose centre of mass is farthest from its equilibrium position in configuration ``q``, and that
    distance [m]."""
    position, _ = poses(compiled.plant, np.ascontiguousarray(np.stack([compiled.q0, q])))
    shift = np.linalg.norm(position[1] - position[0], axis=-1)
    i = int(np.argmax(shift))
    return str(compiled.device.model.body_names[i]), float(shift[i])


def fit_notes(compiled: CompiledScene) -> list[str]:
    """A note when the scene's state-space radiation fit is not passive or not stable (its report says so)."""
    if compiled.radiation_fit is None:
        return []
    report = compiled.radiation_fit.report.attrs
    margin, stable = float(report["passivity_margin"]), int(report["stable"])
    passive = bool(report.get("passive", margin >= 0))  # fits stored before the passivity enforcement lack it
    notes = []
    if not (passive and stable):
        notes.append(
            f"radiation state-space fit: {'passive' if passive else 'NOT PASSIVE (it can add energy)'}, scaled "
            f"passivity margin {margin:.3g}, {'stable' if stable else 'not stable to the required damping'}; "
            f"repair: {report['repair']}; radiation.method = 'convolution' uses the database's kernel instead"
        )
    miss = _largest_target_miss(compiled.radiation_fit.report)
    if miss is not None and miss[1] > FIT_MISS_FACTOR:
        notes.append(
            f"radiation state-space fit: its {miss[0]} is {miss[1]:.3g} times its target (the fit report's "
            f"largest miss; more than {FIT_MISS_FACTOR:g} x): the memory model is not reliable; "
            "radiation.method = 'convolution' uses the database's kernel instead"
        )
    return notes


FIT_MISS_FACTOR: float = 10.0
"""A state-space fit whose largest error exceeds its target by more than this factor gets a note."""


def _largest_target_miss(report: xr.Dataset) -> tuple[str, float] | None:
    """(which error, error / target) of the fit report's largest miss, None when the report has no errors."""
    attrs = report.attrs
    pairs = [("k0_error", "k0_tol"), ("rms_error", "rms_tol"), ("damping_error", "frequency_tol"),
             ("added_mass_error", "frequency_tol")]  # fmt: skip
    ratios = [
        (name.replace("_", " "), float(np.max(report[name].values)) / float(attrs[tol]))
        for name, tol in pairs
        if name in report.data_vars and tol in attrs and report[name].size
    ]
    return max(ratios, key=lambda r: r[1]) if ratios else None
