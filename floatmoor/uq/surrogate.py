"""The gPC surrogate of a model with uncertain inputs, and its statistics.

f(Z) ~ sum_k c_k Phi_k(Z) on an orthonormal basis (gpc paper eqs. 10, 11;
:mod:`floatmoor.uq.basis`), so the mean is c_0, the variance sum_{k != 0} c_k^2, and Sobol'
indices are sums of squared coefficients (Sudret 2008): input j's first-order index sums the
terms in Z_j alone, its total index every term in which Z_j appears, each over the variance.
Densities and confidence bands come from evaluating the surrogate on many samples of the inputs
(paper section 3.4, step 10).
"""

from __future__ import annotations

import datetime as _dt
import json
import os
from typing import Mapping, Sequence

import numpy as np
import openturns as ot
import xarray as xr
from numpy.typing import NDArray

from floatmoor._version import __version__
from floatmoor.io.netcdf import NETCDF_ENGINE, write_dataset
from floatmoor.uq.basis import PolynomialBasis
from floatmoor.uq.designs import seed_sampling
from floatmoor.uq.inputs import UncertainInput
from floatmoor.uq.regression import lar_fit

__all__ = ["Surrogate", "ZERO_STD"]

#: A standard deviation below ``ZERO_STD * |mean|`` is round-off of an output that does not
#: vary (sums of squared coefficients of a constant, each ~1e-16 of it, over a few hundred
#: terms): its Sobol' indices are NaN.
ZERO_STD = 1e-12


def _finite_rows(outputs: NDArray[np.float64]) -> NDArray[np.bool_]:
    return np.all(np.isfinite(outputs), axis=1)


def _as_outputs(outputs: NDArray[np.float64], n: int) -> NDArray[np.float64]:
    y = np.asarray(outputs, dtype=float)
    y = y[:, None] if y.ndim == 1 else y
    if y.ndim != 2 or y.shape[0] != n or y.shape[1] == 0:
        raise ValueError(f"outputs of shape {np.shape(outputs)}: expected ({n}, m), one row per "
                         f"model run")
    return y


