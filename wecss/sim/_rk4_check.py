"""RK4's up-front stability check: the step against RK4's real stability region, for the eigenvalues of the plant
with its PTO gains, joint losses, moorings and radiation states, over the configurations the run may visit.

Why the equilibrium alone is not enough (measured on the NOTC 10 kW device, issue 18): its hydraulic cylinder's
transmission G(q) = dc/dtheta grows as the arm turns (0.77 m/rad at equilibrium, 1.0 m/rad at its largest), and
the fastest mode, the PTO damping's c G^2 / M, grows with G^2: |s| dt = 2.15 at equilibrium became about 2.8, past
the region's 2.785 on the negative real axis, and the run diverged at t = 29 s. So the mechanical eigenvalues
(mass M*(q), damping G(q)' diag(c) G(q) + joint and mooring damping, the static stiffness at equilibrium) are
taken at the equilibrium and at configurations sampled in the box the linear steady state reaches (each
coordinate's bound: the sum of its components' amplitudes, an upper bound of a sum of sinusoids, capped at
``solver.angle_bound`` for hinge angles); the state-space radiation states come with the linear model at the
equilibrium. A step is accepted when every eigenvalue z = s dt * RK4_MARGIN lies in RK4's region
|1 + z + z^2/2 + z^3/6 + z^4/24| <= 1 (eigenvalues with Re s > 0 are the physics' own and are left out).
"""

from __future__ import annotations

import dataclasses
import functools
from typing import Any

import numpy as np

from ..compiled import CompiledScene, linear_damping
from ..compiled.kernels import integrate_configuration, kinematics, pto_strokes, world_jacobian
from ..linear import cartesian_mass, linearize
from ..scene import SceneError

#: The step must be stable at this multiple of itself (the configurations are sampled, not searched).
RK4_MARGIN = 1.1
#: Configurations sampled in the box of the linear steady state, besides the equilibrium and the box's axes.
SAMPLES = 200


def _outside(z: np.ndarray) -> np.ndarray:
    return np.abs(1 + z + z**2 / 2 + z**3 / 6 + z**4 / 24) > 1 + 1e-12


def rk4_radius(angle: np.ndarray) -> np.ndarray:
    """Distance [-] from 0 to the boundary of RK4's stability region along each direction ``angle`` [rad] of the
    complex plane (measured from the positive real axis): the first rho where |R(rho e^{i angle})| exceeds 1
    (0 for directions that leave the region at once). Found on a grid of 0.01 up to 4 and then by bisection (to
    about 1e-9)."""
    angle = np.atleast_1d(np.asarray(angle, dtype=float))
    unit = np.exp(1j * angle)
    rho = np.linspace(0.0, 4.0, 401)[1:]
    outside = _outside(rho[None, :] * unit[:, None])
    first = np.where(outside.any(axis=1), outside.argmax(axis=1), rho.size)
    low = np.where(first > 0, rho[np.maximum(first - 1, 0)], 0.0)  # inside (or 0)
    high = np.where(first < rho.size, rho[np.minimum(first, rho.size - 1)], np.inf)  # outside (or none up to 4)
    bracket = (first > 0) & np.isfinite(high)
    lo, hi = low[bracket], high[bracket]
    for _ in range(24):
        mid = 0.5 * (lo + hi)
        out = _outside(mid * unit[bracket])
        hi = np.where(out, mid, hi)
        lo = np.where(out, lo, mid)
    low[bracket] = lo
    return low


@functools.cache
def _radius_range() -> tuple[float, float]:
    """The smallest and largest :func:`rk4_radius` [-] over the left half-plane's directions (on a grid of 721)."""
    radius = rk4_radius(np.linspace(np.pi / 2, np.pi, 721))
    return float(radius.min()), float(radius.max())


def largest_stable_step(eigenvalues: np.ndarray) -> float:
    """The largest step [s] for which RK4 is stable on every eigenvalue [1/s] with Re s <= 0 (inf for none).

    Only the eigenvalues that can set it get their direction's radius: those with |s| at least (smallest radius /
    largest radius) / 2 of the largest |s| (the others are stable at any step the largest allows)."""
    s = np.asarray(eigenvalues, dtype=complex).ravel()
    s = s[(s.real <= 1e-12 * np.abs(s)) & (np.abs(s) > 0)]
    if s.size == 0:
        return float("inf")
    low, high = _radius_range()
    size = np.abs(s)
    s = s[size >= 0.5 * low / high * size.max()]
    return float(np.min(rk4_radius(np.angle(s)) / np.abs(s)))


def _mechanical_eigenvalues(compiled: CompiledScene, q: np.ndarray) -> np.ndarray:
    p = compiled.plant
    nv = p.twists.shape[0]
    rot, pos, b, _, _ = kinematics(p, q, np.zeros(nv))
    bw = world_jacobian(p, rot, b)[p.hydro_index]
    _, g = pto_strokes(p, q, rot, pos, b)
    mass = b.T @ cartesian_mass(compiled, q) @ b
    damping = linear_damping(p, g, bw)
    a = np.zeros((2 * nv, 2 * nv))
    a[:nv, nv:] = np.eye(nv)
    a[nv:, :nv] = -np.linalg.solve(mass, compiled.stiffness)
    a[nv:, nv:] = -np.linalg.solve(mass, damping)
    return np.linalg.eigvals(a)


