"""The undisturbed incident wave field at many points per step: elevation and Wheeler-stretched Airy pressure.

A sea of components k (frequency omega_k, complex amplitude A_k at x = 0, wavenumber k_k, all travelling in the
direction beta) has, at a point (x, y) and time t, with x' = x cos(beta) + y sin(beta):

    eta(x, y, t)   = sum_k Re[A_k exp(i (omega_k t - k_k x'))]
    p(x, y, z, t)  = rho g sum_k Re[A_k exp(i (omega_k t - k_k x'))] Z_k(z')      below eta, 0 above

with Wheeler's stretched height z' = (z - eta) h / (h + eta) in water of depth h (z - eta in deep water) and the
vertical profile Z_k(z') = cosh(k_k (z' + h)) / cosh(k_k h) (exp(k_k z') in deep water). At z = eta, z' = 0 and
Z_k = 1, so p = rho g eta there and the total pressure -rho g z + p vanishes on the free surface.

Two ways to evaluate it, chosen when the arrays are made (:func:`field_arrays`):

- **direct sums** (regular waves, a few components): every point costs one complex exponential per component;
- **a table** (irregular seas): the field of the current time on a grid in (x', z') that covers the region the
  bodies can reach, and along x' as far beyond it as :data:`TABLE_NODE_BUDGET` allows; at each new time t the
  nodes of the cells the points of that evaluation need are refreshed (:func:`field_refresh`; cost per node about
  (4 + 2 n_z) multiply-adds per component), and interpolated at the points at a cost independent of the number
  of components: cubic Hermite in x' from the values and x'-slopes at the nodes, Chebyshev series (Clenshaw) of
  degree n_z - 1 in z' on [z_min, 0] (the nodes are the Chebyshev-Lobatto points, z' = 0 among them). The node
  spacing and n_z are the smallest that keep the bound sum_k |A_k| e_k (e_k: the interpolation error of
  component k, computed) below ``tolerance`` times the sea's standard deviation, half for x' and half for z'.
  A point outside the table (x' off the active nodes, z' below z_min) is evaluated by direct sums instead and
  sets the flag :data:`OUTSIDE_TABLE` in ``status``.

The field functions are inline kernels for the per-step kernels (no allocation; the table and the phasors are
scratch arrays of :class:`FieldArrays`, updated in place).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np

from ..constants import GRAVITY, RHO_WATER
from ._jit import inline_kernel, kernel

if TYPE_CHECKING:  # pragma: no cover
    from ..waves import WaveComponents

CALM, DIRECT, TABLE = 0, 1, 2
"""Kinds of :class:`FieldArrays`: no waves, direct sums, the table."""

OUTSIDE_TABLE: int = 4
"""Flag bit: a point fell outside the table (it was evaluated by direct sums)."""

DIRECT_MAX_COMPONENTS: int = 4
"""With ``method="auto"``, seas of at most this many components are evaluated by direct sums."""

DEFAULT_TOLERANCE: float = 1e-4
"""Default bound on the table's interpolation error, as a share of the sea's standard deviation of elevation."""

WAVE_MARGIN_SIGMAS: float = 5.0
"""The table reaches this many standard deviations of elevation (or the sum of the amplitudes, if smaller) below
the lowest point of a region, for the stretched height of a point under a crest."""

MAX_TABLE_NODES: int = 200_000
"""Refuse tables with more nodes (x' nodes times z nodes) than this: the regions or the tolerance are unreasonable."""

TABLE_NODE_BUDGET: int = 200_000
"""The table reaches along x' beyond the regions the bodies can reach until it has about this many nodes (x' nodes
times z nodes; 3.2 MB of values and slopes): only the nodes under the bodies are computed at a step."""


class FieldArrays(NamedTuple):
    """The incident wave field as arrays for the kernels (see the module docstring).

    Attributes
    ----------
    kind : int
        CALM, DIRECT or TABLE.
    omega, amplitude, wavenumber : ndarray (n,)
        Frequencies [rad/s], complex amplitudes at x = 0 [m], wavenumbers [rad/m].
    cos_direction, sin_direction : float
        cos and sin of the direction of propagation.
    depth : float
        Water depth [m] (inf: deep water).
    rho, g : float
    ramp : float
        Duration [s] of the cosine ramp-in of the waves (0: none): the phasors are multiplied by
        r(t) = (1 - cos(pi t / ramp)) / 2 for 0 <= t < ramp, 0 for t < 0, 1 after.
    phasor : complex ndarray (n,)
        Scratch: r(t) A_k exp(i omega_k t) at ``time[0]``.
    work : ndarray (2, n)
        Scratch of the table's refresh (real and imaginary parts of the phasors at a node).
    time : ndarray (1,)
        The time [s] of ``phasor`` and the table (NaN before the first evaluation).
    status : int64 ndarray (1,)
        Sticky flags: OUTSIDE_TABLE once a point fell outside the table (clear it with ``status[0] = 0``).
    x_start, x_step : float
        The table's first node and spacing in x' [m].
    segment_start, segment_end : int64 ndarray (n_seg,)
        The runs of active nodes (kept up to date), as node ranges [start, end).
    active : uint8 ndarray (n_x,)
        1 at the active nodes.
    step_cos, step_sin : ndarray (n,)
        cos(k x_step) and -sin(k x_step): exp(-i k x_step).
    z_min : float
        The table's lowest stretched height [m] (< 0).
    profile : ndarray (n, n_z)
        Chebyshev coefficients of each component's vertical profile Z_k on [z_min, 0] (row k: component k).
    elevation, elevation_slope : ndarray (n_x,)
        eta and d eta / dx' at the nodes [m, -].
    head, head_slope : ndarray (n_x, n_z)
        Chebyshev coefficients of the pressure head p / (rho g) and of its x'-slope at the nodes [m, -].
    node_time : ndarray (n_x,)
        The time [s] of each node's values (NaN before the first): :func:`field_refresh` refreshes the nodes a
        step needs, not every active node.
    """

    kind: int
    omega: np.ndarray
    amplitude: np.ndarray
    wavenumber: np.ndarray
    cos_direction: float
    sin_direction: float
    depth: float
    rho: float
    g: float
    ramp: float
    phasor: np.ndarray
    work: np.ndarray
    time: np.ndarray
    status: np.ndarray
    x_start: float
    x_step: float
    segment_start: np.ndarray
    segment_end: np.ndarray
    active: np.ndarray
    step_cos: np.ndarray
    step_sin: np.ndarray
    z_min: float
    profile: np.ndarray
    elevation: np.ndarray
    elevation_slope: np.ndarray
    head: np.ndarray
    head_slope: np.ndarray
    node_time: np.ndarray


@inline_kernel
def vertical_profile(k: float, zs: float, depth: float) -> float:
    """Z(z') = cosh(k (z' + h)) / cosh(k h), or exp(k z') in deep water (written without overflow)."""
    if math.isinf(depth):
        return math.exp(k * zs)
    return math.exp(k * zs) * (1.0 + math.exp(-2.0 * k * (zs + depth))) / (1.0 + math.exp(-2.0 * k * depth))


@inline_kernel
def vertical_profile_slope(k: float, zs: float, depth: float) -> float:
    """dZ/dz' [1/m]: k sinh(k (z' + h)) / cosh(k h), or k exp(k z') in deep water (written without overflow)."""
    if math.isinf(depth):
        return k * math.exp(k * zs)
    return k * math.exp(k * zs) * (1.0 - math.exp(-2.0 * k * (zs + depth))) / (1.0 + math.exp(-2.0 * k * depth))


@inline_kernel
def stretched_height(depth: float, z: float, eta: float) -> float:
    """Wheeler's stretched height z' = (z - eta) h / (h + eta) in water of depth h, or z - eta in deep water [m]."""
    if math.isinf(depth):
        return z - eta
    return (z - eta) * depth / (depth + eta)


@inline_kernel
def stretch_slopes(depth: float, z: float, eta: float, eta_slope: float) -> tuple[float, float]:
    """The derivatives of Wheeler's stretched height z' in x' (at constant z) and in z [-], given eta and its
    x'-slope d eta / dx'."""
    if math.isinf(depth):
        return -eta_slope, 1.0
    scale = depth / (depth + eta)
    return -eta_slope * scale * (depth + z) / (depth + eta), scale


@inline_kernel
def ramp_factor(ramp: float, t: float) -> float:
    """The ramp-in factor r(t) [-]: (1 - cos(pi t / ramp)) / 2 for 0 <= t < ramp, 0 for t < 0, 1 after (and 1 at
    every t when ``ramp`` is 0), the law of :class:`wecss.waves.Ramp`."""
    if ramp <= 0.0 or t >= ramp:
        return 1.0
    if t <= 0.0:
        return 0.0
    return 0.5 * (1.0 - math.cos(math.pi * t / ramp))


@inline_kernel
def field_phasors(field: FieldArrays, t: float) -> None:
    """Bring the phasors to time ``t`` [s] unless they are there already (the ramp included); the table's nodes
    keep their times (:func:`field_refresh` brings them on)."""
    if field.kind == CALM or field.time[0] == t:
        return
    r = ramp_factor(field.ramp, t)
    for k in range(field.omega.shape[0]):
        phase = field.omega[k] * t
        field.phasor[k] = r * field.amplitude[k] * complex(math.cos(phase), math.sin(phase))
    field.time[0] = t


@inline_kernel
def _refresh_run(
    phasor: np.ndarray,
    wavenumber: np.ndarray,
    profile: np.ndarray,
    step_cos: np.ndarray,
    step_sin: np.ndarray,
    x_start: float,
    x_step: float,
    work: np.ndarray,
    elevation: np.ndarray,
    elevation_slope: np.ndarray,
    head: np.ndarray,
    head_slope: np.ndarray,
    i0: int,
    i1: int,
) -> None:
    """The table's values at the nodes i0 <= i < i1 from the current phasors: cost (4 + 2 n_z) multiply-adds per
    node and component, plus one complex exponential per component for the first node."""
    n = phasor.shape[0]
    n_z = profile.shape[1]
    x0 = x_start + i0 * x_step
    for k in range(n):
        phase = -wavenumber[k] * x0
        c = phasor[k] * complex(math.cos(phase), math.sin(phase))
        work[0, k] = c.real
        work[1, k] = c.imag
    for i in range(i0, i1):
        for m in range(n_z):
            head[i, m] = 0.0
            head_slope[i, m] = 0.0
        eta = 0.0
        slope = 0.0
        # components outermost, so that the inner loop over the coefficients is not a reduction (SIMD)
        for k in range(n):
            re = work[0, k]
            im = work[1, k]
            value_slope = wavenumber[k] * im  # d/dx' Re[c exp(-i k x')] = k Im[c]
            eta += re
            slope += value_slope
            for m in range(n_z):
                head[i, m] += re * profile[k, m]
                head_slope[i, m] += value_slope * profile[k, m]
            # one node on: times exp(-i k x_step)
            work[0, k] = re * step_cos[k] - im * step_sin[k]
            work[1, k] = re * step_sin[k] + im * step_cos[k]
        elevation[i] = eta
        elevation_slope[i] = slope


@inline_kernel
def _refresh_nodes(field: FieldArrays, t: float, lo: int, hi: int) -> None:
    """Refresh the active nodes lo <= i <= hi of the table that are not at time ``t`` (the phasors are)."""
    i = lo
    while i <= hi:
        if field.active[i] == 0 or field.node_time[i] == t:
            i += 1
            continue
        j = i
        while j <= hi and field.active[j] == 1 and field.node_time[j] != t:
            field.node_time[j] = t
            j += 1
        _refresh_run(
            field.phasor,
            field.wavenumber,
            field.profile,
            field.step_cos,
            field.step_sin,
            field.x_start,
            field.x_step,
            field.work,
            field.elevation,
            field.elevation_slope,
            field.head,
            field.head_slope,
            i,
            j,
        )
        i = j


@inline_kernel
def field_refresh(field: FieldArrays, t: float, x_low: float, x_high: float) -> None:
    """Bring the phasors to time ``t`` [s] and, with a table, the active nodes of the cells that hold
    x_low <= x' <= x_high [m] (finite; only the nodes not at ``t`` already): a step refreshes the nodes its
    points need."""
    field_phasors(field, t)
    if field.kind != TABLE or not x_low <= x_high:  # (NaN: nothing to refresh; the points go to direct sums)
        return
    last = field.active.shape[0] - 1
    u_low = min(max((x_low - field.x_start) / field.x_step, 0.0), float(last))
    u_high = min(max((x_high - field.x_start) / field.x_step, 0.0), float(last))
    _refresh_nodes(field, t, int(u_low), min(int(u_high) + 1, last))


@inline_kernel
def field_update(field: FieldArrays, t: float) -> None:
    """Bring the phasors and, with a table, every active node to time ``t`` [s] (the ramp included)."""
    field_phasors(field, t)
    if field.kind == TABLE:
        _refresh_nodes(field, t, 0, field.active.shape[0] - 1)


@inline_kernel
def _direct_elevation(phasor: np.ndarray, wavenumber: np.ndarray, xp: float) -> tuple[float, float]:
    eta = 0.0
    slope = 0.0
    for k in range(phasor.shape[0]):
        phase = -wavenumber[k] * xp
        c = phasor[k]
        cos, sin = math.cos(phase), math.sin(phase)
        eta += c.real * cos - c.imag * sin
        slope += wavenumber[k] * (c.real * sin + c.imag * cos)  # d/dx' Re[c exp(-i k x')] = k Im[c exp(-i k x')]
    return eta, slope


@inline_kernel
def _direct_head(
    phasor: np.ndarray, wavenumber: np.ndarray, depth: float, xp: float, zs: float
) -> tuple[float, float, float]:
    head = 0.0
    head_x = 0.0
    head_z = 0.0
    for k in range(phasor.shape[0]):
        phase = -wavenumber[k] * xp
        c = phasor[k]
        cos, sin = math.cos(phase), math.sin(phase)
        re = c.real * cos - c.imag * sin
        profile = vertical_profile(wavenumber[k], zs, depth)
        head += re * profile
        head_x += wavenumber[k] * (c.real * sin + c.imag * cos) * profile
        head_z += re * vertical_profile_slope(wavenumber[k], zs, depth)
    return head, head_x, head_z


# The helpers below that branch take the field's arrays, not the FieldArrays: an inlined helper with branches that
# takes the whole tuple makes numba count references to every array of it at each call (about 0.4 us), even on
# paths that never use them. The public functions taking ``field`` are straight-line wrappers.


@inline_kernel
def _cell(x_start: float, x_step: float, active: np.ndarray, xp: float) -> tuple[int, float]:
    """The table cell [i, i + 1] holding x' and the fraction s in it, or (-1, 0) when off the active nodes."""
    u = (xp - x_start) / x_step
    if not (u >= 0.0 and u < active.shape[0] - 1):
        return -1, 0.0
    i = int(u)
    if active[i] == 0 or active[i + 1] == 0:
        return -1, 0.0
    return i, u - i


@inline_kernel
def _hermite(s: float, h: float) -> tuple[float, float, float, float, float, float, float, float]:
    """Cubic Hermite weights at the fraction s of a cell of length h [m] of the values and x'-slopes at its nodes
    (v0, v0', v1, v1'), and the weights of the same for the x'-derivative [1/m]."""
    r = 1.0 - s
    return (
        (1.0 + 2.0 * s) * r * r,
        s * r * r * h,
        s * s * (3.0 - 2.0 * s),
        -s * s * r * h,
        6.0 * s * (s - 1.0) / h,
        r * (1.0 - 3.0 * s),
        -6.0 * s * (s - 1.0) / h,
        s * (3.0 * s - 2.0),
    )


@inline_kernel
def _elevation(
    kind: int,
    phasor: np.ndarray,
    wavenumber: np.ndarray,
    x_start: float,
    x_step: float,
    active: np.ndarray,
    elevation: np.ndarray,
    elevation_slope: np.ndarray,
    status: np.ndarray,
    xp: float,
) -> tuple[float, float, int]:
    if kind == CALM:
        return 0.0, 0.0, 0
    if kind == DIRECT:
        eta, slope = _direct_elevation(phasor, wavenumber, xp)
        return eta, slope, 0
    i, s = _cell(x_start, x_step, active, xp)
    if i < 0:
        status[0] |= OUTSIDE_TABLE
        eta, slope = _direct_elevation(phasor, wavenumber, xp)
        return eta, slope, OUTSIDE_TABLE
    h00, h10, h01, h11, d00, d10, d01, d11 = _hermite(s, x_step)
    v0, s0, v1, s1 = elevation[i], elevation_slope[i], elevation[i + 1], elevation_slope[i + 1]
    return h00 * v0 + h10 * s0 + h01 * v1 + h11 * s1, d00 * v0 + d10 * s0 + d01 * v1 + d11 * s1, 0


@inline_kernel
def incident_elevation(field: FieldArrays, xp: float) -> tuple[float, float, int]:
    """eta [m] and d eta / dx' [-] at x' (the field at its current time), and flags (OUTSIDE_TABLE or 0)."""
    return _elevation(
        field.kind,
        field.phasor,
        field.wavenumber,
        field.x_start,
        field.x_step,
        field.active,
        field.elevation,
        field.elevation_slope,
        field.status,
        xp,
    )


@inline_kernel
def _head(
    kind: int,
    phasor: np.ndarray,
    wavenumber: np.ndarray,
    depth: float,
    x_start: float,
    x_step: float,
    active: np.ndarray,
    z_min: float,
    head: np.ndarray,
    head_slope: np.ndarray,
    status: np.ndarray,
    xp: float,
    zs: float,
) -> tuple[float, float, float, int]:
    if kind == CALM:
        return 0.0, 0.0, 0.0, 0
    if kind == DIRECT:
        value, value_x, value_z = _direct_head(phasor, wavenumber, depth, xp, zs)
        return value, value_x, value_z, 0
    i, s = _cell(x_start, x_step, active, xp)
    if i < 0 or zs < z_min:
        status[0] |= OUTSIDE_TABLE
        value, value_x, value_z = _direct_head(phasor, wavenumber, depth, xp, zs)
        return value, value_x, value_z, OUTSIDE_TABLE
    h00, h10, h01, h11, d00, d10, d01, d11 = _hermite(s, x_step)
    u = 1.0 - 2.0 * zs / z_min  # z' = 0 -> 1, z' = z_min -> -1
    # Clenshaw for the series of the value (b), its u-derivative (d) and the series of the x'-slope (e)
    b1 = b2 = d1 = d2 = e1 = e2 = 0.0
    for m in range(head.shape[1] - 1, 0, -1):
        v0, s0, v1, s1 = head[i, m], head_slope[i, m], head[i + 1, m], head_slope[i + 1, m]
        d = 2.0 * b1 + 2.0 * u * d1 - d2
        d2 = d1
        d1 = d
        b = h00 * v0 + h10 * s0 + h01 * v1 + h11 * s1 + 2.0 * u * b1 - b2
        b2 = b1
        b1 = b
        e = d00 * v0 + d10 * s0 + d01 * v1 + d11 * s1 + 2.0 * u * e1 - e2
        e2 = e1
        e1 = e
    v0, s0, v1, s1 = head[i, 0], head_slope[i, 0], head[i + 1, 0], head_slope[i + 1, 0]
    value = h00 * v0 + h10 * s0 + h01 * v1 + h11 * s1 + u * b1 - b2
    value_x = d00 * v0 + d10 * s0 + d01 * v1 + d11 * s1 + u * e1 - e2
    value_z = (b1 + u * d1 - d2) * (-2.0 / z_min)
    return value, value_x, value_z, 0


@inline_kernel
def incident_head(field: FieldArrays, xp: float, zs: float) -> tuple[float, float, float, int]:
    """The pressure head p / (rho g) [m] at x' and stretched height z' <= 0 (the field at its current time), its
    partial derivatives in x' (at constant z') and in z' [-], and flags (OUTSIDE_TABLE or 0)."""
    return _head(
        field.kind,
        field.phasor,
        field.wavenumber,
        field.depth,
        field.x_start,
        field.x_step,
        field.active,
        field.z_min,
        field.head,
        field.head_slope,
        field.status,
        xp,
        zs,
    )


@inline_kernel
def field_elevation(field: FieldArrays, x: float, y: float, t: float) -> float:
    """Undisturbed elevation eta(x, y, t) [m] (world coordinates x, y [m], time t [s]). A point outside the table
    sets OUTSIDE_TABLE in ``field.status``."""
    field_update(field, t)
    eta, _, _ = incident_elevation(field, x * field.cos_direction + y * field.sin_direction)
    return eta


@inline_kernel
def field_pressure(field: FieldArrays, x: float, y: float, z: float, t: float) -> float:
    """Incident (Airy, Wheeler-stretched) pressure [Pa] at the world point (x, y, z) [m] and time t [s]: zero above
    the surface. A point outside the table sets OUTSIDE_TABLE in ``field.status``."""
    field_update(field, t)
    xp = x * field.cos_direction + y * field.sin_direction
    eta, _, _ = incident_elevation(field, xp)
    if z > eta:
        return 0.0
    head, _, _, _ = incident_head(field, xp, stretched_height(field.depth, z, eta))
    return field.rho * field.g * head


@kernel
def field_values(field: FieldArrays, x: np.ndarray, y: np.ndarray, z: np.ndarray, t: float) -> np.ndarray:
    """Elevation and pressure at many points at one time (tests and plots): array (2, n) of eta [m] and p [Pa]."""
    out = np.empty((2, x.shape[0]))
    for j in range(x.shape[0]):
        out[0, j] = field_elevation(field, x[j], y[j], t)
        out[1, j] = field_pressure(field, x[j], y[j], z[j], t)
    return out


# --- construction (Python) -----------------------------------------------------------------------------------


def calm_field(*, rho: float = RHO_WATER, g: float = GRAVITY) -> FieldArrays:
    """The arrays of calm water (no incident waves)."""
    return _arrays(CALM, np.zeros(0), np.zeros(0, complex), np.zeros(0), 0.0, math.inf, rho, g, None, 0.0)


def field_arrays(
    components: WaveComponents | None,
    *,
    depth: float = math.inf,
    rho: float = RHO_WATER,
    g: float = GRAVITY,
    regions: Any = None,
    tolerance: float = DEFAULT_TOLERANCE,
    method: str = "auto",
    ramp: float = 0.0,
) -> FieldArrays:
    """The incident field of ``components`` as arrays for the kernels (see the module docstring).

    Parameters
    ----------
    components : WaveComponents or None
        The sea (None: calm water).
    depth : float
        Water depth [m], ``inf`` for deep water.
    rho, g : float
        Water density [kg/m^3] and gravity [m/s^2].
    regions : array (n_b, 2, 3), optional
        Per body, the lower and upper corners [m] of a world box that holds every point of the body it can reach
        during the run (for the table; needed with ``method="table"`` and, for irregular seas, ``"auto"``).
    tolerance : float
        Bound on the table's interpolation error of elevation and pressure head, as a share of the sea's standard
        deviation of elevation [-].
    method : {"auto", "direct", "table"}
        Direct sums, the table, or direct sums for at most :data:`DIRECT_MAX_COMPONENTS` components and the table
        otherwise.
    ramp : float
        Duration [s] of the cosine ramp-in of the waves (0: none; see :func:`ramp_factor`).

    Raises
    ------
    ValueError
        On a non-positive depth, rho or g or tolerance, a negative or non-finite ramp, an unknown method, regions
        of another shape or with lower corners above upper ones, a table asked for without regions, or a table of
        more than :data:`MAX_TABLE_NODES` nodes.
    """
    from ..waves import wavenumber as dispersion

    for name, value in (("rho", rho), ("g", g), ("tolerance", tolerance)):
        if not (math.isfinite(value) and value > 0):
            raise ValueError(f"{name} must be positive and finite; got {value!r}")
    if not depth > 0:
        raise ValueError(f"depth must be positive or inf [m]; got {depth!r}")
    if not (math.isfinite(ramp) and ramp >= 0):
        raise ValueError(f"ramp must be finite and >= 0 [s]; got {ramp!r}")
    if method not in ("auto", "direct", "table"):
        raise ValueError(f"method must be 'auto', 'direct' or 'table'; got {method!r}")
    if components is None or components.omega.size == 0:
        return calm_field(rho=rho, g=g)
    omega = np.asarray(components.omega, dtype=float)
    amplitude = np.asarray(components.amplitude, dtype=complex)
    k = np.asarray(dispersion(omega, depth, g), dtype=float)
    direction = float(components.direction)
    use_table = method == "table" or (method == "auto" and omega.size > DIRECT_MAX_COMPONENTS)
    if not use_table:
        return _arrays(DIRECT, omega, amplitude, k, direction, depth, rho, g, None, ramp)
    if regions is None:
        raise ValueError(
            f"a table of the incident field needs the regions the bodies can reach (regions, shape (n_bodies, 2, 3)); "
            f"got None for a sea of {omega.size} components (or choose method='direct')"
        )
    boxes = np.asarray(regions, dtype=float)
    if boxes.ndim == 2:
        boxes = boxes[None]
    if boxes.ndim != 3 or boxes.shape[1:] != (2, 3) or not np.all(np.isfinite(boxes)):
        raise ValueError(f"regions must be finite, of shape (n_bodies, 2, 3) (lower, upper corners); got {boxes.shape}")
    if np.any(boxes[:, 0] > boxes[:, 1]):
        raise ValueError("regions: every lower corner must lie below its upper corner")
    grid = _table_grid(omega, amplitude, k, direction, depth, boxes, tolerance)
    return _arrays(TABLE, omega, amplitude, k, direction, depth, rho, g, grid, ramp)


class _Grid(NamedTuple):
    x_start: float
    x_step: float
    active: np.ndarray
    z_min: float
    profile: np.ndarray


def _arrays(
    kind: int,
    omega: np.ndarray,
    amplitude: np.ndarray,
    k: np.ndarray,
    direction: float,
    depth: float,
    rho: float,
    g: float,
    grid: _Grid | None,
    ramp: float,
) -> FieldArrays:
    n = omega.size
    if grid is None:
        grid = _Grid(0.0, 1.0, np.zeros(1, np.uint8), -1.0, np.zeros((n, 1)))
    active = grid.active.astype(np.uint8)
    edges = np.diff(np.concatenate([[0], active, [0]]).astype(np.int64))
    n_x, n_z = active.size, grid.profile.shape[1]
    return FieldArrays(
        kind=int(kind),
        omega=omega.astype(float),
        amplitude=amplitude.astype(complex),
        wavenumber=k.astype(float),
        cos_direction=math.cos(direction),
        sin_direction=math.sin(direction),
        depth=float(depth),
        rho=float(rho),
        g=float(g),
        ramp=float(ramp),
        phasor=np.zeros(n, complex),
        work=np.zeros((2, n)),
        time=np.full(1, np.nan),
        status=np.zeros(1, np.int64),
        x_start=float(grid.x_start),
        x_step=float(grid.x_step),
        segment_start=np.flatnonzero(edges == 1).astype(np.int64),
        segment_end=np.flatnonzero(edges == -1).astype(np.int64),
        active=active,
        step_cos=np.cos(k * grid.x_step),
        step_sin=-np.sin(k * grid.x_step),
        z_min=float(grid.z_min),
        profile=np.ascontiguousarray(grid.profile, dtype=float),
        elevation=np.zeros(n_x),
        elevation_slope=np.zeros(n_x),
        head=np.zeros((n_x, n_z)),
        head_slope=np.zeros((n_x, n_z)),
        node_time=np.full(n_x, np.nan),
    )


def _table_grid(
    omega: np.ndarray,
    amplitude: np.ndarray,
    k: np.ndarray,
    direction: float,
    depth: float,
    boxes: np.ndarray,
    tolerance: float,
) -> _Grid:
    sigma = math.sqrt(float(np.sum(np.abs(amplitude) ** 2)) / 2)
    magnitude = np.abs(amplitude)
    budget = 0.5 * tolerance * sigma
    # x': the largest node spacing whose Hermite error bound stays within budget
    step = _hermite_step(k, magnitude, budget)
    corners = np.stack(np.meshgrid([0, 1], [0, 1], [0, 1], indexing="ij"), axis=-1).reshape(-1, 3)
    xs = []
    for box in boxes:
        points = box[corners, [0, 1, 2]]
        xp = points[:, 0] * math.cos(direction) + points[:, 1] * math.sin(direction)
        xs.append((float(xp.min()), float(xp.max())))
    lo = min(a for a, _ in xs) - step
    hi = max(b for _, b in xs) + step
    n_x = math.ceil((hi - lo) / step) + 2
    nodes = lo + step * np.arange(n_x)
    active = np.zeros(n_x, dtype=np.uint8)
    for a, b in xs:
        active[(nodes >= a - 1.5 * step) & (nodes <= b + 1.5 * step)] = 1
    # z': down to the lowest point's stretched height under a crest or trough
    margin = min(float(np.sum(magnitude)), WAVE_MARGIN_SIGMAS * sigma)
    z_low = float(boxes[:, 0, 2].min())
    candidates = [z_low - margin, z_low + margin]
    if math.isfinite(depth):
        candidates = [(z_low - margin) * depth / (depth + margin), (z_low + margin) * depth / max(depth - margin, 1e-9)]
    z_min = min(min(candidates), -1e-3 * max(margin, 1e-9))
    if math.isfinite(depth):
        z_min = max(z_min, -depth)
    profile = _profile_coefficients(k, magnitude, depth, z_min, budget)
    if int(active.sum()) * profile.shape[1] > MAX_TABLE_NODES:
        raise ValueError(
            f"the table of the incident field would have {int(active.sum())} x {profile.shape[1]} nodes (more than "
            f"{MAX_TABLE_NODES}): shrink the regions or loosen the tolerance ({tolerance:g})"
        )
    # along x' the table reaches beyond the regions, every node active, as far as TABLE_NODE_BUDGET allows: a step
    # computes only the nodes under the bodies, so the width costs memory alone, and a body that drifts out of its
    # region (an unmoored float in steep waves) stays in the table
    extra = max(TABLE_NODE_BUDGET // profile.shape[1] - n_x, 0) // 2
    if extra:
        lo -= extra * step
        active = np.ones(n_x + 2 * extra, dtype=np.uint8)
    return _Grid(float(lo), float(step), active, float(z_min), profile)


def _hermite_error(phase: np.ndarray) -> np.ndarray:
    """Largest error of cubic Hermite interpolation of exp(-i phase s) over s in [0, 1] from its values and slopes
    at s = 0 and 1 (per unit amplitude), for each ``phase`` = k x_step."""
    s = np.linspace(0.0, 1.0, 65)[:, None]
    r = 1.0 - s
    h00, h10 = (1 + 2 * s) * r * r, s * r * r
    h01, h11 = s * s * (3 - 2 * s), -s * s * r
    phase = np.asarray(phase, dtype=float)[None, :]
    end = np.exp(-1j * phase)
    interp = h00 + h10 * (-1j * phase) + h01 * end + h11 * (-1j * phase) * end
    return np.max(np.abs(interp - np.exp(-1j * phase * s)), axis=0)


def _hermite_step(k: np.ndarray, magnitude: np.ndarray, budget: float) -> float:
    """The largest x' spacing [m] with sum_k |A_k| e(k h) <= budget (bisection on log h)."""
    lo, hi = 1e-6, 2 * math.pi / max(float(k.max()), 1e-12)
    if float(np.sum(magnitude * _hermite_error(k * hi))) <= budget:
        return hi
    for _ in range(60):
        mid = math.sqrt(lo * hi)
        if float(np.sum(magnitude * _hermite_error(k * mid))) <= budget:
            lo = mid
        else:
            hi = mid
    return lo


def _profile_coefficients(
    k: np.ndarray, magnitude: np.ndarray, depth: float, z_min: float, budget: float, most: int = 64
) -> np.ndarray:
    """Chebyshev coefficients (n_components, n_z) of each component's vertical profile on [z_min, 0], at the
    fewest Chebyshev-Lobatto nodes n_z for which sum_k |A_k| max|Z_k - interpolant| <= budget (checked on a fine
    grid)."""
    u_fine = np.linspace(-1.0, 1.0, 401)
    z_fine = z_min * (1.0 - u_fine) / 2
    exact = _profiles(k, z_fine, depth)
    coefficients = np.zeros((k.size, 1))
    for n_z in range(3, most + 1):
        coefficients = _chebyshev_fit(k, depth, z_min, n_z)
        approx = np.polynomial.chebyshev.chebval(u_fine, coefficients.T)  # (n_components, n_fine)
        if float(np.sum(magnitude * np.max(np.abs(approx - exact), axis=1))) <= budget:
            return coefficients
    return coefficients


def _profiles(k: np.ndarray, z: np.ndarray, depth: float) -> np.ndarray:
    kz = k[:, None] * z[None, :]
    if math.isinf(depth):
        return np.exp(kz)
    return np.exp(kz) * (1 + np.exp(-2 * k[:, None] * (z[None, :] + depth))) / (1 + np.exp(-2 * k[:, None] * depth))


def _chebyshev_fit(k: np.ndarray, depth: float, z_min: float, n_z: int) -> np.ndarray:
    """Chebyshev coefficients of the interpolant at the n_z Chebyshev-Lobatto nodes u_j = cos(pi j / (n_z - 1))
    (z' = z_min (1 - u) / 2; u = 1 is z' = 0), by the discrete cosine transform of type I."""
    n = n_z - 1
    j = np.arange(n_z)
    u = np.cos(np.pi * j / n)
    values = _profiles(k, z_min * (1.0 - u) / 2, depth)  # (n_components, n_z)
    weights = np.ones(n_z)
    weights[0] = weights[-1] = 0.5
    cosines = np.cos(np.pi * np.outer(j, j) / n)  # [m, j]
    coefficients = (2.0 / n) * (values * weights) @ cosines.T
    coefficients[:, 0] *= 0.5
    coefficients[:, -1] *= 0.5
    return coefficients


def table_size(field: FieldArrays) -> tuple[int, int]:
    """Active x' nodes and z' nodes of a field's table ((0, 0) without one)."""
    if field.kind != TABLE:
        return 0, 0
    return int(np.sum(field.active)), int(field.profile.shape[1])
