"""Uncertainty propagation through any model: design, runs, surrogate (gpc paper section 3.4).

The method is chosen by a small value object: :class:`QuadratureMethod` (projection on a full
tensor Gauss grid, (order + 1)^d runs) or :class:`RegressionMethod` (LAR on a Latin hypercube
of ``samples`` runs). :func:`design` gives the runs, :func:`fit` the surrogate from their
outputs; :func:`propagate` does both around a Python callable.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Sequence

import numpy as np
from numpy.typing import NDArray

from floatmoor.uq.designs import lhs_design, quadrature_design
from floatmoor.uq.inputs import UncertainInput
from floatmoor.uq.surrogate import Surrogate

__all__ = ["QuadratureMethod", "RegressionMethod", "Method", "design", "fit", "propagate"]


@dataclass(frozen=True)
class QuadratureMethod:
    """Projection by full tensor Gauss quadrature on the total-degree basis of ``order``.

    Attributes
    ----------
    order
        Total polynomial degree of the basis (order + 1 nodes per input).
    """

    order: int


@dataclass(frozen=True)
class RegressionMethod:
    """LAR on the hyperbolic basis of ``order`` and ``q_norm`` from a Latin hypercube of
    ``samples`` runs drawn with ``seed``.

    Attributes
    ----------
    order
        Largest polynomial degree of the candidate basis.
    q_norm
        Hyperbolic truncation q (1: total degree; smaller keeps fewer interactions).
    samples
        Number of model runs.
    seed
        Seed of the Latin hypercube.
    """

    order: int
    q_norm: float
    samples: int
    seed: int


Method = QuadratureMethod | RegressionMethod


def design(inputs: Sequence[UncertainInput],
           method: Method) -> tuple[NDArray[np.float64], NDArray[np.float64] | None]:
    """The input values (n, d) at which to run the model, and the quadrature weights (n,)
    (None for regression).

    Parameters
    ----------
    inputs
        The uncertain inputs (d of them).
    method
        :class:`QuadratureMethod` or :class:`RegressionMethod`.

    Returns
    -------
    tuple
        (nodes, weights).
    """
    if isinstance(method, QuadratureMethod):
        return quadrature_design(inputs, method.order)
    return lhs_design(inputs, method.samples, method.seed), None


def fit(inputs: Sequence[UncertainInput], method: Method, nodes: NDArray[np.float64],
        weights: NDArray[np.float64] | None, outputs: NDArray[np.float64]) -> Surrogate:
    """The surrogate of the model outputs (n, m) at the design's ``nodes``.

    Parameters
    ----------
    inputs, method
        As for :func:`design`.
    nodes, weights
        What :func:`design` gave.
    outputs
        The model's outputs (n, m) at the nodes.

    Returns
    -------
    Surrogate
        The fitted gPC surrogate.
    """
    if isinstance(method, QuadratureMethod):
        if weights is None:
            raise ValueError("a quadrature fit needs the design's weights")
        return Surrogate.fit_quadrature(inputs, method.order, nodes, weights, outputs)
    return Surrogate.fit_regression(inputs, method.order, method.q_norm, nodes, outputs)


def propagate(model: Callable[[NDArray[np.float64]], NDArray[np.float64] | float],
              inputs: Sequence[UncertainInput], method: Method) -> Surrogate:
    """Run ``model`` on the method's design and fit its surrogate.

    Parameters
    ----------
    model
        model(x) with x (d,) the input values in the order of ``inputs``, returning a scalar
        or an (m,) vector; an exception it raises propagates (regression drops runs that
        return non-finite values, quadrature refuses them).
    inputs, method
        As for :func:`design`.
    """
    nodes, weights = design(inputs, method)
    outputs = np.array([np.atleast_1d(np.asarray(model(x), dtype=float)) for x in nodes])
    return fit(inputs, method, nodes, weights, outputs)
