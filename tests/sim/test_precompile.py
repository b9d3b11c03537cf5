"""``wecss precompile``: its scenes are valid scenes that name every runner that calls the compiled kernels, bad job
counts are refused, and without numba it compiles nothing and says so."""

from __future__ import annotations

import pytest

import wecss.sim._precompile as pc
from wecss.scene import Scene, available_runners
from wecss.sim import compile_scene, precompile


def test_the_scenes_compile_and_cover_the_runners_with_compiled_loops():
    named = set()
    for name in pc.PRECOMPILED:
        sc = Scene.from_dict(pc.PRECOMPILED[name])
        compile_scene(sc)  # a scene the runner takes (its checks run here)
        named.add(sc.solver.method)
    # the runners whose loops numba compiles, and those that call the compiled equations from Python
    compiled = {"beeman", "beeman-explicit", "rk4", "generalized-alpha", "linear", "reference"}
    assert compiled <= set(available_runners())
    assert named == compiled


@pytest.mark.parametrize("jobs", [0, -1, 1.5, True, "2"])
def test_a_bad_job_count_is_refused(jobs):
    with pytest.raises(ValueError, match=f"jobs must be a whole number of at least 1, got {jobs!r}"):
        precompile(jobs)


def test_without_numba_nothing_is_compiled(monkeypatch, capsys):
    monkeypatch.setattr(pc, "JIT", False)
    assert precompile(2) == {}
    assert "numba is not installed (or WECSS_JIT=0): nothing to compile" in capsys.readouterr().err


def test_the_command_refuses_a_bad_job_count_without_a_traceback(capsys):
    from wecss.cli import main

    assert main(["precompile", "--jobs", "0"]) == 2
    assert "wecss: error: jobs must be a whole number of at least 1, got 0" in capsys.readouterr().err
