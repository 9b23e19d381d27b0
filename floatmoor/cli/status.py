"""Exit statuses of the ``floatmoor`` command and its one-line messages."""

from __future__ import annotations

from floatmoor.terminal_text import MESSAGE_LIMIT, shown

__all__ = ["EXIT_OK", "EXIT_FAILED", "EXIT_BAD_INPUT", "EXIT_INTERRUPTED", "EXIT_BROKEN_PIPE",
           "STARTUP_INTERRUPTED", "error_line"]


EXIT_OK, EXIT_FAILED, EXIT_BAD_INPUT, EXIT_INTERRUPTED = 0, 1, 2, 130
#: Status of a command whose standard output was closed early (``floatmoor check ... | head``):
#: 128 + SIGPIPE, what a shell reports for a program the closed pipe stopped.
EXIT_BROKEN_PIPE = 128 + 13
#: What a Ctrl-C before a command has started says (status 130).
STARTUP_INTERRUPTED = "floatmoor: interrupted while starting; nothing was run or written"


def error_line(err: BaseException) -> str:
    """``floatmoor: error: MESSAGE`` as one terminal-safe line (the message quotes file text:
    control characters are escaped and the length bounded, :func:`shown`)."""
    return f"floatmoor: error: {shown(err, MESSAGE_LIMIT)}"
