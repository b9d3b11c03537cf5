"""Device catalogue built from declarative specs: M4 111/132/134, hinged-arm point absorbers, two-body heave."""

from ..structure import Section as Section
from ._beam_modes import beam_frequencies as beam_frequencies
from ._catalogue import DEVICE_DIR as DEVICE_DIR
from ._catalogue import available as available
from ._catalogue import load as load
from ._database_checks import check_against_database as check_against_database
from ._device import Device as Device
from ._flexible import BodyMass as BodyMass
from ._flexible import Flexible as Flexible
from ._flexible import FlexibleBody as FlexibleBody
from ._members import HotSpot as HotSpot
from ._members import Member as Member
from ._spec import DeviceSpecError as DeviceSpecError
from ._spec import hydro_source as hydro_source
from ._spec import read_spec as read_spec
from ._spec import spec_files as spec_files
from ._spec import spec_inputs as spec_inputs
from ._structural_modes import structural_modes as structural_modes
