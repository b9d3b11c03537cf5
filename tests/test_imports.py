"""What ``import wecss.sim`` loads: the heavy modules that only some paths need wait until they are used (issue 15:
numba until the first kernel call, scipy.optimize until a frequency-domain design, the control toolboxes until a
controller needs them)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
DEFERRED = ("numba", "scipy.optimize", "scipy.signal", "scipy.stats", "control", "cvxpy", "matplotlib")


def _loaded_after(code: str) -> set[str]:
    probe = f"{code}\nimport sys\nprint(' '.join(sorted(sys.modules)))"
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    out = subprocess.run([sys.executable, "-c", probe], env=env, check=True, capture_output=True, text=True)
    return set(out.stdout.split())


def test_importing_wecss_sim_loads_none_of_the_deferred_modules():
    loaded = _loaded_after("import wecss.sim")
    assert "wecss.sim" in loaded
    assert sorted(m for m in DEFERRED if m in loaded) == []


def test_the_first_kernel_call_loads_numba_when_it_is_used():
    from wecss.compiled import JIT

    loaded = _loaded_after(
        "import numpy as np\nfrom wecss.compiled import matvec\nout = np.zeros(2)\n"
        "matvec(np.eye(2), np.ones(2), out)\nassert out.tolist() == [1.0, 1.0]"
    )
    assert ("numba" in loaded) == JIT
