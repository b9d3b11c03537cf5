"""A scene compiled to flat arrays once (the plant, the radiation memory, the wave components, the controller),
and the kernels that read them: the MFM equations of motion on arrays, compiled with numba when available."""

from ._compile import CompiledScene as CompiledScene
from ._compile import clear_compile_cache as clear_compile_cache
from ._compile import compile_plant as compile_plant
from ._compile import fit_request as fit_request
from ._compile import make_waves as make_waves
from ._compile import with_linear_gains as with_linear_gains
from ._jit import JIT as JIT
from ._jit import kernel as kernel
from ._jit import reduction_kernel as reduction_kernel
from ._kernels import accelerations as accelerations
from ._kernels import configuration_rate as configuration_rate
from ._kernels import end_stop_force as end_stop_force
from ._kernels import hydro_velocity as hydro_velocity
from ._kernels import hydrostatic_force as hydrostatic_force
from ._kernels import integrate_configuration as integrate_configuration
from ._kernels import kinematics as kinematics
from ._kernels import normalise_quaternions as normalise_quaternions
from ._kernels import poses as poses
from ._kernels import pto_strokes as pto_strokes
from ._kernels import world_jacobian as world_jacobian
from ._phi import phi_functions as phi_functions
from ._plant import Plant as Plant
from ._plant import PtoKind as PtoKind
from ._plant import build_plant as build_plant
from ._radiation import RadiationArrays as RadiationArrays
from ._radiation import RadiationKind as RadiationKind
from ._radiation import RadiationSummary as RadiationSummary
from ._radiation import added_mass_correction as added_mass_correction
from ._radiation import from_impulse_response as from_impulse_response
from ._radiation import from_state_space as from_state_space
from ._radiation import interpolate_matrices as interpolate_matrices
from ._radiation import memory_response as memory_response
from ._radiation import no_radiation as no_radiation
