"""What a run's views need from its case, re-read from the result dataset's attributes: the
seabed depth, the end of the start-up ramp and the floater's reference point."""

from __future__ import annotations

from dataclasses import dataclass

import xarray as xr

from floatmoor.io.run_case import case_from_dataset, default_start

__all__ = ["RunContext", "run_context"]


@dataclass(frozen=True)
class RunContext:
    """Case facts of a run that its views draw.

    Attributes
    ----------
    water_depth
        Depth of the flat seabed below the still water line [m]; None when the case could
        not be re-read (no seabed line is drawn then).
    ramp
        End of the start-up ramp (motion or wave ramp) [s]; 0 without one.
    reference_point
        The floater's reference point at rest [m] (the origin without a floater).
    floater
        The floater's name, or "" for a forced-motion run.
    """

    water_depth: float | None
    ramp: float
    reference_point: tuple[float, float, float]
    floater: str


def run_context(dataset: xr.Dataset) -> RunContext:
    """The :class:`RunContext` of a result dataset (from its ``case_toml`` attribute)."""
    case = case_from_dataset(dataset)
    ramp, _ = default_start(case)
    if case is None:
        return RunContext(None, ramp, (0.0, 0.0, 0.0), "")
    floater = case.floater
    ref = tuple(float(v) for v in floater.reference_point) if floater is not None \
        else (0.0, 0.0, 0.0)
    return RunContext(float(case.environment.water_depth), ramp, ref,  # type: ignore[arg-type]
                      floater.name if floater is not None else "")
