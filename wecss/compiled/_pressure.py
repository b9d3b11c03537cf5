"""Pressure forces on a body's surface mesh below a free surface: hydrostatics and Froude-Krylov, per step.

:func:`mesh_pressure_force` integrates the pressure -rho g z, plus the incident pressure when asked (Wheeler-
stretched Airy waves, ``wecss.compiled._wave_field``), over the part of a body's mesh below the free surface, the
incident surface eta(x, y, t) or the plane z = 0, and gives the force and the moment about the body's centre of
mass, both in world axes.

**Clipping.** Each face is cut by the signed heights d = z - eta of its corners, linearly along its edges (the cut
points are where the linear interpolant of d vanishes): a corner with d < 0 is wet. A face with one wet corner
keeps a triangle, one with two wet corners a quadrilateral (two triangles); faces are never kept or dropped whole.

**Hydrostatic pressure, exactly.** Over a set of flat triangles, the integral of the linear pressure -rho g z is a
linear combination of the triangles' surface moments in the body frame: with the area vector N, centroid c and
second moments Q = int r r' dS / A of a triangle, a = sum N, S = sum c N' (int r n' dS), u = sum c x N
(int r x n dS), T = sum Q x N (row j: int r_j (r x n) dS); and world height z = p_z + e . r (e: the third row of
the rotation), force F = rho g R (p_z a + S' e) and moment M = rho g R (p_z u + T' e) about the centre of mass.
Whole faces add their 24 precomputed moments; cut faces add those of their pieces. The result is exact to
rounding for any pose, in either surface mode.

**Froude-Krylov pressure, by quadrature.** The incident pressure is integrated over every wet triangle (whole face
or piece) by the rule with weights 1/12 at each corner and 3/4 at the centroid, exact for polynomials of degree 2
(error O(h^3) per unit area for panels of size h). The field is evaluated at the corners only, value and gradient
(``wecss.compiled._wave_field`` gives both in one pass over its coefficients): the centroid's value is taken as
mean_i(h_i + (m - r_i) . grad h_i / 2) over the corners r_i, which is exact for a quadratic h (for one, h(m) =
h_i + (m - r_i) . grad h_i + (m - r_i)' H (m - r_i) / 2 and mean_i h_i = h(m) + mean_i (m - r_i)' H (m - r_i) / 2),
so the rule keeps its degree. The corners' values are computed once per vertex and shared by the faces around it;
so each wet vertex costs one evaluation, each cut edge one at its cut point, and a face none of its own. A corner
the clipping counts as wet can lie above the incident surface: in surface mode 1 a little (between the
piecewise-linear cut and the curved surface), in mode 0 anywhere between eta and z = 0 under a trough. There the
incident pressure takes its value on the surface, rho g eta(x) (z' = 0), not zero: this keeps the total pressure
continuous in mode 1, and in mode 0 it makes the force tend to the linear Froude-Krylov force for small waves
(zero there would rectify the pressure at the waterline, an error of the first order in the amplitude).

The kernel allocates nothing: world positions, heights, heads and the sums live in :class:`MeshArrays`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from ._jit import inline_kernel
from ._wave_field import CALM, FieldArrays, _elevation, _head, field_refresh, stretch_slopes, stretched_height

if TYPE_CHECKING:  # pragma: no cover
    from ..hydro.mesh import SurfaceMesh

DRY: int = 1
"""Flag bit of :func:`mesh_pressure_force`: no part of the body is below the surface (the force is zero)."""

SUBMERGED: int = 2
"""Flag bit: every face is wholly below the surface (none cut, none dry)."""

OUTSIDE_TABLE: int = 4
"""Flag bit: a point fell outside the incident field's table (evaluated by direct sums instead)."""

MOMENTS: int = 24
"""Surface moments per face: a (3), S (3 x 3), u (3), T (3 x 3); see the module docstring."""

CLUSTER_FACES: int = 32
"""Faces per cluster: each body's faces are sorted by the height of their centroids (body frame) and taken in
runs of this many, each with its bounding box and the sum of its surface moments, so that a step adds the moments
of a cluster wholly below the surface at once and skips one wholly above it (see :func:`mesh_pressure_force`)."""

