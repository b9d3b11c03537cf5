"""Body surface meshes: triangles in the body frame read from STL files or revolved from the axisymmetric profiles,
checked (closed, consistently oriented, no degenerate faces), clipped at the still water level, with their
displaced volume, waterplane and hydrostatic stiffness exact for the mesh, and compared with a hydrodynamic
database (numpy only; the per-step pressure kernels are in ``wecss.compiled``)."""

from .._polygon import radial_scale as radial_scale
from ._clip import area_vectors as area_vectors
from ._clip import clip_below as clip_below
from ._clip import edge_midpoints as edge_midpoints
from ._compare import BUOYANCY_TOLERANCE as BUOYANCY_TOLERANCE
from ._compare import STIFFNESS_TOLERANCE as STIFFNESS_TOLERANCE
from ._compare import VOLUME_TOLERANCE as VOLUME_TOLERANCE
from ._compare import MeshComparison as MeshComparison
from ._displaced import Displaced as Displaced
from ._errors import MeshError as MeshError
from ._revolve import MIN_SECTORS as MIN_SECTORS
from ._revolve import PANELS_PER_RADIUS as PANELS_PER_RADIUS
from ._revolve import arc_points as arc_points
from ._revolve import polyline_volume as polyline_volume
from ._revolve import revolve as revolve
from ._revolve import revolve_profile as revolve_profile
from ._stl import read_stl as read_stl
from ._stl import write_stl as write_stl
from ._surface import SurfaceMesh as SurfaceMesh
