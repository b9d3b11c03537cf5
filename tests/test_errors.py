"""The package's base warning: one class below every package, the hydro warnings under it, the old import path kept,
and the test configuration turning every wecss warning into an error."""

from __future__ import annotations

import warnings

import pytest

import wecss.hydro
from wecss.errors import WecssWarning


def test_the_hydro_warnings_are_wecss_warnings_and_the_old_name_still_imports():
    assert wecss.hydro.WecssWarning is WecssWarning
    assert issubclass(wecss.hydro.HydroDataWarning, WecssWarning)
    assert issubclass(wecss.hydro.IrregularFrequencyWarning, WecssWarning)
    assert issubclass(WecssWarning, UserWarning)


def test_the_package_warnings_are_errors_in_the_tests():
    """pyproject.toml's filterwarnings: a wecss warning fails a test that does not expect it."""
    with pytest.raises(wecss.hydro.HydroDataWarning, match="changed on reading"):
        warnings.warn("changed on reading", wecss.hydro.HydroDataWarning, stacklevel=1)
