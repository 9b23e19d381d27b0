"""Benchmark: the buoy's line 3 alone on its recorded fairlead path, floatmoor at its
defaults beside MoorDyn 2.7 at its cheapest setting within 1 %.

Line 3 of the buoy (``tests/data/references/buoy_T1.20_line3_forced.toml``: the buoy case's
environment, seabed and chain, no ``[lines.dynamic]`` table, so floatmoor's defaults) with its
fairlead on ``buoy_T1.20_fairleads.nc`` (position and velocity every 0.01 s from today's coupled
run at T = 1.2 s; both codes follow the cubic Hermite path, MoorDyn coupled every 1 ms),
60 s, statistics after the 20 s ramp (dynamic_harness.py: lines alone).

MoorDyn: its reference (:data:`REFERENCE`, finer than the baseline study's 60 segments, which
were not converged), a convergence check (:data:`CHECK` within 1 % of the reference, else no
candidate is searched), then per time scheme (explicit RK2, RK4; implicit BEuler3, Midpoint3,
ACA3, Wilson3) the cheapest (segments, dtM) within 1 % of the reference (STD and maximum)
whose next finer mesh is too. Reported: the wall-time ratio floatmoor / MoorDyn at equal
accuracy (time loop and whole run), or, without a MoorDyn setting within 1 %, against MoorDyn's
reference. No target is set here: nothing but the runs' completion is asserted.

The chain has no internal damping and snaps: MoorDyn did not converge in the baseline study
(README of the references: 60 segments at dt = l / c and 0.5 l / c differ by 10 % in STD,
16 % in the maximum).

Quick mode (``FLOATMOOR_BENCH_QUICK=1``): 30 s, a coarse reference, two schemes, few settings.

Run: ``python -m pytest -m benchmark tests/benchmarks/test_bench_buoy_line_forced.py -s``
(about 8 minutes when MoorDyn's reference is not converged, much longer if it is).
"""

from __future__ import annotations

import numpy as np
import pytest

from tests.benchmarks.dynamic_harness import (MOORDYN_SCHEMES, REFERENCES,
                                              lines_against_moordyn, lines_problem, pick)

pytestmark = pytest.mark.benchmark

DEFINITION = REFERENCES / "buoy_T1.20_line3_forced.toml"
PATHS = REFERENCES / "buoy_T1.20_fairleads.nc"
START = 20.0  # s, the wave ramp of the coupled run
#: MoorDyn's reference and its convergence check: (segments, dtM / (l / c), scheme, coupling).
REFERENCE = pick((80, 0.5, "RK4", 1e-3), (30, 0.5, "RK4", 1e-3))
CHECK = pick((60, 0.5, "RK4", 1e-3), (20, 0.5, "RK4", 1e-3))
SEGMENTS = pick((10, 15, 20, 30, 40, 60), (10, 20))
FRACTIONS = pick((1.0, 0.5, 0.25), (1.0,))
SCHEMES = pick(MOORDYN_SCHEMES, ("RK4", "BEuler3"))


def test_buoy_line_forced_against_moordyn():
    pytest.importorskip("moordyn")
    problem = lines_problem(DEFINITION, PATHS, start=START, duration=pick(None, 30.0))
    ours, _ = lines_against_moordyn(problem, reference=REFERENCE, check=CHECK,
                                    segments=SEGMENTS, fractions=FRACTIONS, schemes=SCHEMES,
                                    couplings=(1e-3,))
    assert all(np.isfinite(v["max"]) for v in ours["lines"].values())