CLUSTER_SLACK: float = 1e-9
"""Margin [m] of the clusters' tests against the surface, for the rounding of the vertices' heights."""

_FK = 24  # acc[24:27]: Froude-Krylov force, acc[27:30]: its moment (body frame, per rho g)


class MeshArrays(NamedTuple):
    """One or several bodies' meshes as arrays for :func:`mesh_pressure_force`.

    Attributes
    ----------
    vertices : ndarray (n_v, 3)
        Body-frame vertices [m], from the centre of mass, every body's after the previous one's.
    faces : int64 ndarray (n_f, 3)
        Vertex indices (into ``vertices``) of each face, outward by the right-hand rule.
    moments : ndarray (n_f, 24)
        Surface moments of each face in the body frame (see the module docstring).
    vertex_start, face_start : int64 ndarray (n_b + 1,)
        Body b owns vertices vertex_start[b]:vertex_start[b + 1] and faces face_start[b]:face_start[b + 1]
        (sorted by the height of their centroids in the body frame).
    cluster_start : int64 ndarray (n_c + 1,)
        Cluster c holds the faces cluster_start[c]:cluster_start[c + 1] (at most :data:`CLUSTER_FACES`, of one body).
    body_cluster_start : int64 ndarray (n_b + 1,)
        Body b owns clusters body_cluster_start[b]:body_cluster_start[b + 1].
    cluster_box : ndarray (n_c, 2, 3)
        Centre and half-widths of each cluster's bounding box (body frame) [m].
    cluster_moments : ndarray (n_c, 24)
        The sum of each cluster's surface moments.
    world : ndarray (n_v, 3)
        Scratch: world positions of the vertices [m].
    height : ndarray (n_v,)
        Scratch: signed height d = z - eta of each vertex [m].
    head : ndarray (n_v,)
        Scratch: incident pressure head at wet vertices [m].
    gradient : ndarray (n_v, 3)
        Scratch: its gradient at wet vertices, body axes [-].
    acc : ndarray (30,)
        Scratch: the sums (24 surface moments, Froude-Krylov force and moment in the body frame).
    """

    vertices: np.ndarray
    faces: np.ndarray
    moments: np.ndarray
    vertex_start: np.ndarray
    face_start: np.ndarray
    cluster_start: np.ndarray
    body_cluster_start: np.ndarray
    cluster_box: np.ndarray
    cluster_moments: np.ndarray
    world: np.ndarray
    height: np.ndarray
    head: np.ndarray
    gradient: np.ndarray
    acc: np.ndarray


def face_moments(triangles: np.ndarray) -> np.ndarray:
    """The 24 surface moments (a, S, u, T; see the module docstring) of each triangle (n, 3, 3) [m], shape (n, 24)."""
    t = np.asarray(triangles, dtype=float)
    a, b, c = t[:, 0], t[:, 1], t[:, 2]
    n = 0.5 * np.cross(b - a, c - a)
    center = (a + b + c) / 3.0
    second = (
        np.einsum("ni,nj->nij", a, a) + np.einsum("ni,nj->nij", b, b) + np.einsum("ni,nj->nij", c, c)
    ) / 12.0 + 0.75 * np.einsum("ni,nj->nij", center, center)
    s = np.einsum("ni,nj->nij", center, n)
    u = np.cross(center, n)
    tt = np.cross(second, n[:, None, :])
    return np.concatenate([n, s.reshape(-1, 9), u, tt.reshape(-1, 9)], axis=1)


