"""The per-step kernels count no references per call beyond a few (docs/architecture.md, "No reference counts per
step"): a helper that numba cannot inline into ``configure`` or ``respond`` would make every array of the Plant and
Workspace tuples count up and down on every evaluation (40 % of a step before issue 15)."""

from __future__ import annotations

import re

import numpy as np
import pytest

from tests.sim.scenes import elastic_notc_spec, scene
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


ELASTIC_LIMITS = {"configure_elastic": 150, "respond_elastic": 120}
"""``NRT_incref`` calls in the flexible bodies' kernels, the elastic NOTC arm (measured: configure_elastic 136,
respond_elastic 104; 577 and 333 when their helpers read the Plant and Workspace after their first opaque call,
docs/architecture.md). Their helpers that stay calls count their own arguments' references."""


@pytest.mark.slow  # (compiles both kernels afresh: about a minute)
@pytest.mark.skipif(not JIT, reason="counts the references of numba-compiled code")
def test_the_elastic_kernels_read_the_tuples_before_their_calls(tmp_path):
    import wecss.hydro
    from wecss.compiled.kernels import configure_elastic, respond_elastic

    if "notc-10kw" not in wecss.hydro.available():
        pytest.skip("shipped database notc-10kw not generated yet")
    compiled = compile_plant(scene(elastic_notc_spec(tmp_path)))
    p, w = compiled.plant, workspace(compiled.plant)
    assert p.n_elastic > 0
    configure(p, compiled.q0, np.zeros(p.hydro_index.size), 0.0, w)
    fresh = {"configure_elastic": _fresh(configure_elastic), "respond_elastic": _fresh(respond_elastic)}
    fresh["configure_elastic"](p, compiled.q0, np.zeros(p.hydro_index.size), 0.0, w)
    n_h = p.hydro_index.size
    fresh["respond_elastic"](p, np.zeros(p.twists.shape[0]), np.zeros((n_h, n_h)), np.zeros(p.pto_kind.size), w)
    for name, kernel in fresh.items():
        irs = list(kernel.inspect_llvm().values())
        assert irs and all("define" in ir for ir in irs), f"{name}: no LLVM IR to count in"
        # the kernel's own body: its callees' bodies are linked into the IR too
        own = [re.search(rf"define [^@]*@\S*{name}\S*\((.*?)^}}", ir, re.S | re.M) for ir in irs]
        counts = [m.group(0).count("call void @NRT_incref") for m in own if m]
        assert counts, f"{name}: its body not found in the IR"
        limit = ELASTIC_LIMITS[name]
        assert max(counts) <= limit, f"{name}: {counts} NRT_incref calls (at most {limit})"
