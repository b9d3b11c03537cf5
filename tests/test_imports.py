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
        "import numpy as np\nfrom wecss.compiled.kernels import matvec\nout = np.zeros(2)\n"
        "matvec(np.eye(2), np.ones(2), out)\nassert out.tolist() == [1.0, 1.0]"
    )
    assert ("numba" in loaded) == JIT


def test_a_run_outside_its_time_loop_loads_no_scipy_signal_stats_integrate_or_optimize(tmp_path):
    """What ``wecss run`` does around the time loop (compile the default scene, write the result and its summary
    plot, with the Welch spectrum and the JONSWAP moments) imports none of scipy.signal, scipy.stats,
    scipy.integrate, scipy.optimize (0.1-0.5 s each at import)."""
    from tests.sim.scenes import scene
    from wecss.results import save
    from wecss.sim import simulate

    result = tmp_path / "r.nc"
    run = scene("m4-111", sea={"duration": "4 Tp", "ramp": "1 Tp"}, outputs={"variables": ["pto", "elevation"]})
    save(simulate(run), result)
    code = (
        "import os\nos.environ['WECSS_JIT'] = '0'\n"
        "from wecss.results import open_result, plot_summary, save\n"
        "from wecss.sim import Scene, compile_scene, default_scene_path\n"
        "compile_scene(Scene.from_toml(default_scene_path()))\n"
        f"ds = open_result({str(result)!r})\n"
        f"save(ds, {str(tmp_path / 'again.nc')!r})\n"
        f"plot_summary(ds, {str(tmp_path / 'r.png')!r})"
    )
    loaded = _loaded_after(code)
    assert "matplotlib" in loaded and (tmp_path / "r.png").is_file()
    heavy = ("scipy.signal", "scipy.stats", "scipy.integrate", "scipy.optimize")
    assert sorted(m for m in heavy if m in loaded) == []
