"""The gPC engine against polynomial models whose expansion is known exactly.

The model is a sum of products of orthonormal Legendre (uniform inputs) and Hermite (normal
input) polynomials written here from their textbook formulas, with known coefficients: its
gPC coefficients, mean (the constant's coefficient), variance (sum of the other squares) and
Sobol' indices (sums of the squares of the terms in an input alone / in which it appears) are
known exactly, and both fits must recover them to round-off.
"""

from __future__ import annotations

import numpy as np
import pytest

from floatmoor import uq

#: Round-off of the fits: coefficients are sums of ~100 products of O(1) double-precision
#: terms (1e-16 each) and the Gauss nodes are computed to ~1e-15; least squares on LHS points
#: multiplies that by the design's condition number (~1e2 here).
ROUND_OFF = 1e-10

INPUTS = [uq.UncertainInput("a", "uniform", {"lower": -1.0, "upper": 3.0}),
          uq.UncertainInput("b", "normal", {"mean": 1.0, "std": 2.0}),
          uq.UncertainInput("c", "uniform", {"lower": 0.0, "upper": 1.0})]


def legendre(n: int, u: np.ndarray) -> np.ndarray:
    """Orthonormal Legendre polynomial of U(-1, 1): sqrt(2n + 1) P_n."""
    p = [np.ones_like(u), u, (3 * u**2 - 1) / 2, (5 * u**3 - 3 * u) / 2][n]
    return np.sqrt(2 * n + 1) * p


def hermite(n: int, v: np.ndarray) -> np.ndarray:
    """Orthonormal probabilists' Hermite polynomial of N(0, 1): He_n / sqrt(n!)."""
    return [np.ones_like(v), v, (v**2 - 1) / np.sqrt(2), (v**3 - 3 * v) / np.sqrt(6)][n]


#: Terms of the model: multi-index (degree in a, b, c) -> coefficient per output (3 outputs).
TERMS = {
    (0, 0, 0): (2.0, -1.0, 0.5),
    (1, 0, 0): (1.5, 0.2, 0.0),
    (0, 1, 0): (-0.7, 0.0, 1.1),
    (0, 2, 0): (0.5, 0.3, 0.0),
    (2, 1, 0): (0.4, -0.6, 0.2),
    (0, 0, 3): (0.3, 0.0, -0.4),
    (1, 1, 1): (-0.25, 0.8, 0.0),
}


def model(x: np.ndarray) -> np.ndarray:
    """The outputs (k, 3) at inputs x (k, 3)."""
    u = (x[:, 0] - 1.0) / 2.0          # U(-1, 3) -> U(-1, 1)
    v = (x[:, 1] - 1.0) / 2.0          # N(1, 2) -> N(0, 1)
    w = 2.0 * x[:, 2] - 1.0            # U(0, 1) -> U(-1, 1)
    y = np.zeros((x.shape[0], 3))
    for (i, j, k), c in TERMS.items():
        y += np.outer(legendre(i, u) * hermite(j, v) * legendre(k, w), c)
    return y


def expected_statistics():
    """Mean, variance, first and total Sobol' indices (3,), (3,), (3, 3), (3, 3) of TERMS."""
    c = {k: np.array(v) for k, v in TERMS.items()}
    mean = c[(0, 0, 0)]
    variance = sum(v**2 for k, v in c.items() if k != (0, 0, 0))
    first = np.array([c[(1, 0, 0)]**2,                         # a alone
                      c[(0, 1, 0)]**2 + c[(0, 2, 0)]**2,       # b alone
                      c[(0, 0, 3)]**2]) / variance             # c alone
    total = np.array([c[(1, 0, 0)]**2 + c[(2, 1, 0)]**2 + c[(1, 1, 1)]**2,
                      c[(0, 1, 0)]**2 + c[(0, 2, 0)]**2 + c[(2, 1, 0)]**2 + c[(1, 1, 1)]**2,
                      c[(0, 0, 3)]**2 + c[(1, 1, 1)]**2]) / variance
    return mean, variance, first, total


