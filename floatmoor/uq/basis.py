"""The orthonormal polynomial basis of a set of independent uncertain inputs.

The univariate families come from OpenTURNS (``StandardDistributionPolynomialFactory``: the
Wiener-Askey family where there is one, Legendre for uniform, Hermite for normal, Jacobi for
beta, Laguerre for gamma; polynomials built by adaptive Stieltjes otherwise), orthonormal for
the standard representative of each input distribution (the *measure*); an input value x maps
to the measure's variable z by OpenTURNS' iso-probabilistic transformation (affine for the
Askey families). The d-variate basis is the tensor product Phi_k(z) = prod_j phi_kj(z_j)
(gpc paper eq. 11) over the multi-indices k of a hyperbolic set {k : ||k||_q <= p} (q = 1: total
degree <= p). Evaluation runs the families' three-term recurrence
phi_{n+1} = (a_n z + b_n) phi_n + c_n phi_{n-1} on numpy arrays, so a surrogate is rebuilt from
its inputs, multi-indices and coefficients alone.
"""

from __future__ import annotations

from typing import Sequence

import numpy as np
import openturns as ot
from numpy.typing import NDArray

from floatmoor.uq.inputs import UncertainInput, joint_distribution

__all__ = ["PolynomialBasis", "probe_input"]


class PolynomialBasis:
    """Orthonormal polynomials of independent ``inputs`` (see the module docstring).

    Parameters
    ----------
    inputs
        The uncertain inputs, in the order of the columns of x.
    """

    def __init__(self, inputs: Sequence[UncertainInput]) -> None:
        self.inputs = tuple(inputs)
        self.distribution = joint_distribution(self.inputs)
        self.dimension = len(self.inputs)
        self.factories = [ot.StandardDistributionPolynomialFactory(
            self.distribution.getMarginal(j)) for j in range(self.dimension)]
        self.measure = ot.JointDistribution([f.getMeasure() for f in self.factories])
        self._to_measure = ot.DistributionTransformation(self.distribution, self.measure)
        self._from_measure = ot.DistributionTransformation(self.measure, self.distribution)

    def enumerate_function(self, q_norm: float) -> ot.EnumerateFunction:
        """The OpenTURNS enumeration of the hyperbolic multi-index set of ``q_norm``."""
        if not 0.0 < q_norm <= 1.0:
            raise ValueError(f"q-norm {q_norm!r}: must be in (0, 1]")
        return ot.HyperbolicAnisotropicEnumerateFunction(self.dimension, float(q_norm))

    def multi_indices(self, order: int, q_norm: float = 1.0) -> NDArray[np.int64]:
        """Multi-indices (P, d) of the basis truncated at degree ``order`` and ``q_norm``,
        the constant first."""
        if order < 0:
            raise ValueError(f"polynomial order {order!r}: must be >= 0")
        enum = self.enumerate_function(q_norm)
        size = enum.getBasisSizeFromTotalDegree(int(order))
        return np.array([list(enum(i)) for i in range(size)], dtype=np.int64)

    def ot_factory(self, q_norm: float) -> ot.OrthogonalProductPolynomialFactory:
        """The same basis as an OpenTURNS product factory (for its regression algorithms)."""
        return ot.OrthogonalProductPolynomialFactory(self.factories,
                                                     self.enumerate_function(q_norm))

    def to_measure(self, x: NDArray[np.float64]) -> NDArray[np.float64]:
        """Input values x (k, d) -> the measure's variables z (k, d)."""
        return np.array(self._to_measure(ot.Sample(self._check(x))))

    def from_measure(self, z: NDArray[np.float64]) -> NDArray[np.float64]:
        """The measure's variables z (k, d) -> input values x (k, d)."""
        return np.array(self._from_measure(ot.Sample(self._check(z))))

    def design_matrix(self, x: NDArray[np.float64],
                      multi_indices: NDArray[np.int64]) -> NDArray[np.float64]:
        """Basis values Psi[i, k] = Phi_k(z(x_i)), shape (k_points, P)."""
        z = self.to_measure(x)
        psi = np.ones((z.shape[0], len(multi_indices)))
        for j in range(self.dimension):
            degrees = multi_indices[:, j]
            values = self._univariate(j, z[:, j], int(degrees.max(initial=0)))
            psi *= values[:, degrees]
        return psi

    def gauss_rule(self, points: int, j: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Gauss nodes and weights (summing to 1) of ``points`` points for input ``j``'s
        measure: exact for polynomials of degree <= 2 points - 1."""
        nodes, weights = self.factories[j].getNodesAndWeights(int(points))
        return np.array(nodes, dtype=float), np.array(weights, dtype=float)

    def _univariate(self, j: int, z: NDArray[np.float64], degree: int) -> NDArray[np.float64]:
        """phi_0..phi_degree of input ``j`` at z, shape (len(z), degree + 1)."""
        factory = self.factories[j]
        values = np.empty((z.size, degree + 1))
        values[:, 0] = 1.0
        previous = np.zeros_like(z)
        for n in range(degree):
            a, b, c = factory.getRecurrenceCoefficients(n)
            values[:, n + 1] = (a * z + b) * values[:, n] + c * previous
            previous = values[:, n]
        return values

    def _check(self, x: NDArray[np.float64]) -> NDArray[np.float64]:
        x = np.asarray(x, dtype=float)
        if x.ndim != 2 or x.shape[1] != self.dimension:
            keys = ", ".join(i.key for i in self.inputs)
            raise ValueError(f"points of shape {x.shape}: expected (k, {self.dimension}), one "
                             f"column per uncertain input ({keys})")
        return x


def probe_input(inp: UncertainInput, order: int) -> str | None:
    """Why ``inp`` cannot be propagated at ``order`` in double precision, or None.

    Builds what a study builds from it (its OpenTURNS distribution and polynomial family, the
    Gauss rule of ``order + 1`` points mapped back to input values, the basis values there) and
    requires every number to be finite: extreme but valid parameters (bounds of +-1e308, a
    gamma shape of 1e300, beta exponents of 1e-300) otherwise fail inside OpenTURNS, or give
    infinite nodes, only after the runs.
    """
    try:
        with np.errstate(all="ignore"):
            basis = PolynomialBasis([inp])
            nodes, weights = basis.gauss_rule(order + 1, 0)
            values = basis.from_measure(nodes[:, None])
            psi = basis.design_matrix(values, basis.multi_indices(order))
    except (TypeError, RuntimeError, ValueError, ArithmeticError) as err:  # OpenTURNS' errors
        text = str(err).strip().splitlines()
        return f"OpenTURNS refuses them ({text[0] if text else type(err).__name__})"
    for name, array in (("Gauss nodes", values), ("Gauss weights", weights),
                        ("basis values", psi)):
        if not np.all(np.isfinite(array)):
            return f"non-finite {name} at order {order}"
    return None
