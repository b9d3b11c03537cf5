"""The displaced volume of a mesh at a pose below z = 0: volume, centre of buoyancy, waterplane, stiffness.

Exact for the mesh: the surface below z = 0 (faces clipped, see ``_clip``) and the waterplane at z = 0 close the
displaced volume, and every quantity is a surface integral over the wet faces only, by the divergence theorem with
fields that vanish on z = 0 or are vertical there:

- volume V = int z n_z dS (field z e_z), V x_B = int x z n_z dS, V y_B = int y z n_z dS, V z_B = int z^2/2 n_z dS;
- waterplane (normal +z on z = 0): A_w = -int n_z dS, int_wp x dA = -int x n_z dS, and so on to the second
  moments, since the fields e_z, x e_z, x^2 e_z ... have no divergence.

The integrands are polynomials of degree at most 2 on each flat triangle, which the edge-midpoint rule integrates
exactly, so the results are exact to rounding (waterplanes of several loops, holes and all).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...constants import GRAVITY, RHO_WATER
from ._clip import area_vectors, clip_below, edge_midpoints


@dataclass(frozen=True)
class Displaced:
    """The water a body displaces at one pose (world axes, still water level z = 0).

    Attributes
    ----------
    volume : float
        Displaced volume [m^3].
    center_of_buoyancy : ndarray (3,)
        Centroid of the displaced volume [m], world frame.
    waterplane_area : float
        Area of the body's section at z = 0 [m^2].
    waterplane_center : ndarray (2,)
        Centroid (x, y) of the waterplane [m], world frame (NaN when the waterplane is empty).
    waterplane_inertia : ndarray (3,)
        Second moments of the waterplane area about its centroid [m^4]: I_xx = int (y - y_f)^2 dA (about the
        x axis), I_yy = int (x - x_f)^2 dA, I_xy = int (x - x_f)(y - y_f) dA.
    wetted_area : float
        Area of the hull below z = 0 [m^2].
    """

    volume: float
    center_of_buoyancy: np.ndarray
    waterplane_area: float
    waterplane_center: np.ndarray
    waterplane_inertia: np.ndarray
    wetted_area: float

    def stiffness(self, reference_point: np.ndarray, *, rho: float = RHO_WATER, g: float = GRAVITY) -> np.ndarray:
        """The hydrostatic stiffness of the pressure force alone (no weight) about ``reference_point`` [m], in
        the DOF order Surge, Sway, Heave, Roll, Pitch, Yaw, for small motions about this pose (rotations about
        the reference point, world axes): the schema's ``hydrostatic_stiffness`` (Newman, Marine Hydrodynamics,
        section 6.16, without the weight's terms).

        K33 = rho g A_w, K34 = rho g int y' dA, K35 = -rho g int x' dA, K44 = rho g (int y'^2 dA + V z'_B),
        K45 = -rho g int x' y' dA, K55 = rho g (int x'^2 dA + V z'_B), K46 = -rho g V x'_B, K56 = -rho g V y'_B,
        with x', y', z' measured from the reference point; symmetric in the heave-roll-pitch block.

        Returns
        -------
        ndarray (6, 6)
            [N/m, N/rad, N m/m, N m/rad] as the DOFs pair.
        """
        p = np.asarray(reference_point, dtype=float).reshape(3)
        rho_g = rho * g
        area = self.waterplane_area
        if area > 0:
            xf, yf = self.waterplane_center[0] - p[0], self.waterplane_center[1] - p[1]
        else:
            xf = yf = 0.0
        ixx, iyy, ixy = self.waterplane_inertia
        sx, sy = area * xf, area * yf  # first moments about the reference point
        b = self.center_of_buoyancy - p
        k = np.zeros((6, 6))
        k[2, 2] = rho_g * area
        k[2, 3] = k[3, 2] = rho_g * sy
        k[2, 4] = k[4, 2] = -rho_g * sx
        k[3, 3] = rho_g * (ixx + area * yf**2 + self.volume * b[2])
        k[4, 4] = rho_g * (iyy + area * xf**2 + self.volume * b[2])
        k[3, 4] = k[4, 3] = -rho_g * (ixy + area * xf * yf)
        k[3, 5] = -rho_g * self.volume * b[0]
        k[4, 5] = -rho_g * self.volume * b[1]
        return k


def displaced(triangles: np.ndarray) -> Displaced:
    """The displaced volume below z = 0 of the closed surface whose faces are ``triangles`` (n, 3, 3) [m], world
    frame. See the module docstring."""
    pieces, _ = clip_below(triangles, 0.0)
    n = area_vectors(pieces)
    nz = n[:, 2]
    mid = edge_midpoints(pieces)
    x, y, z = mid[..., 0], mid[..., 1], mid[..., 2]

    def integral(values: np.ndarray) -> float:  # int f n_z dS for f given at the edge midpoints
        return float(np.sum(nz * values.mean(axis=1)))

    volume = integral(z)
    if volume > 0:
        center = np.array([integral(x * z), integral(y * z), integral(0.5 * z * z)]) / volume
    else:
        center = np.full(3, np.nan)
    area = -float(np.sum(nz))
    if area > 0:
        xf, yf = -integral(x) / area, -integral(y) / area
        ixx = -integral(y * y) - area * yf**2
        iyy = -integral(x * x) - area * xf**2
        ixy = -integral(x * y) - area * xf * yf
    else:
        xf = yf = np.nan
        ixx = iyy = ixy = 0.0
    return Displaced(
        volume=volume,
        center_of_buoyancy=center,
        waterplane_area=area,
        waterplane_center=np.array([xf, yf]),
        waterplane_inertia=np.array([ixx, iyy, ixy]),
        wetted_area=float(np.sum(np.linalg.norm(n, axis=1))),
    )
