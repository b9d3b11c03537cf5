"""Sweeps over sea states and designs: a base scene and axes of dotted scene paths, every case run in this process,
a pool of processes or on a Dask cluster, one netCDF file per case, resumable, and a combined dataset with the
axes as dimensions.

Example::

    from wecss.sweep import Sweep, run_sweep
    sweep = Sweep.of(scene, {"sea.period": [0.8, 1.0, 1.2], "sea.height": [0.04, 0.06]})
    ds = run_sweep(sweep, "out/power-matrix", executor="processes", workers=2)  # total_power over the axes
"""

from ._case import CaseOutcome as CaseOutcome
from ._case import run_case as run_case
from ._combine import case_statistics as case_statistics
from ._combine import combine as combine
from ._executors import BLAS_THREADS as BLAS_THREADS
from ._executors import EXECUTORS as EXECUTORS
from ._executors import Executor as Executor
from ._files import case_paths as case_paths
from ._files import case_status as case_status
from ._progress import Progress as Progress
from ._run import prepare_folder as prepare_folder
from ._run import run_sweep as run_sweep
from ._spec import SWEEP_MODES as SWEEP_MODES
from ._spec import Case as Case
from ._spec import Sweep as Sweep
from ._spec import apply_overrides as apply_overrides
from ._spec import parse_value as parse_value
from ._spec import set_path as set_path