def mesh_arrays(meshes: SurfaceMesh | Sequence[SurfaceMesh]) -> MeshArrays:
    """The arrays of one mesh, or of several bodies' meshes one after the other (body b is the b-th mesh).

    Raises
    ------
    TypeError
        If an item is not a ``SurfaceMesh``.
    """
    from ..hydro.mesh import SurfaceMesh

    items = [meshes] if isinstance(meshes, SurfaceMesh) else list(meshes)
    if not items or not all(isinstance(m, SurfaceMesh) for m in items):
        raise TypeError("mesh_arrays takes a SurfaceMesh or a non-empty sequence of them")
    vertex_start = np.cumsum([0] + [m.vertices.shape[0] for m in items]).astype(np.int64)
    face_start = np.cumsum([0] + [m.n_faces for m in items]).astype(np.int64)
    vertices = np.ascontiguousarray(np.concatenate([m.vertices for m in items]), dtype=float)
    per_body = []
    for b, m in enumerate(items):
        body_faces = m.faces + vertex_start[b]
        per_body.append(body_faces[np.argsort(vertices[body_faces, 2].mean(axis=1), kind="stable")])
    faces = np.concatenate(per_body).astype(np.int64)
    moments = np.ascontiguousarray(face_moments(vertices[faces]))
    starts = [np.arange(face_start[b], face_start[b + 1], CLUSTER_FACES) for b in range(len(items))]
    body_cluster_start = np.cumsum([0] + [c.size for c in starts]).astype(np.int64)
    cluster_start = np.append(np.concatenate(starts), face_start[-1]).astype(np.int64)
    n_c = cluster_start.size - 1
    box = np.zeros((n_c, 2, 3))
    cluster_moments = np.zeros((n_c, MOMENTS))
    for c in range(n_c):
        corners = vertices[faces[cluster_start[c] : cluster_start[c + 1]]].reshape(-1, 3)
        low, high = corners.min(axis=0), corners.max(axis=0)
        box[c] = 0.5 * (low + high), 0.5 * (high - low)
        cluster_moments[c] = moments[cluster_start[c] : cluster_start[c + 1]].sum(axis=0)
    n_v = vertices.shape[0]
    return MeshArrays(
        vertices=vertices,
        faces=np.ascontiguousarray(faces),
        moments=moments,
        vertex_start=vertex_start,
        face_start=face_start,
        cluster_start=cluster_start,
        body_cluster_start=body_cluster_start,
        cluster_box=box,
        cluster_moments=cluster_moments,
        world=np.zeros((n_v, 3)),
        height=np.zeros(n_v),
        head=np.zeros(n_v),
        gradient=np.zeros((n_v, 3)),
        acc=np.zeros(30),
    )


@inline_kernel
def _add_moments(acc: np.ndarray, ax, ay, az, bx, by, bz, cx, cy, cz) -> None:
    """Add the 24 surface moments of the triangle (a, b, c) (body frame) to acc[0:24]."""
    ux, uy, uz = bx - ax, by - ay, bz - az
    vx, vy, vz = cx - ax, cy - ay, cz - az
    nx = 0.5 * (uy * vz - uz * vy)
    ny = 0.5 * (uz * vx - ux * vz)
    nz = 0.5 * (ux * vy - uy * vx)
    mx = (ax + bx + cx) / 3.0
    my = (ay + by + cy) / 3.0
    mz = (az + bz + cz) / 3.0
    acc[0] += nx
    acc[1] += ny
    acc[2] += nz
    acc[3] += mx * nx
    acc[4] += mx * ny
    acc[5] += mx * nz
    acc[6] += my * nx
    acc[7] += my * ny
    acc[8] += my * nz
    acc[9] += mz * nx
    acc[10] += mz * ny
    acc[11] += mz * nz
    acc[12] += my * nz - mz * ny
    acc[13] += mz * nx - mx * nz
    acc[14] += mx * ny - my * nx
    # Q = (a a' + b b' + c c') / 12 + 3/4 m m'; row j of T is Q[j] x N
    qxx = (ax * ax + bx * bx + cx * cx) / 12.0 + 0.75 * mx * mx
    qyy = (ay * ay + by * by + cy * cy) / 12.0 + 0.75 * my * my
    qzz = (az * az + bz * bz + cz * cz) / 12.0 + 0.75 * mz * mz
    qxy = (ax * ay + bx * by + cx * cy) / 12.0 + 0.75 * mx * my
    qxz = (ax * az + bx * bz + cx * cz) / 12.0 + 0.75 * mx * mz
    qyz = (ay * az + by * bz + cy * cz) / 12.0 + 0.75 * my * mz
    acc[15] += qxy * nz - qxz * ny
    acc[16] += qxz * nx - qxx * nz
    acc[17] += qxx * ny - qxy * nx
    acc[18] += qyy * nz - qyz * ny
    acc[19] += qyz * nx - qxy * nz
    acc[20] += qxy * ny - qyy * nx
    acc[21] += qyz * nz - qzz * ny
    acc[22] += qzz * nx - qxz * nz
    acc[23] += qxz * ny - qyz * nx


