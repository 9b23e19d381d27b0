"""Progress of long runs, on standard error."""

from __future__ import annotations

import sys
import time as _time
from typing import Callable, TextIO

__all__ = ["ProgressReporter", "COMPILING_MESSAGE"]

#: Said once when a run has to compile kernels (numba's on-disk cache is empty or stale).
COMPILING_MESSAGE = "floatmoor: compiling kernels (first run only)"


class ProgressReporter:
    """Reports simulated time against wall time, once a run has lasted ``delay`` seconds.

    Short runs stay silent. On a terminal the line is rewritten in place; otherwise (a log
    file, CI) one line is written every ``interval`` seconds. The time left is estimated
    from the rate since the first report (so neither set-up nor a resumed run's earlier part
    counts). When kernels compile (:meth:`compiling`, :meth:`compiled`), that is said once,
    and the estimate starts again from the first report after the compilation: a chunk that
    included compiling says nothing about the rest of the run.

    Parameters
    ----------
    total
        Simulated time at the end of the run [s].
    stream
        Where to write (standard error by default).
    delay
        Wall time before the first report [s].
    interval
        Wall time between reports [s].
    clock
        Wall clock [s] (``time.perf_counter``; tests pass their own).
    """

    def __init__(self, total: float, stream: TextIO | None = None, delay: float = 1.0,
                 interval: float = 2.0, clock: Callable[[], float] = _time.perf_counter
                 ) -> None:
        self.total = total
        self.stream = stream if stream is not None else sys.stderr
        self.delay = delay
        self.interval = interval
        self._clock = clock
        self._start = clock()
        self._last = -float("inf")
        self._shown = False  # a progress line is on a terminal, not yet ended
        self._tty = bool(getattr(self.stream, "isatty", lambda: False)())
        # the estimate's origin: (wall time, simulated time); None until the first report,
        # and again after a compilation
        self._origin: tuple[float, float] | None = None
        self._compiling = False
        self._announced = False
        #: wall time spent compiling kernels [s]
        self.compile_time = 0.0

    def compiling(self) -> None:
        """A kernel compilation starts: say so (once per run) and drop the estimate."""
        self._compiling = True
        self._origin = None
        if not self._announced:
            self._announced = True
            self._write(COMPILING_MESSAGE, end=True)

    def compiled(self, seconds: float = 0.0) -> None:
        """The compilation that :meth:`compiling` announced has ended after ``seconds``."""
        self._compiling = False
        self._origin = None
        self.compile_time += seconds

    def restarted(self, message: str) -> None:
        """The run starts again from t = 0 (a coupled run whose probe raised a line's
        elements): say why, on a line of its own, and drop the estimate."""
        self._origin = None
        self._last = -float("inf")
        self._write(f"floatmoor: {message}", end=True)

    def __call__(self, simulated: float) -> None:
        now = self._clock()
        if self._origin is None and not self._compiling:
            self._origin = (now, simulated)  # the estimate starts here
            left = None
        else:
            left = self._left(now, simulated)
        elapsed = now - self._start
        if elapsed < self.delay or now - self._last < self.interval:
            return
        self._last = now
        fraction = simulated / self.total if self.total > 0 else 1.0
        text = (f"floatmoor: t = {simulated:.4g} / {self.total:.4g} s ({fraction:.0%}), "
                f"{elapsed:.1f} s elapsed")
        if left is not None:
            text += f", ~{left:.1f} s left"
        self._write(text, end=False)

    def _left(self, now: float, simulated: float) -> float | None:
        """Wall time left at the rate since the estimate's origin, None when unknown."""
        if self._compiling or self._origin is None:
            return None
        wall0, sim0 = self._origin
        if simulated <= sim0:
            return None
        return (now - wall0) * max(self.total - simulated, 0.0) / (simulated - sim0)

    def _write(self, text: str, end: bool) -> None:
        """Write a line; on a terminal a progress line (``end`` False) stays open to be
        rewritten."""
        if self._tty:
            self.stream.write("\r" + text + "\x1b[K" + ("\n" if end else ""))
            self._shown = not end
        else:
            self.stream.write(text + "\n")
        self.stream.flush()

    def close(self) -> None:
        """End the progress line on a terminal."""
        if self._shown and self._tty:
            self.stream.write("\n")
            self.stream.flush()
            self._shown = False
