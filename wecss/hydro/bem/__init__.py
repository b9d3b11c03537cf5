"""BEM generation with Capytaine (optional extra ``bem``: ``pip install "wecss[bem]"``).

Axisymmetric floats described by their meridian profile (flat, hemispherical, rounded or conical bottom)
are meshed, solved together with all interactions, with lids against irregular frequencies, at omega = 0
and infinity besides the requested frequencies, and returned as a wecss hydrodynamic dataset about each
body's centre of mass. Capytaine is imported only when a mesh is built or a run starts.
"""

from ._geometry_file import GeometryFileError as GeometryFileError
from ._geometry_file import read_geometry as read_geometry
from ._mesh import DEFAULT_ASPECT_RATIO as DEFAULT_ASPECT_RATIO
from ._mesh import MIN_SECTORS as MIN_SECTORS
from ._mesh import hull_mesh as hull_mesh
from ._mesh import lid_mesh as lid_mesh
from ._mesh import sectors_for as sectors_for
from ._profile import BOTTOM_KINDS as BOTTOM_KINDS
from ._profile import AxisymmetricProfile as AxisymmetricProfile
from ._run import run_bem as run_bem
from ._spec import BEMSpec as BEMSpec
from ._spec import FloatBody as FloatBody
from ._spec import omega_grid as omega_grid
