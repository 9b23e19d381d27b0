"""Benchmark: the cost of one quasi-dynamic step against one quasi-static and one dynamic step
of the same line (the verification chain of docs/cases/qd_verification.md, its fairlead path, 2.5 ms steps).

The goals: a quasi-dynamic step at most 3 times a quasi-static one, and at least 30
times cheaper than the dynamic model over the same simulated time. Each model runs its
``solve_path`` on the same samples; the quasi-static and quasi-dynamic runs alternate, and
the medians over the repetitions are compared (this machine's timings vary by +-30 %).
The dynamic model is timed per output sample (its ~60 SSP-RK3 steps of 42 us in 2.5 ms) and
per step of its own.

Status on the development machine (shared, 2 cores, one busy with another job; 9 runs):
quasi-dynamic / quasi-static 1.91 to 2.05 with 31 stations (0.67-0.73 us against 0.34-0.38
us) and 1.77 to 1.89 with 21 (0.63-0.70 us), so the 3x goal is met with the default 31 (it
was 3.1-3.5 before the vector loops used unsigned indices and whole vectors of stations);
dynamic / quasi-dynamic 610 to 720 with the case file's former 6 dynamic elements, 1636 with
its 10 (for convergence; more, shorter steps). The asserted bound on the first ratio is the
goal. The
quasi-dynamic step is one catenary solve (as the quasi-static step) plus one static profile at
the fixed stations and the force integral, each loop vectorised over whole vectors of
stations: about 5 ns per station (two square roots, two divisions and the log series per
station, 8 stations per vector) and 0.2 us per step of fixed cost.

Run with ``python -m pytest -m benchmark tests/benchmarks/test_bench_quasidynamic.py -s``.
"""

from __future__ import annotations

import time

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.mooring.dg.line import DynamicLine
from floatmoor.mooring.quasidynamic import QuasiDynamicLine
from floatmoor.mooring.quasistatic import QuasiStaticLine
from floatmoor.motion.fairlead import fairlead_state
from tests.conftest import CASES

pytestmark = pytest.mark.benchmark

CASE_B = CASES / "qd_verification" / "s2_d2.toml"
#: The goals (docs/validation/performance.md#line-models).
QS_RATIO_GOAL = 3.0
DYNAMIC_RATIO_GOAL = 30.0
#: Asserted bound on the quasi-dynamic / quasi-static ratio: the goal (measured 1.9-2.05).
QS_RATIO_BOUND = QS_RATIO_GOAL
SAMPLES = 20001  # 50 s of the case-B motion at 2.5 ms
REPEATS = 9


def _outputs(n):
    return [np.zeros((n, 3)), np.zeros((n, 3)), np.zeros(n), np.zeros(n)]


def test_quasi_dynamic_step_cost_against_quasi_static_and_dynamic():
    case = load_case(CASE_B)
    line = case.lines[0]
    t = np.arange(SAMPLES) * case.simulation.output_interval
    p, v = fairlead_state(case.motion, line, t)
    out = _outputs(SAMPLES)
    lines = {n: load_case(CASE_B, [f"lines.chain.quasi_dynamic.integration_points={n}"]).lines[0]
             for n in (31, 21)}

    def quasi_static():
        model = QuasiStaticLine.from_case(line, case.environment, case.seabed)
        start = time.perf_counter()
        model.solve_path(t, p, v, *out)
        return time.perf_counter() - start

    def quasi_dynamic(n_points):
        model = QuasiDynamicLine.from_case(lines[n_points], case.environment, case.seabed)
        start = time.perf_counter()
        model.solve_path(t, p, v, *out)
        return time.perf_counter() - start

    quasi_static(), quasi_dynamic(31), quasi_dynamic(21)  # compile / load the caches
    runs = np.array([(quasi_static(), quasi_dynamic(31), quasi_dynamic(21))
                     for _ in range(REPEATS)]) / (SAMPLES - 1) * 1e6  # us per step
    qs, qd31, qd21 = np.median(runs, axis=0)
    ratio31 = float(np.median(runs[:, 1] / runs[:, 0]))
    ratio21 = float(np.median(runs[:, 2] / runs[:, 0]))

    n_dyn = 401  # 1 s
    dyn_out = _outputs(n_dyn)
    DynamicLine.from_case(line, case.environment, case.seabed).solve_path(
        t[:3], p[:3], v[:3], *_outputs(3))
    best = np.inf
    for _ in range(3):
        dyn = DynamicLine.from_case(line, case.environment, case.seabed)
        start = time.perf_counter()
        dyn.solve_path(t[:n_dyn], p[:n_dyn], v[:n_dyn], *dyn_out)
        best = min(best, time.perf_counter() - start)
    dyn_sample = best / (n_dyn - 1) * 1e6
    dyn_step = best / dyn_out[3].sum() * 1e6
    print(f"\ncase B line (C22), {SAMPLES - 1} steps of {case.simulation.output_interval * 1e3:g}"
          f" ms, median of {REPEATS} alternating runs, us per step:")
    print(f"  quasi-static:                  {qs:8.3f}")
    print(f"  quasi-dynamic, 31 stations:    {qd31:8.3f}  ({ratio31:.2f} x quasi-static)")
    print(f"  quasi-dynamic, 21 stations:    {qd21:8.3f}  ({ratio21:.2f} x quasi-static)")
    print(f"  dynamic ({line.dynamic.elements} x p{line.dynamic.order}), per 2.5 ms sample: "
          f"{dyn_sample:8.1f}  ({dyn_sample / qd31:.0f} x quasi-dynamic); per own step "
          f"({dyn.time_step * 1e6:.1f} us): {dyn_step:.2f}")
    cheaper = dyn_sample / qd31
    print(f"  goals: quasi-dynamic <= {QS_RATIO_GOAL:g} x quasi-static: "
          f"{'met' if ratio31 <= QS_RATIO_GOAL else 'NOT met'}; >= {DYNAMIC_RATIO_GOAL:g} x "
          f"cheaper than dynamic: {'met' if cheaper >= DYNAMIC_RATIO_GOAL else 'NOT met'}")
    assert dyn_sample / qd31 >= DYNAMIC_RATIO_GOAL
    assert ratio31 <= QS_RATIO_BOUND
