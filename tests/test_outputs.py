"""The one output table (``wecss.outputs``) drives the runs: its quantities are the ones the result builder
computes, its groups the ones a scene accepts, its channels the arrays the runs record, and every variable of a
result carries its row's units and long name."""

from __future__ import annotations

import numpy as np

from tests.sim.scenes import scene
from wecss.outputs import CHANNEL_NAMES, CHANNELS, GROUP_NAMES, VARIABLES, variable_attrs
from wecss.scene import OUTPUT_GROUPS
from wecss.sim import simulate
from wecss.sim._quantities import LOAD_PICKS, QUANTITIES

_HELPERS = {"poses", "loads", "spectral_loads", "bound", "terms", "fibre_field"}
"""Quantities other quantities are made of (not variables themselves)."""


def test_every_variable_has_a_quantity_and_every_quantity_a_variable():
    named = {v.quantity for v in VARIABLES}
    assert named <= set(QUANTITIES), sorted(named - set(QUANTITIES))
    assert set(QUANTITIES) - named == _HELPERS
    assert {v.quantity for v in VARIABLES if v.spectral} == set(LOAD_PICKS)


def test_the_scene_accepts_the_tables_groups():
    assert OUTPUT_GROUPS == GROUP_NAMES
    for channel in CHANNELS:
        assert set(channel.groups) <= set(GROUP_NAMES)


def test_a_run_has_the_tables_variables_with_their_units():
    groups = [g for g in GROUP_NAMES if g != "hydrodynamics"]  # (needs a scene with nonlinear hydrodynamics)
    ds = simulate(scene("m4-111", sea={"duration": "4 Tp", "ramp": "1 Tp"}, outputs={"variables": groups}))
    table = {v.name: v for v in VARIABLES}
    attrs = variable_attrs()
    for name, variable in ds.data_vars.items():
        assert name in table, name
        assert variable.dims == table[name].dims, name
        assert variable.attrs["units"] == attrs[name]["units"], name
        assert variable.attrs["long_name"] == attrs[name]["long_name"], name
    # every group the scene asked for is there (m4-111: rotary PTOs only, no generalised modes)
    present = {table[n].group for n in ds.data_vars}
    assert present == {*groups, "statistics"}


def test_the_record_holds_every_channel():
    from wecss.sim import compile_scene
    from wecss.sim.runners import BEEMAN

    compiled = compile_scene(scene("m4-111", sea={"duration": "4 Tp", "ramp": "1 Tp"}))
    record = BEEMAN.run(compiled)
    assert list(record.series) == list(CHANNEL_NAMES)
    assert all(np.all(np.isfinite(record[name])) for name in CHANNEL_NAMES)
