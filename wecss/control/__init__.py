"""PTO control: the controller interface (what a controller declares, the context it is set up with, the
measurement it gets), the registry of controllers by name (entry-point group ``wecss.controllers``), and the
attachment of a controller to a compiled scene (:class:`ControlledScene`, what a runner runs).

The design tools are ``wecss.control.design`` (power bound, optimal damping and spring-damper), the machinery of
estimation and model predictive control ``wecss.control.mpc``.
"""

from ..compiled import pto_control_force as pto_control_force
from ._attach import ControlledScene as ControlledScene
from ._attach import attach_controller as attach_controller
from ._attach import compile_scene as compile_scene
from ._attach import control_context as control_context
from ._protocol import ControlContext as ControlContext
from ._protocol import Controller as Controller
from ._protocol import Measurement as Measurement
from ._provenance import UNREGISTERED as UNREGISTERED
from ._provenance import controller_attrs as controller_attrs
from ._provenance import registered_name as registered_name
from ._registry import ENTRY_POINT_GROUP as ENTRY_POINT_GROUP
from ._registry import available as available
from ._registry import check_controller as check_controller
from ._registry import create as create