@inline_kernel
def _wet_head(
    kind, phasor, wavenumber, depth, x_start, x_step, active, z_min, table_head, table_slope, status, cos_d, sin_d,
    rot, xp: float, wz: float, eta: float, eta_slope: float,
):  # fmt: skip
    """The incident pressure head [m] at a world point of the wet part (x' = ``xp``, height ``wz``; eta and its
    x'-slope there), Wheeler-stretched and taken at z' = 0 above eta (see the module docstring), its gradient in
    the body's axes [-] (below the surface), and flags; from the field's arrays (see :func:`mesh_pressure_force`)."""
    zs = stretched_height(depth, wz, eta)
    value, value_x, value_z, flags = _head(
        kind, phasor, wavenumber, depth, x_start, x_step, active, z_min, table_head, table_slope, status, xp,
        min(zs, 0.0),
    )  # fmt: skip
    # the gradient of the field below the surface, also at a point above it (its limit from below at z' = 0): a
    # face reaches above the surface by a sliver at most, and the gradient extrapolates into the face (a held
    # value's zero z-slope would err by the first order in the amplitude there)
    slope_x, slope_z = stretch_slopes(depth, wz, eta, eta_slope)
    gx = value_x + value_z * slope_x  # d/dx' at constant z
    wx_, wy_, wz_ = gx * cos_d, gx * sin_d, value_z * slope_z
    return (
        value,
        rot[0, 0] * wx_ + rot[1, 0] * wy_ + rot[2, 0] * wz_,
        rot[0, 1] * wx_ + rot[1, 1] * wy_ + rot[2, 1] * wz_,
        rot[0, 2] * wx_ + rot[1, 2] * wy_ + rot[2, 2] * wz_,
        flags,
    )


@inline_kernel
def _add_fk(acc, ax, ay, az, ha, gax, gay, gaz, bx, by, bz, hb, gbx, gby, gbz, cx, cy, cz, hc, gcx, gcy, gcz):
    """Add the Froude-Krylov force and moment (body frame, per rho g) of the wet triangle with body-frame corners
    a, b, c, their heads h [m] and head gradients g (body axes): minus the head integrated with the weights 1/12 at
    the corners and 3/4 at the centroid m, where the head is mean(h_i + (m - r_i) . g_i / 2) (exact for a
    quadratic head; see the module docstring)."""
    ux, uy, uz = bx - ax, by - ay, bz - az
    vx, vy, vz = cx - ax, cy - ay, cz - az
    nx = 0.5 * (uy * vz - uz * vy)
    ny = 0.5 * (uz * vx - ux * vz)
    nz = 0.5 * (ux * vy - uy * vx)
    mx = (ax + bx + cx) / 3.0
    my = (ay + by + cy) / 3.0
    mz = (az + bz + cz) / 3.0
    lean = (
        (mx - ax) * gax + (my - ay) * gay + (mz - az) * gaz
        + (mx - bx) * gbx + (my - by) * gby + (mz - bz) * gbz
        + (mx - cx) * gcx + (my - cy) * gcy + (mz - cz) * gcz
    )  # fmt: skip
    hm = (ha + hb + hc) / 3.0 + lean / 6.0
    mean = (ha + hb + hc) / 12.0 + 0.75 * hm
    px = (ha * ax + hb * bx + hc * cx) / 12.0 + 0.75 * hm * mx  # int h r dS / A
    py = (ha * ay + hb * by + hc * cy) / 12.0 + 0.75 * hm * my
    pz = (ha * az + hb * bz + hc * cz) / 12.0 + 0.75 * hm * mz
    acc[_FK] -= mean * nx
    acc[_FK + 1] -= mean * ny
    acc[_FK + 2] -= mean * nz
    acc[_FK + 3] -= py * nz - pz * ny
    acc[_FK + 4] -= pz * nx - px * nz
    acc[_FK + 5] -= px * ny - py * nx


