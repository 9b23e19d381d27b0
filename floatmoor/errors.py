"""Exceptions raised by floatmoor.

Every error a user can cause or meet derives from :class:`FloatmoorError`, so the command
line can print its message (and nothing else) and choose the exit status.
"""

from __future__ import annotations

__all__ = ["FloatmoorError", "CaseError", "SolverError"]


class FloatmoorError(Exception):
    """Base class of floatmoor's errors."""


class CaseError(FloatmoorError, ValueError):
    """A case file (or a ``--set`` override) is malformed.

    The message names the file, the key path, what was expected and what was found:
    ``cases/a.toml: lines[0].length: expected a number > 0 [m], found -3.0``.

    Parameters
    ----------
    source
        The case file path, or a description such as ``"--set motion.period=3"``.
    key
        The key path (``lines[0].length``), or ``""`` for the whole file.
    expected
        What the key should hold.
    found
        What it holds (already formatted for the message).
    """

    def __init__(self, source: str, key: str, expected: str, found: str) -> None:
        self.source = source
        self.key = key
        self.expected = expected
        self.found = found
        where = f"{source}: {key}" if key else str(source)
        super().__init__(f"{where}: expected {expected}, found {found}")


class SolverError(FloatmoorError, RuntimeError):
    """A model cannot produce a valid state (no solution, divergence, instability).

    The message names the line, the simulated time and the quantity concerned.
    """