def motion_box(compiled: CompiledScene) -> np.ndarray:
    """Per generalised velocity, a bound [m or rad] of the displacement of the linear steady state from the
    equilibrium: the sum over the wave components of its amplitudes (zero in calm water), capped at
    ``solver.angle_bound`` for revolute coordinates."""
    nv = compiled.plant.twists.shape[0]
    if compiled.excitation is None or compiled.excitation.omega.size == 0:
        return np.zeros(nv)
    exc = compiled.excitation
    response = linearize(compiled).frequency_response(exc.omega)  # (n_w, nv, n_h)
    amplitude = np.abs(np.einsum("wvj,jw->vw", response, exc.coefficients)).sum(axis=1)
    model = compiled.device.model
    for j in model.ordered_joints:
        if j.kind == "revolute":
            k = model.velocity_names.index(f"{j.name}__{j.labels[0]}")
            amplitude[k] = min(amplitude[k], compiled.scene.solver.angle_bound)
    return np.asarray(amplitude, dtype=float)


def configurations(compiled: CompiledScene) -> list[np.ndarray]:
    """The equilibrium, the ends of each axis of :func:`motion_box` and SAMPLES seeded random points in it."""
    p = compiled.plant
    box = motion_box(compiled)
    steps = [np.zeros_like(box)]
    for k in np.flatnonzero(box > 0):
        for sign in (-1.0, 1.0):
            step = np.zeros_like(box)
            step[k] = sign * box[k]
            steps.append(step)
    if np.any(box > 0):
        rng = np.random.default_rng(0)
        steps.extend(rng.uniform(-1.0, 1.0, (SAMPLES, box.size)) * box)
    return [integrate_configuration(p, compiled.q0, dv) for dv in steps]


LIMITS_KEPT = 8
"""Step limits :func:`rk4_step_limit` keeps per process (a scene whose step is chosen from ``solver.tolerance``
asks for its limit when choosing and again when it runs)."""

_LIMITS: dict[tuple[Any, ...], tuple[float, str, object]] = {}


def _limit_key(compiled: CompiledScene) -> tuple[Any, ...]:
    """What the limit depends on: the scene but its step and outputs, the device (by identity: the compile cache
    makes a new one when its files change) and the PTO gains in the plant."""
    scene = compiled.scene
    solver = dataclasses.replace(scene.solver, dt=None, tolerance=None)  # sections, not a Scene: no step to check
    sections = (scene.device, scene.sea, scene.controller, solver, scene.radiation, scene.hydrodynamics, scene.initial)
    p = compiled.plant
    gains = (p.pto_damping.tobytes(), p.pto_stiffness.tobytes(), compiled.linear_controller)
    return (*sections, id(compiled.device), *gains)


def rk4_step_limit(compiled: CompiledScene) -> tuple[float, str]:
    """The largest RK4 step [s] (with RK4_MARGIN) over the configurations and radiation states, and what sets it
    (kept for the last :data:`LIMITS_KEPT` plants)."""
    key = _limit_key(compiled)
    if key not in _LIMITS:
        if len(_LIMITS) >= LIMITS_KEPT:
            _LIMITS.pop(next(iter(_LIMITS)))
        _LIMITS[key] = (*_step_limit(compiled), compiled.device)  # the device kept: its id stays its own
    limit, cause, _ = _LIMITS[key]
    return limit, cause


def _step_limit(compiled: CompiledScene) -> tuple[float, str]:
    mechanical = np.concatenate([_mechanical_eigenvalues(compiled, q) for q in configurations(compiled)])
    limit, cause = largest_stable_step(mechanical), "the mechanical modes (mass, PTO and joint damping, stiffness)"
    if compiled.radiation_fit is not None:
        system = linearize(compiled).state_space
        step = largest_stable_step(np.linalg.eigvals(system.A))
        if step < limit:
            limit, cause = step, "the linear model with its radiation states"
    return limit / RK4_MARGIN, cause


def check_rk4(compiled: CompiledScene, gains: str, elastic: str = "") -> None:
    """Refuse RK4 when the step passes :func:`rk4_step_limit`.

    Parameters
    ----------
    gains : str
        The PTO gains, as text for the message (empty when there are none).
    elastic : str
        A sentence naming the elastic bodies when their modes set the limit (empty otherwise).

    Raises
    ------
    SceneError
        Giving the largest stable step, what sets it and the PTO gains when there are any.
    """
    limit, cause = rk4_step_limit(compiled)
    dt = compiled.dt
    if dt <= limit:
        return
    head = (
        f"RK4 is unstable for this plant: {cause} over the configurations the run may reach need dt <= "
        f"{limit:.3g} s (given {dt:.3g} s, with a margin of {RK4_MARGIN:g}); "
    )
    if elastic:
        raise SceneError(head + elastic)
    likely = f"the PTO gains ({gains} [SI]) are the likely cause; " if gains else ""
    raise SceneError(head + f"{likely}reduce the PTO gain, use 'beeman' or give a smaller solver.dt")
