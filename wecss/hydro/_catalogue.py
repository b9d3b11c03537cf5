"""The hydrodynamic databases shipped in ``wecss/data/hydro``: ``wecss.hydro.load("m4-134")``."""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

from ._hydrodata import HydroData

DATA_DIR = Path(__file__).resolve().parent.parent / "data" / "hydro"
"""Folder of the shipped databases (``<name>.nc``) and their geometry files (``<name>.toml``)."""


def available() -> list[str]:
    """Names of the shipped hydrodynamic databases."""
    return sorted(p.stem for p in DATA_DIR.glob("*.nc"))


@lru_cache(maxsize=16)
def _load_cached(name: str) -> HydroData:
    return HydroData.from_netcdf(DATA_DIR / f"{name}.nc")


def load(name: str) -> HydroData:
    """Load a shipped hydrodynamic database by name.

    Parameters
    ----------
    name : str
        One of :func:`available` (``"m4-111"``, ``"m4-132"``, ``"m4-134"``, ``"notc-10kw"``).

    Returns
    -------
    HydroData
        The database, with coefficients about each body's centre of mass.

    Raises
    ------
    ValueError
        If no database of that name is shipped (the message lists the ones that are).
    """
    names = available()
    if name not in names:
        raise ValueError(f"no shipped hydrodynamic database {name!r}; available: {', '.join(names) or 'none'}")
    return _load_cached(name)
