"""The per-step kernels count no references per call beyond a few (docs/architecture.md, "No reference counts per
step"): a helper that numba cannot inline into ``configure`` or ``respond`` would make every array of the Plant and
Workspace tuples count up and down on every evaluation (40 % of a step before issue 15)."""

from __future__ import annotations

import numpy as np
import pytest

from tests.sim.scenes import scene
from wecss.compiled import JIT, compile_plant
from wecss.compiled.kernels import configure, configure_core, respond_core, workspace

LIMITS = {"configure_core": 11, "respond_core": 3}
"""``NRT_incref`` calls in the kernels' LLVM IR (measured: configure_core 11, respond_core 3). ``configure`` is
``configure_core`` plus, only for plants with body-exact forces, a call of the mesh kernels (which pays its own
arguments' counts: it cannot be inlined); ``respond`` is ``respond_core`` (plants with flexible bodies go
through ``configure_elastic`` and ``respond_elastic`` instead)."""


def _fresh(kernel):  # type: ignore[no-untyped-def]
    """The kernel compiled afresh with its own options but no disk cache (numba gives no IR for cached code)."""
    import numba

    options = {k: v for k, v in kernel.targetoptions.items() if k not in ("cache", "nopython")}
    return numba.njit(**options)(kernel.py_func)


@pytest.mark.skipif(not JIT, reason="counts the references of numba-compiled code")
def test_the_per_step_kernels_count_few_references():
    compiled = compile_plant(scene("m4-134"))
    p, w = compiled.plant, workspace(compiled.plant)
    configure(p, compiled.q0, np.zeros(p.hydro_index.size), 0.0, w)  # (the real kernels first: numba imported)
    fresh = {"configure_core": _fresh(configure_core), "respond_core": _fresh(respond_core)}
    fresh["configure_core"](p, compiled.q0, np.zeros(p.hydro_index.size), 0.0, w)
    fresh["respond_core"](p, np.zeros(p.twists.shape[0]), compiled.radiation.newest, np.zeros(p.pto_kind.size), w)
    for name, kernel in fresh.items():
        irs = list(kernel.inspect_llvm().values())
        assert irs and all("define" in ir for ir in irs), f"{name}: no LLVM IR to count in"
        counts = [ir.count("call void @NRT_incref") for ir in irs]
        assert max(counts) <= LIMITS[name], f"{name}: {counts} NRT_incref calls (at most {LIMITS[name]})"
