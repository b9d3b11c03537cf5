"""Scenes, their compilation to flat arrays, and the nonlinear MFM simulator (Beeman, RK4, scipy reference)."""

from ._compile import CompiledScene as CompiledScene
from ._compile import compile_scene as compile_scene
from ._jit import JIT as JIT
from ._linear import LinearModel as LinearModel
from ._linear import linearize as linearize
from ._linear import simulate_linear as simulate_linear
from ._scene import ControllerChoice as ControllerChoice
from ._scene import DeviceChoice as DeviceChoice
from ._scene import Outputs as Outputs
from ._scene import Radiation as Radiation
from ._scene import Scene as Scene
from ._scene import SceneError as SceneError
from ._scene import SeaState as SeaState
from ._scene import Solver as Solver
from ._scene import default_scene_path as default_scene_path
from ._simulate import SimulationDiverged as SimulationDiverged
from ._simulate import simulate as simulate
