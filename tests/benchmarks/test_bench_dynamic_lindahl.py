"""Benchmark: the dynamic (DG) line on the Lindahl chain, beside MoorDyn at equal accuracy.

For the snap case (r = 0.2 m, T = 1.25 s) and the smooth one (T = 3.5 s) with the physical
seabed, both codes go through the same study (``tests/benchmarks/moordyn_lindahl.py``: the same
fairlead path sampled every 1 ms, the same measured cycles, the same acceptance rule): a
converged reference, then the cheapest discretisation whose mean cycle maximum of the fairlead
tension is within 1 % of its own reference *and* whose next finer mesh is too. Reported: wall
seconds per simulated second of that discretisation and of floatmoor's default settings, and
the ratio MoorDyn / floatmoor at equal accuracy. Wall time counts only the solvers' stepping.

Run: ``python -m pytest -m benchmark tests/benchmarks/test_bench_dynamic_lindahl.py -s``
(about 5 minutes, most of it MoorDyn's reference runs).
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.case.schema import DynamicSettings
from floatmoor.mooring.dg.line import DynamicLine
from floatmoor.motion.fairlead import fairlead_state
from tests.benchmarks import moordyn_lindahl as md
from tests.conftest import LINDAHL_CASE

pytestmark = pytest.mark.benchmark

#: "1 % accuracy of the maximum tension against a converged reference" (the target).
TOLERANCE = 0.01
#: Converged reference: 40 elements of order 5 (error below 0.3 % from 20 elements on).
REFERENCE = (40, 5)
#: Candidates (elements, order), tried in increasing number of unknowns x steps.
ELEMENTS = (3, 4, 5, 6, 8, 10, 12, 16, 20)
ORDERS = (3, 4, 5, 6)
DEFAULT = (10, 5)


@dataclass(frozen=True)
class Result:
    elements: int
    order: int
    mean_max: float
    maxima: np.ndarray
    wall_per_simulated: float


def run(problem: md.Problem, elements: int, order: int, repeats: int = 1) -> Result:
    case = load_case(LINDAHL_CASE, [f"motion.radius={md.RADIUS}",
                                    f"motion.period={problem.period}",
                                    f"motion.ramp_duration={md.RAMP_PERIODS * problem.period}"])
    line = case.lines[0]
    settings = DynamicSettings(elements=elements, order=order, cfl=0.8, max_time_step=None,
                               slack_filter=True, seabed_contact="implicit")
    path, velocity = fairlead_state(case.motion, line, problem.time)
    n = problem.time.size
    best = np.inf
    for _ in range(repeats):
        dg = DynamicLine(DynamicLine.from_case(line, case.environment, case.seabed).properties,
                         settings, np.asarray(line.anchor), np.asarray(line.fairlead))
        ff = np.zeros((n, 3))
        start = time.perf_counter()
        dg.solve_path(problem.time, path, velocity, ff, np.zeros((n, 3)), np.zeros(n),
                      np.zeros(n))
        best = min(best, time.perf_counter() - start)
    mean_max, maxima = md.mean_cycle_maximum(problem, problem.time, np.linalg.norm(ff, axis=1))
    return Result(elements, order, mean_max, maxima, best / problem.duration)


def study(period: float, echo=print) -> dict:
    problem = md.lindahl_problem(period)
    run(problem, 3, 3)  # compile or load the kernels
    ref = run(problem, *REFERENCE)
    echo(f"floatmoor DG, Lindahl T = {period} s: reference {REFERENCE[0]} elements p = "
         f"{REFERENCE[1]}: mean max {ref.mean_max:.3f} N ({ref.wall_per_simulated:.3f} s/s)")
    results = {}

    def result(k, p):
        if (k, p) not in results:
            results[k, p] = r = run(problem, k, p, repeats=3)
            err = r.mean_max / ref.mean_max - 1.0
            echo(f"  {k:3d} elements p = {p}: mean max {r.mean_max:7.3f} N {100 * err:+6.2f} %  "
                 f"{r.wall_per_simulated:.4f} wall s / sim s")
        return results[k, p]

    def within(r):
        return abs(r.mean_max / ref.mean_max - 1.0) <= TOLERANCE

    candidates = sorted(((k, p) for k in ELEMENTS for p in ORDERS),
                        key=lambda c: (c[0] * (c[1] + 1) ** 2, c[0]))  # ~ unknowns / time step
    cheapest = None
    for k, p in candidates:
        r = result(k, p)
        finer = [m for m in ELEMENTS if m > k]
        if within(r) and (not finer or within(result(finer[0], p))):
            cheapest = r
            break
    default = result(*DEFAULT)
    return {"reference": ref, "cheapest": cheapest, "default": default}


@pytest.mark.parametrize("period", md.PERIODS)
def test_dynamic_lindahl_against_moordyn(period):
    pytest.importorskip("moordyn")
    ours = study(period)
    theirs = md.study(period)
    c, m = ours["cheapest"], theirs["cheapest"]
    assert c is not None and m is not None
    ratio = m.wall_per_simulated / c.wall_per_simulated
    print(f"\nT = {period} s, within 1 % of each code's converged mean cycle maximum "
          f"(floatmoor {ours['reference'].mean_max:.2f} N, MoorDyn "
          f"{theirs['reference'].mean_max:.2f} N):")
    print(f"  floatmoor {c.elements} elements p = {c.order}: {c.wall_per_simulated:.4f} s/s; "
          f"default {DEFAULT[0]} elements p = {DEFAULT[1]}: "
          f"{ours['default'].wall_per_simulated:.4f} s/s")
    print(f"  MoorDyn {m.segments} segments dt = {m.dt * 1e6:g} us: {m.wall_per_simulated:.4f} s/s")
    print(f"  ratio MoorDyn / floatmoor at equal accuracy: {ratio:.1f}")
    assert ratio >= 2.0  # the goal (docs/validation/performance.md#line-models)
