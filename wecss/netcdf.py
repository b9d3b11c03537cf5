"""netCDF interchange for every wecss dataset: complex values and atomic writes.

netCDF has no complex type, so complex variables are written with a trailing ``complex`` dimension
holding ``[re, im]`` and merged back on read. Writes go to a temporary file in the target folder
that is renamed over the target only when complete, so a failed write never leaves a half file. An interrupt
(Ctrl-C) during a write is held until the temporary file is closed, then the temporary file is removed, the
previous file left as it was and the interrupt raised (the netCDF library's file lock would otherwise hang the
process); temporary files left by killed processes are removed by the next write to the same target.
"""

from __future__ import annotations

import contextlib
import os
import signal
import tempfile
import threading
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import xarray as xr

COMPLEX_DIM = "complex"
COMPLEX_COORD = ("re", "im")
_COMPLEX_FLAG = "wecss_complex"


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


def storage_encoding(ds: xr.Dataset, *, compress: int | bool = 0, float32: bool = False) -> dict[str, dict]:
    """The netCDF encoding of every data variable of ``ds`` for a zlib level ``compress`` (0-9; True: 6, False: 0; on
    variables of at least :data:`COMPRESS_MIN_SIZE` values) and, with ``float32``, single-precision storage of the
    floating-point data variables (coordinates such as time keep their precision; values come back within float32
    rounding, a relative 6e-8).

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
        if level and ds[name].size >= COMPRESS_MIN_SIZE:
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
    """
    target = Path(path)
    folder = target.parent if str(target.parent) else Path(".")
    if not folder.is_dir():
        raise FileNotFoundError(f"folder {str(folder)!r} for {str(target)!r} does not exist")
    if target.is_dir():
        raise IsADirectoryError(f"{str(target)!r} is a folder; give a file name")
    remove_stale_temporaries(target)
    split = split_complex(ds)
    encoding = storage_encoding(split, compress=compress, float32=float32) or None
    with _interrupts_held() as interrupted:
        fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.{os.getpid()}.", suffix=".tmp", dir=folder)
        os.close(fd)
        try:
            split.to_netcdf(tmp, engine="netcdf4", encoding=encoding)
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


@contextlib.contextmanager
def _interrupts_held() -> Iterator[list[bool]]:
    """Record SIGINT (Ctrl-C) for the duration instead of raising it (on the main thread, where Python handles
    signals); yields a list that is true once one came, and raises KeyboardInterrupt on leaving if one did."""
    interrupted: list[bool] = []
    if threading.current_thread() is not threading.main_thread():
        yield interrupted
        return

    def record(signum: int, frame: object) -> None:
        interrupted.append(True)

    previous = signal.signal(signal.SIGINT, record)
    try:
        yield interrupted
    finally:
        signal.signal(signal.SIGINT, previous)
    if interrupted:
        raise KeyboardInterrupt


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
