"""The public face: ``import wecss`` offers a hand-written list of the names a user needs, each the object of its
home package, loaded on first use (``import wecss`` itself stays cheap); the kernel helpers live in an internal
namespace; ``wecss.control`` is split so that no name clashes with ``wecss.results``."""

from __future__ import annotations

import importlib
import subprocess
import sys

import wecss


def test_every_name_of_the_face_is_its_home_packages_object():
    assert "simulate" in wecss.__all__ and "Scene" in wecss.__all__
    for name in wecss.__all__:
        value = getattr(wecss, name)
        assert value is not None, name
        assert name in dir(wecss)
    assert wecss.simulate is importlib.import_module("wecss.sim").simulate
    assert wecss.load_device is importlib.import_module("wecss.devices").load
    assert wecss.mean_power is importlib.import_module("wecss.results").mean_power


def test_an_unknown_name_is_an_attribute_error():
    try:
        wecss.no_such_name  # noqa: B018
    except AttributeError as err:
        assert "no_such_name" in str(err)
    else:  # pragma: no cover
        raise AssertionError("no AttributeError")


def test_import_wecss_loads_no_package_of_its_own():
    out = subprocess.run(
        [sys.executable, "-c", "import wecss, sys; print(' '.join(m for m in sys.modules if m.startswith('wecss')))"],
        check=True,
        capture_output=True,
        text=True,
    )
    assert out.stdout.split() == ["wecss"]


def test_kernel_helpers_are_not_in_the_compiled_packages_face():
    import wecss.compiled
    import wecss.compiled.kernels

    for helper in ("matvec", "cholesky", "configure", "respond", "kernel", "step_kernel"):
        assert not hasattr(wecss.compiled, helper), helper
        assert hasattr(wecss.compiled.kernels, helper), helper


def test_no_name_of_wecss_control_clashes_with_wecss_results():
    import wecss.control
    import wecss.control.design
    import wecss.control.mpc
    import wecss.results

    results = {n for n in dir(wecss.results) if not n.startswith("_")}
    for package in (wecss.control, wecss.control.design, wecss.control.mpc):
        public = {n for n in dir(package) if not n.startswith("_")} - {"design", "mpc"}
        assert not public & results, (package.__name__, public & results)