# The helpers take arrays, not the MeshArrays or FieldArrays: an inlined helper with branches that takes a whole
# tuple of arrays makes numba count references to every array of it at each call (measured: the field's evaluation
# at a vertex took 2.5 times as long through the tuple). ``mesh_pressure_force`` takes the arrays out once.


@inline_kernel
def _corner(vertices: np.ndarray, head: np.ndarray, gradient: np.ndarray, i: int):
    """Vertex i as (x, y, z, head, gradient x, y, z), body frame."""
    return (
        vertices[i, 0], vertices[i, 1], vertices[i, 2], head[i], gradient[i, 0], gradient[i, 1], gradient[i, 2]
    )  # fmt: skip


@inline_kernel
def _cut_point(vertices: np.ndarray, s: float, i: int, j: int) -> tuple[float, float, float]:
    """The point at the fraction s from vertex i (wet) to vertex j (dry), body frame."""
    x = vertices[i, 0] + s * (vertices[j, 0] - vertices[i, 0])
    y = vertices[i, 1] + s * (vertices[j, 1] - vertices[i, 1])
    z = vertices[i, 2] + s * (vertices[j, 2] - vertices[i, 2])
    return x, y, z


@inline_kernel
def mesh_pressure_force(
    mesh: MeshArrays,
    rot: np.ndarray,
    pos: np.ndarray,
    field: FieldArrays,
    t: float,
    surface_mode: int,
    include_fk: bool,
    rho: float,
    g: float,
    out: np.ndarray,
    body=0,
) -> int:
    """Pressure force and moment on a body's mesh below the free surface (see the module docstring).

    Parameters
    ----------
    mesh : MeshArrays
    rot : ndarray (3, 3)
        Rotation of the body (body axes to world axes).
    pos : ndarray (3,)
        World position of the body's centre of mass (the mesh's origin) [m].
    field : FieldArrays
        The incident wave field (``calm_field()`` for none).
    t : float
        Time [s].
    surface_mode : int
        0: the body is wet below z = 0; 1: below the incident surface eta(x, y, t).
    include_fk : bool
        Add the incident (Froude-Krylov) pressure to the hydrostatic -rho g z.
    rho, g : float
        Water density [kg/m^3] and gravity [m/s^2].
    out : ndarray (6,)
        Written: force [N] and moment about the centre of mass [N m], world axes.
    body : int
        Which body of ``mesh`` (default 0).

    Returns
    -------
    int
        Flags: DRY, SUBMERGED, OUTSIDE_TABLE (bits).
    """
    v0, v1 = mesh.vertex_start[body], mesh.vertex_start[body + 1]
    f0, f1 = mesh.face_start[body], mesh.face_start[body + 1]
    vertices, faces, world, height, head, acc = mesh.vertices, mesh.faces, mesh.world, mesh.height, mesh.head, mesh.acc
    moments, gradient, cluster_box, cluster_moments = (
        mesh.moments,
        mesh.gradient,
        mesh.cluster_box,
        mesh.cluster_moments,
    )
    use_field = field.kind != CALM and (surface_mode == 1 or include_fk)
    kind, phasor, wavenumber, depth, status = field.kind, field.phasor, field.wavenumber, field.depth, field.status
    x_start, x_step, active, z_min = field.x_start, field.x_step, field.active, field.z_min
    elevation, elevation_slope, table_head, table_slope = (
        field.elevation, field.elevation_slope, field.head, field.head_slope
    )  # fmt: skip
    cos_d, sin_d = field.cos_direction, field.sin_direction
    flags = 0
    eta_low = math.inf
    eta_high = -math.inf
    x_low = math.inf
    x_high = -math.inf
    for v in range(v0, v1):
        x, y, z = vertices[v, 0], vertices[v, 1], vertices[v, 2]
        wz = pos[2] + rot[2, 0] * x + rot[2, 1] * y + rot[2, 2] * z
        if not use_field:
            height[v] = wz
            continue
        wx = pos[0] + rot[0, 0] * x + rot[0, 1] * y + rot[0, 2] * z
        wy = pos[1] + rot[1, 0] * x + rot[1, 1] * y + rot[1, 2] * z
        world[v, 0] = wx
        world[v, 1] = wy
        world[v, 2] = wz
        xp = wx * field.cos_direction + wy * field.sin_direction
        x_low = min(x_low, xp)
        x_high = max(x_high, xp)
    if use_field:
        # the table's nodes under this body (every point of the mesh's wet part lies between its vertices in x')
        field_refresh(field, t, x_low, x_high)
        for v in range(v0, v1):
            wz = world[v, 2]
            xp = world[v, 0] * cos_d + world[v, 1] * sin_d
            eta, eta_slope, fe = _elevation(
                kind, phasor, wavenumber, x_start, x_step, active, elevation, elevation_slope, status, xp
            )
            flags |= fe
            eta_low = min(eta_low, eta)
            eta_high = max(eta_high, eta)
            d = wz - eta if surface_mode == 1 else wz
            height[v] = d
            if include_fk and d < 0.0:
                hv, gx, gy, gz, fh = _wet_head(
                    kind, phasor, wavenumber, depth, x_start, x_step, active, z_min, table_head, table_slope, status,
                    cos_d, sin_d, rot, xp, wz, eta, eta_slope,
                )  # fmt: skip
                head[v] = hv
                gradient[v, 0] = gx
                gradient[v, 1] = gy
                gradient[v, 2] = gz
                flags |= fh
            else:
                head[v] = 0.0
    for q in range(30):
        acc[q] = 0.0
    n_wet = 0
    n_cut = 0
    # the clusters wholly above or below the surface (their boxes against the range of eta at the body's vertices
    # in surface mode 1: the clipping takes the surface's heights at the vertices) at once, the others face by face
    if not (surface_mode == 1 and use_field):
        eta_low = eta_high = 0.0
    e0, e1, e2 = rot[2, 0], rot[2, 1], rot[2, 2]
    for cl in range(mesh.body_cluster_start[body], mesh.body_cluster_start[body + 1]):
        middle = pos[2] + e0 * cluster_box[cl, 0, 0] + e1 * cluster_box[cl, 0, 1] + e2 * cluster_box[cl, 0, 2]
        half = abs(e0) * cluster_box[cl, 1, 0] + abs(e1) * cluster_box[cl, 1, 1] + abs(e2) * cluster_box[cl, 1, 2]
        if middle - half > eta_high + CLUSTER_SLACK:
            continue  # dry
        below = middle + half < eta_low - CLUSTER_SLACK
        if below:
            n_wet += mesh.cluster_start[cl + 1] - mesh.cluster_start[cl]
            for q in range(24):
                acc[q] += cluster_moments[cl, q]
            if not include_fk:
                continue
        for f in range(mesh.cluster_start[cl], mesh.cluster_start[cl + 1]):
            i0, i1, i2 = faces[f, 0], faces[f, 1], faces[f, 2]
            w0, w1, w2 = height[i0] < 0.0, height[i1] < 0.0, height[i2] < 0.0
            n_corners = w0 + w1 + w2
            if n_corners == 0:
                continue
            whole = n_corners == 3
            single = n_corners == 1
            if whole:
                if not below:
                    n_wet += 1
                    for q in range(24):
                        acc[q] += moments[f, q]
                if not include_fk:
                    continue
                ia, ib, ic = i0, i1, i2
            else:
                n_cut += 1
                # corners in cyclic order starting at the odd one out: the wet corner (one wet) or the corner after
                # the dry one (two wet)
                if single:
                    ia, ib, ic = (i0, i1, i2) if w0 else ((i1, i2, i0) if w1 else (i2, i0, i1))
                else:
                    ia, ib, ic = (i1, i2, i0) if not w0 else ((i2, i0, i1) if not w1 else (i0, i1, i2))
            # corners and cut points as (x, y, z, head, gradient): body frame
            a = _corner(vertices, head, gradient, ia)
            b = _corner(vertices, head, gradient, ib)
            c = _corner(vertices, head, gradient, ic)
            cut_p = cut_q = a
            if not whole:
                # the cut points: on the edges a-b and a-c (one wet corner, a), or b-c and a-c (two, a and b); one call
                # site of each helper, so that numba inlines the field's code once (compile time)
                for e in range(2):
                    i, j = (ia, ic) if e == 1 else ((ia, ib) if single else (ib, ic))
                    x, y, z = _cut_point(vertices, height[i] / (height[i] - height[j]), i, j)
                    hv = gx = gy = gz = 0.0
                    if include_fk:
                        wx = pos[0] + rot[0, 0] * x + rot[0, 1] * y + rot[0, 2] * z
                        wy = pos[1] + rot[1, 0] * x + rot[1, 1] * y + rot[1, 2] * z
                        wz = pos[2] + rot[2, 0] * x + rot[2, 1] * y + rot[2, 2] * z
                        xp = wx * cos_d + wy * sin_d
                        eta, eta_slope, fe = _elevation(
                            kind, phasor, wavenumber, x_start, x_step, active, elevation, elevation_slope, status, xp
                        )
                        hv, gx, gy, gz, fv = _wet_head(
                            kind, phasor, wavenumber, depth, x_start, x_step, active, z_min, table_head, table_slope,
                            status, cos_d, sin_d, rot, xp, wz, eta, eta_slope,
                        )  # fmt: skip
                        flags |= fe | fv
                    if e == 0:
                        cut_p = (x, y, z, hv, gx, gy, gz)
                    else:
                        cut_q = (x, y, z, hv, gx, gy, gz)
            # the wet pieces: the whole face (its moments precomputed), (a, p, q) for one wet corner, (a, b, p) and
            # (a, p, q) for two
            for k in range(1 if whole or single else 2):
                if whole:
                    u, v, w = a, b, c
                elif single or k == 1:
                    u, v, w = a, cut_p, cut_q
                else:
                    u, v, w = a, b, cut_p
                if not whole:
                    _add_moments(acc, u[0], u[1], u[2], v[0], v[1], v[2], w[0], w[1], w[2])
                if include_fk:
                    _add_fk(
                        acc, u[0], u[1], u[2], u[3], u[4], u[5], u[6], v[0], v[1], v[2], v[3], v[4], v[5], v[6],
                        w[0], w[1], w[2], w[3], w[4], w[5], w[6],
                    )  # fmt: skip
    if n_wet == 0 and n_cut == 0:
        flags |= DRY
    elif n_cut == 0 and n_wet == f1 - f0:
        flags |= SUBMERGED
    # hydrostatics: F = rho g R (p_z a + S' e), M = rho g R (p_z u + T' e), e = third row of R; plus Froude-Krylov
    rho_g = rho * g
    e0, e1, e2 = rot[2, 0], rot[2, 1], rot[2, 2]
    pz = pos[2]
    fx = pz * acc[0] + e0 * acc[3] + e1 * acc[6] + e2 * acc[9] + acc[_FK]
    fy = pz * acc[1] + e0 * acc[4] + e1 * acc[7] + e2 * acc[10] + acc[_FK + 1]
    fz = pz * acc[2] + e0 * acc[5] + e1 * acc[8] + e2 * acc[11] + acc[_FK + 2]
    mx = pz * acc[12] + e0 * acc[15] + e1 * acc[18] + e2 * acc[21] + acc[_FK + 3]
    my = pz * acc[13] + e0 * acc[16] + e1 * acc[19] + e2 * acc[22] + acc[_FK + 4]
    mz = pz * acc[14] + e0 * acc[17] + e1 * acc[20] + e2 * acc[23] + acc[_FK + 5]
    for a in range(3):
        out[a] = rho_g * (rot[a, 0] * fx + rot[a, 1] * fy + rot[a, 2] * fz)
        out[3 + a] = rho_g * (rot[a, 0] * mx + rot[a, 1] * my + rot[a, 2] * mz)
    return flags
