"""The structural model of a device's members: 3D beam finite elements (Euler-Bernoulli or Timoshenko, consistent
mass, geometric stiffness), frames meshed from members, static and modal solutions, Craig-Bampton reduction with
inertia-relief vectors, the floating-frame inertia invariants, the geometric stiffness of a basis's own axial strain
and stress modes."""

from ._build import LumpedMass as LumpedMass
from ._build import MemberLine as MemberLine
from ._build import build_frame as build_frame
from ._element import NODE_DOFS as NODE_DOFS
from ._element import THEORIES as THEORIES
from ._element import BeamElement as BeamElement
from ._element import shape_functions as shape_functions
from ._frame import COMPONENTS as COMPONENTS
from ._frame import RIGID_LOADS as RIGID_LOADS
from ._frame import Frame as Frame
from ._frame import PointMass as PointMass
from ._frame import offset_map as offset_map
from ._frame import rigid_load_coordinates as rigid_load_coordinates
from ._geometric import axial_forces as axial_forces
from ._geometric import axial_geometric_stiffness as axial_geometric_stiffness
from ._invariants import Invariants as Invariants
from ._invariants import invariants as invariants
from ._material import MATERIALS as MATERIALS
from ._material import Material as Material
from ._reduction import INTERFACE_KINDS as INTERFACE_KINDS
from ._reduction import ModalBasis as ModalBasis
from ._reduction import craig_bampton as craig_bampton
from ._section import Section as Section
from ._section import member_axes as member_axes
from ._solve import free_dofs as free_dofs
from ._solve import natural_modes as natural_modes
from ._solve import static_response as static_response
from ._stress import StressModes as StressModes
from ._stress import StressPoint as StressPoint
from ._stress import default_points as default_points
from ._stress import stress_modes as stress_modes
from ._stress import von_mises as von_mises
