"""Analysis of results: netCDF I/O, metrics (mean power, CWR, RMS angle, RAO) and plots. (The result Dataset is
built by the runs in ``wecss.sim``.)"""

from ._io import open_result as open_result
from ._io import save as save
from ._metrics import capture_width_ratio as capture_width_ratio
from ._metrics import mean_power as mean_power
from ._metrics import rao_irregular as rao_irregular
from ._metrics import rao_regular as rao_regular
from ._metrics import response_amplitude as response_amplitude
from ._metrics import rms_hinge_angle as rms_hinge_angle
from ._metrics import spectral_moments as spectral_moments
from ._metrics import wecccomp_score as wecccomp_score
from ._plot import plot_power_curve as plot_power_curve
from ._plot import plot_rao as plot_rao
from ._plot import plot_timeseries as plot_timeseries
