"""Waves: spectra, elevation records (regular, irregular, periodic, measured), directional spreading and
excitation forces in time."""

from ._blocks import BlockSum as BlockSum
from ._directional import SPREADING_TYPES as SPREADING_TYPES
from ._directional import HeadingWeights as HeadingWeights
from ._directional import Spreading as Spreading
from ._directional import heading_bins as heading_bins
from ._directional import heading_weights as heading_weights
from ._directional import spread as spread
from ._elevation import DEFAULT_ENERGY_THRESHOLD as DEFAULT_ENERGY_THRESHOLD
from ._elevation import DroppedComponents as DroppedComponents
from ._elevation import Ramp as Ramp
from ._elevation import WaveComponents as WaveComponents
from ._elevation import drop_negligible as drop_negligible
from ._elevation import evaluate as evaluate
from ._elevation import from_elevation as from_elevation
from ._elevation import irregular as irregular
from ._elevation import regular as regular
from ._excitation import ExcitationModel as ExcitationModel
from ._excitation import SampledForce as SampledForce
from ._excitation import excitation_coefficients as excitation_coefficients
from ._excitation import excitation_model as excitation_model
from ._spectra import Jonswap as Jonswap
from ._spectra import PiersonMoskowitz as PiersonMoskowitz
from ._spectra import Spectrum as Spectrum
from ._spectra import TabulatedSpectrum as TabulatedSpectrum
from ._spectra import deep_water_wavelength as deep_water_wavelength
from ._spectra import energy_flux as energy_flux
from ._spectra import energy_period as energy_period
from ._spectra import group_velocity as group_velocity
from ._spectra import hm0 as hm0
from ._spectra import mean_period as mean_period
from ._spectra import peak_period as peak_period
from ._spectra import wavenumber as wavenumber
