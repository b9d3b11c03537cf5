"""What a BEM run solves: axisymmetric floats, frequencies, water and mesh settings (frozen dataclasses)."""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from ...constants import GRAVITY, RHO_WATER, RIGID_BODY_DOFS
from .._schema import DOF_SEPARATOR
from ._mesh import DEFAULT_ASPECT_RATIO
from ._profile import AxisymmetricProfile


@dataclass(frozen=True)
class FloatBody:
    """One axisymmetric float with a vertical axis.

    Parameters
    ----------
    name : str
        Body name (DOFs are named ``<name>__<Dof>``).
    profile : AxisymmetricProfile
        Immersed shape.
    center_of_mass_z : float
        Height of the centre of mass [m] (on the float's axis: a float of revolution floats upright only
        with its centre of mass on the axis).
    inertia : (float, float, float)
        Principal moments of inertia Ixx, Iyy, Izz about the centre of mass [kg m^2], axes along x, y, z.
    position : (float, float)
        Horizontal position (x, y) of the float's axis [m].
    mass : float, optional
        Mass [kg]. Default: rho times the displaced volume of the mesh (the float in equilibrium).
    dofs : tuple of str
        Rigid-body DOFs solved for, among Surge, Sway, Heave, Roll, Pitch, Yaw (stored in that order).

    Raises
    ------
    ValueError
        For an empty name or one containing ``__``, unknown or repeated DOFs, non-positive inertia or
        mass, or non-finite coordinates.
    """

    name: str
    profile: AxisymmetricProfile
    center_of_mass_z: float
    inertia: tuple[float, float, float]
    position: tuple[float, float] = (0.0, 0.0)
    mass: float | None = None
    dofs: tuple[str, ...] = ("Surge", "Heave", "Pitch")

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name or DOF_SEPARATOR in self.name:
            raise ValueError(f"body name must be a non-empty string without {DOF_SEPARATOR!r}; got {self.name!r}")
        if not isinstance(self.profile, AxisymmetricProfile):
            raise TypeError(
                f"profile of body {self.name!r} must be an AxisymmetricProfile; got {type(self.profile).__name__}"
            )
        object.__setattr__(self, "position", _floats(self.position, 2, f"position (x, y) of body {self.name!r} [m]"))
        object.__setattr__(
            self, "inertia", _floats(self.inertia, 3, f"inertia (Ixx, Iyy, Izz) of body {self.name!r} [kg m^2]")
        )
        if min(self.inertia) <= 0:
            raise ValueError(f"inertia of body {self.name!r} must be positive; got {self.inertia}")
        if not math.isfinite(self.center_of_mass_z):
            raise ValueError(
                f"center_of_mass_z of body {self.name!r} must be finite [m]; got {self.center_of_mass_z!r}"
            )
        if self.mass is not None and not (math.isfinite(self.mass) and self.mass > 0):
            raise ValueError(f"mass of body {self.name!r} must be positive [kg] or None; got {self.mass!r}")
        dofs = tuple(self.dofs)
        unknown = [d for d in dofs if d not in RIGID_BODY_DOFS]
        if unknown or not dofs or len(set(dofs)) != len(dofs):
            raise ValueError(
                f"dofs of body {self.name!r} must be distinct names among {', '.join(RIGID_BODY_DOFS)}; "
                f"got {list(dofs)}"
            )
        object.__setattr__(self, "dofs", tuple(d for d in RIGID_BODY_DOFS if d in dofs))

    @property
    def center_of_mass(self) -> np.ndarray:
        """Centre of mass (x, y, z) [m]."""
        return np.array([self.position[0], self.position[1], self.center_of_mass_z])


