"""Optional numba compilation of the simulator's hot loops.

Functions decorated with :func:`kernel` are compiled with ``numba.njit(cache=True)`` when numba is installed
(``pip install "wecss[fast]"``) and run as plain Python/numpy otherwise, from the same source, so both paths give
the same numbers (to rounding). Set the environment variable ``WECSS_JIT=0`` before importing wecss to force the
pure-Python path.

numba itself is imported on the first call of a kernel, not when wecss is imported (importing numba takes about
0.35 s): until then a decorated function is a :class:`LazyKernel`. The first call makes every pending kernel a numba
dispatcher at once and puts the dispatchers in place of the lazy kernels among the globals of the modules that
define kernels, which is where numba looks up the kernels a kernel calls. Elsewhere a lazy kernel forwards its calls
to its dispatcher.
"""

from __future__ import annotations

import functools
import importlib.util
import os
from collections.abc import Callable
from typing import Any, TypeVar

F = TypeVar("F", bound=Callable[..., Any])


def _numba_available() -> bool:
    if os.environ.get("WECSS_JIT", "1").strip() in ("0", "false", "no", "off"):
        return False
    return importlib.util.find_spec("numba") is not None


JIT: bool = _numba_available()
"""True when the kernels are compiled with numba."""

_PENDING: list[LazyKernel] = []
_NUMBA: list[Any] = []  # the numba module once imported by the first call of a kernel


class LazyKernel:
    """A function that becomes ``numba.njit(**options)(fn)`` on the first call of any kernel (see the module
    docstring); calls and attributes (``py_func``, ``signatures`` ...) go to the dispatcher."""

    def __init__(self, fn: Callable[..., Any], options: dict[str, Any]) -> None:
        functools.update_wrapper(self, fn)
        self.fn = fn
        self.options = options
        self.dispatcher: Any = None

    def compiled(self) -> Any:
        """The numba dispatcher (importing numba and making every pending kernel on the first use)."""
        if self.dispatcher is None:
            _make_pending()
        return self.dispatcher

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        return self.compiled()(*args, **kwargs)

    def __getattr__(self, name: str) -> Any:
        if name.startswith("__") or name in ("fn", "options", "dispatcher"):
            raise AttributeError(name)
        return getattr(self.compiled(), name)

    def __repr__(self) -> str:
        return f"<LazyKernel {self.fn.__module__}.{self.fn.__qualname__}>"


def _numba() -> Any:
    if not _NUMBA:
        import warnings

        import numba
        from numba.core.errors import NumbaPerformanceWarning

        # small-matrix products on slices: numba notes they are not contiguous; the cost is measured, not guessed
        warnings.filterwarnings("ignore", category=NumbaPerformanceWarning)
        _register_reshaped()
        _NUMBA.append(numba)
    return _NUMBA[0]


def reshaped(a: Any, shape: tuple[int, ...]) -> Any:
    """``a.reshape(shape)`` for a C-contiguous array ``a`` (compiled: of numba's layout "C", such as a unit-step
    slice of a contiguous 1-D array or an entry of a contiguous array's first axis) whose size is the shape's
    product. Compiled, the view is made in place of numba's reshape, which calls out to a helper and
    may raise (about 30 ns per view, and a possible raise keeps numba from pruning a kernel's reference counts: the
    flexible bodies' kernels make a few dozen views of the plant's packed arrays per evaluation); the size is not
    checked there."""
    return a.reshape(shape)


def _register_reshaped() -> None:
    """The compiled form of :func:`reshaped` (numba imported: called once, by :func:`_numba`)."""
    from numba.core import cgutils, types
    from numba.core.errors import TypingError
    from numba.core.imputils import impl_ret_borrowed
    from numba.extending import intrinsic, overload
    from numba.np.arrayobj import make_array, populate_array

    @intrinsic
    def view(typingctx: Any, a: Any, shape: Any) -> Any:
        nd = len(shape)
        result = types.Array(a.dtype, nd, "C")

        def codegen(context: Any, builder: Any, sig: Any, args: Any) -> Any:
            ary = make_array(sig.args[0])(context, builder, args[0])
            items = cgutils.unpack_tuple(builder, args[1], nd)
            dims = [context.cast(builder, v, t, types.intp) for v, t in zip(items, sig.args[1], strict=True)]
            strides = [ary.itemsize] * nd
            for d in range(nd - 2, -1, -1):
                strides[d] = builder.mul(strides[d + 1], dims[d + 1])
            out = make_array(result)(context, builder)
            populate_array(out, data=ary.data, shape=dims, strides=strides, itemsize=ary.itemsize,
                           meminfo=ary.meminfo, parent=ary.parent)  # fmt: skip
            return impl_ret_borrowed(context, builder, result, out._getvalue())

        return result(a, shape), codegen

    @overload(reshaped, inline="always")
    def compiled(a, shape):  # (unannotated: numba compares this signature with the lambda's)
        if not (isinstance(a, types.Array) and a.layout == "C"):
            raise TypingError(f"reshaped takes a C-contiguous array; got {a}")
        if not (
            isinstance(shape, types.UniTuple | types.Tuple) and all(isinstance(t, types.Integer) for t in shape.types)
        ):
            raise TypingError(f"reshaped takes a tuple of integers as the shape; got {shape}")
        return lambda a, shape: view(a, shape)  # type: ignore[call-arg]  # (typingctx: numba's)


