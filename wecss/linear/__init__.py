"""The MFM equations linearised about the static equilibrium: one model (state-space system with radiation
states, and the exact frequency response from A(omega) and B(omega)), its exact discretisation and runs in modal
coordinates, the frequency-domain steady state and the elastic bodies' stress transfer functions, the modal table,
and the model's inputs rebuilt from a result."""

from ._frequency import response_amplitudes as response_amplitudes
from ._frequency import steady_state as steady_state
from ._inputs import linear_inputs as linear_inputs
from ._modal_recursion import ModalForm as ModalForm
from ._modal_recursion import ModalSteps as ModalSteps
from ._modal_recursion import NotDiagonalisable as NotDiagonalisable
from ._model import HydroResponse as HydroResponse
from ._model import LinearModel as LinearModel
from ._model import NoStateSpace as NoStateSpace
from ._model import cartesian_mass as cartesian_mass
from ._model import equilibrium_maps as equilibrium_maps
from ._model import exact_step as exact_step
from ._model import linearize as linearize
from ._modes import format_modal_table as format_modal_table
from ._modes import modal_table as modal_table
from ._run import Feedback as Feedback
from ._run import closed_loop as closed_loop
from ._run import open_loop as open_loop
from ._stress_response import stress_response as stress_response
