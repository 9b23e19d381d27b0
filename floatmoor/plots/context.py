"""What a run's views need from its case, re-read from the result dataset's attributes: the
seabed depth, the end of the start-up ramp, the floater's reference point and its body
(:mod:`floatmoor.plots.body_pose`).

A run whose body cannot be drawn (its case no longer re-reads, or its hull mesh file is
missing or changed) is drawn without it, and one warning line on the ``floatmoor.plots``
logger says why (standard error when logging is not configured).
"""

from __future__ import annotations

import logging
from dataclasses import dataclass

import xarray as xr

from floatmoor.io.run_case import case_from_dataset, default_start
from floatmoor.plots.body_pose import BodyModel, body_model

__all__ = ["RunContext", "run_context", "LOGGER"]


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
    body
        The body drawn in the line-shape views, or None (none, or it cannot be drawn).
    """

    water_depth: float | None
    ramp: float
    reference_point: tuple[float, float, float]
    floater: str
    body: BodyModel | None = None


#: Logger of the views' warnings.
LOGGER = logging.getLogger("floatmoor.plots")


def _warn_no_body(dataset: xr.Dataset, reason: str) -> None:
    run = dataset.attrs.get("case_file") or dataset.attrs.get("title") or "run"
    LOGGER.warning("floatmoor: warning: %s: the views are drawn without the body: %s",
                   run, reason)


def run_context(dataset: xr.Dataset) -> RunContext:
    """The :class:`RunContext` of a result dataset (from its ``case_toml`` attribute).

    Parameters
    ----------
    dataset
        A run's result dataset.

    Returns
    -------
    RunContext
        What the views take from the run's case.
    """
    from floatmoor.io.bem_data import BemFileError

    case = case_from_dataset(dataset)
    ramp, _ = default_start(case)
    if case is None:
        if "body_displacement" in dataset or "prescribed_displacement" in dataset:
            _warn_no_body(dataset, "its case could not be re-read from the run file's "
                          "attributes (a file the case names moved or changed?)")
        return RunContext(None, ramp, (0.0, 0.0, 0.0), "")
    floater = case.floater
    ref = tuple(float(v) for v in floater.reference_point) if floater is not None \
        else (0.0, 0.0, 0.0)
    try:
        body = body_model(case, dataset)
    except BemFileError as err:
        _warn_no_body(dataset, str(err))
        body = None
    return RunContext(float(case.environment.water_depth), ramp, ref,  # type: ignore[arg-type]
                      floater.name if floater is not None else "", body)
