"""Exceptions raised by floatmoor.

Every error a user can cause or meet derives from :class:`FloatmoorError`, so the command
line can print its message (and nothing else) and choose the exit status.
"""

from __future__ import annotations

__all__ = ["FloatmoorError", "CaseError", "SolverError", "FloatmoorWarning",
           "ImplausibleInputWarning", "ModelValidityWarning", "AcceptedCheckWarning"]


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


class FloatmoorWarning(UserWarning):
    """Base class of floatmoor's warnings: what a user should know but that stops nothing.

    The command line prints each as ``floatmoor: warning: MESSAGE`` (no source line).
    """


class ImplausibleInputWarning(FloatmoorWarning):
    """A case value that is valid but implausible by orders of magnitude (a unit typed wrong:
    a diameter in mm given as m, a density in t/m^3 given as kg/m^3), found at load
    (:mod:`floatmoor.case.plausibility`).

    The message reads like a :class:`CaseError`'s: the file, the key path, what was expected
    and what was found.
    """


class ModelValidityWarning(FloatmoorWarning):
    """A run left the range in which a model it uses is valid (a floater's rotations beyond
    linear hydrostatics and radiation, a quasi-dynamic line beyond its verified accelerations;
    :mod:`floatmoor.simulation.validity`). Each condition warns once per run; the run records
    the messages in its output file (attribute ``validity_warnings``) and its summary."""


class AcceptedCheckWarning(FloatmoorWarning):
    """A hydrodynamic database fails checks that its case accepts (``[hydro]
    accept_failed_checks``): the run goes on with it. Said once per database file version and
    accepted checks (:mod:`floatmoor.hydro.database`); the command line always shows it."""
