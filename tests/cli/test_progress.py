"""The progress reporter's first-run behaviour: kernel compilation is announced once, and the
time-left estimate never includes compile time; numba's compile events reach it."""

from __future__ import annotations

import io

import numba
import pytest

from floatmoor._numba import watch_compilation
from floatmoor.cli.progress import COMPILING_MESSAGE, ProgressReporter


class _Clock:
    """A wall clock the test moves by hand [s]."""

    def __init__(self) -> None:
        self.now = 0.0

    def __call__(self) -> float:
        return self.now


def _reporter(stream: io.StringIO, clock: _Clock) -> ProgressReporter:
    return ProgressReporter(15.0, stream=stream, delay=0.0, interval=0.0, clock=clock)


def test_estimate_starts_after_compiling_and_the_message_is_said_once():
    """Lindahl's first run: 20 s of compiling in the first chunk, then 1 s per 5 s simulated.
    Before, the line said '~44.9 s left' at t = 5 s; the truth is 1 s."""
    stream, clock = io.StringIO(), _Clock()
    report = _reporter(stream, clock)
    report.compiling()
    clock.now = 20.0
    report.compiled(20.0)
    report.compiling()  # a second kernel: no second message
    clock.now = 20.2
    report.compiled(0.2)
    clock.now = 21.0
    report(5.0)  # the chunk that compiled: no estimate
    clock.now = 22.0
    report(10.0)
    lines = stream.getvalue().splitlines()
    assert lines[0] == COMPILING_MESSAGE
    assert sum(COMPILING_MESSAGE in line for line in lines) == 1
    assert "t = 5 / 15 s" in lines[1] and "left" not in lines[1]
    assert "t = 10 / 15 s" in lines[2] and lines[2].endswith("~1.0 s left")
    assert report.compile_time == pytest.approx(20.2)


def test_no_estimate_while_compiling():
    """A kernel compiled mid-run (a report from another thread, or a callback inside the
    compiled code) shows no estimate until a chunk after it has been simulated."""
    stream, clock = io.StringIO(), _Clock()
    report = _reporter(stream, clock)
    clock.now = 1.0
    report(3.0)
    clock.now = 2.0
    report(6.0)
    report.compiling()
    clock.now = 12.0
    report(7.0)
    lines = stream.getvalue().splitlines()
    assert lines[1].endswith("~3.0 s left")  # 3 s simulated per wall second since t = 3 s
    assert lines[2] == COMPILING_MESSAGE and "left" not in lines[3]


def test_warm_run_estimates_from_the_first_report():
    """No compilation: no message; the rate since the first report, not since the reporter
    was made (set-up, or the part of a resumed run done before)."""
    stream, clock = io.StringIO(), _Clock()
    report = _reporter(stream, clock)
    clock.now = 4.0  # set-up, or a resumed run's first chunk starting at t = 7.5 s
    report(7.5)
    clock.now = 5.0
    report(10.0)
    text = stream.getvalue()
    assert COMPILING_MESSAGE not in text
    assert text.splitlines()[1].endswith("~2.0 s left")


def test_message_on_a_terminal_ends_the_open_progress_line():
    class Tty(io.StringIO):
        def isatty(self) -> bool:
            return True

    stream, clock = Tty(), _Clock()
    report = _reporter(stream, clock)
    report(5.0)
    report.compiling()
    report.compiled(1.0)
    report.close()
    assert stream.getvalue() == ("\rfloatmoor: t = 5 / 15 s (33%), 0.0 s elapsed\x1b[K"
                                 f"\r{COMPILING_MESSAGE}\x1b[K\n")


def test_watch_compilation_reports_compiles_not_calls():
    """A fresh kernel and the one it calls make one (outermost) compilation; calling it
    again compiles nothing."""
    @numba.njit
    def inner(x):
        return 2.0 * x

    @numba.njit
    def outer(x):
        return inner(x) + 1.0

    events = []
    with watch_compilation(lambda: events.append("start"), events.append):
        assert outer(1.0) == 3.0
        assert outer(2.0) == 5.0
    assert events[0] == "start" and len(events) == 2 and events[1] > 0.0
    with watch_compilation(lambda: events.append("start"), events.append):
        outer(3.0)
    assert len(events) == 2


def test_a_restarted_run_says_why_and_estimates_again():
    """A coupled run whose probe raised a line's elements starts again from t = 0: the reason
    is said on its own line, and the estimate is not taken across the restart (t falling)."""
    stream, clock = io.StringIO(), _Clock()
    report = _reporter(stream, clock)
    clock.now = 1.0
    report(3.0)
    clock.now = 2.0
    report(6.0)
    report.restarted("line 'line1' raised from 8 to 11 elements: the run starts again")
    clock.now = 3.0
    report(2.0)
    clock.now = 4.0
    report(4.0)
    lines = stream.getvalue().splitlines()
    assert lines[2] == ("floatmoor: line 'line1' raised from 8 to 11 elements: the run starts "
                        "again")
    assert "t = 2 / 15 s" in lines[3] and "left" not in lines[3]
    assert lines[4].endswith("~5.5 s left")
