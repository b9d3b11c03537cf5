"""A device's body surface meshes (``[[meshes]]`` in its spec), for the body-exact hydrostatic and Froude-Krylov
forces: an STL file, or an axisymmetric float of a BEM geometry file revolved with a freeboard above its waterline.

Spec entries::

    [[meshes]]
    body = "float"                 # the device's body
    stl = "Float.STL"              # a file (relative to the spec's folder), in metres after ``scale``
    position = [0.0, 0.0, 0.0]     # where the STL's origin lies in the world, reference configuration [m]
    scale = 1.0                    # factor from the file's units to metres (optional)
    open_above = 0.1               # a hull open above this height of the body frame [m] (optional)

    [[meshes]]
    body = "float_1"
    geometry = "m4-111"            # a BEM geometry file (wecss.hydro.bem.read_geometry): a shipped name or a path
    freeboard = 0.05               # height of the float's wall above the still water line [m]
    panel_size = 0.01              # optional (default: the waterline radius / 6); sectors optional

The float of a geometry file is its body of the device body's ``hydro_body`` name.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:  # pragma: no cover
    from ..hydro.mesh import SurfaceMesh
    from ..multibody import Multibody

MESH_KEYS = {"body", "stl", "position", "scale", "open_above", "geometry", "freeboard", "panel_size", "sectors"}
"""Accepted keys of a ``[[meshes]]`` entry."""


@dataclass(frozen=True)
class BodyMesh:
    """A body's surface mesh as its device spec declares it (see the module docstring); :meth:`surface` builds it.

    Attributes
    ----------
    body : str
        The device's body.
    stl : Path or None
        An STL file, with ``position`` [m] (world position of the file's origin in the reference configuration),
        ``scale`` and ``open_above`` [m] (``wecss.hydro.mesh.SurfaceMesh``).
    geometry : Path or None
        A BEM geometry file whose float of the body's hydro_body is revolved with ``freeboard`` [m] above the
        still water line, panels of ``panel_size`` [m] and ``sectors`` (both optional).
    """

    body: str
    stl: Path | None = None
    position: tuple[float, float, float] = (0.0, 0.0, 0.0)
    scale: float = 1.0
    open_above: float | None = None
    geometry: Path | None = None
    freeboard: float | None = None
    panel_size: float | None = None
    sectors: int | None = None

    @property
    def files(self) -> tuple[Path, ...]:
        """The files the mesh is read from."""
        return tuple(p for p in (self.stl, self.geometry) if p is not None)

    def surface(self, model: Multibody) -> SurfaceMesh:
        """The mesh in the body frame (from the body's centre of mass in the reference configuration).

        Raises
        ------
        ValueError
            If the geometry file has no float for the body's hydro_body; ``wecss.hydro.mesh.MeshError`` if the
            mesh fails its checks; FileNotFoundError if a file is missing.
        """
        from ..hydro.bem import read_geometry
        from ..hydro.mesh import SurfaceMesh, revolve_profile

        body = model.bodies[list(model.body_names).index(self.body)]
        com = np.asarray(body.center_of_mass, dtype=float)
        if self.stl is not None:
            origin = com - np.asarray(self.position)  # the centre of mass in the file's frame
            return SurfaceMesh.from_stl(self.stl, origin=origin, scale=self.scale, open_above=self.open_above)
        assert self.geometry is not None and self.freeboard is not None
        spec = read_geometry(self.geometry)
        floats = {f.name: f for f in spec.bodies}
        name = body.hydro_body or self.body
        if name not in floats:
            raise ValueError(
                f"mesh of body {self.body!r}: the geometry file {str(self.geometry)!r} has no float {name!r}; it has "
                f"{', '.join(floats)}"
            )
        float_body = floats[name]
        mesh = revolve_profile(
            float_body.profile,
            self.freeboard,
            center_of_mass_z=float(com[2]),
            panel_size=self.panel_size,
            sectors=self.sectors,
            name=f"{self.geometry.stem}:{name} (freeboard {self.freeboard:g} m)",
        )
        axis = np.array([float_body.position[0], float_body.position[1], com[2]])
        offset = axis - com  # the float's axis from the body's centre of mass (zero when it lies on the axis)
        if np.any(offset):
            return SurfaceMesh(mesh.vertices + offset, mesh.faces, name=mesh.name)
        return mesh


def read_meshes(spec: Mapping[str, Any], folder: Path | None, model: Multibody) -> tuple[BodyMesh, ...]:
    """The spec's ``[[meshes]]`` entries (empty when it has none); relative paths are taken from ``folder``.

    Raises
    ------
    ValueError
        On unknown or missing keys, an unknown body, two meshes of one body, neither or both of ``stl`` and
        ``geometry``, or bad values (the message names the entry, the key and what is accepted).
    """
    from ..hydro import DATA_DIR

    entries = spec.get("meshes", [])
    if not isinstance(entries, list):
        raise ValueError(f"device {spec.get('name')!r}: meshes must be an array of tables ([[meshes]])")
    out: list[BodyMesh] = []
    names = list(model.body_names)
    for k, entry in enumerate(entries):
        where = f"device {spec.get('name')!r}, meshes[{k}]"
        if not isinstance(entry, Mapping):
            raise ValueError(f"{where}: must be a table; got {entry!r}")
        unknown = sorted(set(entry) - MESH_KEYS)
        if unknown:
            raise ValueError(f"{where}: unknown keys {unknown}; accepted: {sorted(MESH_KEYS)}")
        body = entry.get("body")
        if body not in names:
            raise ValueError(f"{where}: body {body!r} is not a body of the device; bodies: {', '.join(names)}")
        if ("stl" in entry) == ("geometry" in entry):
            raise ValueError(f"{where}: give either stl (a file) or geometry (a BEM geometry file and a freeboard)")
        if "stl" in entry:
            wrong = sorted({"freeboard", "panel_size", "sectors"} & set(entry))
            if wrong:
                raise ValueError(f"{where}: {wrong} apply to a geometry file's float, not to an STL")
            x, y, z = _floats(entry.get("position", [0.0, 0.0, 0.0]), 3, f"{where}: position [m]")
            position = (x, y, z)
            scale = _positive(entry.get("scale", 1.0), f"{where}: scale")
            open_above = entry.get("open_above")
            if open_above is not None:
                open_above = _floats([open_above], 1, f"{where}: open_above [m]")[0]
            out.append(BodyMesh(body, stl=_path(entry["stl"], folder), position=position, scale=scale,
                                open_above=open_above))  # fmt: skip
        else:
            wrong = sorted({"position", "scale", "open_above"} & set(entry))
            if wrong:
                raise ValueError(f"{where}: {wrong} apply to an STL file, not to a geometry file's float")
            if "freeboard" not in entry:
                raise ValueError(f"{where}: a geometry file's float needs freeboard [m] (the wall above the waterline)")
            geometry = str(entry["geometry"])
            shipped = DATA_DIR / f"{geometry}.toml"
            path = shipped if ("/" not in geometry and not geometry.endswith(".toml")) else _path(geometry, folder)
            sectors = entry.get("sectors")
            if sectors is not None and (isinstance(sectors, bool) or not isinstance(sectors, int) or sectors < 3):
                raise ValueError(f"{where}: sectors must be an integer >= 3; got {sectors!r}")
            panel = entry.get("panel_size")
            out.append(
                BodyMesh(
                    body,
                    geometry=path,
                    freeboard=_positive(entry["freeboard"], f"{where}: freeboard [m]"),
                    panel_size=None if panel is None else _positive(panel, f"{where}: panel_size [m]"),
                    sectors=sectors,
                )
            )
    twice = sorted({m.body for m in out if [n.body for n in out].count(m.body) > 1})
    if twice:
        raise ValueError(f"device {spec.get('name')!r}: more than one [[meshes]] entry for bodies {twice}")
    return tuple(out)


def _path(value: Any, folder: Path | None) -> Path:
    if not isinstance(value, str) or not value:
        raise ValueError(f"a mesh file must be a path (string); got {value!r}")
    path = Path(value)
    return (folder / path).resolve() if folder is not None and not path.is_absolute() else path


def _floats(value: Any, size: int, what: str) -> tuple[float, ...]:
    try:
        arr = np.asarray(value, dtype=float).reshape(-1)
    except (TypeError, ValueError):
        raise ValueError(f"{what} must be {size} numbers; got {value!r}") from None
    if arr.size != size or not np.all(np.isfinite(arr)):
        raise ValueError(f"{what} must be {size} finite numbers; got {value!r}")
    return tuple(float(x) for x in arr)


def _positive(value: Any, what: str) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float) or not (math.isfinite(value) and value > 0):
        raise ValueError(f"{what} must be a positive number; got {value!r}")
    return float(value)