def check_exact(surrogate: uq.Surrogate, outputs: slice) -> None:
    mean, variance, first, total = expected_statistics()
    found = {tuple(k): surrogate.coefficients[i] for i, k in enumerate(surrogate.multi_indices)}
    for index, coefficient in found.items():
        expected = np.array(TERMS.get(index, (0.0, 0.0, 0.0)))[outputs]
        np.testing.assert_allclose(coefficient, expected, rtol=0, atol=ROUND_OFF,
                                   err_msg=f"coefficient of {index}")
    assert set(TERMS) <= set(found)
    np.testing.assert_allclose(surrogate.mean, mean[outputs], rtol=ROUND_OFF)
    np.testing.assert_allclose(surrogate.variance, variance[outputs], rtol=ROUND_OFF)
    np.testing.assert_allclose(surrogate.sobol_first, first[:, outputs], atol=ROUND_OFF)
    np.testing.assert_allclose(surrogate.sobol_total, total[:, outputs], atol=ROUND_OFF)
    x = uq.designs.lhs_design(INPUTS, 50, seed=3)
    np.testing.assert_allclose(surrogate.evaluate(x), model(x)[:, outputs], atol=ROUND_OFF)


@pytest.mark.parametrize("outputs", [slice(0, 1), slice(0, 3)], ids=["scalar", "vector"])
def test_quadrature_is_exact_on_a_polynomial(outputs):
    method = uq.QuadratureMethod(order=3)
    nodes, weights = uq.design(INPUTS, method)
    assert nodes.shape == (4**3, 3) and weights.shape == (4**3,)
    surrogate = uq.fit(INPUTS, method, nodes, weights, model(nodes)[:, outputs])
    check_exact(surrogate, outputs)
    assert surrogate.method == "quadrature" and surrogate.n_runs == 64
    # the degree-3 terms hold this share of the variance (the quadrature's error estimate)
    mean, variance, _, _ = expected_statistics()
    top = sum(np.array(v)**2 for k, v in TERMS.items() if sum(k) == 3) / variance
    np.testing.assert_allclose(surrogate.validation_error, top[outputs], rtol=ROUND_OFF)


@pytest.mark.parametrize("outputs", [slice(0, 1), slice(0, 3)], ids=["scalar", "vector"])
def test_lar_recovers_a_sparse_polynomial(outputs):
    # 20 candidate polynomials of degree <= 3 in 3 inputs, 7 of them in the model: 60 points
    method = uq.RegressionMethod(order=3, q_norm=1.0, samples=60, seed=11)
    nodes, weights = uq.design(INPUTS, method)
    assert weights is None
    surrogate = uq.fit(INPUTS, method, nodes, None, model(nodes)[:, outputs])
    check_exact(surrogate, outputs)
    assert surrogate.method == "regression" and surrogate.dropped == 0
    assert np.all(surrogate.validation_error < ROUND_OFF)


def test_lar_drops_failed_runs():
    method = uq.RegressionMethod(order=3, q_norm=1.0, samples=64, seed=11)
    nodes, _ = uq.design(INPUTS, method)
    outputs = model(nodes)
    outputs[[5, 17], 1] = np.nan
    outputs[40, 0] = np.inf
    surrogate = uq.fit(INPUTS, method, nodes, None, outputs)
    assert surrogate.dropped == 3 and surrogate.n_runs == 61
    check_exact(surrogate, slice(0, 3))


def test_hyperbolic_truncation_limits_interactions():
    # q = 0.5 at p = 3 keeps no product of two inputs beyond (1, 1): ||(1,1)||_0.5 = 4 > 3
    surrogate = uq.fit(INPUTS, uq.RegressionMethod(3, 0.5, 40, 2),
                       *uq.design(INPUTS, uq.RegressionMethod(3, 0.5, 40, 2)),
                       model(uq.designs.lhs_design(INPUTS, 40, 2))[:, 0])
    assert np.all((surrogate.multi_indices > 0).sum(axis=1) <= 1)


def test_constant_output_has_no_sobol_indices():
    nodes, weights = uq.designs.quadrature_design(INPUTS, 2)
    outputs = np.column_stack([np.full(len(nodes), 4.0), model(nodes)[:, 0]])
    surrogate = uq.Surrogate.fit_quadrature(INPUTS, 2, nodes, weights, outputs)
    assert np.all(np.isnan(surrogate.sobol_first[:, 0]))
    assert np.all(np.isnan(surrogate.sobol_total[:, 0]))
    assert np.all(np.isfinite(surrogate.sobol_total[:, 1]))
    np.testing.assert_allclose(surrogate.mean[0], 4.0, rtol=ROUND_OFF)