class Surrogate:
    """A polynomial-chaos surrogate of m model outputs.

    Build one with :meth:`fit_quadrature` or :meth:`fit_regression` (or
    :func:`floatmoor.uq.propagate`), or read one with :meth:`load`.

    Attributes
    ----------
    inputs
        The uncertain inputs, in the order of the columns of x.
    method
        ``"quadrature"`` or ``"regression"``.
    order, q_norm
        Polynomial degree and hyperbolic truncation (1 for quadrature: total degree <= order).
    n_outputs, n_runs, dropped
        Outputs m; model runs used; runs dropped for non-finite outputs (regression only).
    mean
        Output means (m,).
    variance
        Output variances (m,).
    std
        Output standard deviations (m,).
    sobol_first, sobol_total
        First-order and total Sobol' indices (d, m); NaN for an output whose std is below
        :data:`ZERO_STD` times ``|mean|`` (no variance to share).
    validation_error
        (m,) relative error estimate. Regression: corrected leave-one-out error
        (:mod:`floatmoor.uq.regression`). Quadrature: the share of the variance held by the
        terms of degree ``order`` exactly, (var_p - var_(p-1)) / var_p, where var_(p-1) is the
        variance of the order p - 1 projection from the same runs (the (p + 1)-point rule
        integrates it exactly too); with coefficients decaying with degree (smooth models) it
        indicates the truncation error's order of magnitude (case E at p = 6: 8e-6, against a
        true relative error of the variance of 2.8e-5). NaN where the variance is zero.
    coefficients, multi_indices
        Coefficients (P, m) of the orthonormal polynomials of degrees (P, d), constant first.
    """

    def __init__(self, inputs: Sequence[UncertainInput], method: str, order: int,
                 q_norm: float, multi_indices: NDArray[np.int64],
                 coefficients: NDArray[np.float64], validation_error: NDArray[np.float64], *,
                 n_runs: int, dropped: int = 0) -> None:
        self._basis = PolynomialBasis(inputs)
        self.inputs = tuple(inputs)
        self.method = method
        self.order = int(order)
        self.q_norm = float(q_norm)
        self.multi_indices = np.asarray(multi_indices, dtype=np.int64)
        self.coefficients = np.asarray(coefficients, dtype=float)
        self.validation_error = np.asarray(validation_error, dtype=float)
        self.n_runs = int(n_runs)
        self.dropped = int(dropped)
        self.n_outputs = self.coefficients.shape[1]
        degree = self.multi_indices.sum(axis=1)
        if degree[0] != 0:
            raise ValueError("the first multi-index must be the constant (all zeros)")
        squares = self.coefficients[1:] ** 2
        self.mean = self.coefficients[0].copy()
        self.variance = squares.sum(axis=0)
        self.std = np.sqrt(self.variance)
        varies = self.std > ZERO_STD * np.abs(self.mean)
        in_term = self.multi_indices[1:] > 0                     # (P - 1, d)
        alone = in_term & (in_term.sum(axis=1, keepdims=True) == 1)
        with np.errstate(divide="ignore", invalid="ignore"):
            self.sobol_first = np.where(varies, alone.T.astype(float) @ squares / self.variance,
                                        np.nan)
            self.sobol_total = np.where(varies, in_term.T.astype(float) @ squares / self.variance,
                                        np.nan)

    # -- fitting ------------------------------------------------------------------------------

    @classmethod
    def fit_quadrature(cls, inputs: Sequence[UncertainInput], order: int,
                       nodes: NDArray[np.float64], weights: NDArray[np.float64],
                       outputs: NDArray[np.float64]) -> "Surrogate":
        """Project the outputs on the total-degree basis of ``order`` with the quadrature
        (gpc paper eq. 12): one matrix product, C = Psi^T (w * Y).

        Parameters
        ----------
        inputs, order
            As given to :func:`floatmoor.uq.designs.quadrature_design`.
        nodes, weights
            The design: (n, d) and (n,).
        outputs
            (n, m) or (n,) model outputs at the nodes.

        Raises
        ------
        ValueError
            When an output is not finite (the rows are named: a quadrature needs every run),
            or the shapes disagree.
        """
        nodes = np.asarray(nodes, dtype=float)
        weights = np.asarray(weights, dtype=float)
        y = _as_outputs(outputs, nodes.shape[0])
        if weights.shape != (nodes.shape[0],):
            raise ValueError(f"weights of shape {weights.shape}: expected ({nodes.shape[0]},)")
        bad = np.flatnonzero(~_finite_rows(y))
        if bad.size:
            raise ValueError(f"quadrature outputs not finite in rows {bad.tolist()} (model "
                             f"runs that failed): a quadrature needs every node's run")
        basis = PolynomialBasis(inputs)
        indices = basis.multi_indices(order, 1.0)
        coefficients = basis.design_matrix(nodes, indices).T @ (weights[:, None] * y)
        top = indices.sum(axis=1) == order
        variance = np.sum(coefficients[1:] ** 2, axis=0)
        with np.errstate(divide="ignore", invalid="ignore"):
            error = np.where(variance > 0.0, np.sum(coefficients[top & (order > 0)] ** 2,
                                                    axis=0) / variance, np.nan)
        return cls(inputs, "quadrature", order, 1.0, indices, coefficients, error,
                   n_runs=nodes.shape[0])

    @classmethod
    def fit_regression(cls, inputs: Sequence[UncertainInput], order: int, q_norm: float,
                       nodes: NDArray[np.float64],
                       outputs: NDArray[np.float64]) -> "Surrogate":
        """Sparse coefficients by LAR with the corrected leave-one-out error on the
        hyperbolic basis of ``order`` and ``q_norm`` (:mod:`floatmoor.uq.regression`).

        Rows with a non-finite output (failed runs) are dropped and counted in ``dropped``.

        Raises
        ------
        ValueError
            When fewer than two runs are left, or the shapes disagree.
        """
        nodes = np.asarray(nodes, dtype=float)
        y = _as_outputs(outputs, nodes.shape[0])
        keep = _finite_rows(y)
        if keep.sum() < 2:
            raise ValueError(f"regression: {int(keep.sum())} of {y.shape[0]} runs have finite "
                             f"outputs, at least 2 are needed")
        basis = PolynomialBasis(inputs)
        indices, coefficients, error = lar_fit(basis, order, q_norm, nodes[keep], y[keep])
        return cls(inputs, "regression", order, q_norm, indices, coefficients, error,
                   n_runs=int(keep.sum()), dropped=int((~keep).sum()))

    # -- use ----------------------------------------------------------------------------------

    def evaluate(self, x: NDArray[np.float64]) -> NDArray[np.float64]:
        """The surrogate's outputs (k, m) at input values x (k, d)."""
        return self._basis.design_matrix(x, self.multi_indices) @ self.coefficients

    def sample_inputs(self, n: int, seed: int) -> NDArray[np.float64]:
        """n random input values (n, d) from the joint distribution (same seed, same
        values)."""
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
            raise ValueError(f"number of samples {n!r}: must be an integer >= 1")
        seed_sampling(seed)
        return np.array(self._basis.distribution.getSample(int(n)), dtype=float)

    def sample(self, n: int, seed: int) -> NDArray[np.float64]:
        """The surrogate's outputs (n, m) at n random inputs (:meth:`sample_inputs`)."""
        return self.evaluate(self.sample_inputs(n, seed))

    def bands(self, level: float = 0.95, n: int = 10000,
              seed: int = 0) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Central ``level`` confidence band of each output: its (1 - level) / 2 and
        (1 + level) / 2 quantiles over n surrogate samples, each (m,)."""
        if not 0.0 < level < 1.0:
            raise ValueError(f"confidence level {level!r}: must be in (0, 1)")
        values = self.sample(n, seed)
        return (np.quantile(values, (1.0 - level) / 2.0, axis=0),
                np.quantile(values, (1.0 + level) / 2.0, axis=0))

    def density(self, output: int, grid: NDArray[np.float64], n: int = 3000,
                seed: int = 0) -> NDArray[np.float64]:
        """Gaussian-kernel density of output ``output`` at the points of ``grid``, from n
        surrogate samples (OpenTURNS ``KernelSmoothing``, its default bandwidth rule).

        Raises
        ------
        ValueError
            When the output does not vary (no density).
        """
        values = self.sample(n, seed)[:, output]
        if not np.ptp(values) > ZERO_STD * max(abs(float(values.mean())), 1.0):
            raise ValueError(f"output {output} does not vary over the inputs: no density")
        kernel = ot.KernelSmoothing().build(ot.Sample(values[:, None]))
        points = ot.Sample(np.asarray(grid, dtype=float).reshape(-1, 1))
        return np.array(kernel.computePDF(points), dtype=float)[:, 0]

    # -- files --------------------------------------------------------------------------------

    def to_dataset(self, attrs: Mapping[str, str | float | int] | None = None, *,
                   output_units: str = "1") -> xr.Dataset:
        """The surrogate as a labelled dataset: what :meth:`load` needs (inputs,
        multi-indices, coefficients) and its statistics, with provenance ``attrs`` added and
        the outputs' UDUNITS string ``output_units``."""
        squared = "1" if output_units == "1" else f"({output_units})^2"
        keys = [inp.key for inp in self.inputs]
        out = np.arange(self.n_outputs, dtype=np.int32)
        data = {
            "coefficients": (("basis", "output"), self.coefficients,
                             {"long_name": "coefficient of the orthonormal polynomial",
                              "units": output_units}),
            "multi_indices": (("basis", "input"), self.multi_indices.astype(np.int32),
                              {"long_name": "degree of the polynomial in each input",
                               "units": "1"}),
            "input_distribution": (("input",), np.array([i.distribution for i in self.inputs]),
                                   {"long_name": "distribution of the input", "units": "1"}),
            "input_parameters": (("input",), np.array([json.dumps(dict(i.parameters))
                                                       for i in self.inputs]),
                                 {"long_name": "parameters of the distribution (JSON, in the "
                                               "units of the input)", "units": "1"}),
            "mean": (("output",), self.mean, {"long_name": "mean", "units": output_units}),
            "variance": (("output",), self.variance,
                         {"long_name": "variance", "units": squared}),
            "sobol_first": (("input", "output"), self.sobol_first,
                            {"long_name": "first-order Sobol' index", "units": "1"}),
            "sobol_total": (("input", "output"), self.sobol_total,
                            {"long_name": "total Sobol' index", "units": "1"}),
            "validation_error": (("output",), self.validation_error,
                                 {"long_name": f"relative validation error ({self.method})",
                                  "units": "1"}),
        }
        coords = {"input": ("input", np.array(keys), {"long_name": "uncertain input key",
                                                      "units": "1"}),
                  "output": ("output", out, {"long_name": "output index", "units": "1"})}
        attributes: dict[str, str | float | int] = {
            "title": "floatmoor polynomial-chaos surrogate",
            "method": self.method, "order": self.order, "q_norm": self.q_norm,
            "n_runs": self.n_runs, "dropped": self.dropped,
            "basis": "orthonormal polynomials of OpenTURNS StandardDistributionPolynomialFactory "
                     "of each input, tensor products",
            "floatmoor_version": __version__,
            "openturns_version": ot.__version__,
            "created": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
        }
        attributes.update(attrs or {})
        return xr.Dataset(data, coords=coords, attrs=attributes)

    def save(self, path: str | os.PathLike[str],
             attrs: Mapping[str, str | float | int] | None = None, *,
             output_units: str = "1") -> None:
        """Write the surrogate to a netCDF file (atomically, :func:`floatmoor.io.netcdf.
        write_dataset`); ``attrs`` adds provenance (e.g. the study text)."""
        write_dataset(self.to_dataset(attrs, output_units=output_units), path)

    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> "Surrogate":
        """Read a surrogate written by :meth:`save`: evaluation is rebuilt from the inputs,
        multi-indices and coefficients."""
        with xr.open_dataset(path, engine=NETCDF_ENGINE) as ds:
            ds = ds.load()
        inputs = [UncertainInput(str(key), str(dist), json.loads(str(params)))
                  for key, dist, params in zip(ds["input"].values,
                                               ds["input_distribution"].values,
                                               ds["input_parameters"].values)]
        return cls(inputs, str(ds.attrs["method"]), int(ds.attrs["order"]),
                   float(ds.attrs["q_norm"]), ds["multi_indices"].values,
                   ds["coefficients"].values, ds["validation_error"].values,
                   n_runs=int(ds.attrs["n_runs"]), dropped=int(ds.attrs["dropped"]))
