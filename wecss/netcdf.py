"""netCDF interchange for every wecss dataset: complex values and atomic writes.

netCDF has no complex type, so complex variables are written with a trailing ``complex`` dimension
holding ``[re, im]`` and merged back on read. Writes go to a temporary file in the target folder
that is renamed over the target only when complete, so a failed write never leaves a half file. An interrupt
(Ctrl-C, SIGTERM) during a write is held until the temporary file is closed, then the temporary file is removed,
the previous file left as it was and the interrupt raised (``wecss.interrupts.interrupts_held``; the netCDF
library's file lock would otherwise hang the process); temporary files left by killed processes are removed by the
next write to the same target, whole or part by part.
"""

from __future__ import annotations

import contextlib
import errno
import os
import shutil
import tempfile
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import xarray as xr

from .files import WriteFailed as WriteFailed
from .interrupts import interrupts_held

if TYPE_CHECKING:
    import netCDF4

COMPLEX_DIM = "complex"
COMPLEX_COORD = ("re", "im")
_COMPLEX_FLAG = "wecss_complex"


#: Free space [bytes] below which a failed write is put down to a full disk.
FULL_DISK_BYTES: int = 64 * 2**20


def write_failure(path: Path, err: BaseException, what: str) -> WriteFailed:
    """The :class:`WriteFailed` of a write to ``path`` that raised ``err`` (an OSError, or the netCDF library's
    RuntimeError such as "NetCDF: HDF error", which carries no errno): the disk is named full when the error says so
    (ENOSPC, EDQUOT) or when its folder has less than :data:`FULL_DISK_BYTES` free; ``what`` says what became of
    the file."""
    code = getattr(err, "errno", None)
    try:
        free: int | None = shutil.disk_usage(path.parent if str(path.parent) else ".").free
    except OSError:
        free = None
    if code in (errno.ENOSPC, errno.EDQUOT) or (free is not None and free < FULL_DISK_BYTES):
        cause = "the disk is full" + (f" ({free} bytes free in {str(path.parent)!r})" if free is not None else "")
    else:
        cause = "the write failed"
    message = f"writing {str(path)!r} failed: {cause} ({type(err).__name__}: {err}); {what}"
    return WriteFailed(message, code or errno.EIO, str(path))


def split_complex(ds: xr.Dataset) -> xr.Dataset:
    """Return ``ds`` with each complex variable as a real variable with a trailing ``complex`` dimension."""
    out = ds.copy()
    for name in list(out.variables):
        da = out[name]
        if np.iscomplexobj(da.values):
            stacked = xr.concat([da.real, da.imag], dim=COMPLEX_DIM).transpose(*da.dims, COMPLEX_DIM)
            stacked.attrs = {**da.attrs, _COMPLEX_FLAG: 1}
            out[name] = stacked
    if COMPLEX_DIM in out.dims:
        out = out.assign_coords({COMPLEX_DIM: list(COMPLEX_COORD)})
    return out


def merge_complex(ds: xr.Dataset) -> xr.Dataset:
    """Inverse of :func:`split_complex`: merge ``[re, im]`` pairs back into complex variables."""
    if COMPLEX_DIM not in ds.dims:
        return ds
    out = ds.copy()
    for name in list(out.data_vars):
        da = out[name]
        if COMPLEX_DIM in da.dims:
            merged = da.sel({COMPLEX_DIM: "re"}) + 1j * da.sel({COMPLEX_DIM: "im"})
            merged = merged.drop_vars(COMPLEX_DIM, errors="ignore")
            merged.attrs = {k: v for k, v in da.attrs.items() if k != _COMPLEX_FLAG}
            out[name] = merged
    return out.drop_dims(COMPLEX_DIM, errors="ignore")


COMPRESSION_LEVELS = range(10)
"""zlib levels :func:`write_netcdf` accepts: 0 (none) to 9 (smallest, slowest)."""

COMPRESS_MIN_SIZE = 1024
"""Variables with fewer values are stored uncompressed: a compressed (chunked) variable costs kilobytes of index,
more than zlib saves on a few hundred values."""


