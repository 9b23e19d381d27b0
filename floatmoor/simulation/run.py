"""Running any case: coupled when it has a ``[floater]``, in forced motion otherwise (as
``floatmoor run`` and the campaign workers do)."""

from __future__ import annotations

from pathlib import Path
from typing import Callable

from floatmoor.case.schema import Case
from floatmoor.simulation.forced import RunResult, run_forced_motion

__all__ = ["run_case"]


def run_case(case: Case, *, output: str | Path | None = None,
             progress: Callable[[float], None] | None = None) -> RunResult:
    """Run ``case`` with the runner it needs.

    A case with a ``[floater]`` runs coupled
    (:func:`floatmoor.simulation.coupled_run.run_coupled`: the body in waves on its lines),
    any other in forced motion (:func:`floatmoor.simulation.forced.run_forced_motion`: the
    fairleads follow ``[motion]``).

    Parameters
    ----------
    case
        A validated case.
    output
        netCDF file written as the run goes (partial on failure or interruption), or None.
    progress
        Called with the simulated time as the run goes.

    Raises
    ------
    HydroDatabaseError
        A floater case's database is missing, damaged, stale or fails a check.
    SolverError
        The run failed (the partial results are written first).
    """
    if case.floater is not None:
        from floatmoor.simulation.coupled_run import run_coupled

        return run_coupled(case, output=output, progress=progress)
    return run_forced_motion(case, output=output, progress=progress)
