"""The progress report (issue 18): the time left on a terminal; on a log (not a terminal) a plain line per tenth
of the run, not a bar redrawn every chunk."""

from __future__ import annotations

import io

from wecss.sim._progress import Progress, format_seconds


class _Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


def test_a_log_gets_one_plain_line_per_tenth():
    log = io.StringIO()
    bar = Progress(1000, True, log)
    for done in range(10, 1001, 10):  # 100 updates
        bar.update(done)
    lines = log.getvalue().splitlines()
    assert 10 <= len(lines) <= 11
    assert "\r" not in log.getvalue()
    assert lines[-1].startswith("100% 1000/1000 steps") and lines[-1].endswith("left")


def test_a_terminal_gets_a_bar_with_the_time_left():
    term = _Terminal()
    bar = Progress(100, True, term)
    bar.update(50)
    bar.update(100)
    text = term.getvalue()
    assert text.count("\r") == 2 and "left" in text and text.endswith("\n")


def test_disabled_writes_nothing():
    log = io.StringIO()
    Progress(10, False, log).update(10)
    assert log.getvalue() == ""


def test_format_seconds():
    assert (format_seconds(12.4), format_seconds(185), format_seconds(3720)) == ("12s", "3m05s", "1h02m")
