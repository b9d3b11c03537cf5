"""``SurfaceMesh``: a body's surface as triangles in the body frame, checked on construction."""

from __future__ import annotations

import os
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from ._clip import area_vectors
from ._displaced import Displaced, displaced
from ._errors import MeshError

if TYPE_CHECKING:  # pragma: no cover
    from .._hydrodata import HydroData
    from ._compare import MeshComparison

DEGENERATE_AREA: float = 1e-14
"""A face whose area is below this share of the square of the mesh's largest extent is degenerate."""


@dataclass(frozen=True, eq=False)
class SurfaceMesh:
    """A body's surface as a triangle mesh in the body frame.

    Parameters
    ----------
    vertices : ndarray (n_v, 3)
        Vertex coordinates [m] in the body frame: measured from the body's centre of mass, axes along the world
        axes in the body's reference configuration.
    faces : ndarray (n_f, 3) of int
        Vertex indices of each triangle, ordered so that the right-hand rule gives the outward normal.
    open_above : float or None
        None: the surface must be closed (every edge shared by exactly two faces). A height [m] (body frame):
        the surface may be open, but only along edges whose two vertices lie at or above it (a hull meshed up to
        some freeboard); such a mesh is only meaningful while the water stays below that height.
    name : str
        What the mesh is called in messages (the file it was read from).

    Raises
    ------
    MeshError
        On bad shapes or values, faces with a repeated or unknown vertex or no area, edges shared by more than two
        faces, neighbouring faces of opposite orientation, open edges (below ``open_above``), or faces oriented
        inwards (a negative enclosed volume). The message names the mesh, the faces and the vertices.
    """

    vertices: np.ndarray
    faces: np.ndarray
    open_above: float | None = None
    name: str = "mesh"

    def __post_init__(self) -> None:
        vertices = np.array(self.vertices, dtype=float)
        faces = np.array(self.faces)
        where = f"mesh {self.name!r}"
        if vertices.ndim != 2 or vertices.shape[1] != 3 or vertices.shape[0] < 4:
            raise MeshError(f"{where}: vertices must be an (n, 3) array with n >= 4; got shape {vertices.shape}")
        if not np.all(np.isfinite(vertices)):
            raise MeshError(f"{where}: vertices must be finite numbers [m]")
        if faces.ndim != 2 or faces.shape[1] != 3 or faces.shape[0] < 4:
            raise MeshError(f"{where}: faces must be an (n, 3) array of vertex indices with n >= 4; got {faces.shape}")
        if not np.issubdtype(faces.dtype, np.integer):
            raise MeshError(f"{where}: faces must hold integer vertex indices; got dtype {faces.dtype}")
        faces = faces.astype(np.int64)
        if self.open_above is not None and not np.isfinite(self.open_above):
            raise MeshError(f"{where}: open_above must be a finite height [m] or None; got {self.open_above!r}")
        vertices.setflags(write=False)
        faces.setflags(write=False)
        object.__setattr__(self, "vertices", vertices)
        object.__setattr__(self, "faces", faces)
        _check_faces(vertices, faces, where)
        _check_edges(vertices, faces, self.open_above, where)
        volume = self.enclosed_volume
        if not volume > 0:
            raise MeshError(
                f"{where}: the faces are oriented inwards (enclosed volume {volume:.6g} m^3): the right-hand rule on "
                "each face's vertex order must give the outward normal; reverse the order of every face"
            )

    # --- constructors -----------------------------------------------------------------------------
    @classmethod
    def from_stl(
        cls,
        path: str | os.PathLike[str],
        *,
        origin: Any = (0.0, 0.0, 0.0),
        scale: float = 1.0,
        open_above: float | None = None,
    ) -> SurfaceMesh:
        """Read an STL file (ASCII or binary) into a mesh in the body frame.

        Vertices that coincide (to 1e-9 of the mesh's size) are merged; the facets' stored normals are not used
        (the vertex order gives the normal, as the STL format prescribes).

        Parameters
        ----------
        path : path-like
            The ``.stl`` file.
        origin : (3,) float
            The body's centre of mass in the STL's frame [m] (after ``scale``): vertices become
            ``scale * stl - origin``.
        scale : float
            Factor from the file's units to metres (0.001 for a file in millimetres).
        open_above : float or None
            See :class:`SurfaceMesh` (a height in the body frame [m]).

        Raises
        ------
        FileNotFoundError
            If the file does not exist.
        MeshError
            If the file is not a readable STL of triangles, or the mesh fails the checks of :class:`SurfaceMesh`
            (the message names the file).
        """
        from ._stl import read_stl

        file = os.fspath(path)
        triangles = read_stl(file)
        origin_arr = np.asarray(origin, dtype=float).reshape(-1)
        if origin_arr.shape != (3,) or not np.all(np.isfinite(origin_arr)):
            raise MeshError(f"{file}: origin must be 3 finite coordinates [m]; got {origin!r}")
        if not (np.isfinite(scale) and scale > 0):
            raise MeshError(f"{file}: scale must be a positive number; got {scale!r}")
        vertices, faces = merge_vertices(triangles * scale - origin_arr, file)
        return cls(vertices, faces, open_above=open_above, name=file)

    # --- geometry ---------------------------------------------------------------------------------
    @property
    def n_faces(self) -> int:
        """Number of triangles."""
        return int(self.faces.shape[0])

    @property
    def triangles(self) -> np.ndarray:
        """Corner coordinates of every face, shape (n_f, 3, 3) [m], body frame."""
        return self.vertices[self.faces]

    @property
    def area(self) -> float:
        """Surface area [m^2]."""
        return float(np.sum(np.linalg.norm(area_vectors(self.triangles), axis=1)))

    @property
    def enclosed_volume(self) -> float:
        """Volume enclosed by a closed mesh [m^3] (sum of signed tetrahedra from the origin); for a mesh open
        above ``open_above``, the volume below that height."""
        if self.open_above is not None:
            shifted = self.triangles - np.array([0.0, 0.0, self.open_above])
            return displaced(shifted).volume
        t = self.triangles
        return float(np.sum(np.einsum("ij,ij->i", t[:, 0], np.cross(t[:, 1], t[:, 2]))) / 6.0)

    def posed(self, position: Any = (0.0, 0.0, 0.0), rotation: Any = None) -> np.ndarray:
        """Corner coordinates of every face in the world frame [m], shape (n_f, 3, 3), for the body's centre of mass
        at ``position`` [m] and its orientation ``rotation`` (3, 3) (body axes to world axes; identity by default).
        """
        p = np.asarray(position, dtype=float).reshape(3)
        r = np.eye(3) if rotation is None else np.asarray(rotation, dtype=float).reshape(3, 3)
        return self.triangles @ r.T + p

    def displaced(self, position: Any = (0.0, 0.0, 0.0), rotation: Any = None) -> Displaced:
        """The water displaced below the still water level z = 0 at a pose: volume, centre of buoyancy (world),
        waterplane area, centroid and second moments, and the hydrostatic stiffness through
        :meth:`Displaced.stiffness`. Exact for the mesh (divergence theorem on the clipped surface; see
        ``wecss.hydro.mesh._displaced``).

        Parameters
        ----------
        position : (3,) float
            World position of the body's centre of mass (the body frame's origin) [m].
        rotation : (3, 3) float, optional
            Rotation from body axes to world axes (identity by default).
        """
        return displaced(self.posed(position, rotation))

    def compare_with(self, hydro: HydroData, body: str) -> MeshComparison:
        """Volume, centre of buoyancy and hydrostatic stiffness of the mesh against a hydrodynamic database, at the
        database's pose of ``body`` (its centre of mass, unrotated). See :class:`MeshComparison`.

        Raises
        ------
        ValueError
            If the database has no body of that name.
        """
        from ._compare import compare

        return compare(self, hydro, body)

    def summary(self) -> str:
        """One line: name, faces, vertices, size."""
        lo, hi = self.vertices.min(axis=0), self.vertices.max(axis=0)
        closed = "closed" if self.open_above is None else f"open above z = {self.open_above:g} m"
        return (
            f"mesh {self.name!r}: {self.n_faces} triangles, {self.vertices.shape[0]} vertices, {closed}, "
            f"extent {np.round(hi - lo, 4).tolist()} m"
        )

    def __repr__(self) -> str:
        return self.summary()


