"""Test meshes with known geometry: a subdivided box, a revolved sphere, an icosphere."""

from __future__ import annotations

import math

import numpy as np

from wecss.hydro.mesh import SurfaceMesh, arc_points, revolve
from wecss.hydro.mesh._surface import merge_vertices


def box_mesh(lower, upper, divisions=(4, 3, 5), name: str = "box") -> SurfaceMesh:
    """A closed box with corners ``lower`` and ``upper`` (body frame) [m], each face split into a grid of
    rectangles of two triangles (``divisions`` cells along x, y, z), outward normals."""
    lo, hi = np.asarray(lower, float), np.asarray(upper, float)
    n = np.asarray(divisions, dtype=int)

    def point(index: np.ndarray) -> np.ndarray:  # grid node from integer indices (the same on every face)
        return lo + (hi - lo) * index / n

    soup = []
    for axis in range(3):
        u_axis, v_axis = (axis + 1) % 3, (axis + 2) % 3  # e_u x e_v = +e_axis
        for side in (0, 1):
            if side:
                a, b = u_axis, v_axis
            else:  # outward normal -e_axis: swap the pair
                a, b = v_axis, u_axis
            for i in range(n[a]):
                for j in range(n[b]):
                    k = np.zeros(3, dtype=int)
                    k[axis] = n[axis] * side
                    corners = []
                    for di, dj in ((0, 0), (1, 0), (1, 1), (0, 1)):
                        c = k.copy()
                        c[a] += i + di
                        c[b] += j + dj
                        corners.append(point(c))
                    soup.append([corners[0], corners[1], corners[2]])
                    soup.append([corners[0], corners[2], corners[3]])
    vertices, faces = merge_vertices(np.array(soup), name)
    return SurfaceMesh(vertices, faces, name=name)


def sphere_mesh(radius: float, segments: int = 22, sectors: int = 48, center=(0.0, 0.0, 0.0)) -> SurfaceMesh:
    """A sphere revolved from a meridian of two volume-preserving quarter arcs (the equator a vertex on the
    sphere): ``segments`` chords from pole to pole (even) and ``sectors`` sectors, 2 x sectors x (segments - 1)
    triangles (2,016 by default); centre at ``center`` (body frame) [m]. Its volume, the volume below its equator
    and its equator's area (radii scaled by ``radial_scale``) are the sphere's, to rounding."""
    half = segments // 2
    upper = arc_points((0.0, 0.0), radius, math.pi / 2, 0.0, half)
    lower = arc_points((0.0, 0.0), radius, 0.0, -math.pi / 2, half)
    meridian = np.concatenate([upper, lower[1:]])
    meridian[0, 0] = meridian[-1, 0] = 0.0
    mesh = revolve(meridian, sectors, name=f"sphere R {radius:g} m")
    return SurfaceMesh(mesh.vertices + np.asarray(center, float), mesh.faces, name=mesh.name)
