"""PTO control: the controller interface (what a controller declares, the context it is set up with, the
measurement it gets), the registry of controllers by name (entry-point group ``wecss.controllers``), and the
attachment of a controller to a compiled scene."""

from ..compiled import pto_control_force as pto_control_force
from ._attach import ControlledScene as ControlledScene
from ._attach import attach_controller as attach_controller
from ._attach import compile_scene as compile_scene
from ._attach import control_context as control_context
from ._estimation import ExcitationEstimator as ExcitationEstimator
from ._estimation import measured_rms as measured_rms
from ._estimation import pto_referred as pto_referred
from ._frequency_design import LinearGains as LinearGains
from ._frequency_design import PowerBound as PowerBound
from ._frequency_design import mean_power as mean_power
from ._frequency_design import optimal_damping as optimal_damping
from ._frequency_design import optimal_spring_damper as optimal_spring_damper
from ._frequency_design import power_bound as power_bound
from ._frequency_design import pto_response as pto_response
from ._horizon import HorizonModel as HorizonModel
from ._observer import StateObserver as StateObserver
from ._power_qp import PowerQP as PowerQP
from ._prediction import ARPredictor as ARPredictor
from ._protocol import ControlContext as ControlContext
from ._protocol import Controller as Controller
from ._protocol import Measurement as Measurement
from ._qp_solvers import CvxpyPath as CvxpyPath
from ._qp_solvers import OsqpPath as OsqpPath
from ._qp_solvers import Solution as Solution
from ._registry import ENTRY_POINT_GROUP as ENTRY_POINT_GROUP
from ._registry import available as available
from ._registry import check_controller as check_controller
from ._registry import create as create
