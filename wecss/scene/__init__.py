"""Scenes: everything one run needs (device, sea state, controller, solver, radiation, outputs), declared in TOML
or as frozen (hashable) dataclasses and validated on construction; and the registry of runners that
``solver.method`` names."""

from ._errors import SceneError as SceneError
from ._hydrodynamics import Hydrodynamics as Hydrodynamics
from ._hydrodynamics import Initial as Initial
from ._paths import plain_copy as plain_copy
from ._paths import set_path as set_path
from ._runners import RADIATION_METHODS as RADIATION_METHODS
from ._runners import Capabilities as Capabilities
from ._runners import Runner as Runner
from ._runners import available_runners as available_runners
from ._runners import register_runner as register_runner
from ._runners import runner as runner
from ._runners import unregister_runner as unregister_runner
from ._scene import EXPLICIT_RUNNER as EXPLICIT_RUNNER
from ._scene import LINEAR_HOLDS as LINEAR_HOLDS
from ._scene import OUTPUT_GROUPS as OUTPUT_GROUPS
from ._scene import SEA_KINDS as SEA_KINDS
from ._scene import ControllerChoice as ControllerChoice
from ._scene import DeviceChoice as DeviceChoice
from ._scene import Outputs as Outputs
from ._scene import Radiation as Radiation
from ._scene import Scene as Scene
from ._scene import SeaState as SeaState
from ._scene import Solver as Solver
from ._scene import default_scene_path as default_scene_path
from ._scene import resolve_time as resolve_time
