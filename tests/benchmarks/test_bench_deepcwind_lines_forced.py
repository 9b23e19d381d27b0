"""Benchmark: the three DeepCwind lines alone on recorded fairlead paths, floatmoor at
its defaults beside MoorDyn 2.7 at its cheapest setting within 1 % of its converged tension.

``tests/data/references/deepcwind_lines_forced.toml`` (the LC34 case's environment, seabed,
chain, anchors; no ``[lines.dynamic]`` table, so floatmoor's defaults) with each fairlead on
``deepcwind_lc34_fairleads_600s.nc`` (position and velocity every 0.5 s, the first 600 s of
today's coupled LC34 run with dynamic lines; both codes follow the cubic Hermite path),
statistics from t = 60 s (after the wave ramp). Lines one after the other
(dynamic_harness.py: lines alone).

MoorDyn: its converged reference (80 segments, RK4, dtM = 0.5 l / c, coupled every 1 ms; the
baseline study's, which failed on line 2 at 20 ms coupling), checked against 60 segments, then
for each coupling interval of :data:`COUPLINGS` and each time scheme (explicit RK2, RK4;
implicit BEuler3, Midpoint3, ACA3, Wilson3) the cheapest (segments, dtM) within 1 % of the
reference (every line's STD and maximum) whose next finer mesh is too. MoorDyn's cost depends
on the coupling (it steps at min(dtM, coupling)); the baseline found 20 ms cheapest of 1 and
20 ms, so coarser ones are tried too.

Targets: floatmoor at the defaults at most half MoorDyn's time loop and at most its whole run,
each against MoorDyn's cheapest accepted setting by that measure (floatmoor whole:
construction, settling, loop; MoorDyn whole: input, creation, initial-condition solve, loop;
summed over the three lines; docs/validation/performance.md).

Quick mode (``FLOATMOOR_BENCH_QUICK=1``): 180 s, a coarse reference, two schemes at 20 ms.

Run: ``python -m pytest -m benchmark tests/benchmarks/test_bench_deepcwind_lines_forced.py -s``
(about 10 minutes).
"""

from __future__ import annotations

import pytest

from tests.benchmarks.dynamic_harness import (MOORDYN_SCHEMES, REFERENCES,
                                              lines_against_moordyn, lines_problem, pick)

pytestmark = pytest.mark.benchmark

DEFINITION = REFERENCES / "deepcwind_lines_forced.toml"
PATHS = REFERENCES / "deepcwind_lc34_fairleads_600s.nc"
START = 60.0  # s, the wave ramp of LC34
#: MoorDyn's reference and its convergence check: (segments, dtM / (l / c), scheme, coupling).
REFERENCE = pick((80, 0.5, "RK4", 1e-3), (40, 0.5, "RK4", 1e-3))
CHECK = pick((60, 0.5, "RK4", 1e-3), (30, 0.5, "RK4", 1e-3))
SEGMENTS = pick((10, 15, 20, 30, 40), (10, 15, 20))
FRACTIONS = pick((1.0, 0.5), (1.0,))
SCHEMES = pick(MOORDYN_SCHEMES, ("RK2", "Midpoint3"))
#: MoorDyn coupling intervals tried [s].
COUPLINGS = pick((0.1, 0.05, 0.02, 0.01), (0.02,))
#: The targets, floatmoor / MoorDyn at most: half MoorDyn's time loop (the implicit line's
#: steps at half the cost of MoorDyn's cheapest 1 % setting), and its whole run (floatmoor's
#: construction and settling included).
SPEED_RATIO_MAX = {"loop": 0.5, "whole": 1.0}


def test_deepcwind_lines_forced_against_moordyn():
    pytest.importorskip("moordyn")
    problem = lines_problem(DEFINITION, PATHS, start=START, duration=pick(None, 180.0))
    _, ratios = lines_against_moordyn(problem, reference=REFERENCE, check=CHECK,
                                      segments=SEGMENTS, fractions=FRACTIONS, schemes=SCHEMES,
                                      couplings=COUPLINGS)
    assert ratios, "MoorDyn: no setting within 1 % of its converged reference"
    assert set(ratios) == set(SPEED_RATIO_MAX), ratios.keys()
    failures = [f"floatmoor's {measure} is {ratio:.3f} of MoorDyn's at its cheapest within 1 % "
                f"by that measure (target <= {SPEED_RATIO_MAX[measure]:g})"
                for measure, (_, ratio) in ratios.items()
                if not ratio <= SPEED_RATIO_MAX[measure]]
    assert not failures, "\n".join(failures)
