"""Compile the time loops into numba's on-disk cache ahead of their first use (``wecss precompile``).

With numba (``wecss[fast]``) the kernels are compiled on their first call and cached on disk beside their modules
(``cache=True``); a fresh install compiles them in its first runs, minutes for each runner's loop (the default
scene's Beeman loop alone about 3.5 minutes of one core). :func:`precompile` runs a few steps of small scenes that
call every runner's loop and the nonlinear hydrodynamics' kernels, the first alone (it compiles the kernels the loops
share) and the others in ``jobs`` processes at once, so that later runs (the test suite's workers, which would each
compile them, a sweep's workers on a cluster sharing the install) load them from the cache. A numba type the scenes here
do not meet is still compiled on first use.
"""

from __future__ import annotations

import sys
import time
from concurrent.futures import ProcessPoolExecutor, as_completed
from multiprocessing import get_context
from typing import Any

from ..compiled import JIT

_SEA = {"kind": "jonswap", "height": 0.04, "period": 1.2, "duration": 0.6, "ramp": 0.1, "seed": 1}
_BASE: dict[str, Any] = {
    "device": {"name": "m4-134"},
    "sea": _SEA,
    "controller": {"name": "damping", "parameters": {"damping": 6.0}},
    "radiation": {"method": "state_space"},
    "outputs": {"variables": ["motion", "pto"]},
}
_NONLINEAR = {"hydrostatics": "body-exact", "froude_krylov": "body-exact"}


def _scene(**sections: dict[str, Any]) -> dict[str, Any]:
    """A 0.6 s JONSWAP run of M4 134 with state-space radiation and a damping PTO, with ``sections`` replaced."""
    return {**_BASE, **sections}


PRECOMPILED: dict[str, dict[str, Any]] = {
    "beeman": _scene(solver={"method": "beeman"}),
    "rk4": _scene(solver={"method": "rk4"}),
    "generalized-alpha": _scene(solver={"method": "generalized-alpha"}),
    "beeman-explicit": _scene(solver={"method": "beeman-explicit"}),
    "beeman, convolution memory": _scene(solver={"method": "beeman"}, radiation={"method": "convolution"}),
    "beeman, body-exact": _scene(solver={"method": "beeman"}, hydrodynamics=_NONLINEAR),
    "rk4, body-exact": _scene(solver={"method": "rk4"}, hydrodynamics=_NONLINEAR),
    "generalized-alpha, body-exact": _scene(solver={"method": "generalized-alpha"}, hydrodynamics=_NONLINEAR),
    "linear": _scene(solver={"method": "linear"}),
    "reference": _scene(solver={"method": "reference"}),
}
"""The scenes :func:`precompile` runs, by name (``Scene.from_dict``'s input): a few steps of each runner whose time
loop numba compiles, with linear and with body-exact hydrodynamics, and of the runners that call the compiled
equations from Python (the linear model's linearisation, the reference solver)."""


def precompile(jobs: int = 2, progress: bool = True) -> dict[str, float]:
    """Run every scene of :data:`PRECOMPILED` in ``jobs`` processes (each compiles or loads what its loop needs) and
    return each one's wall time [s] (nothing without numba: the kernels then run as Python).

    Raises
    ------
    ValueError
        If ``jobs`` is not a whole number of at least 1.
    """
    if isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1:
        raise ValueError(f"jobs must be a whole number of at least 1, got {jobs!r}")
    if not JIT:
        if progress:
            print("precompile: numba is not installed (or WECSS_JIT=0): nothing to compile", file=sys.stderr)
        return {}
    times: dict[str, float] = {}
    start = time.perf_counter()
    first, *rest = PRECOMPILED
    with ProcessPoolExecutor(max_workers=jobs, mp_context=get_context("spawn")) as pool:
        # the first scene alone: it compiles the kernels every loop shares, which the others then load
        for names in ([first], rest):
            futures = {pool.submit(_run, name): name for name in names}
            for future in as_completed(futures):
                name = futures[future]
                times[name] = future.result()
                if progress:
                    print(
                        f"precompile: {name} ({times[name]:.0f} s; {len(times)}/{len(PRECOMPILED)}, "
                        f"{time.perf_counter() - start:.0f} s in all)",
                        file=sys.stderr,
                    )
    return times


def _run(name: str) -> float:
    """Run the scene ``name`` of :data:`PRECOMPILED`; its wall time [s]."""
    from ..scene import Scene
    from ._simulate import simulate

    begin = time.perf_counter()
    simulate(Scene.from_dict(PRECOMPILED[name]))
    return time.perf_counter() - begin
