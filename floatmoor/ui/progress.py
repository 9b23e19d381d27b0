"""Progress of long runs, on standard error."""

from __future__ import annotations

import sys
import time as _time
from typing import TextIO

__all__ = ["ProgressReporter"]


class ProgressReporter:
    """Reports simulated time against wall time, once a run has lasted ``delay`` seconds.

    Short runs stay silent. On a terminal the line is rewritten in place; otherwise (a log
    file, CI) one line is written every ``interval`` seconds.

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
    """

    def __init__(self, total: float, stream: TextIO | None = None, delay: float = 1.0,
                 interval: float = 2.0) -> None:
        self.total = total
        self.stream = stream if stream is not None else sys.stderr
        self.delay = delay
        self.interval = interval
        self._start = _time.perf_counter()
        self._last = -float("inf")
        self._shown = False
        self._tty = bool(getattr(self.stream, "isatty", lambda: False)())

    def __call__(self, simulated: float) -> None:
        now = _time.perf_counter()
        elapsed = now - self._start
        if elapsed < self.delay or now - self._last < self.interval:
            return
        self._last = now
        fraction = simulated / self.total if self.total > 0 else 1.0
        left = elapsed * (1.0 - fraction) / fraction if fraction > 0 else float("nan")
        text = (f"floatmoor: t = {simulated:.4g} / {self.total:.4g} s ({fraction:.0%}), "
                f"{elapsed:.1f} s elapsed, ~{left:.1f} s left")
        if self._tty:
            self.stream.write("\r" + text + "\x1b[K")
        else:
            self.stream.write(text + "\n")
        self.stream.flush()
        self._shown = True

    def close(self) -> None:
        """End the progress line on a terminal."""
        if self._shown and self._tty:
            self.stream.write("\n")
            self.stream.flush()
