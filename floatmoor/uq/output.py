"""The results of a study as one labelled dataset (``DIR/uq.nc``).

Dimensions: ``run`` (the design's runs), ``input`` (the uncertain keys, by name) and, per
history quantity ``Q``, ``Q_time`` (its window's output times). Variables: the design
(``design_nodes``, ``design_weights`` of a quadrature rule), each run's ``run_status`` and
whether the fit used it (``run_used``), and per quantity ``Q``: its value in every run
(``Q_runs``), the surrogate's ``Q_mean``, ``Q_variance``, ``Q_std``, first-order and total
Sobol indices per input (``Q_sobol_first``, ``Q_sobol_total``), ``Q_validation_error`` and the
central band holding :data:`BAND_LEVEL` of the output (``Q_lower``, ``Q_upper``, from the
surrogate's samples); history quantities have all of these over time. Attributes: the study
file and text, the case file and text, the method, the failed and dropped runs, the floatmoor
version and the creation time (UTC).
"""

from __future__ import annotations

import datetime as _dt
from pathlib import Path
from typing import Any, Sequence

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from floatmoor._version import __version__
from floatmoor.uq.propagate import QuadratureMethod
from floatmoor.uq.results import StudyResult, StudyRuns
from floatmoor.uq.study import Quantity, Study
from floatmoor.uq.surrogate import Surrogate

__all__ = ["build_uq_dataset", "study_summary", "weighted_sobol", "BAND_LEVEL", "BAND_SEED",
           "method_text", "input_text"]

#: Probability content of the central bands (gpc paper section 4.3: 95 % bands).
BAND_LEVEL = 0.95
#: Seed of the surrogate samples behind the bands and densities (reproducible files).
BAND_SEED = 0


def method_text(study: Study) -> str:
    """The method in words, e.g. ``quadrature, order 5``."""
    m = study.method
    if isinstance(m, QuadratureMethod):
        return f"full tensor Gauss quadrature, order {m.order}"
    return (f"least-angle regression on {m.samples} Latin-hypercube samples (seed {m.seed}), "
            f"order {m.order}, q-norm {m.q_norm:g}")


def input_text(study: Study, k: int) -> str:
    """An input's distribution in words, e.g. ``uniform(lower=1.25, upper=3.75)``."""
    inp = study.inputs[k]
    return f"{inp.distribution}(" + ", ".join(f"{p}={v:g}" for p, v in
                                              inp.parameters.items()) + ")"


def weighted_sobol(indices: NDArray[np.float64], variance: NDArray[np.float64]
                   ) -> NDArray[np.float64]:
    """Sobol indices (inputs, times) of a history aggregated over its window: each time
    weighted by the output's variance there, sum_t S_i(t) V(t) / sum_t V(t). Times whose
    indices are NaN (the output does not vary there) weigh nothing; all zero when the output
    never varies."""
    indices = np.asarray(indices, dtype=float)
    variance = np.where(np.all(np.isfinite(indices), axis=0), np.asarray(variance, float), 0.0)
    total = float(np.sum(variance))
    if not total > 0.0:
        return np.zeros(indices.shape[0])
    return np.nan_to_num(indices) @ variance / total


def _squared(units: str) -> str:
    return "1" if units in ("", "1") else f"{units}^2"


def _quantity_variables(q: Quantity, runs: StudyRuns, surrogate: Surrogate,
                        samples: int) -> tuple[dict[str, Any], dict[str, Any]]:
    """The variables (and the time coordinate of a history) of one quantity."""
    what = q.describe()
    out_dims: tuple[str, ...] = (f"{q.name}_time",) if q.is_history else ()

    def vector(values: Any) -> np.ndarray:
        values = np.asarray(values, dtype=float)
        return values if q.is_history else values[..., 0]

    lower, upper = surrogate.bands(level=BAND_LEVEL, n=samples, seed=BAND_SEED)
    data = {
        f"{q.name}_runs": (("run",) + out_dims, vector(runs.outputs[q.name]),
                           {"long_name": f"{what}, in each run (NaN: failed)",
                            "units": q.units}),
        f"{q.name}_mean": (out_dims, vector(surrogate.mean),
                           {"long_name": f"mean of the {what}", "units": q.units}),
        f"{q.name}_variance": (out_dims, vector(surrogate.variance),
                               {"long_name": f"variance of the {what}",
                                "units": _squared(q.units)}),
        f"{q.name}_std": (out_dims, vector(surrogate.std),
                          {"long_name": f"standard deviation of the {what}", "units": q.units}),
        f"{q.name}_sobol_first": (("input",) + out_dims, vector(surrogate.sobol_first),
                                  {"long_name": f"first-order Sobol index of each input for the "
                                   f"{what}", "units": "1"}),
        f"{q.name}_sobol_total": (("input",) + out_dims, vector(surrogate.sobol_total),
                                  {"long_name": f"total Sobol index of each input for the "
                                   f"{what}", "units": "1"}),
        f"{q.name}_validation_error": (out_dims, vector(surrogate.validation_error), {
            "long_name": f"validation error of the surrogate of the {what} (relative: the "
                         "surrogate engine's error estimate over the output's variance)",
            "units": "1"}),
        f"{q.name}_lower": (out_dims, vector(lower), {
            "long_name": f"lower end of the central {BAND_LEVEL:.0%} band of the {what} "
                         f"({samples} surrogate samples)", "units": q.units}),
        f"{q.name}_upper": (out_dims, vector(upper), {
            "long_name": f"upper end of the central {BAND_LEVEL:.0%} band of the {what} "
                         f"({samples} surrogate samples)", "units": q.units}),
    }
    coords = {}
    if q.is_history:
        coords[f"{q.name}_time"] = (f"{q.name}_time", runs.times[q.name], {
            "long_name": f"simulated time of the samples of {q.name}", "units": "s"})
    return data, coords


