"""A time limit on each call of a controller's ``compute`` (the scene's ``controller.time_limit`` [s]): a call that
runs past it raises :class:`ControllerTimeout` in the run, naming the controller, the call's time and the limit.

How, and why this way. A ``compute`` that never returns cannot be caught by a clock read after it returns, and
arming a timer (``signal.setitimer``) around every call costs two system calls per call (measured 3.8 us, a third
of the 11 us a controller call costs on the test scene). So each call only writes its start time into a shared
slot (one clock read, well under a microsecond), and a daemon thread, one per process, reads the slot every
``POLL_S`` seconds; when a call has run past its limit it sends SIGALRM to the main thread, whose handler raises
the error inside the stuck call (and again after every further limit, should the call catch it and carry on). The
signal is sent only then: a normal run sees no signal and pays nothing else. The handler is installed once per run
with a sampled controller and left in place after it (installing it costs some 10 us, too much per call); a SIGALRM
the watchdog did not send gets its default action, as without it.

Limits: a signal handler runs between Python bytecodes, so a ``compute`` stuck inside compiled code (a C extension
that never returns to Python) is stopped only when it does; a blocking system call such as ``time.sleep`` is
interrupted. The watchdog needs the main thread (Python runs signal handlers there) and SIGALRM free (its handler
the default one or this module's): elsewhere (a run in another thread, a process that uses SIGALRM itself, Windows)
the run goes on without it and the result's notes say so (:func:`unenforced`).
"""

from __future__ import annotations

import math
import os
import signal
import threading
import time
from types import FrameType

from ._errors import ControllerTimeout

POLL_S: float = 0.05
"""How often [s] the watchdog thread looks at the call in progress: a call is stopped between ``limit`` and
``limit + POLL_S`` seconds after it started."""


class _Slot:
    """The call in progress (shared by the run and the watchdog thread): its start [s, ``time.perf_counter``],
    its limit [s], its run's watchdog and the simulation time of the call [s]; ``sent`` counts the signals the
    thread sent, ``handled`` those the handler took."""

    def __init__(self) -> None:
        self.started: float | None = None
        self.limit = math.inf
        self.owner: Watchdog | None = None
        self.t = 0.0
        self.sent = 0
        self.handled = 0


_SLOT = _Slot()
_THREAD: threading.Thread | None = None
_MAIN = threading.main_thread()


def _watch() -> None:
    """The watchdog thread: signal the main thread when a call runs past its limit, and again after every further
    limit while the same call goes on (a ``compute`` that catches the error and carries on is stopped again)."""
    call: float | None = None  # the start of the call last signalled
    signals = 0  # signals sent to that call
    while True:
        started, limit = _SLOT.started, _SLOT.limit
        if started is None:
            time.sleep(POLL_S)
            continue
        if started != call:
            call, signals = started, 0
        left = started + (signals + 1) * limit - time.perf_counter()
        if left > 0:
            time.sleep(min(left, POLL_S))
            continue
        signals += 1
        _SLOT.sent += 1
        if _MAIN.ident is not None:
            signal.pthread_kill(_MAIN.ident, signal.SIGALRM)


def _on_alarm(signum: int, frame: FrameType | None) -> None:
    """SIGALRM in the main thread: the watchdog's (raise in the stuck call) or anyone else's (its default action:
    the process ends, as it would have without this handler)."""
    if _SLOT.sent > _SLOT.handled:
        _SLOT.handled = _SLOT.sent
        if _SLOT.started is not None and _SLOT.owner is not None:
            raise ControllerTimeout(_SLOT.owner.message(_SLOT.t))
        return  # the call returned between the thread's look and the signal
    signal.signal(signal.SIGALRM, signal.SIG_DFL)
    os.kill(os.getpid(), signal.SIGALRM)


def unenforced(limit: float) -> str | None:
    """A note for the result of a run in this thread with a sampled controller and ``controller.time_limit``
    ``limit`` [s] when the watchdog could not enforce it here (None when it could, or there is no limit)."""
    why = None if math.isinf(limit) else _can_watch()
    if why is None:
        return None
    return (
        f"controller.time_limit ({limit:g} s) was not enforced: {why} (the watchdog needs the main thread and SIGALRM)"
    )


def _can_watch() -> str | None:
    """None when the watchdog can run here, else why not (a sentence for the result's notes)."""
    if not hasattr(signal, "pthread_kill") or not hasattr(signal, "SIGALRM"):
        return "this platform has no SIGALRM"
    if threading.current_thread() is not _MAIN:
        return "the run is not in the main thread"
    if signal.getsignal(signal.SIGALRM) not in (signal.SIG_DFL, _on_alarm):
        return "SIGALRM has a handler of its own in this process"
    return None


class Watchdog:
    """The time limit of one run's controller calls.

    Parameters
    ----------
    limit : float
        Time limit of one call [s] (``controller.time_limit``); ``inf``: none.
    name : str
        The controller, as the error names it (``'mpc' (MPC)``).
    """

    def __init__(self, limit: float, name: str) -> None:
        self.limit, self.name = float(limit), name
        self.active = not math.isinf(self.limit) and _can_watch() is None
        if self.active:
            signal.signal(signal.SIGALRM, _on_alarm)
            _start_thread()

    def enter(self, t: float) -> None:
        """A call at simulation time ``t`` [s] starts."""
        if self.active:
            _SLOT.owner, _SLOT.t, _SLOT.limit = self, t, self.limit
            _SLOT.started = time.perf_counter()

    def message(self, t: float) -> str:
        """The error of a call at simulation time ``t`` [s] that ran past the limit."""
        return (
            f"controller {self.name}: compute at t = {t:.6g} s did not return within controller.time_limit = "
            f"{self.limit:g} s; make the call faster or give a larger controller.time_limit [s] (inf: no limit)"
        )

    def leave(self) -> None:
        """The call returned (or raised)."""
        _SLOT.started = None


def _start_thread() -> None:
    global _THREAD
    if _THREAD is None or not _THREAD.is_alive():
        _THREAD = threading.Thread(target=_watch, name="wecss-controller-watchdog", daemon=True)
        _THREAD.start()
