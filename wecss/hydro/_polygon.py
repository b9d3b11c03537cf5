"""The area of a regular polygon against its circle's, for meshes revolved with straight sectors (the BEM meshes of
``wecss.hydro.bem`` and the surface meshes of ``wecss.hydro.mesh``)."""

from __future__ import annotations

import math


def radial_scale(sectors: int) -> float:
    """Factor on radii that gives a regular ``sectors``-gon the area of its circle, sqrt(theta / sin theta) with
    theta = 2 pi / sectors [-]."""
    theta = 2 * math.pi / sectors
    return math.sqrt(theta / math.sin(theta))