def build_uq_dataset(study: Study, runs: StudyRuns, surrogates: dict[str, Surrogate],
                     dropped: Sequence[int] = ()) -> xr.Dataset:
    """The study's results (see the module docstring); ``dropped``: runs a regression left
    out."""
    n = len(runs.labels)
    used = np.ones(n)
    used[list(dropped)] = 0.0
    inputs_units = "as the case file gives the key (SI)" if study.case is not None else \
        "as the model's parameter (SI)"
    coords: dict[str, Any] = {
        "input": ("input", np.array(study.keys, dtype=str),
                  {"long_name": "uncertain input (its --set key path or model parameter)",
                   "units": "1"}),
        "run": ("run", np.arange(n, dtype=np.int32),
                {"long_name": "design run number", "units": "1"}),
    }
    data: dict[str, Any] = {
        "input_distribution": ("input", np.array([input_text(study, k) for k in
                                                  range(len(study.inputs))], dtype=str),
                               {"long_name": "probability distribution of each input",
                                "units": "1"}),
        "design_nodes": (("run", "input"), runs.nodes,
                         {"long_name": "input values of each design run",
                          "units": inputs_units}),
        "run_status": ("run", np.array(runs.status, dtype=str),
                       {"long_name": "run status (complete or failed: why)", "units": "1"}),
        "run_used": ("run", used, {"long_name": "1: the surrogates use the run; 0: dropped "
                                   "(failed or non-finite output)", "units": "1"}),
    }
    if runs.weights is not None:
        data["design_weights"] = ("run", runs.weights, {
            "long_name": "quadrature weight of each design run (sum 1)", "units": "1"})
    for q in study.quantities:
        more, more_coords = _quantity_variables(q, runs, surrogates[q.name],
                                                study.surrogate_samples)
        data.update(more)
        coords.update(more_coords)
    failed = [label for label, status in zip(runs.labels, runs.status) if status != "complete"]
    attrs = {
        "title": study.title,
        "study_file": study.path,
        "study_toml": study.text,
        "case_file": study.case or "none",
        "case_toml": Path(study.case).read_text(encoding="utf-8") if study.case else "none",
        "case_overrides": "\n".join(study.base_overrides) or "none",
        "model": study.model or "none",
        "method": method_text(study),
        "runs": n,
        "runs_failed": "; ".join(failed) or "none",
        "runs_dropped": "; ".join(runs.labels[k] for k in dropped) or "none",
        "surrogate_samples": study.surrogate_samples,
        "floatmoor_version": __version__,
        "created": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
    }
    return xr.Dataset(data, coords=coords, attrs=attrs)


def study_summary(result: StudyResult) -> dict[str, Any]:
    """A JSON-ready summary: the study, its runs and per quantity its statistics (a
    history's over its window: the extremes of its mean and band, its largest standard
    deviation and validation error, and its variance-weighted total Sobol indices)."""
    study, ds = result.study, result.dataset
    keys = list(study.keys)
    out: dict[str, Any] = {
        "title": study.title, "study": study.path, "case": study.case, "model": study.model,
        "method": method_text(study), "inputs": {k: input_text(study, i)
                                                 for i, k in enumerate(keys)},
        "runs": len(result.runs.labels),
        "failed_runs": [lb for lb, st in zip(result.runs.labels, result.runs.status)
                        if st != "complete"],
        "dropped_runs": [result.runs.labels[k] for k in result.dropped],
        "output": None if result.folder is None else str(result.folder),
        "quantities": {},
    }
    for q in study.quantities:
        v = {name: ds[f"{q.name}_{name}"].values for name in
             ("mean", "std", "variance", "lower", "upper", "validation_error", "sobol_first",
              "sobol_total")}
        entry: dict[str, Any] = {"description": q.describe(), "units": q.units}
        if q.is_history:
            entry.update(window_s=list(q.window), max_mean=float(v["mean"].max()),
                         min_mean=float(v["mean"].min()), max_upper=float(v["upper"].max()),
                         min_lower=float(v["lower"].min()), max_std=float(v["std"].max()),
                         max_validation_error=float(v["validation_error"].max()),
                         sobol_total_weighted=dict(zip(keys, map(float, weighted_sobol(
                             v["sobol_total"], v["variance"])))))
        else:
            entry.update({name: float(v[name]) for name in
                          ("mean", "std", "variance", "lower", "upper", "validation_error")})
            entry.update(sobol_first=dict(zip(keys, map(float, v["sobol_first"]))),
                         sobol_total=dict(zip(keys, map(float, v["sobol_total"]))))
        out["quantities"][q.name] = entry
    return out
