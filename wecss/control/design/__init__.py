"""Design tools of linear PTO control in the frequency domain, on a scene's exact linear model: the complex-conjugate
power bound, the mean power of given gains, the optimal passive damping and the best causal spring-damper."""

from ._frequency_design import LinearGains as LinearGains
from ._frequency_design import PowerBound as PowerBound
from ._frequency_design import gains_power as gains_power
from ._frequency_design import optimal_damping as optimal_damping
from ._frequency_design import optimal_spring_damper as optimal_spring_damper
from ._frequency_design import power_bound as power_bound
from ._frequency_design import pto_response as pto_response
from ._optimum import NonCausalOptimum as NonCausalOptimum
from ._optimum import noncausal_optimum as noncausal_optimum
from ._periodic import PeriodicResponse as PeriodicResponse
from ._periodic import periodic_response as periodic_response
