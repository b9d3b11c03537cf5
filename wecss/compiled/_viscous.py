"""The viscous forces and Morison elements as kernel terms (``hydrodynamics.drag``): body drag and linear damping per
DOF in body axes, and Morison cylinders, on the velocity relative to the undisturbed fluid (or the body's own).

``configure`` calls :func:`configure_viscous` (the fluid at the drag points and the Morison segments at this time and
configuration; the Morison segments' fluid-inertia force, which depends on them alone), ``respond`` calls
:func:`respond_viscous` (the drag forces, which depend on the velocities). Both do nothing for a plant without
these terms (empty arrays). See ``wecss.multibody._viscous`` for the models.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ._jit import inline_kernel, kernel
from ._wave_kinematics import WaveArrays, no_waves, wave_phasors, wave_point

TERM_ROWS: tuple[str, ...] = ("hydrostatic", "froude_krylov", "remainder", "drag", "morison_inertia")
"""What the per-body output of the hydrodynamic terms holds (``TermsWork.out[:, row]``): the body-exact hydrostatic
and Froude-Krylov forces (whole), what the body-exact forces add to the linear ones (the remainder, or in the
"replace" formulation their difference from the database's), the viscous forces (drag, linear damping, Morison
drag) and the Morison elements' fluid inertia; world axes, moments about the centre of mass."""

DRAG_ROW, MORISON_ROW = (TERM_ROWS.index(k) for k in ("drag", "morison_inertia"))

TERM_COLUMNS: int = len(TERM_ROWS) * 6
"""Columns of one body in the ``terms`` channel: a force and a moment (6) per row of ``TERM_ROWS``."""


class ViscousArrays(NamedTuple):
    """The viscous terms of a plant (empty: none).

    Body drag (n_d entries): ``drag_body`` (n_d,) body index, ``drag_quadratic`` (n_d, 6) c per body-axis DOF
    [N s^2/m^2, N m s^2/rad^2], ``drag_linear`` (n_d, 6) [N s/m, N m s/rad], ``drag_point`` (n_d, 3) the centre of
    mass at equilibrium, world [m] (where the undisturbed fluid velocity is taken). Morison segments (n_s):
    ``morison_body`` (n_s,), ``morison_point`` (n_s, 3) the segment's midpoint from the centre of mass and
    ``morison_axis`` (n_s, 3) its unit axis, body axes; ``morison_inertia`` (n_s,) rho (1 + Ca) pi D^2 / 4 L [kg],
    ``morison_drag`` (n_s,) rho Cd D L / 2 [kg/m]. ``relative`` (1,): 1.0 to act on the velocity relative to the
    fluid, 0.0 on the body's. ``wave``: the incident wave (empty without waves).
    """

    wave: WaveArrays
    drag_body: np.ndarray
    drag_quadratic: np.ndarray
    drag_linear: np.ndarray
    drag_point: np.ndarray
    morison_body: np.ndarray
    morison_point: np.ndarray
    morison_axis: np.ndarray
    morison_inertia: np.ndarray
    morison_drag: np.ndarray
    relative: np.ndarray


def no_viscous() -> ViscousArrays:
    """No viscous terms."""
    i0, f0, f3, f6 = np.zeros(0, dtype=np.int64), np.zeros(0), np.zeros((0, 3)), np.zeros((0, 6))
    return ViscousArrays(no_waves(), i0, f6, f6, f3, i0, f3, f3, f0, f0, np.zeros(1))


class TermsWork(NamedTuple):
    """Scratch and outputs of the hydrodynamic terms in a workspace: ``phasor`` (n_w,) complex the waves' phasors at
    the evaluation's time, ``fluid`` (n_d + n_s, 6) the fluid's velocity and acceleration at the drag points and the
    Morison segments (world), ``wet`` (n_d + n_s,) 1.0 where the point is below the surface, ``out`` (n_body,
    len(TERM_ROWS), 6) the terms' forces and moments per body (world axes, about the centre of mass), ``flags``
    (n_body,) the body-exact forces' flags, ORed over a run (``wecss.compiled._pressure``), ``vec6``, ``delta`` (6,),
    ``offset`` (3,) and ``axis`` (3,) scratch."""

    phasor: np.ndarray
    fluid: np.ndarray
    wet: np.ndarray
    out: np.ndarray
    flags: np.ndarray
    vec6: np.ndarray
    delta: np.ndarray
    offset: np.ndarray
    axis: np.ndarray


@kernel
def terms_work(viscous: ViscousArrays, n_body: int) -> TermsWork:
    """A :class:`TermsWork` for the terms ``viscous`` of a plant of ``n_body`` bodies."""
    n_points = viscous.drag_body.shape[0] + viscous.morison_body.shape[0]
    return TermsWork(
        np.zeros(viscous.wave.omega.shape[0], dtype=np.complex128),
        np.zeros((n_points, 6)),
        np.zeros(n_points),
        np.zeros((n_body, len(TERM_ROWS), 6)),
        np.zeros(n_body, dtype=np.int64),
        np.zeros(6),
        np.zeros(6),
        np.zeros(3),
        np.zeros(3),
    )


