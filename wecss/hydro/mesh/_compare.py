"""A mesh against a hydrodynamic database: volume, centre of buoyancy, hydrostatic stiffness."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np

if TYPE_CHECKING:  # pragma: no cover
    from .._hydrodata import HydroData
    from ._displaced import Displaced


class _Mesh(Protocol):
    """What :func:`compare` reads of a mesh (a ``SurfaceMesh``)."""

    @property
    def name(self) -> str: ...

    def displaced(self, position: Any = ..., rotation: Any = ...) -> Displaced: ...


VOLUME_TOLERANCE: float = 1e-4
"""Relative difference of displaced volume up to which a mesh and a database agree (:meth:`MeshComparison.agrees`)."""

STIFFNESS_TOLERANCE: float = 1e-3
"""Relative difference of the heave, roll and pitch hydrostatic stiffness up to which they agree."""

BUOYANCY_TOLERANCE: float = 1e-3
"""Distance between the centres of buoyancy, over the cube root of the volume, up to which they agree."""

_STIFFNESS_DOFS = ("Heave", "Roll", "Pitch")


@dataclass(frozen=True)
class MeshComparison:
    """A body's mesh against its database, at the database's pose of the body (centre of mass, unrotated).

    Attributes
    ----------
    body : str
        The database's body.
    mesh_name : str
    volume : (float, float)
        Displaced volume of the mesh and of the database [m^3].
    volume_difference : float
        (mesh - database) / database [-].
    center_of_buoyancy : (ndarray, ndarray)
        Centres of buoyancy of the mesh and the database [m], world frame.
    buoyancy_offset : float
        Distance between them over the cube root of the database's volume [-].
    stiffness : dict of str to (float, float)
        Heave, Roll and Pitch diagonal hydrostatic stiffness (pressure only, about the database's reference point)
        of the mesh and the database, for the DOFs the database holds.
    stiffness_difference : dict of str to float
        (mesh - database) / database for each of them [-] (NaN where the database's value is 0).
    """

    body: str
    mesh_name: str
    volume: tuple[float, float]
    volume_difference: float
    center_of_buoyancy: tuple[np.ndarray, np.ndarray]
    buoyancy_offset: float
    stiffness: dict[str, tuple[float, float]]
    stiffness_difference: dict[str, float]

    def disagreements(
        self,
        *,
        volume: float = VOLUME_TOLERANCE,
        stiffness: float = STIFFNESS_TOLERANCE,
        buoyancy: float = BUOYANCY_TOLERANCE,
    ) -> list[str]:
        """What differs by more than the tolerances (relative), one sentence each (empty when they agree)."""
        out = []
        if not abs(self.volume_difference) <= volume:
            out.append(
                f"displaced volume {self.volume[0]:.6g} m^3 against the database's {self.volume[1]:.6g} m^3 "
                f"({self.volume_difference:+.2e}, tolerance {volume:.0e})"
            )
        if not self.buoyancy_offset <= buoyancy:
            mesh, data = self.center_of_buoyancy
            out.append(
                f"centre of buoyancy {np.round(mesh, 6).tolist()} m against {np.round(data, 6).tolist()} m "
                f"({self.buoyancy_offset:.2e} of the volume's cube root, tolerance {buoyancy:.0e})"
            )
        for dof, diff in self.stiffness_difference.items():
            if not abs(diff) <= stiffness:
                mesh_k, data_k = self.stiffness[dof]
                out.append(
                    f"{dof} hydrostatic stiffness {mesh_k:.6g} against {data_k:.6g} ({diff:+.2e}, tolerance "
                    f"{stiffness:.0e})"
                )
        return out

    def agrees(self, **tolerances: float) -> bool:
        """True when nothing differs by more than the tolerances (keywords of :meth:`disagreements`)."""
        return not self.disagreements(**tolerances)

    def __str__(self) -> str:
        parts = [f"volume {self.volume_difference:+.2e}", f"centre of buoyancy {self.buoyancy_offset:.2e}"]
        parts += [f"{dof} stiffness {diff:+.2e}" for dof, diff in self.stiffness_difference.items()]
        return f"mesh {self.mesh_name!r} against the database's body {self.body!r}: " + ", ".join(parts)


def compare(mesh: _Mesh, hydro: HydroData, body: str) -> MeshComparison:
    """See :meth:`SurfaceMesh.compare_with`."""
    if body not in hydro.bodies:
        raise ValueError(f"the database has no body {body!r}; bodies: {', '.join(hydro.bodies)}")
    ds = hydro.dataset
    b = hydro.bodies.index(body)
    center_of_mass = np.asarray(ds.center_of_mass.values[b], dtype=float)
    reference = np.asarray(ds.reference_point.values[b], dtype=float)
    data_volume = float(ds.displaced_volume.values[b])
    data_buoyancy = np.asarray(ds.center_of_buoyancy.values[b], dtype=float)
    at_rest = mesh.displaced(center_of_mass)
    k_mesh = at_rest.stiffness(reference, rho=hydro.rho, g=hydro.g)
    dofs = hydro.dofs
    stiffness: dict[str, tuple[float, float]] = {}
    difference: dict[str, float] = {}
    for index, name in enumerate(("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")):
        if name not in _STIFFNESS_DOFS:
            continue
        dof = f"{body}__{name}"
        if dof not in dofs:
            continue
        i = dofs.index(dof)
        data_k = float(ds.hydrostatic_stiffness.values[i, i])
        mesh_k = float(k_mesh[index, index])
        stiffness[name] = (mesh_k, data_k)
        difference[name] = (mesh_k - data_k) / data_k if data_k != 0 else float("nan")
    scale = data_volume ** (1 / 3) if data_volume > 0 else 1.0
    return MeshComparison(
        body=body,
        mesh_name=mesh.name,
        volume=(at_rest.volume, data_volume),
        volume_difference=(at_rest.volume - data_volume) / data_volume if data_volume else float("nan"),
        center_of_buoyancy=(at_rest.center_of_buoyancy, data_buoyancy),
        buoyancy_offset=float(np.linalg.norm(at_rest.center_of_buoyancy - data_buoyancy) / scale),
        stiffness=stiffness,
        stiffness_difference=difference,
    )
