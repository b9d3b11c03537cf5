"""The nonlinear loop's excitation: evaluated once for the whole run (one inverse FFT on a record whose components
are harmonics of its duration) or per chunk of steps (sums of the components) gives the same run to round-off."""

from __future__ import annotations

import numpy as np
import pytest

import wecss.sim._fixed_step as fixed_step
from tests.sim.scenes import compiled_with_state_space, scene
from wecss.sim import simulate


@pytest.mark.parametrize("method", ["beeman", "rk4"])
def test_excitation_table_and_per_chunk_sums_give_the_same_run(method, monkeypatch):
    compiled = compiled_with_state_space(
        scene("m4-111", solver={"method": method}, sea={"duration": 12.0}, radiation={"method": "none"})
    )
    table = fixed_step._Excitation(compiled, 2 if method == "rk4" else 1)
    assert table.table is not None  # (the test compares the two paths: the table must be in use)
    with_table = simulate(compiled)
    monkeypatch.setattr(fixed_step, "EXCITATION_TABLE_MAX", 0)
    assert fixed_step._Excitation(compiled, 1).table is None
    per_chunk = simulate(compiled)
    scale = np.max(np.abs(per_chunk.angle.values))
    assert scale > 1e-3  # the sea moves the device
    np.testing.assert_allclose(with_table.angle.values, per_chunk.angle.values, rtol=0.0, atol=1e-10 * scale)
    np.testing.assert_allclose(with_table.pto_power.values, per_chunk.pto_power.values, rtol=1e-9, atol=1e-14)