@dataclass(frozen=True)
class BEMSpec:
    """A Capytaine run: bodies solved together (all interactions), frequencies, water and mesh.

    Parameters
    ----------
    bodies : sequence of FloatBody
        The floats, solved together.
    omega : sequence of float
        Finite wave frequencies [rad/s], positive and strictly increasing. omega = inf is always solved
        (radiation only); omega = 0 too when ``zero_frequency``.
    panel_size : float
        Target panel height along each hull's meridian [m].
    panel_aspect_ratio : float
        Target panel width around the floats (and ring spacing of the lids) in units of ``panel_size``.
    water_depth : float
        [m]; ``inf`` for deep water.
    rho, g : float
        Water density [kg/m^3] and gravity [m/s^2].
    wave_directions : sequence of float
        Directions of wave propagation [rad] (0: towards +x).
    lid : bool
        Close each waterplane with a lid at z = 0 to remove irregular frequencies.
    zero_frequency : bool
        Also solve omega = 0 (``added_mass_zero``); Capytaine supports it in deep water only.
    method : {"direct", "indirect"}
        Capytaine's boundary integral equation. ``"direct"`` (default) is the more accurate here: for the
        heaving hemisphere at 1716 panels its largest added-mass error against Hulme (1982) is 0.5 % against
        1.3 % for ``"indirect"``, and the M4 floats' matrices come out symmetric within 0.4 % against 1.9 %.
    name : str
        Label used in progress messages and attributes.

    Raises
    ------
    ValueError
        For no bodies, repeated body names, overlapping floats, bad frequencies, a non-positive panel size,
        depth, rho or g, a float deeper than the water, omega = 0 asked in finite depth, or an unknown method.
    """

    bodies: tuple[FloatBody, ...]
    omega: tuple[float, ...]
    panel_size: float
    panel_aspect_ratio: float = DEFAULT_ASPECT_RATIO
    water_depth: float = math.inf
    rho: float = RHO_WATER
    g: float = GRAVITY
    wave_directions: tuple[float, ...] = (0.0,)
    lid: bool = True
    zero_frequency: bool = True
    method: str = "direct"
    name: str = "bem"

    def __post_init__(self) -> None:
        bodies = tuple(self.bodies)
        if not bodies or not all(isinstance(b, FloatBody) for b in bodies):
            raise ValueError("bodies must be a non-empty sequence of FloatBody")
        names = [b.name for b in bodies]
        if len(set(names)) != len(names):
            raise ValueError(f"body names must be distinct; got {names}")
        object.__setattr__(self, "bodies", bodies)
        _check_overlap(bodies)
        omega = np.asarray(self.omega, dtype=float).ravel()
        if omega.size == 0 or not np.all(np.isfinite(omega)) or np.any(omega <= 0) or np.any(np.diff(omega) <= 0):
            raise ValueError(
                "omega must hold finite, positive, strictly increasing frequencies [rad/s] "
                "(omega = 0 and inf are added by the run); got "
                f"{omega[:6].tolist()}{' ...' if omega.size > 6 else ''}"
            )
        object.__setattr__(self, "omega", tuple(float(w) for w in omega))
        for attr in ("panel_size", "panel_aspect_ratio", "rho", "g"):
            value = getattr(self, attr)
            if not (math.isfinite(value) and value > 0):
                raise ValueError(f"{attr} must be positive and finite; got {value!r}")
        if not self.water_depth > 0:
            raise ValueError(f"water_depth must be positive or inf [m]; got {self.water_depth!r}")
        deepest = max(b.profile.draft for b in bodies)
        if deepest >= self.water_depth:
            raise ValueError(f"water depth {self.water_depth} m is not larger than the deepest draft {deepest} m")
        if self.zero_frequency and math.isfinite(self.water_depth):
            raise ValueError("omega = 0 is only available in deep water in Capytaine; set zero_frequency=False")
        if self.method not in ("direct", "indirect"):
            raise ValueError(f"method must be 'direct' or 'indirect'; got {self.method!r}")
        directions = _floats(self.wave_directions, None, "wave_directions [rad]")
        if not directions:
            raise ValueError("wave_directions must hold at least one direction [rad]")
        if any(abs(d) > 2 * math.pi for d in directions):
            warnings.warn(
                f"wave_directions {list(directions)} look like degrees; they must be radians", UserWarning, stacklevel=3
            )
        object.__setattr__(self, "wave_directions", directions)

    @property
    def dofs(self) -> list[str]:
        """All DOF names ``<body>__<Dof>``, body by body."""
        return [f"{b.name}{DOF_SEPARATOR}{d}" for b in self.bodies for d in b.dofs]


def omega_grid(start: float, stop: float, step: float) -> tuple[float, ...]:
    """Uniform frequencies start, start + step, ... up to stop (included when on the grid) [rad/s].

    Raises
    ------
    ValueError
        If the values are not finite, ``start`` or ``step`` is not positive, or ``stop < start``.
    """
    if not all(math.isfinite(v) for v in (start, stop, step)) or start <= 0 or step <= 0 or stop < start:
        raise ValueError(f"need 0 < start <= stop and step > 0 [rad/s]; got start={start}, stop={stop}, step={step}")
    n = math.floor((stop - start) / step + 1e-9) + 1
    return tuple(round(start + k * step, 12) for k in range(n))  # rounding: 25.0, not 25.000000000000004


def _floats(values: object, size: int | None, what: str) -> tuple[float, ...]:
    try:
        out = tuple(float(v) for v in values)  # type: ignore[attr-defined]
    except (TypeError, ValueError):
        raise ValueError(f"{what} must be a sequence of numbers; got {values!r}") from None
    if (size is not None and len(out) != size) or not all(math.isfinite(v) for v in out):
        count = f"{size} " if size is not None else ""
        raise ValueError(f"{what} must be {count}finite numbers; got {values!r}")
    return out


def _check_overlap(bodies: tuple[FloatBody, ...]) -> None:
    for i, a in enumerate(bodies):
        for b in bodies[i + 1 :]:
            gap = math.dist(a.position, b.position) - a.profile.radius - b.profile.radius
            if gap <= 0:
                raise ValueError(f"floats {a.name!r} and {b.name!r} overlap (gap {gap:.4g} m between their waterlines)")
