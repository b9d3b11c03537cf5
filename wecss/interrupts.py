"""Interrupts from outside a run (floor 0): Ctrl-C (SIGINT) and, under the ``wecss`` command, SIGTERM.

An interrupt is never a failure of the run: it stops it, what was finished is kept and what was not stays to be
done. :class:`Terminated` (a KeyboardInterrupt) is what SIGTERM raises where :func:`sigterm_raises` is in force
(the ``wecss`` command), so every path that handles Ctrl-C handles it too. :func:`interrupts_surfaced` finds an
interrupt that numba reported as a SystemError. :func:`interrupts_held` defers both signals while a file is written
(the netCDF library's file lock would otherwise hang the process) and raises them after.
"""

from __future__ import annotations

import contextlib
import signal
import threading
from collections.abc import Iterator


class Terminated(KeyboardInterrupt):
    """The process was asked to end (SIGTERM): an interrupt from outside, handled as Ctrl-C is."""


def interrupt_behind(err: BaseException) -> KeyboardInterrupt | None:
    """The interrupt that ``err`` stands for, or None.

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
    """Raise the interrupt (a KeyboardInterrupt, or :class:`Terminated`) behind any exception of the block that one
    caused (:func:`interrupt_behind`): Ctrl-C inside a compiled loop is an interrupt, not an error of the run."""
    try:
        yield
    except Exception as err:
        interrupt = interrupt_behind(err)
        if interrupt is None:
            raise
        raise type(interrupt)(*interrupt.args) from None


def _raise_terminated(signum: int, frame: object) -> None:
    raise Terminated(f"terminated ({signal.Signals(signum).name})")


@contextlib.contextmanager
def sigterm_raises() -> Iterator[None]:
    """SIGTERM raises :class:`Terminated` in the block (on the main thread; elsewhere nothing changes), so that a
    terminated run cleans up as an interrupted one: temporary files removed, a partial file's status saying it
    stopped."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = signal.signal(signal.SIGTERM, _raise_terminated)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


HELD = (signal.SIGINT, signal.SIGTERM)
"""The signals :func:`interrupts_held` defers."""


@contextlib.contextmanager
def interrupts_held() -> Iterator[list[int]]:
    """Record SIGINT (Ctrl-C) and SIGTERM for the duration instead of acting on them (on the main thread, where Python
    handles signals; a signal the process ignores stays ignored); yields a list of the signals that came, a block
    that sees one abandons its work. On leaving, a SIGTERM is delivered again to the handler it had before
    (:class:`Terminated` under :func:`sigterm_raises`; by default the process ends) and, when that handler returns,
    raises :class:`Terminated`; a SIGINT raises KeyboardInterrupt."""
    came: list[int] = []
    if threading.current_thread() is not threading.main_thread():
        yield came
        return

    def record(signum: int, frame: object) -> None:
        came.append(signum)

    # a handler installed outside Python (None) could not be put back: such signals are left alone, as ignored ones
    held = [signum for signum in HELD if signal.getsignal(signum) not in (signal.SIG_IGN, None)]
    previous = {signum: signal.signal(signum, record) for signum in held}
    try:
        yield came
    finally:
        for signum, handler in previous.items():
            signal.signal(signum, handler)
    if signal.SIGTERM in came:
        signal.raise_signal(signal.SIGTERM)
        raise Terminated("terminated (SIGTERM)")
    if came:
        raise KeyboardInterrupt
