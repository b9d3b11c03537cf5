"""The built-in runners (``solver.method``), registered under the entry-point group ``wecss.runners``.

Each is an instance of a :class:`wecss.scene.Runner`; the fixed-step integrators subclass
:class:`FixedStepRunner`, which owns the time loop (a new integrator gives the kernel that advances a chunk of
steps; see ``docs/architecture.md``). The pieces such a kernel uses are here too: the loop's state and settings,
the recorder, the checks, the radiation memory's history and advance; the equations of motion themselves are
``wecss.compiled.kernels.configure`` and ``respond``.
"""

from ._alpha import GENERALIZED_ALPHA as GENERALIZED_ALPHA
from ._alpha import GeneralizedAlphaRunner as GeneralizedAlphaRunner
from ._beeman import BEEMAN as BEEMAN
from ._beeman import Beeman as Beeman
from ._explicit import BEEMAN_EXPLICIT as BEEMAN_EXPLICIT
from ._explicit import BeemanExplicit as BeemanExplicit
from ._fixed_step import FixedStepRunner as FixedStepRunner
from ._frequency import FREQUENCY as FREQUENCY
from ._frequency import FrequencyDomain as FrequencyDomain
from ._linear import LINEAR as LINEAR
from ._linear import LinearRunner as LinearRunner
from ._loop import Chunk as Chunk
from ._loop import LoopState as LoopState
from ._loop import LoopStatus as LoopStatus
from ._loop import StepSettings as StepSettings
from ._loop import Store as Store
from ._loop import out_of_bounds as out_of_bounds
from ._loop import passes_stroke_limit as passes_stroke_limit
from ._loop import record_step as record_step
from ._memory import block_history as block_history
from ._memory import memory_advance as memory_advance
from ._reference import REFERENCE as REFERENCE
from ._reference import ReferenceSolver as ReferenceSolver
from ._rk4 import RK4 as RK4
from ._rk4 import Rk4 as Rk4
