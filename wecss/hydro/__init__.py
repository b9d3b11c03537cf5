"""Hydrodynamic databases: one xarray schema, readers, BEM generation, reference-point transforms, checks."""

from ._catalogue import DATA_DIR as DATA_DIR
from ._catalogue import available as available
from ._catalogue import load as load
from ._hydrodata import HydroData as HydroData
from ._interactions import without_body_interactions as without_body_interactions
from ._irregular import IrregularFrequencyReport as IrregularFrequencyReport
from ._irregular import find_irregular_frequencies as find_irregular_frequencies
from ._irregular import remove_irregular_frequencies as remove_irregular_frequencies
from ._repair import RepairReport as RepairReport
from ._repair import repair as repair
from ._schema import dof_index as dof_index
from ._schema import dof_name as dof_name
from ._schema import split_dof as split_dof
from ._select import select as select
from ._transform import move_reference_point as move_reference_point
from ._transform import move_to_center_of_mass as move_to_center_of_mass
from ._validate import HydroDataError as HydroDataError
from ._validate import HydroDataWarning as HydroDataWarning
from ._validate import IrregularFrequencyWarning as IrregularFrequencyWarning
from ._validate import WecssWarning as WecssWarning
from ._validate import validate as validate
from .readers.bemio import BemioFormatError as BemioFormatError
from .readers.bemio import read_bemio as read_bemio
from .readers.capytaine import read_capytaine as read_capytaine
from .readers.wamit import WamitFormatError as WamitFormatError
from .readers.wamit import read_wamit as read_wamit
