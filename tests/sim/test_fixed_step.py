"""The nonlinear loop's excitation: evaluated once for the whole run (one inverse FFT on a record whose components
are harmonics of its duration), in blocks of samples (a chirp-z transform each, for runs too long for one table)
or per chunk of steps (sums of the components, for records that do not repeat) gives the same run to round-off."""

from __future__ import annotations

import numpy as np
import pytest

import wecss.sim._fixed_step as fixed_step
from tests.sim.scenes import compiled_with_state_space, scene
from wecss.sim import simulate

BLOCK: int = 500
"""Samples per block in the tests (the 12 s runs below span several blocks, at 2000 or 4000 samples)."""


def _same_run(first, second) -> None:  # type: ignore[no-untyped-def]
    scale = np.max(np.abs(second.angle.values))
    assert scale > 1e-3  # the sea moves the device
    np.testing.assert_allclose(first.angle.values, second.angle.values, rtol=0.0, atol=1e-10 * scale)
    np.testing.assert_allclose(first.pto_power.values, second.pto_power.values, rtol=1e-9, atol=1e-14)


@pytest.mark.parametrize("method", ["beeman", "rk4"])
def test_excitation_table_and_blocks_give_the_same_run(method, monkeypatch):
    compiled = compiled_with_state_space(
        scene("m4-111", solver={"method": method}, sea={"duration": 12.0}, radiation={"method": "none"})
    )
    per_step = 2 if method == "rk4" else 1
    table = fixed_step._Excitation(compiled, per_step)
    assert table.table is not None and table.sampled is None  # (the test compares the two paths)
    with_table = simulate(compiled)
    monkeypatch.setattr(fixed_step, "EXCITATION_TABLE_MAX", BLOCK * compiled.plant.hydro_index.size)
    blocks = fixed_step._Excitation(compiled, per_step)
    assert blocks.table is None and blocks.sampled is not None
    _same_run(with_table, simulate(compiled))


@pytest.mark.parametrize("per_step", [1, 2])
def test_excitation_blocks_equal_the_table_at_every_chunk(per_step, monkeypatch):
    """Chunk by chunk through a run, across the blocks' boundaries (the chunks end inside blocks and the next chunk
    starts a new one)."""
    compiled = compiled_with_state_space(scene("m4-111", sea={"duration": 12.0}, radiation={"method": "none"}))
    table = fixed_step._Excitation(compiled, per_step).table
    assert table is not None
    monkeypatch.setattr(fixed_step, "EXCITATION_TABLE_MAX", BLOCK * compiled.plant.hydro_index.size)
    excitation = fixed_step._Excitation(compiled, per_step)
    done, starts = 0, set()
    while done < compiled.n_steps:
        m = min(333, compiled.n_steps - done)
        got = excitation.chunk(done, m)
        np.testing.assert_allclose(
            got, table[per_step * done : per_step * (done + m) + 1], rtol=0, atol=1e-13 * np.abs(table).max()
        )
        starts.add(excitation.start)
        done += m
    assert len(starts) > 2  # several blocks were made
    assert excitation.table is not None and excitation.table.shape[0] <= max(333 * per_step + 1, 2 * BLOCK)


def test_excitation_table_and_per_chunk_sums_give_the_same_run(monkeypatch):
    """A record that does not repeat (frequencies drawn in their bins) is summed per chunk of steps."""
    compiled = compiled_with_state_space(
        scene("m4-111", sea={"duration": 12.0, "periodic": False}, radiation={"method": "none"})
    )
    assert fixed_step._Excitation(compiled, 1).table is not None
    with_table = simulate(compiled)
    monkeypatch.setattr(fixed_step, "EXCITATION_TABLE_MAX", 0)
    per_chunk = fixed_step._Excitation(compiled, 1)
    assert per_chunk.table is None and per_chunk.sampled is None
    _same_run(with_table, simulate(compiled))
