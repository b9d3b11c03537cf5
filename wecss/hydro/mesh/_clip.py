"""Clipping a triangle mesh at a horizontal plane, in numpy (all faces at once).

A face is cut by the signed heights d = z - z_plane of its vertices, linearly along its edges: a vertex with d < 0
is wet, one with d >= 0 dry. A face with one wet vertex keeps the triangle at that vertex; a face with two keeps a
quadrilateral, split into two triangles from its first wet vertex. The pieces keep the face's orientation (the
cyclic order of its vertices), so their area vectors are the face's normal times their areas.
"""

from __future__ import annotations

import numpy as np

_NEXT = np.array([1, 2, 0])
_AFTER = np.array([2, 0, 1])


def clip_below(triangles: np.ndarray, plane_z: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """The parts of ``triangles`` below the plane z = ``plane_z``, as triangles.

    Parameters
    ----------
    triangles : ndarray (n, 3, 3)
        Corner coordinates [m] of each triangle (rows: corners in order; columns: x, y, z).
    plane_z : float
        Height of the cutting plane [m].

    Returns
    -------
    pieces : ndarray (m, 3, 3)
        The wet triangles: whole faces below the plane, the triangle or the two triangles of each cut face.
    source : ndarray (m,) of int
        Index of the face each piece comes from.
    """
    triangles = np.asarray(triangles, dtype=float)
    d = triangles[:, :, 2] - plane_z
    wet = d < 0.0
    count = wet.sum(axis=1)
    whole = np.flatnonzero(count == 3)
    pieces = [triangles[whole]]
    source = [whole]
    rows = np.arange(triangles.shape[0])

    one = np.flatnonzero(count == 1)  # the wet corner first: (a, cut a-b, cut a-c)
    if one.size:
        k = np.argmax(wet[one], axis=1)
        a, b, c = _corners(triangles[one], k)
        da, db, dc = _heights(d[one], k)
        pieces.append(np.stack([a, _cut(a, b, da, db), _cut(a, c, da, dc)], axis=1))
        source.append(rows[one])

    two = np.flatnonzero(count == 2)  # the dry corner last: (a, b, cut b-c, cut c-a)
    if two.size:
        k = _NEXT[np.argmin(wet[two], axis=1)]
        a, b, c = _corners(triangles[two], k)
        da, db, dc = _heights(d[two], k)
        p_bc = _cut(b, c, db, dc)
        p_ca = _cut(a, c, da, dc)
        pieces.append(np.stack([a, b, p_bc], axis=1))
        pieces.append(np.stack([a, p_bc, p_ca], axis=1))
        source.extend([rows[two], rows[two]])
    return np.concatenate(pieces), np.concatenate(source)


def _corners(tri: np.ndarray, first: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The corners of each triangle in cyclic order starting at corner ``first``."""
    index = np.arange(tri.shape[0])
    return tri[index, first], tri[index, _NEXT[first]], tri[index, _AFTER[first]]


def _heights(d: np.ndarray, first: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    index = np.arange(d.shape[0])
    return d[index, first], d[index, _NEXT[first]], d[index, _AFTER[first]]


def _cut(wet: np.ndarray, dry: np.ndarray, d_wet: np.ndarray, d_dry: np.ndarray) -> np.ndarray:
    """The point of the edge from a wet corner (d < 0) to a dry one (d >= 0) where the linear height is zero."""
    s = d_wet / (d_wet - d_dry)
    return wet + s[:, None] * (dry - wet)


def area_vectors(triangles: np.ndarray) -> np.ndarray:
    """Area times unit normal of each triangle (right-hand rule on the corner order) [m^2], shape (n, 3)."""
    a, b, c = triangles[:, 0], triangles[:, 1], triangles[:, 2]
    return 0.5 * np.cross(b - a, c - a)


def edge_midpoints(triangles: np.ndarray) -> np.ndarray:
    """Midpoints of the three edges of each triangle, shape (n, 3, 3): the nodes of a rule exact for quadratics
    (the integral of a polynomial f of degree <= 2 over a triangle is its area times the mean of f there)."""
    return 0.5 * (triangles + triangles[:, _NEXT])
