"""Analysis of results: netCDF I/O, metrics (mean power, CWR, RMS angle, RAO), fatigue (rainflow, streamed over
many channels; stress fields and life maps) and plots. (The result Dataset is
built by the runs in ``wecss.sim``.)"""

from ._fatigue import SECONDS_PER_YEAR as SECONDS_PER_YEAR
from ._fatigue import Cycles as Cycles
from ._fatigue import damage_equivalent_range as damage_equivalent_range
from ._fatigue import fatigue_life as fatigue_life
from ._fatigue import life_years as life_years
from ._fatigue import long_term_life as long_term_life
from ._fatigue import miner_damage as miner_damage
from ._fatigue import rainflow_cycles as rainflow_cycles
from ._io import open_result as open_result
from ._io import save as save
from ._life_map_plot import plot_life_map as plot_life_map
from ._metrics import capture_width_ratio as capture_width_ratio
from ._metrics import mean_power as mean_power
from ._metrics import rao_irregular as rao_irregular
from ._metrics import rao_regular as rao_regular
from ._metrics import response_amplitude as response_amplitude
from ._metrics import rms_hinge_angle as rms_hinge_angle
from ._metrics import spectral_moments as spectral_moments
from ._metrics import wecccomp_score as wecccomp_score
from ._mode_plot import plot_structural_modes as plot_structural_modes
from ._plot import plot_power_curve as plot_power_curve
from ._plot import plot_rao as plot_rao
from ._plot import plot_timeseries as plot_timeseries
from ._sn_curves import SN_CURVES as SN_CURVES
from ._sn_curves import SNCurve as SNCurve
from ._sn_curves import sn_curve as sn_curve
from ._streaming_rainflow import StreamingRainflow as StreamingRainflow
from ._stress_field import StressFieldRecorder as StressFieldRecorder
from ._summary_plot import plot_summary as plot_summary
