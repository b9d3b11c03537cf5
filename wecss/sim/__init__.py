"""Runs: ``simulate(scene)`` for every runner (the nonlinear MFM equations by Beeman, RK4 or the scipy reference;
the linear model; the frequency-domain solution), the result Dataset every run returns, and the built-in runners
(``wecss.sim.runners``).

For convenience the scene types (``wecss.scene``), the compilation (``wecss.compiled``, ``wecss.control``) and the
linear model (``wecss.linear``) are re-exported here.
"""

from ..compiled import JIT as JIT
from ..compiled import CompiledScene as CompiledScene
from ..control import ControlledScene as ControlledScene
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
from ._dataset import build_result as build_result
from ._errors import ControllerTimeout as ControllerTimeout
from ._errors import PtoLimitExceeded as PtoLimitExceeded
from ._errors import SimulationDiverged as SimulationDiverged
from ._linear import simulate_linear as simulate_linear
from ._precompile import precompile as precompile
from ._progress import format_seconds as format_seconds
from ._record import Record as Record
from ._record import window_statistics as window_statistics
from ._reproduce import fit_difference as fit_difference
from ._reproduce import gains_difference as gains_difference
from ._reproduce import scene_from_result as scene_from_result
from ._simulate import simulate as simulate
from ._tolerance import StepChoice as StepChoice
from ._tolerance import choose_step as choose_step
