"""Analysis of results: netCDF I/O, annual energy (power matrix and scatter diagram), metrics (mean power,
CWR, RMS angle, RAO), fatigue (rainflow, streamed over many channels; stress fields and life maps; spectral: narrow
band and Dirlik), plots and animations. (The result Dataset is built by the runs in ``wecss.sim``.)"""

from ._animate import animate as animate
from ._animate import check_animation as check_animation
from ._annual_energy import HOURS_PER_YEAR as HOURS_PER_YEAR
from ._annual_energy import annual_energy as annual_energy
from ._annual_energy import power_matrix as power_matrix
from ._annual_energy_plot import plot_annual_energy as plot_annual_energy
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
from ._spectral_fatigue import SPECTRAL_METHODS as SPECTRAL_METHODS
from ._spectral_fatigue import dirlik_range_pdf as dirlik_range_pdf
from ._spectral_fatigue import line_moments as line_moments
from ._spectral_fatigue import narrow_band_range_pdf as narrow_band_range_pdf
from ._spectral_fatigue import psd_moments as psd_moments
from ._spectral_fatigue import spectral_damage_rate as spectral_damage_rate
from ._spectral_fatigue import spectral_fatigue as spectral_fatigue
from ._streaming_rainflow import StreamingRainflow as StreamingRainflow
from ._stress_field import StressFieldRecorder as StressFieldRecorder
from ._summary_plot import plot_summary as plot_summary
from ._sweep_plot import plot_sweep as plot_sweep
