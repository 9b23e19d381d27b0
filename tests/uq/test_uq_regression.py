"""LAR on a time series: the corrected leave-one-out error tells the surrogate's error."""

from __future__ import annotations

import numpy as np

from floatmoor import uq
from floatmoor.uq.taut_string import taut_string

INPUTS = [uq.UncertainInput("T", "uniform", {"lower": 100.0, "upper": 116.0}),
          uq.UncertainInput("m", "uniform", {"lower": 1.0, "upper": 5.0})]
#: Case E's mid-string displacement over one reference period: 50 outputs, the first (t = 0)
#: the same for every input.
TIMES = np.linspace(0.0, 1.0, 50)
#: The median over the outputs of LOO error / hold-out error is within this factor of 1
#: (measured 1.39 at p = 8 on 100 runs, 1.04 at p = 6 on 60, 1.12 at p = 4 on 40).
LOO_FACTOR = 2.0


def series(x: np.ndarray) -> np.ndarray:
    return taut_string(T=x[:, :1], m=x[:, 1:], t=TIMES)


def test_loo_error_matches_the_hold_out_error_of_a_time_series():
    method = uq.RegressionMethod(order=8, q_norm=1.0, samples=100, seed=5)
    nodes, _ = uq.design(INPUTS, method)
    surrogate = uq.fit(INPUTS, method, nodes, None, series(nodes))
    assert surrogate.n_outputs == TIMES.size
    check = uq.designs.lhs_design(INPUTS, 2000, seed=9)
    exact = series(check)
    hold_out = np.mean((surrogate.evaluate(check) - exact) ** 2, axis=0)[1:] / exact.var(axis=0)[1:]
    ratio = np.median(surrogate.validation_error[1:] / hold_out)
    assert 1.0 / LOO_FACTOR < ratio < LOO_FACTOR
    assert np.median(hold_out) < 1e-3
    # the release instant does not vary: no validation error, no Sobol' indices
    assert np.isnan(surrogate.validation_error[0])
    assert np.all(np.isnan(surrogate.sobol_total[:, 0]))
