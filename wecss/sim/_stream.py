"""A run's result streamed to its netCDF file as the run goes (``simulate(scene, path=...)``).

The fixed-step loop hands over its saved rows every :data:`STREAM_STEPS` steps or so; their time series are derived
(the same functions as :func:`build_result`, on the rows alone) and appended along the file's unlimited ``time``
dimension, and the loop's buffers are used again: memory stays flat whatever the number of saved steps. What needs
the whole record is gathered as it goes: the statistics over the final window are the loop's running sums as
always, the notes on the motion a :class:`MotionSummary`. The file is readable after every part (``run_status``
says how far it got; a failed or interrupted run leaves it as ``NAME.partial.nc``); at the end the statistics and
the attributes are added and it is renamed to ``NAME.nc``, equal in content to ``save(build_result(...))``.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import xarray as xr

from ..attributes import apply_attrs
from ..compiled.kernels import poses
from ..control import ControlledScene
from ..interrupts import Terminated
from ..netcdf import AppendingWriter
from ..outputs import STREAMED_GROUPS
from ..provenance import with_relative_paths
from ._dataset import series_variables, statistics_dataset
from ._guards import MotionSummary
from ._quantities import elevation_series, probe_series
from ._record import Record

STREAM_STEPS: int = 10_000
"""Steps between two parts written to the file (at most this many are lost to a crash; the buffers hold about
this many saved rows: ~10 MB for m4-134 with the default outputs)."""


def streamable(controlled: ControlledScene) -> bool:
    """Whether ``simulate(..., path=...)`` streams this scene's result to the file as it runs: a runner that can
    (``Capabilities.streaming``) saving time series of streamed groups only (``wecss.outputs.Group.streamed``;
    statistics-only runs hold nothing per step and are written at the end)."""
    scene = controlled.scene
    return (
        scene.runner.capabilities.streaming
        and not scene.outputs.statistics_only
        and set(scene.outputs.variables) <= set(STREAMED_GROUPS)
    )


class ResultStream:
    """Where a fixed-step run sends its saved rows when the result goes to a file as it runs."""

    def __init__(
        self, compiled: ControlledScene, path: str | os.PathLike[str], *, compress: int = 0, float32: bool = False
    ) -> None:
        self.compiled = compiled
        outputs = compiled.scene.outputs
        self.every = outputs.every
        self.n_save = compiled.n_steps // outputs.every + 1
        self.writer = AppendingWriter(path, self.n_save, compress=compress, float32=float32)
        self.motion = MotionSummary(compiled, self.n_save)
        # the elevation of the whole run (8 bytes per saved step), evaluated as build_result does (one FFT over
        # the record's times where it is periodic): the file's values are those of a whole run, not round-off apart
        self.elevation: np.ndarray | None = None
        self.probes: np.ndarray | None = None
        if "elevation" in outputs.variables:
            times = np.arange(self.n_save) * self.every * compiled.dt
            self.elevation = elevation_series(compiled, times)
            self.probes = probe_series(compiled, times)  # (8 bytes per probe and saved step)

    @property
    def rows(self) -> int:
        """Saved rows written so far."""
        return self.writer.rows

    def add(self, part: Record) -> None:
        """The next saved rows (``part.time`` their times)."""
        if not part.time.size:
            return
        rows = slice(self.writer.rows, self.writer.rows + part.time.size)
        eta = None if self.elevation is None else self.elevation[rows]
        probes = None if self.probes is None else self.probes[rows]
        data, coords, known = series_variables(self.compiled, part, eta, probes)
        if known is None:  # the notes read the poses; computed here when no output has them
            known = poses(self.compiled.plant, np.ascontiguousarray(part["q"]))
        self.motion.add(part["q"], known)
        ds = apply_attrs(xr.Dataset(data, coords=coords))
        if self.writer.rows == 0:
            ds.attrs["scene"] = self.compiled.scene.to_json()  # a partial file is a result file (``wecss info``)
        t_end = self.compiled.n_steps * self.compiled.dt
        self.writer.append(
            ds,
            f"partial: {self.writer.rows + part.time.size} of {self.n_save} saved steps written "
            f"(to t = {float(part.time[-1]):.6g} s of {t_end:.6g} s); the run goes on",
        )

    def finish(self, record: Record) -> Path:
        """The statistics and attributes of the finished run (``record``: its sums and solver); returns the file."""
        if self.writer.rows != self.n_save:
            raise RuntimeError(f"{self.writer.rows} of {self.n_save} saved steps reached the file")
        rest = statistics_dataset(self.compiled, record, self.motion.notes())
        rest.attrs = with_relative_paths(rest.attrs, self.writer.target)  # input files from the result's folder
        return self.writer.finish(rest)

    def stop(self, err: BaseException) -> Path | None:
        """The run stopped with ``err``: the partial file says so (returned; None when nothing was written)."""
        if isinstance(err, Terminated):
            what = str(err) or "terminated"
        elif isinstance(err, KeyboardInterrupt):
            what = "interrupted"
        else:
            what = f"{type(err).__name__}: {err}"
        return self.writer.stop(f"stopped after {self.writer.rows} of {self.n_save} saved steps: {what}")
