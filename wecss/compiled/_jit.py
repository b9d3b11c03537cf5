"""Optional numba compilation of the simulator's hot loops.

Functions decorated with :func:`kernel` are compiled with ``numba.njit(cache=True)`` when numba is installed
(``pip install "wecss[fast]"``) and run as plain Python/numpy otherwise, from the same source, so both paths give
the same numbers (to rounding). Set the environment variable ``WECSS_JIT=0`` before importing wecss to force the
pure-Python path.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from typing import Any, TypeVar

F = TypeVar("F", bound=Callable[..., Any])


def _numba_available() -> bool:
    if os.environ.get("WECSS_JIT", "1").strip() in ("0", "false", "no", "off"):
        return False
    try:
        import numba  # noqa: F401
    except ImportError:
        return False
    return True


JIT: bool = _numba_available()
"""True when the kernels are compiled with numba."""

if JIT:
    import warnings

    from numba.core.errors import NumbaPerformanceWarning

    # small-matrix products on slices: numba notes they are not contiguous; the cost is measured, not guessed
    warnings.filterwarnings("ignore", category=NumbaPerformanceWarning)


def kernel(fn: F) -> F:
    """Compile ``fn`` with numba when available (see the module docstring)."""
    if not JIT:
        return fn
    import numba

    return numba.njit(cache=True)(fn)  # type: ignore[return-value]


def reduction_kernel(fn: F) -> F:
    """As :func:`kernel`, allowing numba to reorder floating-point sums (SIMD) for long dot products only.

    Use it only for functions without NaN or infinity checks: fast-math assumes finite values.
    """
    if not JIT:
        return fn
    import numba

    return numba.njit(cache=True, fastmath={"reassoc", "contract", "arcp"})(fn)  # type: ignore[return-value]


def loop_kernel(fallback: Callable[..., Any]) -> Callable[[F], F]:
    """Compile the decorated loop with numba (fast-math reassociation, as :func:`reduction_kernel`); without
    numba use ``fallback`` instead: the same operation written with numpy, which the interpreter runs far faster
    than the loop. Both give the same numbers to rounding (the tests run the pure path against the compiled one).
    """

    def decorate(fn: F) -> F:
        return reduction_kernel(fn) if JIT else fallback  # type: ignore[return-value]

    return decorate