def merge_vertices(triangles: np.ndarray, where: str) -> tuple[np.ndarray, np.ndarray]:
    """Vertices and faces of a triangle soup (n, 3, 3), merging corners closer than 1e-9 of the soup's size
    (quantised coordinates)."""
    points = triangles.reshape(-1, 3)
    size = float(np.max(points.max(axis=0) - points.min(axis=0)))
    if not size > 0:
        raise MeshError(f"{where}: all vertices coincide")
    quantum = 1e-9 * size
    keys = np.round((points - points.min(axis=0)) / quantum).astype(np.int64)
    _, first, inverse = np.unique(keys, axis=0, return_index=True, return_inverse=True)
    return points[first], inverse.reshape(-1, 3).astype(np.int64)


def _check_faces(vertices: np.ndarray, faces: np.ndarray, where: str) -> None:
    n_v = vertices.shape[0]
    bad = np.flatnonzero(np.any((faces < 0) | (faces >= n_v), axis=1))
    if bad.size:
        raise MeshError(f"{where}: faces {_list(bad)} name vertices outside 0..{n_v - 1}")
    repeated = np.flatnonzero(
        (faces[:, 0] == faces[:, 1]) | (faces[:, 1] == faces[:, 2]) | (faces[:, 2] == faces[:, 0])
    )
    if repeated.size:
        raise MeshError(
            f"{where}: {repeated.size} degenerate faces repeat a vertex (faces {_list(repeated)}, "
            f"face {repeated[0]} = {faces[repeated[0]].tolist()})"
        )
    size = float(np.max(vertices.max(axis=0) - vertices.min(axis=0)))
    area = np.linalg.norm(area_vectors(vertices[faces]), axis=1)
    tiny = np.flatnonzero(area <= DEGENERATE_AREA * size**2)
    if tiny.size:
        k = tiny[0]
        raise MeshError(
            f"{where}: {tiny.size} degenerate faces have no area (faces {_list(tiny)}; face {k} has corners "
            f"{np.round(vertices[faces[k]], 6).tolist()} m)"
        )


