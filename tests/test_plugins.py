"""The plugin groups' entry points are read once per process (``wecss.plugins``), and still seen when a test (or a
notebook) registers one: a folder with a ``.dist-info`` put on ``sys.path``, or ``importlib.metadata.entry_points``
replaced."""

from __future__ import annotations

import importlib.metadata
import sys

import pytest

from tests.toy_plugins import write_distribution
from wecss import plugins
from wecss.control import available, create, registered_name

TOY = '''
from wecss_controllers import LinearDamping


class ToyDamping(LinearDamping):
    """Linear damping under another name (a third-party plugin in a test)."""
'''


@pytest.fixture
def toy_plugin(tmp_path):
    """A folder holding a distribution that registers ``toy-damping`` under ``wecss.controllers`` (not yet on the
    path)."""
    yield write_distribution(tmp_path, "wecss.controllers", "toy-damping", "toy_plugin_module", "ToyDamping", TOY)
    sys.modules.pop("toy_plugin_module", None)


def test_a_group_is_read_once_while_nothing_changes(monkeypatch):
    calls = []
    real = importlib.metadata.entry_points

    def counted(**kwargs):
        calls.append(kwargs)
        return real(**kwargs)

    monkeypatch.setattr(importlib.metadata, "entry_points", counted)
    first = plugins.entry_points("wecss.controllers")
    assert "damping" in [ep.name for ep in first]
    assert plugins.entry_points("wecss.controllers") == first
    available()
    assert calls == [{"group": "wecss.controllers"}]
    plugins.refresh()
    plugins.entry_points("wecss.controllers")
    assert len(calls) == 2


def test_an_entry_point_registered_on_the_path_is_seen_after_the_group_was_read(toy_plugin, monkeypatch):
    assert "toy-damping" not in available()  # the group read and kept
    monkeypatch.syspath_prepend(str(toy_plugin))
    assert "toy-damping" in available()
    controller = create("toy-damping", damping=3.0)
    assert type(controller).__name__ == "ToyDamping"
    assert registered_name(controller) == "toy-damping"


def test_an_entry_point_gone_from_the_path_is_gone_from_the_group(toy_plugin, monkeypatch):
    monkeypatch.syspath_prepend(str(toy_plugin))
    assert "toy-damping" in available()
    monkeypatch.undo()  # the folder leaves sys.path
    assert "toy-damping" not in available()
    with pytest.raises(ValueError, match="unknown controller 'toy-damping'"):
        create("toy-damping")


def test_a_replaced_reader_is_used(monkeypatch):
    plugins.entry_points("wecss.controllers")
    fake = importlib.metadata.EntryPoint("fake", "controllers:LinearDamping", "wecss.controllers")
    monkeypatch.setattr(importlib.metadata, "entry_points", lambda group: [fake])
    assert available() == ["fake"]
