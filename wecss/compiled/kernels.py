"""The compiled kernels and their pieces, for writers of integrators and force terms (an internal namespace: it
follows the kernels, not a deprecation policy).

The decorators (``kernel``, ``inline_kernel``, ``step_kernel``, ``reduction_kernel``, ``loop_kernel``), the
equations of motion on a :class:`~wecss.compiled.Plant` (``configure`` the configuration's part into a
``Workspace``, ``respond`` the velocity's, ``accelerations`` both), the kinematics (``kinematics``, ``poses``,
``world_jacobian``, ``hydro_velocity``, ``integrate_configuration``, ``configuration_rate``,
``normalise_quaternions``), the PTO and static forces, and the small linear algebra the kernels use. See
``docs/architecture.md`` ("No reference counts per step") before writing a per-step kernel.
"""

from ._jit import inline_kernel as inline_kernel
from ._jit import kernel as kernel
from ._jit import loop_kernel as loop_kernel
from ._jit import reduction_kernel as reduction_kernel
from ._jit import step_kernel as step_kernel
from ._kernels import Workspace as Workspace
from ._kernels import accelerations as accelerations
from ._kernels import configuration_rate as configuration_rate
from ._kernels import configure as configure
from ._kernels import configure_core as configure_core
from ._kernels import configure_elastic as configure_elastic
from ._kernels import elastic_pto_end_points as elastic_pto_end_points
from ._kernels import end_stop_force as end_stop_force
from ._kernels import hydro_velocity as hydro_velocity
from ._kernels import hydrostatic_force as hydrostatic_force
from ._kernels import integrate_configuration as integrate_configuration
from ._kernels import kinematics as kinematics
from ._kernels import normalise_quaternions as normalise_quaternions
from ._kernels import poses as poses
from ._kernels import pto_strokes as pto_strokes
from ._kernels import respond as respond
from ._kernels import respond_core as respond_core
from ._kernels import respond_elastic as respond_elastic
from ._kernels import workspace as workspace
from ._kernels import world_jacobian as world_jacobian
from ._linalg import cholesky as cholesky
from ._linalg import cholesky_solve as cholesky_solve
from ._linalg import complex_columns as complex_columns
from ._linalg import lu_factor as lu_factor
from ._linalg import lu_solve as lu_solve
from ._linalg import matvec as matvec
from ._linalg import matvec_add as matvec_add
from ._linalg import real_part_rows as real_part_rows
from ._phi import phi_functions as phi_functions
from ._pto_law import pto_control_force_kernel as pto_control_force_kernel