def _check_edges(vertices: np.ndarray, faces: np.ndarray, open_above: float | None, where: str) -> None:
    n_v = vertices.shape[0]
    start = faces.reshape(-1)
    end = faces[:, [1, 2, 0]].reshape(-1)
    owner = np.repeat(np.arange(faces.shape[0]), 3)
    key = start * n_v + end
    order = np.argsort(key, kind="stable")
    sorted_key = key[order]
    twice = np.flatnonzero(sorted_key[1:] == sorted_key[:-1])
    if twice.size:
        e = order[twice[0]]
        other = order[twice[0] + 1]
        a, b = int(start[e]), int(end[e])
        undirected = np.minimum(start, end) * n_v + np.maximum(start, end)
        shared = int(np.count_nonzero(undirected == undirected[e]))
        problem = (
            f"is shared by {shared} faces (a non-manifold edge)"
            if shared > 2
            else "is run in the same direction by both its faces (neighbouring faces of opposite orientation)"
        )
        raise MeshError(
            f"{where}: the edge between vertices {a} {np.round(vertices[a], 6).tolist()} and {b} "
            f"{np.round(vertices[b], 6).tolist()} {problem}: faces {int(owner[e])} and {int(owner[other])}"
        )
    reverse = end * n_v + start
    position = np.searchsorted(sorted_key, reverse)
    found = (position < key.size) & (sorted_key[np.minimum(position, key.size - 1)] == reverse)
    open_edges = np.flatnonzero(~found)
    if open_edges.size == 0:
        return
    if open_above is not None:
        low = np.minimum(vertices[start[open_edges], 2], vertices[end[open_edges], 2])
        open_edges = open_edges[low < open_above - 1e-12 * max(1.0, abs(open_above))]
        if open_edges.size == 0:
            return
    e = open_edges[0]
    a, b = int(start[e]), int(end[e])
    limit = "" if open_above is None else f" below open_above = {open_above:g} m"
    raise MeshError(
        f"{where}: the surface is not closed: {open_edges.size} edges{limit} belong to one face only, e.g. the "
        f"edge of face {int(owner[e])} between vertices {a} {np.round(vertices[a], 6).tolist()} and {b} "
        f"{np.round(vertices[b], 6).tolist()} m (give open_above to accept a hull open above some height)"
    )


def _list(index: np.ndarray, most: int = 5) -> str:
    shown = ", ".join(str(int(k)) for k in index[:most])
    return shown + (" ..." if index.size > most else "")