@inline_kernel
def configure_viscous(
    vis: ViscousArrays, t: float, rot: np.ndarray, pos: np.ndarray, cart_start: np.ndarray, tw: TermsWork,
    force: np.ndarray,
) -> None:  # fmt: skip
    """The fluid at the drag points and Morison segments at time ``t`` [s] and the bodies' frames ``rot``, ``pos``
    (world), into ``tw``; the Morison segments' fluid-inertia force and moment added to ``force`` (Cartesian rows,
    world axes) and to ``tw.out``."""
    n_d = vis.drag_body.shape[0]
    n_s = vis.morison_body.shape[0]
    if n_d + n_s == 0:
        return
    for i in range(tw.out.shape[0]):
        for a in range(6):
            tw.out[i, MORISON_ROW, a] = 0.0
    waves = vis.wave.omega.shape[0] > 0
    if waves:
        wave_phasors(vis.wave, t, tw.phasor)
    for d in range(n_d):
        for a in range(6):
            tw.fluid[d, a] = 0.0
        tw.wet[d] = 1.0
        if waves and vis.relative[0] > 0.0:
            point = vis.drag_point
            wet = wave_point(vis.wave, tw.phasor, point[d, 0], point[d, 1], point[d, 2], tw.vec6)
            tw.wet[d] = 1.0 if wet else 0.0
            for a in range(6):
                tw.fluid[d, a] = tw.vec6[a]
    for s in range(n_s):
        i = vis.morison_body[s]
        _segment_frame(vis, rot[i], s, tw)
        x, y, z = pos[i, 0] + tw.offset[0], pos[i, 1] + tw.offset[1], pos[i, 2] + tw.offset[2]
        for a in range(6):
            tw.vec6[a] = 0.0
        wet = wave_point(vis.wave, tw.phasor, x, y, z, tw.vec6) if waves else z <= 0.0
        tw.wet[n_d + s] = 1.0 if wet else 0.0
        for a in range(6):
            tw.fluid[n_d + s, a] = tw.vec6[a]
        if not (wet and waves):
            continue
        # rho (1 + Ca) V times the fluid's acceleration normal to the axis
        e = tw.axis
        along = tw.vec6[3] * e[0] + tw.vec6[4] * e[1] + tw.vec6[5] * e[2]
        m = vis.morison_inertia[s]
        f0, f1, f2 = m * (tw.vec6[3] - along * e[0]), m * (tw.vec6[4] - along * e[1]), m * (tw.vec6[5] - along * e[2])
        _add_point_force(i, tw.offset[0], tw.offset[1], tw.offset[2], f0, f1, f2, cart_start, force, tw, MORISON_ROW)


@inline_kernel
def _segment_frame(vis: ViscousArrays, r: np.ndarray, s: int, tw: TermsWork) -> None:
    """Morison segment ``s``'s offset from its body's centre of mass and its unit axis, world axes, into
    ``tw.offset`` and ``tw.axis`` (``r`` the body's rotation)."""
    for a in range(3):
        o = 0.0
        e = 0.0
        for c in range(3):
            o += r[a, c] * vis.morison_point[s, c]
            e += r[a, c] * vis.morison_axis[s, c]
        tw.offset[a] = o
        tw.axis[a] = e


@inline_kernel
def _add_point_force(
    i: int, r0: float, r1: float, r2: float, f0: float, f1: float, f2: float, cart_start: np.ndarray,
    force: np.ndarray, tw: TermsWork, row: int,
) -> None:  # fmt: skip
    """A world force (f0, f1, f2) at the world offset (r0, r1, r2) from body i's centre of mass into ``force``
    (Cartesian rows, world axes) and ``tw.out[i, row]``."""
    m0, m1, m2 = r1 * f2 - r2 * f1, r2 * f0 - r0 * f2, r0 * f1 - r1 * f0
    c = cart_start[i]
    force[c] += f0
    force[c + 1] += f1
    force[c + 2] += f2
    force[c + 3] += m0
    force[c + 4] += m1
    force[c + 5] += m2
    tw.out[i, row, 0] += f0
    tw.out[i, row, 1] += f1
    tw.out[i, row, 2] += f2
    tw.out[i, row, 3] += m0
    tw.out[i, row, 4] += m1
    tw.out[i, row, 5] += m2


