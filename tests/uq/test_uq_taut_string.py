"""Case E (docs/cases/taut_string.md; gpc paper section 4.1): the taut string with uncertain tension and mass.

y = A sin(pi x / L) cos(pi sqrt(T / m) t / L) at x = 1.5 m, t = 0.25 s, T ~ U(100, 116) N,
m ~ U(1, 5) kg/m, Legendre basis, full quadrature. The exact mean and variance come from direct
integration; the paper prints the mean as +9.39e-2 m, its sign lost: the cosine is negative
where c t / L > 1/2 (T / m > 36, m below about 3 kg/m, half of the inputs), down to -0.95, and
at most +0.39 elsewhere, so the exact mean is -9.38508e-2 m.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy import integrate

from floatmoor import uq
from floatmoor.uq.taut_string import taut_string

INPUTS = [uq.UncertainInput("T", "uniform", {"lower": 100.0, "upper": 116.0}),
          uq.UncertainInput("m", "uniform", {"lower": 1.0, "upper": 5.0})]
#: Mean [m] and variance [m^2] by scipy dblquad (absolute and relative tolerance 1e-13),
#: checked by test_direct_integration.
EXACT_MEAN = -0.09385081476534583
EXACT_VARIANCE = 0.126327729751294
#: The task's reference values, to the digits given (7 significant).
PRINTED_DIGITS = 5e-8


def string(z: np.ndarray) -> float:
    return float(taut_string(T=z[0], m=z[1]))


def quadrature_errors(orders):
    """|mean - exact|, |variance - exact| of the order-p quadrature surrogates."""
    errors = []
    for p in orders:
        s = uq.propagate(string, INPUTS, uq.QuadratureMethod(p))
        errors.append((abs(s.mean[0] - EXACT_MEAN), abs(s.variance[0] - EXACT_VARIANCE)))
    return np.array(errors)


def test_direct_integration():
    area = 16.0 * 4.0

    def integrand(power):
        return lambda m, T: taut_string(T=T, m=m) ** power / area

    mean = integrate.dblquad(integrand(1), 100, 116, 1, 5, epsabs=1e-13, epsrel=1e-13)[0]
    second = integrate.dblquad(integrand(2), 100, 116, 1, 5, epsabs=1e-13, epsrel=1e-13)[0]
    assert mean == pytest.approx(EXACT_MEAN, abs=1e-12)
    assert second - mean**2 == pytest.approx(EXACT_VARIANCE, abs=1e-12)
    assert mean == pytest.approx(-0.0938508, abs=PRINTED_DIGITS)
    assert second - mean**2 == pytest.approx(0.1263277, abs=PRINTED_DIGITS)


#: Paper Fig. 3b: the gPC error of the mean is about 1e-5 at p = 5 and 1e-6 at p = 6 (absolute
#: errors, read off a log plot: a factor 2 allowed). Measured here: mean 1.0e-5, 1.5e-6;
#: variance 2.9e-5, 3.5e-6.
PAPER_ERROR = {5: 2e-5, 6: 2e-6}
#: Relative accuracy of the p = 7 surrogate (measured 2.2e-6 mean, 1.9e-6 variance; at p = 6
#: 1.6e-5 and 2.8e-5).
RELATIVE_AT_7 = 1e-5


def test_quadrature_reaches_the_exact_statistics():
    errors = quadrature_errors([5, 6, 7])
    assert errors[0, 0] < PAPER_ERROR[5]
    assert errors[1, 0] < PAPER_ERROR[6]
    assert errors[1, 1] < 2 * PAPER_ERROR[6]      # the variance converges a little slower
    assert errors[2, 0] < RELATIVE_AT_7 * abs(EXACT_MEAN)
    assert errors[2, 1] < RELATIVE_AT_7 * EXACT_VARIANCE


#: Exponential convergence: log10 of the error falls linearly with p, measured -0.78 decades per
#: order for both statistics from p = 2 to 8; -0.6 leaves margin.
DECADES_PER_ORDER = -0.6


def test_exponential_convergence_in_order():
    orders = np.arange(2, 9)
    errors = quadrature_errors(orders)
    for column in range(2):
        slope, _ = np.polyfit(orders, np.log10(errors[:, column]), 1)
        assert slope < DECADES_PER_ORDER


#: Monte Carlo errors fall as N^-1/2; the slope of log RMS error against log N, each RMS over
#: REPEATS seeds, scatters by about 0.03 (RMS of 40 errors: 11 % relative, over 2 decades).
MC_SLOPE_TOLERANCE = 0.1
REPEATS = 40


def test_monte_carlo_converges_as_inverse_square_root():
    sizes = np.array([100, 1000, 10000])
    rms = np.zeros((sizes.size, 2))
    rng = np.random.default_rng(20200306)
    for i, n in enumerate(sizes):
        for _ in range(REPEATS):
            y = taut_string(T=rng.uniform(100, 116, n), m=rng.uniform(1, 5, n))
            rms[i] += (y.mean() - EXACT_MEAN) ** 2, (y.var(ddof=1) - EXACT_VARIANCE) ** 2
    rms = np.sqrt(rms / REPEATS)
    for column in range(2):
        slope, _ = np.polyfit(np.log10(sizes), np.log10(rms[:, column]), 1)
        assert slope == pytest.approx(-0.5, abs=MC_SLOPE_TOLERANCE)
    # 49 model runs of the p = 6 quadrature beat 10000 Monte Carlo runs by a factor > 100
    assert np.all(quadrature_errors([6])[0] * 100 < rms[-1])


#: Pick-freeze estimates agree with the gPC indices within this many standard errors.
STANDARD_ERRORS = 4.0


def test_sobol_indices_against_pick_freeze_monte_carlo():
    s = uq.propagate(string, INPUTS, uq.QuadratureMethod(8))
    rng = np.random.default_rng(7)
    n = 200_000
    low, high = np.array([100.0, 1.0]), np.array([116.0, 5.0])
    a = rng.uniform(low, high, (n, 2))
    b = rng.uniform(low, high, (n, 2))
    fa = taut_string(T=a[:, 0], m=a[:, 1])
    fb = taut_string(T=b[:, 0], m=b[:, 1])
    variance = np.var(np.concatenate([fa, fb]))
    for j in range(2):
        ab = a.copy()
        ab[:, j] = b[:, j]          # a with input j from b
        fab = taut_string(T=ab[:, 0], m=ab[:, 1])
        first = fb * (fab - fa)     # Saltelli et al. 2010: E[.] = V_j
        total = 0.5 * (fa - fab) ** 2   # Jansen: E[.] = V * S_Tj
        for terms, index in ((first, s.sobol_first[j, 0]), (total, s.sobol_total[j, 0])):
            estimate = terms.mean() / variance
            error = terms.std(ddof=1) / np.sqrt(n) / variance
            assert abs(estimate - index) < STANDARD_ERRORS * error
    # the mass dominates: S_m about 0.99, S_T about 0.008
    assert s.sobol_first[1, 0] > 0.99 and s.sobol_total[0, 0] < 0.01
