"""Moving Frame Method multibody core: SE(3) helpers, bodies (with generalised modes, or flexible in a floating frame)
and joints, tree kinematics (B, Bdot, D) and dynamics."""

from ._dynamics import Dynamics as Dynamics
from ._dynamics import body_mass_matrix as body_mass_matrix
from ._dynamics import elastic_energy as elastic_energy
from ._dynamics import frame_centre as frame_centre
from ._dynamics import gravity_force as gravity_force
from ._dynamics import inertial_terms as inertial_terms
from ._dynamics import potential_energy as potential_energy
from ._dynamics import structural_force as structural_force
from ._elastic import Attachment as Attachment
from ._elastic import ElasticBody as ElasticBody
from ._hydrostatics import HydroCoupling as HydroCoupling
from ._kinematics import KinematicState as KinematicState
from ._kinematics import configuration_rate as configuration_rate
from ._kinematics import difference as difference
from ._kinematics import integrate as integrate
from ._kinematics import kinematics as kinematics
from ._loads import joint_reactions as joint_reactions
from ._modes import GeneralisedModes as GeneralisedModes
from ._mooring import Mooring as Mooring
from ._mooring import mooring_matrices as mooring_matrices
from ._pto import PTO as PTO
from ._pto import ActuatorPTO as ActuatorPTO
from ._pto import JointPTO as JointPTO
from ._se3 import cross3 as cross3
from ._se3 import hat as hat
from ._statics import EQUILIBRIUM_TOL as EQUILIBRIUM_TOL
from ._statics import EquilibriumError as EquilibriumError
from ._statics import StaticModel as StaticModel
from ._tree import Body as Body
from ._tree import Joint as Joint
from ._tree import Multibody as Multibody
from ._viscous import BodyDrag as BodyDrag
from ._viscous import MorisonElement as MorisonElement