@inline_kernel
def respond_viscous(
    vis: ViscousArrays, rot: np.ndarray, lin: np.ndarray, omega: np.ndarray, b: np.ndarray, cart_start: np.ndarray,
    tw: TermsWork, gen: np.ndarray,
) -> None:  # fmt: skip
    """The drag forces at the velocities of the bodies' centres of mass ``lin`` (world) and their angular velocities
    ``omega`` (body axes), added to the generalised force ``gen`` through B (``b``) and to ``tw.out``.
    """
    n_d = vis.drag_body.shape[0]
    n_s = vis.morison_body.shape[0]
    for i in range(tw.out.shape[0]):
        for a in range(6):
            tw.out[i, DRAG_ROW, a] = 0.0
    cart = tw.vec6
    for d in range(n_d):
        i = vis.drag_body[d]
        r = rot[i]
        # relative velocity of the centre of mass, body axes
        u0 = lin[i, 0] - vis.relative[0] * tw.fluid[d, 0]
        u1 = lin[i, 1] - vis.relative[0] * tw.fluid[d, 1]
        u2 = lin[i, 2] - vis.relative[0] * tw.fluid[d, 2]
        for a in range(3):
            rel = r[0, a] * u0 + r[1, a] * u1 + r[2, a] * u2  # R' u
            cart[a] = -(vis.drag_quadratic[d, a] * abs(rel) + vis.drag_linear[d, a]) * rel
            spin = omega[i, a]
            cart[3 + a] = -(vis.drag_quadratic[d, 3 + a] * abs(spin) + vis.drag_linear[d, 3 + a]) * spin
        # the force back to world axes on the translation rows; the moment stays in body axes (B's rotation rows)
        tw.offset[0] = r[0, 0] * cart[0] + r[0, 1] * cart[1] + r[0, 2] * cart[2]
        tw.offset[1] = r[1, 0] * cart[0] + r[1, 1] * cart[1] + r[1, 2] * cart[2]
        tw.offset[2] = r[2, 0] * cart[0] + r[2, 1] * cart[1] + r[2, 2] * cart[2]
        for a in range(3):
            tw.out[i, DRAG_ROW, a] += tw.offset[a]
            tw.out[i, DRAG_ROW, 3 + a] += r[a, 0] * cart[3] + r[a, 1] * cart[4] + r[a, 2] * cart[5]
            cart[a] = tw.offset[a]
        add_generalised(b, cart_start[i], cart, gen)
    for s in range(n_s):
        k = n_d + s
        if tw.wet[k] == 0.0 or vis.morison_drag[s] == 0.0:
            continue
        i = vis.morison_body[s]
        r = rot[i]
        _segment_frame(vis, r, s, tw)
        x0, x1, x2 = tw.offset[0], tw.offset[1], tw.offset[2]
        # the segment's velocity, world: the centre of mass's plus (R omega) x offset
        w0 = r[0, 0] * omega[i, 0] + r[0, 1] * omega[i, 1] + r[0, 2] * omega[i, 2]
        w1 = r[1, 0] * omega[i, 0] + r[1, 1] * omega[i, 1] + r[1, 2] * omega[i, 2]
        w2 = r[2, 0] * omega[i, 0] + r[2, 1] * omega[i, 1] + r[2, 2] * omega[i, 2]
        rel0 = vis.relative[0] * tw.fluid[k, 0] - (lin[i, 0] + w1 * x2 - w2 * x1)
        rel1 = vis.relative[0] * tw.fluid[k, 1] - (lin[i, 1] + w2 * x0 - w0 * x2)
        rel2 = vis.relative[0] * tw.fluid[k, 2] - (lin[i, 2] + w0 * x1 - w1 * x0)
        e = tw.axis
        along = rel0 * e[0] + rel1 * e[1] + rel2 * e[2]
        n0, n1, n2 = rel0 - along * e[0], rel1 - along * e[1], rel2 - along * e[2]
        scale = vis.morison_drag[s] * np.sqrt(n0 * n0 + n1 * n1 + n2 * n2)
        f0, f1, f2 = scale * n0, scale * n1, scale * n2
        m0, m1, m2 = x1 * f2 - x2 * f1, x2 * f0 - x0 * f2, x0 * f1 - x1 * f0
        cart[0], cart[1], cart[2] = f0, f1, f2
        for a in range(3):  # the moment in body axes: R' m
            cart[3 + a] = r[0, a] * m0 + r[1, a] * m1 + r[2, a] * m2
        tw.out[i, DRAG_ROW, 0] += f0
        tw.out[i, DRAG_ROW, 1] += f1
        tw.out[i, DRAG_ROW, 2] += f2
        tw.out[i, DRAG_ROW, 3] += m0
        tw.out[i, DRAG_ROW, 4] += m1
        tw.out[i, DRAG_ROW, 5] += m2
        add_generalised(b, cart_start[i], cart, gen)


@inline_kernel
def add_generalised(b: np.ndarray, row: int, cart: np.ndarray, gen: np.ndarray) -> None:
    """gen += B[row : row + 6]' cart (a body's Cartesian force: world force, body-axes moment)."""
    for c in range(gen.shape[0]):
        s = 0.0
        for a in range(6):
            s += b[row + a, c] * cart[a]
        gen[c] += s
