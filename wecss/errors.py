"""The base classes of what wecss raises and warns, below every package (floor 0).

``WecssWarning`` is the base of every warning wecss issues, so that users (and the test suite, which turns them into
errors) can filter the package's own warnings at once: ``warnings.simplefilter("error", WecssWarning)`` or
``-W error::wecss.errors.WecssWarning``.
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterator


class WecssWarning(UserWarning):
    """Base class of the warnings wecss issues (the test suite turns them into errors)."""


def interrupt_behind(err: BaseException) -> KeyboardInterrupt | None:
    """The Ctrl-C that ``err`` stands for, or None.

    An interrupt that arrives while a numba-compiled function runs can surface as ``SystemError:
    CPUDispatcher(<function ...>) returned a result with an exception set``, the KeyboardInterrupt as its
    ``__cause__`` or ``__context__``; this finds it along the chain of causes and contexts.
    """
    seen: set[int] = set()
    current: BaseException | None = err
    while current is not None and id(current) not in seen:
        if isinstance(current, KeyboardInterrupt):
            return current
        seen.add(id(current))
        current = current.__cause__ or current.__context__
    return None


@contextlib.contextmanager
def interrupts_surfaced() -> Iterator[None]:
    """Raise a KeyboardInterrupt for any exception in the block that an interrupt caused (:func:`interrupt_behind`):
    Ctrl-C inside a compiled loop is an interrupt, not an error of the run."""
    try:
        yield
    except Exception as err:
        if interrupt_behind(err) is None:
            raise
        raise KeyboardInterrupt from None
