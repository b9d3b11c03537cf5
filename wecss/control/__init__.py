"""PTO control: the controller protocol, the context and measurement a controller receives, and the registry of
controllers by name (entry-point group ``wecss.controllers``)."""

from ._protocol import ControlContext as ControlContext
from ._protocol import Controller as Controller
from ._protocol import Measurement as Measurement
from ._registry import ENTRY_POINT_GROUP as ENTRY_POINT_GROUP
from ._registry import available as available
from ._registry import create as create
