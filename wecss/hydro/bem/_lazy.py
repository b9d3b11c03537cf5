"""Lazy import of Capytaine, the optional BEM solver (extra ``bem``)."""

from __future__ import annotations

from types import ModuleType

INSTALL_HINT = 'BEM generation needs Capytaine >= 3: pip install "wecss[bem]"'


def import_capytaine() -> ModuleType:
    """Return the ``capytaine`` module.

    Raises
    ------
    ImportError
        If Capytaine is not installed (the message says how to install it).
    """
    try:
        import capytaine
    except ImportError as err:
        raise ImportError(INSTALL_HINT) from err
    return capytaine
