"""A run keeps its time series once: the loop stores only the arrays the scene's outputs read, and the Dataset's
variables are views of them (a run of 10^6 saved steps must fit in about 1 GB, ``docs/benchmarks.md``)."""

from __future__ import annotations

import numpy as np

from tests.sim.scenes import scene
from wecss.sim import build_result, compile_scene, simulate
from wecss.sim.runners import BEEMAN


def test_dataset_variables_are_views_of_the_record():
    compiled = compile_scene(scene("m4-134", outputs={"variables": ["motion", "pto", "excitation"]}))
    record = BEEMAN.run(compiled)
    ds = build_result(compiled, record)
    assert np.shares_memory(ds.angle.values, record["q"])
    assert np.shares_memory(ds.angular_velocity.values, record["v"])
    assert np.shares_memory(ds.pto_angle.values, record["x"])
    assert np.shares_memory(ds.excitation_force.values, record["exc"])
    assert not np.shares_memory(ds.pto_angle.values, ds.pto_angular_velocity.values)


def test_arrays_no_output_reads_are_not_kept_and_the_run_is_the_same():
    only_motion = compile_scene(scene("m4-134", outputs={"variables": ["motion"]}))
    record = BEEMAN.run(only_motion)
    n_save = record.time.size
    assert record["q"].shape[0] == record["a"].shape[0] == n_save
    assert record["x"].shape[0] == record["rad"].shape[0] == record["exc"].shape[0] == 1
    everything = simulate(scene("m4-134", outputs={"variables": ["motion", "pto", "excitation", "radiation"]}))
    motion = build_result(only_motion, record)
    np.testing.assert_array_equal(motion.angle.values, everything.angle.values)
    np.testing.assert_array_equal(motion.mean_pto_power.values, everything.mean_pto_power.values)
    # the scratch rows hold the last step's values, as the full record does
    np.testing.assert_array_equal(record["x"][0], everything.pto_angle.values[-1])