def _put_in_place(namespace: dict[str, Any]) -> None:
    """Replace the made lazy kernels among a module's globals by their dispatchers."""
    for name, value in list(namespace.items()):
        if isinstance(value, LazyKernel) and value.dispatcher is not None:
            namespace[name] = value.dispatcher


def _make_pending() -> None:
    numba = _numba()
    pending = list(_PENDING)
    _PENDING.clear()
    for lazy in pending:
        lazy.dispatcher = numba.njit(**lazy.options)(lazy.fn)
    namespaces = {id(lazy.fn.__globals__): lazy.fn.__globals__ for lazy in pending}
    for namespace in namespaces.values():
        _put_in_place(namespace)


def _njit(fn: F, options: dict[str, Any]) -> F:
    if _NUMBA:  # numba already imported: compile as usual
        _put_in_place(fn.__globals__)
        return _NUMBA[0].njit(**options)(fn)
    lazy = LazyKernel(fn, options)
    _PENDING.append(lazy)
    return lazy  # type: ignore[return-value]


def kernel(fn: F) -> F:
    """Compile ``fn`` with numba when available (see the module docstring)."""
    if not JIT:
        return fn
    return _njit(fn, {"cache": True})


def inline_kernel(fn: F) -> F:
    """As :func:`kernel`, and inlined into its compiled callers (numba's ``inline="always"``).

    A compiled function that takes tuples of arrays (the Plant, the Workspace) and calls another compiled function
    pays a reference count up and down for every array of those tuples on each of its calls: numba cannot prune
    the counts across an opaque call. A function whose callees are all inlined pays none (numba prunes them), so
    the helpers of the per-step kernels (``configure``, ``respond``) are inline kernels, and those kernels allocate
    nothing and assign no array slices (both are calls too).
    """
    if not JIT:
        return fn
    return _njit(fn, {"cache": True, "inline": "always"})


def reduction_kernel(fn: F) -> F:
    """As :func:`kernel`, allowing numba to reorder floating-point sums (SIMD) and to contract multiply-adds: for
    kernels made of products (long dot products; the per-step kernels, whose loop kernels are inlined and take
    these flags). Results change at round-off only. The flags keep NaN and infinity semantics (no "nnan" or
    "ninf"), so comparisons with them stay exact; still, keep divergence checks out of these kernels.
    """
    if not JIT:
        return fn
    return _njit(fn, {"cache": True, "fastmath": {"reassoc", "contract", "arcp"}})


def step_kernel(fn: F) -> F:
    """As :func:`reduction_kernel`, for the kernels the time loops call every step or evaluation (``configure``,
    ``respond``, the radiation memory's updates), with numpy's error model: a float division by zero gives inf or
    NaN instead of raising, which the loops' finiteness checks catch. (A possible raise is a branch out of the
    function that keeps numba from pruning the reference counts of the Plant and Workspace arrays; see
    :func:`inline_kernel`.)
    """
    if not JIT:
        return fn
    return _njit(fn, {"cache": True, "fastmath": {"reassoc", "contract", "arcp"}, "error_model": "numpy"})


def loop_kernel(fallback: Callable[..., Any]) -> Callable[[F], F]:
    """Compile the decorated loop with numba, inlined into its compiled callers (as :func:`inline_kernel`: the
    caller's fast-math flags apply, see :func:`reduction_kernel`); without numba use ``fallback`` instead: the same
    operation written with numpy, which the interpreter runs far faster than the loop. Both give the same numbers
    to rounding (the tests run the pure path against the compiled one).
    """

    def decorate(fn: F) -> F:
        if not JIT:
            return fallback  # type: ignore[return-value]
        return _njit(fn, {"cache": True, "fastmath": {"reassoc", "contract", "arcp"}, "inline": "always"})

    return decorate
