"""The machinery of estimation and model predictive control: the excitation estimator and its autoregressive
predictor, the state observer, the prediction matrices over a horizon (:class:`HorizonModel`), the absorbed-power
quadratic programme built once (:class:`PowerQP`) and its solvers (OSQP directly or through cvxpy)."""

from ._estimation import ExcitationEstimator as ExcitationEstimator
from ._estimation import measured_rms as measured_rms
from ._estimation import pto_equivalent as pto_equivalent
from ._estimation import pto_referred as pto_referred
from ._horizon import HorizonModel as HorizonModel
from ._observer import StateObserver as StateObserver
from ._power_qp import PowerQP as PowerQP
from ._prediction import ARPredictor as ARPredictor
from ._qp_solvers import ClarabelPath as ClarabelPath
from ._qp_solvers import CvxpyPath as CvxpyPath
from ._qp_solvers import OsqpPath as OsqpPath
from ._qp_solvers import Solution as Solution
from ._wave_estimation import WaveExcitationEstimator as WaveExcitationEstimator