def storage_encoding(
    ds: xr.Dataset, *, compress: int | bool = 0, float32: bool = False, sizes: dict[str, int] | None = None
) -> dict[str, dict]:
    """The netCDF encoding of every data variable of ``ds`` for a zlib level ``compress`` (0-9; True: 6, False: 0; on
    variables of at least :data:`COMPRESS_MIN_SIZE` values) and, with ``float32``, single-precision storage of the
    floating-point data variables (coordinates such as time keep their precision; values come back within float32
    rounding, a relative 6e-8). ``sizes``: the lengths of dimensions of which ``ds`` holds a part (a file written
    part by part), for the variables' whole sizes.

    Raises
    ------
    ValueError
        If ``compress`` is not a whole number from 0 to 9, or ``float32`` not a bool.
    """
    level = {True: 6, False: 0}[compress] if isinstance(compress, bool) else compress
    if not isinstance(level, int | np.integer) or level not in COMPRESSION_LEVELS:
        raise ValueError(f"compress must be a zlib level 0 (none) to 9 (smallest); got {compress!r}")
    if not isinstance(float32, bool | np.bool_):
        raise ValueError(f"float32 must be true or false; got {float32!r}")
    encoding: dict[str, dict] = {}
    for name in ds.data_vars:
        entry: dict[str, object] = {}
        size = int(np.prod([(sizes or {}).get(str(d), n) for d, n in ds[name].sizes.items()]))
        if level and size >= COMPRESS_MIN_SIZE:
            entry.update(zlib=True, complevel=int(level))
        if float32 and np.issubdtype(ds[name].dtype, np.floating):
            entry["dtype"] = "float32"
        if entry:
            encoding[str(name)] = entry
    return encoding


def write_netcdf(
    ds: xr.Dataset, path: str | os.PathLike[str], *, compress: int | bool = 0, float32: bool = False
) -> Path:
    """Write ``ds`` to ``path`` atomically (temporary file in the same folder, then rename).

    Complex variables are split into ``[re, im]``. ``compress``: zlib level of every variable, 0 (none) to 9
    (lossless; True means 6); ``float32``: floating-point data variables stored in single precision (lossy: a
    relative 6e-8; coordinates keep theirs). Returns the path written.

    Raises
    ------
    FileNotFoundError
        If the target folder does not exist.
    ValueError
        For a ``compress`` level outside 0-9.
    WriteFailed
        If the write fails (a full disk: the message says so); the target is left as it was.
    """
    target = _target(path)
    folder = target.parent
    remove_stale_temporaries(target)
    split = split_complex(ds)
    # a whole Dataset has fixed dimensions: one read from a file written part by part (AppendingWriter) would
    # otherwise keep its unlimited time dimension, whose default chunks are one row each once re-encoded
    split.encoding = {k: v for k, v in split.encoding.items() if k != "unlimited_dims"}
    encoding = storage_encoding(split, compress=compress, float32=float32) or None
    with interrupts_held() as interrupted:
        fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.{os.getpid()}.", suffix=".tmp", dir=folder)
        os.close(fd)
        try:
            try:
                split.to_netcdf(tmp, engine="netcdf4", encoding=encoding)
            except (OSError, RuntimeError) as err:
                raise write_failure(target, err, "nothing was written (any previous file there is unchanged)") from err
            umask = os.umask(0)
            os.umask(umask)
            os.chmod(tmp, 0o666 & ~umask)  # mkstemp makes the file private; give it the usual permissions
            if interrupted:  # Ctrl-C during the write: the previous file stays; raised on leaving
                Path(tmp).unlink(missing_ok=True)
            else:
                os.replace(tmp, target)
        except BaseException:
            Path(tmp).unlink(missing_ok=True)
            raise
    return target


CHUNK_VALUES = 2**15
"""Values per chunk (256 kB of float64) of a variable on the unlimited dimension of a file written part by part."""


CHUNK_CACHE_CHUNKS = 4
"""Chunks of each variable the netCDF library keeps in memory while a file is appended to (AppendingWriter)."""


