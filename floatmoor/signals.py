"""Interrupts and termination: what SIGINT, a repeated SIGINT, SIGTERM and a dead parent do.

A command runs inside :func:`interrupt_handling`: the first SIGINT raises
:class:`KeyboardInterrupt` and SIGTERM raises :class:`Terminated` (a ``KeyboardInterrupt``), so
both take the same path (partial results, checkpoint, campaign file); a second signal while
that path writes is announced and waits for the writes, and a third stops at once
(:data:`EXIT_STATUS`, writes in progress abandoned: atomic writes leave the old file). Outside
a command, :func:`deferred_interrupts` keeps a signal from breaking an atomic write: it is
delivered when the write is done. :func:`die_with_parent` is the initializer of local worker
processes: they ignore SIGINT (the parent stops them) and die when the parent dies, even by
SIGKILL.

This module imports nothing from floatmoor, so every layer may use it.
"""

from __future__ import annotations

import ctypes
import os
import signal
import sys
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from types import FrameType

__all__ = ["Terminated", "interrupt_handling", "deferred_interrupts", "exit_status",
           "signal_name", "die_with_parent", "EXIT_STATUS", "PARENT_POLL_INTERVAL_S"]

#: Exit status of a command stopped by a signal: 128 + the signal number, as a shell reports
#: a process killed by it.
EXIT_STATUS = {signal.SIGINT: 130, signal.SIGTERM: 143}

#: Seconds between checks that a worker's parent is alive, where the kernel cannot tell the
#: worker (no prctl): a worker outlives a killed parent by at most this long.
PARENT_POLL_INTERVAL_S = 1.0

_HANDLED = (signal.SIGINT, signal.SIGTERM)
#: linux/prctl.h: deliver a signal to this process when its parent thread exits.
_PR_SET_PDEATHSIG = 1


class Terminated(KeyboardInterrupt):
    """Raised by SIGTERM inside :func:`interrupt_handling`: an interrupt, handled as Ctrl-C."""

    signal_number = signal.SIGTERM


def exit_status(interrupt: BaseException) -> int:
    """The exit status of a command stopped by ``interrupt`` (130 SIGINT, 143 SIGTERM)."""
    return EXIT_STATUS[getattr(interrupt, "signal_number", signal.SIGINT)]


def signal_name(interrupt: BaseException) -> str:
    """``"interrupted"`` (SIGINT) or ``"terminated (SIGTERM)"``: how a command was stopped."""
    return "terminated (SIGTERM)" if isinstance(interrupt, Terminated) else "interrupted"


def _in_main_thread() -> bool:
    return threading.current_thread() is threading.main_thread()


class _CommandHandler:
    """The first signal raises; the next ones let the clean-up finish; a third ends it."""

    def __init__(self) -> None:
        self.received: list[int] = []

    def __call__(self, number: int, frame: FrameType | None) -> None:
        self.received.append(number)
        first = self.received[0]
        if len(self.received) == 1:
            raise Terminated() if number == signal.SIGTERM else KeyboardInterrupt()
        if len(self.received) == 2:
            os.write(2, b"floatmoor: still writing the results so far; interrupt once more "
                        b"to stop at once (the write in progress is then lost)\n")
            return
        os.write(2, b"floatmoor: stopped at once; the write in progress is lost\n")
        os._exit(EXIT_STATUS[signal.Signals(first)])


@contextmanager
def interrupt_handling() -> Iterator[None]:
    """Handle SIGINT and SIGTERM as a command does (see the module); the previous handlers
    are restored on exit. Does nothing outside the main thread (signals go to it only)."""
    if not _in_main_thread():
        yield
        return
    handler = _CommandHandler()
    previous = {number: signal.signal(number, handler) for number in _HANDLED}
    try:
        yield
    finally:
        for number, old in previous.items():
            signal.signal(number, old)


@contextmanager
def deferred_interrupts() -> Iterator[None]:
    """Hold SIGINT and SIGTERM until the block (a write that must not be cut) ends, then
    deliver them to the handlers that were in place. Inside :func:`interrupt_handling` or
    outside the main thread it does nothing (the command's handler already lets writes
    finish; other threads receive no signals)."""
    if not _in_main_thread() or isinstance(signal.getsignal(signal.SIGINT), _CommandHandler):
        yield
        return
    held: list[int] = []

    def hold(number: int, frame: FrameType | None) -> None:
        held.append(number)

    previous = {number: signal.signal(number, hold) for number in _HANDLED}
    try:
        yield
    finally:
        for number, old in previous.items():
            signal.signal(number, old)
        for number in dict.fromkeys(held):
            signal.raise_signal(number)


def die_with_parent(parent: int) -> None:
    """Initializer of a local worker process of ``parent``: ignore SIGINT (Ctrl-C reaches
    the whole process group; the parent records what finished, then stops its workers), take
    SIGTERM's default action (a handler inherited through fork would only raise), and die
    with the parent: by ``prctl(PR_SET_PDEATHSIG)`` on Linux, else by a thread that polls the
    parent every :data:`PARENT_POLL_INTERVAL_S`."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    if _kill_with_parent():
        if os.getppid() != parent:  # the parent died before prctl took effect
            os._exit(1)
        return
    if os.getppid() != parent:
        os._exit(1)
    threading.Thread(target=_watch_parent, args=(parent,), daemon=True,
                     name="floatmoor-parent-watch").start()


def _kill_with_parent() -> bool:
    """Ask Linux to SIGKILL this process when its parent exits; False where it cannot."""
    if not sys.platform.startswith("linux"):
        return False
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        return libc.prctl(_PR_SET_PDEATHSIG, int(signal.SIGKILL), 0, 0, 0) == 0
    except (OSError, AttributeError):
        return False


def _watch_parent(parent: int) -> None:
    stop = threading.Event()
    while not stop.wait(PARENT_POLL_INTERVAL_S):
        if os.getppid() != parent:  # re-parented: the parent is gone
            os._exit(1)
