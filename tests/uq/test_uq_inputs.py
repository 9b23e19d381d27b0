"""Uncertain inputs: each distribution's parameters mean what DISTRIBUTIONS says, and bad
inputs are refused with a message naming the problem."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import stats

from floatmoor import uq

#: Quadrature of order 2 integrates x and x^2 exactly for every family (degree <= 5 exact).
ROUND_OFF = 1e-9

#: name -> (parameters, exact mean, exact variance) from the distributions' textbook formulas.
CASES = {
    "uniform": ({"lower": 2.0, "upper": 5.0}, 3.5, 9.0 / 12.0),
    "normal": ({"mean": -1.0, "std": 0.3}, -1.0, 0.09),
    "lognormal": ({"mean": 2.0, "std": 0.5}, 2.0, 0.25),
    "truncated_normal": ({"mean": 0.5, "std": 1.0, "lower": 0.0, "upper": 2.0},
                         stats.truncnorm(-0.5, 1.5, loc=0.5).mean(),
                         stats.truncnorm(-0.5, 1.5, loc=0.5).var()),
    "beta": ({"alpha": 2.0, "beta": 3.0, "lower": 1.0, "upper": 3.0},
             1.0 + 2.0 * 2.0 / 5.0, 4.0 * 6.0 / (25.0 * 6.0)),
    "triangular": ({"lower": 0.0, "mode": 1.0, "upper": 4.0}, 5.0 / 3.0,
                   (0.0 + 1.0 + 16.0 - 0.0 - 0.0 - 4.0) / 18.0),
    "gamma": ({"shape": 2.0, "rate": 4.0, "location": 1.0}, 1.0 + 2.0 / 4.0, 2.0 / 16.0),
}


def test_every_distribution_is_covered():
    assert set(CASES) == set(uq.DISTRIBUTIONS)
    for name, (parameters, _, _) in CASES.items():
        assert tuple(parameters) == uq.DISTRIBUTIONS[name]


@pytest.mark.parametrize("name", CASES)
def test_distribution_parameters_give_their_moments(name):
    parameters, mean, variance = CASES[name]
    inputs = [uq.UncertainInput("a", name, parameters)]
    s = uq.propagate(lambda x: x[0], inputs, uq.QuadratureMethod(2))
    assert s.mean[0] == pytest.approx(mean, rel=ROUND_OFF)
    assert s.variance[0] == pytest.approx(variance, rel=ROUND_OFF)


@pytest.mark.parametrize("inp, message", [
    (uq.UncertainInput("a", "weibull", {"scale": 1.0}), "unknown distribution 'weibull'"),
    (uq.UncertainInput("a", "uniform", {"lower": 2.0, "upper": 2.0}),
     "lower = 2.0 >= upper = 2.0"),
    (uq.UncertainInput("a", "normal", {"mean": 1.0, "std": 0.0}), r"std = 0.0: must be > 0"),
    (uq.UncertainInput("a", "normal", {"mean": 1.0, "std": -1.0}), r"std = -1.0: must be > 0"),
    (uq.UncertainInput("a", "normal", {"mean": 1.0}), "missing std"),
    (uq.UncertainInput("a", "normal", {"mean": 1.0, "std": 1.0, "sd": 1.0}), "unknown sd"),
    (uq.UncertainInput("a", "normal", {"mean": math.nan, "std": 1.0}),
     "mean must be a finite number"),
    (uq.UncertainInput("a", "triangular", {"lower": 0.0, "mode": 3.0, "upper": 2.0}),
     "mode = 3.0 outside"),
    (uq.UncertainInput("a", "lognormal", {"mean": -1.0, "std": 1.0}), "mean = -1.0: must be"),
])
def test_bad_inputs_are_refused(inp, message):
    with pytest.raises(ValueError, match=message) as info:
        uq.check_input(inp)
    assert "'a'" in str(info.value)
    with pytest.raises(ValueError, match=message):
        uq.designs.quadrature_design([inp], 2)


def test_repeated_and_missing_inputs():
    a = uq.UncertainInput("a", "uniform", {"lower": 0.0, "upper": 1.0})
    with pytest.raises(ValueError, match="'a' given more than once"):
        uq.joint_distribution([a, a])
    with pytest.raises(ValueError, match="no uncertain input"):
        uq.joint_distribution([])


def test_quadrature_refuses_failed_runs_naming_them():
    inputs = [uq.UncertainInput("a", "uniform", {"lower": 0.0, "upper": 1.0})]
    nodes, weights = uq.designs.quadrature_design(inputs, 3)
    outputs = np.column_stack([nodes[:, 0], nodes[:, 0] ** 2])
    outputs[2, 1] = np.nan
    with pytest.raises(ValueError, match=r"not finite in rows \[2\]"):
        uq.Surrogate.fit_quadrature(inputs, 3, nodes, weights, outputs)


def test_bad_methods_are_refused():
    inputs = [uq.UncertainInput("a", "uniform", {"lower": 0.0, "upper": 1.0})]
    with pytest.raises(ValueError, match="quadrature order -1"):
        uq.design(inputs, uq.QuadratureMethod(-1))
    with pytest.raises(ValueError, match="samples 0"):
        uq.design(inputs, uq.RegressionMethod(2, 1.0, 0, 1))
    x = uq.designs.lhs_design(inputs, 10, 1)
    with pytest.raises(ValueError, match="q-norm 1.5"):
        uq.Surrogate.fit_regression(inputs, 2, 1.5, x, x[:, 0])
    with pytest.raises(ValueError, match="1 of 10 runs have finite outputs"):
        uq.Surrogate.fit_regression(inputs, 2, 1.0, x, np.r_[1.0, np.full(9, np.nan)])