class AppendingWriter:
    """A netCDF file written part by part along an unlimited dimension (a long run's time series, chunk by chunk
    as it goes), complete and readable after every part.

    The parts go to ``NAME.partial.nc`` next to the target, whose global attribute ``status_attr`` says how far it
    got (``append``'s ``status``); :meth:`finish` adds the variables without the dimension and the global
    attributes, removes the status and renames the file over the target (a previous file there stays until then).
    :meth:`stop` leaves the partial file with a last status (the run failed or was interrupted). Each part is written
    with Ctrl-C held, so an interrupt never leaves a damaged part. The stored values equal those that
    :func:`write_netcdf` writes of the whole Dataset (the layout differs: chunks along the unlimited dimension).

    Parameters
    ----------
    path : target file
    length : int
        The dimension's final length (for the compression threshold and the chunk sizes).
    dim : str
        The unlimited dimension; every part's variables on it have it first.
    compress, float32 : as :func:`write_netcdf`
    """

    def __init__(
        self,
        path: str | os.PathLike[str],
        length: int,
        *,
        dim: str = "time",
        compress: int | bool = 0,
        float32: bool = False,
        status_attr: str = "run_status",
    ) -> None:
        self.target = _target(path)
        storage_encoding(xr.Dataset(), compress=compress, float32=float32)  # refuse bad options before any work
        self.partial = partial_path(self.target)
        remove_stale_temporaries(self.target)  # left by a whole-file write to the same target that was killed
        self.length, self.dim, self.compress, self.float32 = length, dim, compress, float32
        self.status_attr = status_attr
        self.rows = 0
        self.failed = False  # a write failed (the partial file's last part may be incomplete)
        self._nc: netCDF4.Dataset | None = None

    def append(self, part: xr.Dataset, status: str) -> None:
        """Write the next rows: ``part``'s variables on the dimension (the first part also writes every other
        variable, the coordinates and the global attributes of ``part``)."""
        with interrupts_held():
            try:
                if self._nc is None:
                    self._create(part, status)
                else:
                    k = part.sizes[self.dim]
                    for name, variable in part.variables.items():
                        if self.dim in variable.dims:
                            self._nc.variables[str(name)][self.rows : self.rows + k] = variable.values
                    self._nc.setncattr(self.status_attr, status)
                    self._nc.sync()
            except (OSError, RuntimeError) as err:
                self.failed = True
                if self._nc is None:  # the first part: a half-made file holds nothing of use
                    with contextlib.suppress(OSError):
                        self.partial.unlink()
                raise write_failure(self.partial, err, self._failed_state()) from err
            self.rows += part.sizes[self.dim]

    def _failed_state(self) -> str:
        """What a failed append left in the partial file."""
        if self._nc is None:
            return "nothing of the run was kept (the half-made partial file was removed)"
        return (
            f"the partial file keeps the first {self.rows} of {self.length} rows whole; its status attribute "
            f"{self.status_attr!r} is updated to say the run stopped if the disk lets it (else it still says how "
            "far the last whole part got)"
        )

    def _create(self, part: xr.Dataset, status: str) -> None:
        import netCDF4

        for name, variable in part.variables.items():
            if self.dim in variable.dims and variable.dims[0] != self.dim:
                raise ValueError(f"variable {name!r} has {self.dim!r} as dimension {variable.dims.index(self.dim)}")
        encoding = storage_encoding(part, compress=self.compress, float32=self.float32, sizes={self.dim: self.length})
        for name, variable in part.variables.items():
            if self.dim in variable.dims:
                other = [int(n) for d, n in variable.sizes.items() if d != self.dim]
                rows = max(1, min(self.length, CHUNK_VALUES // max(1, int(np.prod(other)))))
                encoding.setdefault(str(name), {})["chunksizes"] = (rows, *other)
        part = part.assign_attrs({**part.attrs, self.status_attr: status})
        part.to_netcdf(self.partial, engine="netcdf4", unlimited_dims=[self.dim], encoding=encoding)
        self._nc = netCDF4.Dataset(self.partial, "a")
        for stored in self._nc.variables.values():
            # the library's chunk cache (64 MB per variable in netCDF-C 4.9+) would keep each written chunk:
            # memory would grow with the file; a few chunks are enough to append
            if self.dim in stored.dimensions:
                stored.set_var_chunk_cache(size=CHUNK_CACHE_CHUNKS * CHUNK_VALUES * stored.dtype.itemsize)

    def finish(self, rest: xr.Dataset) -> Path:
        """Add ``rest`` (variables without the dimension, their coordinates, and the global attributes, which
        replace the parts') and rename the file over the target; returns the target."""
        if self._nc is None:
            raise RuntimeError(f"nothing was written to {str(self.partial)!r}")
        split = split_complex(rest)
        try:
            self._finish(split)
        except (OSError, RuntimeError) as err:
            self.failed = True
            self._mark_unfinished()
            raise write_failure(
                self.partial,
                err,
                f"the partial file keeps the run's {self.rows} rows; its statistics and attributes are missing (its "
                f"status attribute {self.status_attr!r} says so if the disk let it be written)",
            ) from err
        return self.target

    def _mark_unfinished(self) -> None:
        """After a failed :meth:`finish`: the partial file's status says the run ended but the file is unfinished
        (where the disk lets it be written)."""
        import netCDF4

        with contextlib.suppress(OSError, RuntimeError):
            if self._nc is not None:
                self._nc.close()
            self._nc = None
            with netCDF4.Dataset(self.partial, "a") as nc:
                nc.setncattr(
                    self.status_attr,
                    f"stopped: all {self.rows} of {self.length} rows written, but writing the statistics and "
                    "attributes failed (unfinished file)",
                )

    def _finish(self, split: xr.Dataset) -> None:
        assert self._nc is not None
        with interrupts_held():
            for name in self._nc.ncattrs():  # the parts' attributes give way to the whole's (in its order)
                self._nc.delncattr(name)
            self._nc.close()
            self._nc = None
            split.to_netcdf(
                self.partial,
                mode="a",
                engine="netcdf4",
                encoding=storage_encoding(split, compress=self.compress, float32=self.float32) or None,
            )
            os.replace(self.partial, self.target)

    def stop(self, status: str) -> Path | None:
        """Leave the partial file with the last ``status`` (a failure or an interrupt); returns it (None when no
        part was written)."""
        if self._nc is None:
            return None
        with interrupts_held():
            try:
                self._nc.setncattr(self.status_attr, status)
                self._nc.close()
            except (OSError, RuntimeError):  # the disk that stopped the run may refuse the status too
                with contextlib.suppress(OSError, RuntimeError):
                    self._nc.close()
        self._nc = None
        return self.partial


def partial_path(target: Path) -> Path:
    """The file ``NAME.partial.nc`` an :class:`AppendingWriter` of ``NAME.nc`` writes its parts to."""
    return target.with_name(f"{target.stem}.partial{target.suffix}")


def _target(path: str | os.PathLike[str]) -> Path:
    """``path`` as a file to write, its folder checked."""
    target = Path(path)
    folder = target.parent if str(target.parent) else Path(".")
    if not folder.is_dir():
        raise FileNotFoundError(f"folder {str(folder)!r} for {str(target)!r} does not exist")
    if target.is_dir():
        raise IsADirectoryError(f"{str(target)!r} is a folder; give a file name")
    return target


def remove_stale_temporaries(target: Path) -> list[Path]:
    """Remove the temporary files ``.NAME.PID.*.tmp`` next to ``target`` whose writing process is gone (killed
    during a write); returns them."""
    removed = []
    for candidate in target.parent.glob(f".{target.name}.*.tmp"):
        pid_text = candidate.name[len(target.name) + 2 :].split(".", 1)[0]
        if pid_text.isdigit() and _alive(int(pid_text)):
            continue  # another process is writing it now
        with contextlib.suppress(OSError):
            candidate.unlink()
            removed.append(candidate)
    return removed


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


class NetCDFFileError(ValueError):
    """A file is not a readable netCDF file (empty, truncated, damaged or of another format); the message names
    the file and says which."""


#: The first bytes of netCDF files: classic (CDF 1, 2, 5) and netCDF-4 (HDF5).
_SIGNATURES = (b"CDF\x01", b"CDF\x02", b"CDF\x05", b"\x89HDF\r\n\x1a\n")


def unreadable(path: str | os.PathLike[str], err: BaseException) -> NetCDFFileError:
    """The error for a netCDF file the library could not read: empty, not netCDF, or truncated / damaged."""
    source = Path(path)
    size = source.stat().st_size
    with source.open("rb") as fh:
        head = fh.read(8)
    if size == 0:
        what = "the file is empty (0 bytes)"
    elif not any(head.startswith(sig) for sig in _SIGNATURES):
        what = f"it is not a netCDF file (it starts with {head[:4]!r}, not a netCDF or HDF5 signature)"
    else:
        what = f"it is truncated or damaged ({size} bytes; the netCDF library says: {err})"
    return NetCDFFileError(f"cannot read {str(source)!r}: {what}")


def global_attributes(path: str | os.PathLike[str]) -> dict[str, object]:
    """The global attributes of a netCDF file, without reading its data.

    Raises
    ------
    FileNotFoundError
        If ``path`` does not exist.
    NetCDFFileError
        If it is not a readable netCDF file.
    """
    import netCDF4

    source = Path(path)
    if not source.is_file():
        raise FileNotFoundError(f"no netCDF file at {str(source)!r}")
    try:
        with netCDF4.Dataset(source) as nc:
            return {name: nc.getncattr(name) for name in nc.ncattrs()}
    except (OSError, RuntimeError) as err:
        raise unreadable(source, err) from None


def read_netcdf(path: str | os.PathLike[str]) -> xr.Dataset:
    """Read a dataset written by :func:`write_netcdf` fully into memory (the file is closed on return).

    Raises
    ------
    FileNotFoundError
        If ``path`` does not exist.
    NetCDFFileError
        If it is not a readable netCDF file (empty, truncated, damaged, another format).
    """
    source = Path(path)
    if not source.is_file():
        raise FileNotFoundError(f"no netCDF file at {str(source)!r}")
    try:
        with xr.open_dataset(source, engine="netcdf4") as ds:
            loaded = ds.load()
    except (OSError, RuntimeError, ValueError, KeyError, IndexError) as err:
        raise unreadable(source, err) from None
    return merge_complex(loaded)
