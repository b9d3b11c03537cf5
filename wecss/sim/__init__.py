"""Runs: ``simulate(scene)`` for the nonlinear MFM equations (Beeman, RK4, scipy reference), the linear model and
the frequency-domain solution, and the result Dataset every run returns.

For convenience the scene types (``wecss.scene``), the compilation (``wecss.compiled``) and the linear model
(``wecss.linear``) are re-exported here.
"""

from ..compiled import JIT as JIT
from ..compiled import CompiledScene as CompiledScene
from ..control import compile_scene as compile_scene
from ..linear import LinearModel as LinearModel
from ..linear import linearize as linearize
from ..scene import ControllerChoice as ControllerChoice
from ..scene import DeviceChoice as DeviceChoice
from ..scene import Outputs as Outputs
from ..scene import Radiation as Radiation
from ..scene import Scene as Scene
from ..scene import SceneError as SceneError
from ..scene import SeaState as SeaState
from ..scene import Solver as Solver
from ..scene import default_scene_path as default_scene_path
from ._linear import simulate_linear as simulate_linear
from ._nonlinear import PtoLimitExceeded as PtoLimitExceeded
from ._nonlinear import SimulationDiverged as SimulationDiverged
from ._progress import format_seconds as format_seconds
from ._result import Record as Record
from ._result import build_result as build_result
from ._result import window_statistics as window_statistics
from ._simulate import simulate as simulate
