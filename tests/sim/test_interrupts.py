"""Ctrl-C inside the compiled time loop (issue 31, data safety): numba reports it as ``SystemError:
CPUDispatcher(<function beeman_chunk>) returned a result with an exception set`` with the KeyboardInterrupt as its
cause; ``simulate`` raises it as the KeyboardInterrupt it is, statistics-only or streamed, and an error that no
interrupt caused stays what it is."""

from __future__ import annotations

import pytest
import xarray as xr

from tests.sim.scenes import scene
from wecss.interrupts import Terminated, interrupt_behind, interrupts_surfaced
from wecss.sim import compile_scene, simulate
from wecss.sim._beeman import Beeman


def numba_interrupt() -> SystemError:
    """The exception numba's dispatcher leaves when Ctrl-C came during a compiled call (as CPython builds it:
    the interrupt as ``__cause__`` and ``__context__``)."""
    try:
        try:
            raise KeyboardInterrupt
        except KeyboardInterrupt as interrupt:
            raise SystemError("CPUDispatcher(<function beeman_chunk>) returned a result with an exception set") from (
                interrupt
            )
    except SystemError as err:
        return err


def interrupt_in_second_chunk(monkeypatch: pytest.MonkeyPatch) -> list[int]:
    """Beeman's kernel call raises numba's SystemError on its second chunk; returns the calls made."""
    calls: list[int] = []
    advance = Beeman.advance

    def interrupted(self, prepared, chunk):  # type: ignore[no-untyped-def]
        calls.append(1)
        if len(calls) == 2:
            raise numba_interrupt()
        return advance(self, prepared, chunk)

    monkeypatch.setattr(Beeman, "advance", interrupted)
    return calls


def test_an_interrupt_in_the_compiled_loop_of_a_statistics_only_run_is_a_keyboard_interrupt(monkeypatch):
    compiled = compile_scene(scene("m4-111", outputs={"statistics_only": True, "variables": []}))
    calls = interrupt_in_second_chunk(monkeypatch)
    with pytest.raises(KeyboardInterrupt) as info:
        simulate(compiled)
    assert len(calls) == 2
    assert info.value.__suppress_context__  # one clean interrupt, not numba's SystemError


def test_an_interrupt_in_the_compiled_loop_of_a_streamed_run_marks_its_partial_file_interrupted(tmp_path, monkeypatch):
    monkeypatch.setattr("wecss.sim._fixed_step.STREAM_STEPS", 100)  # a part is written before the interrupt
    compiled = compile_scene(scene("m4-111"))
    interrupt_in_second_chunk(monkeypatch)
    with pytest.raises(KeyboardInterrupt):
        simulate(compiled, path=tmp_path / "run.nc")
    assert not (tmp_path / "run.nc").exists()
    with xr.open_dataset(tmp_path / "run.partial.nc") as ds:
        assert ds.attrs["run_status"].endswith(": interrupted")


def test_a_system_error_without_an_interrupt_behind_it_stays_an_error(monkeypatch):
    compiled = compile_scene(scene("m4-111", outputs={"statistics_only": True, "variables": []}))

    def broken(self, prepared, chunk):  # type: ignore[no-untyped-def]
        raise SystemError("a kernel bug")

    monkeypatch.setattr(Beeman, "advance", broken)
    with pytest.raises(SystemError, match="a kernel bug"):
        simulate(compiled)


def test_the_interrupt_is_found_along_causes_and_contexts():
    assert isinstance(interrupt_behind(numba_interrupt()), KeyboardInterrupt)
    assert interrupt_behind(ValueError("no")) is None
    try:
        try:
            raise KeyboardInterrupt
        except KeyboardInterrupt:
            raise RuntimeError("raised while handling it")  # noqa: B904 - the context is what is tested
    except RuntimeError as err:
        assert isinstance(interrupt_behind(err), KeyboardInterrupt)


def test_a_sigterm_behind_numbas_system_error_stays_a_terminate():
    with pytest.raises(Terminated, match="SIGTERM"):
        with interrupts_surfaced():
            try:
                raise Terminated("terminated (SIGTERM)")
            except Terminated as terminated:
                raise SystemError("CPUDispatcher(<function beeman_chunk>) returned a result") from terminated
