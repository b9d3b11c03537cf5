"""Keeping dask out of a process that does not use it (the ``wecss`` commands but ``sweep``).

With the dask extra installed, xarray imports ``dask`` and ``dask.array`` when it makes its first variable (to
ask whether the data is a dask array) and ``distributed`` when it writes a netCDF file (to ask whether a dask
client is active): about 0.35 s of a 2-core machine's CPU for a run that uses neither, a quarter of the time of
``wecss run``. xarray has no option to skip these checks; it skips them when dask is not installed, which
:func:`keep_dask_out` makes this process see (Python's documented way: ``None`` in ``sys.modules``). Whatever
then imports dask in the process gets a ``ModuleNotFoundError`` naming it; :func:`refusal_hint` says why.
"""

from __future__ import annotations

import sys

DASK_MODULES = ("dask", "distributed")
"""The top-level modules kept out."""

_KEPT_OUT: list[str] = []


def keep_dask_out() -> bool:
    """Make dask and distributed look not installed to this process, unless one of them or xarray is imported
    already (then nothing changes: dask's users would break, and xarray decides whether dask is there when it is
    imported). Returns whether they are kept out. It cannot be undone (xarray keeps what it found)."""
    if _KEPT_OUT:
        return True
    if any(name in sys.modules for name in (*DASK_MODULES, "xarray")):
        return False
    for name in DASK_MODULES:
        sys.modules[name] = None  # type: ignore[assignment]
        _KEPT_OUT.append(name)
    return True


def dask_kept_out() -> bool:
    """Whether :func:`keep_dask_out` kept dask out of this process."""
    return bool(_KEPT_OUT)


def refusal_hint(err: ImportError) -> str | None:
    """Why ``err`` happened when it is the import of a module that :func:`keep_dask_out` kept out, else None."""
    name = (err.name or "").split(".")[0]
    if name in _KEPT_OUT:
        return f"{name} is kept out of this command's process (xarray would import it for nothing)"
    return None
