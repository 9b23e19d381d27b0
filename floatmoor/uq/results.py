"""What a study's runs gave and what was made of it (shared by the results file, the report
and the orchestration)."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from floatmoor.uq.study import Study
from floatmoor.uq.surrogate import Surrogate

__all__ = ["StudyRuns", "StudyResult"]


@dataclass
class StudyRuns:
    """The design and what its runs gave."""

    nodes: NDArray[np.float64]  #: (runs, inputs)
    weights: NDArray[np.float64] | None  #: (runs,) quadrature weights, None for regression
    labels: list[str]  #: ``key=value, ...`` per run
    status: list[str]  #: ``complete`` or ``failed: ...`` per run
    outputs: dict[str, NDArray[np.float64]]  #: per quantity (runs, outputs)
    times: dict[str, NDArray[np.float64] | None]  #: per quantity its window's times [s]


@dataclass
class StudyResult:
    """A finished study."""

    study: Study
    runs: StudyRuns
    surrogates: dict[str, Surrogate]
    dataset: xr.Dataset  #: what ``uq.nc`` holds
    dropped: list[int] = field(default_factory=list)  #: runs left out of a regression
    folder: Path | None = None
