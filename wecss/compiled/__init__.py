"""A scene compiled to flat arrays once (the plant, the radiation memory, the wave components), without its
controller (``wecss.control`` attaches it). The kernels that read the arrays are in ``wecss.compiled.kernels``."""

from ._compile import MIN_STEPS_PER_PERIOD as MIN_STEPS_PER_PERIOD
from ._compile import CompiledScene as CompiledScene
from ._compile import clear_compile_cache as clear_compile_cache
from ._compile import compile_plant as compile_plant
from ._compile import fit_request as fit_request
from ._compile import initial_increments as initial_increments
from ._compile import make_radiation as make_radiation
from ._compile import make_waves as make_waves
from ._compile import with_linear_gains as with_linear_gains
from ._inputs import scene_inputs as scene_inputs
from ._jit import JIT as JIT
from ._plant import Plant as Plant
from ._plant import PtoKind as PtoKind
from ._plant import build_plant as build_plant
from ._plant import linear_damping as linear_damping
from ._plant import mooring_damping_matrix as mooring_damping_matrix
from ._pressure import DRY as DRY
from ._pressure import SUBMERGED as SUBMERGED
from ._pto_law import pto_control_force as pto_control_force
from ._pto_law import pto_gains as pto_gains
from ._pto_law import saturate as saturate
from ._radiation import RadiationArrays as RadiationArrays
from ._radiation import RadiationKind as RadiationKind
from ._radiation import RadiationSummary as RadiationSummary
from ._radiation import added_mass_correction as added_mass_correction
from ._radiation import from_impulse_response as from_impulse_response
from ._radiation import from_state_space as from_state_space
from ._radiation import interpolate_matrices as interpolate_matrices
from ._radiation import memory_response as memory_response
from ._radiation import no_radiation as no_radiation
from ._radiation import weighted_memory_response as weighted_memory_response
from ._viscous import TERM_COLUMNS as TERM_COLUMNS
from ._viscous import TERM_ROWS as TERM_ROWS
from ._wave_field import OUTSIDE_TABLE as OUTSIDE_TABLE
