"""Radiation memory: impulse responses, convolution, state-space fits (Prony / matrix pencil, Hankel-SVD
realisation), stability and passivity checks and repair, fit reports."""

from ._cache import SHIPPED_FITS_DIR as SHIPPED_FITS_DIR
from ._cache import CacheWarning as CacheWarning
from ._cache import cache_dir as cache_dir
from ._cache import load_cached_fit as load_cached_fit
from ._cache import store_fit as store_fit
from ._convolution import MEMORY_FACTOR as MEMORY_FACTOR
from ._convolution import RadiationConvolution as RadiationConvolution
from ._couplings import significant_couplings as significant_couplings
from ._fit import FitSettings as FitSettings
from ._fit import RadiationFit as RadiationFit
from ._fit import fit_cache_key as fit_cache_key
from ._fit import fit_radiation as fit_radiation
from ._irf import ImpulseResponse as ImpulseResponse
from ._irf import filon_cosine_weights as filon_cosine_weights
from ._irf import impulse_response as impulse_response
from ._passivity import Passivation as Passivation
from ._passivity import PassivityCheck as PassivityCheck
from ._passivity import check_passivity as check_passivity
from ._passivity import damping_scale as damping_scale
from ._passivity import enforce_passivity as enforce_passivity
from ._passivity import passivity_grid as passivity_grid
from ._passivity import tail_bound as tail_bound
from ._plot import plot_fit as plot_fit
from ._reduce import Reduction as Reduction
from ._reduce import balanced_truncation as balanced_truncation
from ._reduce import truncate_to_error as truncate_to_error
from ._statespace import STABILITY_DAMPING as STABILITY_DAMPING
from ._statespace import RadiationStateSpace as RadiationStateSpace
