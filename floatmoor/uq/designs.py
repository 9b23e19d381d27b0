"""Where the model is run: Gauss quadrature grids and Latin-hypercube samples.

The quadrature design is the full tensor product of (order + 1)-point Gauss rules of the
inputs' measures (gpc paper section 3.2, eq. 12): it integrates exactly every product of basis
polynomials of degree <= 2 order + 1 in each input, so the projection of a polynomial model of
degree <= order is exact. The Latin hypercube spreads ``samples`` points evenly over each
input's probability (the paper's sampling for LAR, section 3.2).
"""

from __future__ import annotations

from typing import Sequence

import numpy as np
import openturns as ot
from numpy.typing import NDArray

from floatmoor.uq.basis import PolynomialBasis
from floatmoor.uq.inputs import UncertainInput, joint_distribution

__all__ = ["quadrature_design", "lhs_design"]


def quadrature_design(inputs: Sequence[UncertainInput],
                      order: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Full tensor Gauss quadrature for the input distributions.

    Parameters
    ----------
    inputs
        The uncertain inputs (d of them).
    order
        Polynomial order p >= 0 of the surrogate the design serves.

    Returns
    -------
    nodes, weights
        Nodes (n, d) in the inputs' units and weights (n,) summing to 1, n = (p + 1)^d; the
        last input varies fastest.
    """
    if isinstance(order, bool) or not isinstance(order, (int, np.integer)) or order < 0:
        raise ValueError(f"quadrature order {order!r}: must be an integer >= 0")
    basis = PolynomialBasis(inputs)
    rules = [basis.gauss_rule(int(order) + 1, j) for j in range(basis.dimension)]
    z = np.stack(np.meshgrid(*[r[0] for r in rules], indexing="ij"), axis=-1)
    w = np.prod(np.stack(np.meshgrid(*[r[1] for r in rules], indexing="ij"), axis=-1), axis=-1)
    return basis.from_measure(z.reshape(-1, basis.dimension)), w.reshape(-1)


def lhs_design(inputs: Sequence[UncertainInput], samples: int,
               seed: int) -> NDArray[np.float64]:
    """A Latin-hypercube sample (samples, d) of the joint input distribution; the same
    ``seed`` gives the same sample."""
    if isinstance(samples, bool) or not isinstance(samples, (int, np.integer)) or samples < 1:
        raise ValueError(f"Latin-hypercube samples {samples!r}: must be an integer >= 1")
    distribution = joint_distribution(inputs)
    ot.RandomGenerator.SetSeed(int(seed))
    return np.array(ot.LHSExperiment(distribution, int(samples)).generate(), dtype=float)
