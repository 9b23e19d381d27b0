"""The DG numerics chosen from the default accuracy (1 %) reproduce the shipped cases'
reference numerics within the accuracy asked.

Lindahl (docs/cases/lindahl.md), all 30 runs (r x T) as the validation runs them
(``unchanged_dynamic.lindahl_figures``: two ramp periods, six cycles), at the accuracy default
(12 elements of order 3, ``"auto"`` integration: the file's reference numerics set to "auto")
and held with MooDy's 10 x p5 (the file's, stored in ``issue17_unchanged.json``) against a
finer 20 x p6 run (``lindahl_converged_20xp6.json``): the mean cycle maximum of each run.

The snap runs (T <= 1.5 s) scatter chaotically from cycle to cycle by ~1.5 %, so a six-cycle
mean carries ~0.6 % of noise whatever the discretisation: 10 x p5 itself is 1.59 % from 20 x
p6 at r = 0.2 m, T = 1.5 s (RMS over the 30: 0.42 %). The bounds are therefore on the RMS over
the 30 runs (the accuracy asked) and on the largest single run (the reference numerics' own
largest distance, rounded up), and the default must do as well as the reference numerics on
the RMS, within the noise. Measured: RMS 0.53 %, largest +1.35 % (r = 0.15 m, T = 1.25 s),
since "auto" leaves the implicit steps after one window when they cost more than 1.5 times the
explicit ones (they jittered the cycle maxima by up to 0.9 % and put that run at +2.08 %).

About 40 s (the 30 runs at the default).

Run: ``python -m pytest -m slow tests/simulation/test_default_numerics.py -s``.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from tests.conftest import ACCURACY_DEFAULT, REPO
from tests.simulation.unchanged_dynamic import lindahl_figures


pytestmark = pytest.mark.validation

REFERENCES = REPO / "tests" / "data" / "references"
#: The accuracy asked (the default, 1 %): bound on the RMS over the 30 runs of the relative
#: difference of the mean cycle maximum to the 20 x p6 run.
ACCURACY = 0.01
#: Largest single run's difference: 10 x p5's own largest is 1.59 % (module docstring).
LARGEST = 0.02
#: The default's RMS may exceed the reference numerics' by the six-cycle noise of the snap
#: runs (~0.6 % per run: module docstring), a fifth of it over 30 runs with ~10 snap runs.
NOISE_RMS = 0.002


def _by_run(cases):
    return {(c["radius"], c["period"]): c["mean_cycle_max_N"] for c in cases}


@pytest.mark.slow
def test_lindahl_accuracy_default_reproduces_the_reference_numerics() -> None:
    converged = _by_run(json.loads((REFERENCES / "lindahl_converged_20xp6.json").read_text())
                        ["cases"])
    reference = _by_run(json.loads((REFERENCES / "issue17_unchanged.json").read_text())
                        ["lindahl"]["cases"])
    default = {(r, T): lindahl_figures(r, T, ACCURACY_DEFAULT)["mean_cycle_max_N"]
               for r, T in converged}
    rel = {k: (default[k] / converged[k] - 1.0, reference[k] / converged[k] - 1.0)
           for k in converged}
    d = np.array([v[0] for v in rel.values()])
    ref = np.array([v[1] for v in rel.values()])
    rms, rms_ref = float(np.sqrt(np.mean(d ** 2))), float(np.sqrt(np.mean(ref ** 2)))
    worst = max(rel, key=lambda k: abs(rel[k][0]))
    print(f"\naccuracy default against 20 x p6: RMS {100 * rms:.2f} %, largest "
          f"{100 * rel[worst][0]:+.2f} % (r = {worst[0]} m, T = {worst[1]} s); 10 x p5: RMS "
          f"{100 * rms_ref:.2f} %, largest {100 * np.abs(ref).max():.2f} %")
    assert rms <= ACCURACY
    assert np.abs(d).max() <= LARGEST
    assert rms <= rms_ref + NOISE_RMS
