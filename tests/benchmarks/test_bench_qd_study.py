"""Benchmark: the whole quasi-dynamic set of the verification study (docs/cases/qd_verification.md, 180 runs)
on one core, the goal being under a minute
(docs/validation/performance.md#line-models).

Each of the 180 combinations (6 configurations x 5 amplitudes x 6 accelerations) runs the
quasi-dynamic model exactly as the study does: the case file loaded with the run's
overrides (``floatmoor.studies.qd_verification.motion_overrides``), a ramp of two periods and
five steady cycles at the paper's 2.5 ms step, one ``run_forced_motion`` each, in this one
process. Also printed: the same runs with the quasi-static model, and how the time splits
between the steps and the rest (case loading, dataset assembly).

Run with ``python -m pytest -m benchmark tests/benchmarks/test_bench_qd_study.py -s``.
"""

from __future__ import annotations

import time

import pytest

from floatmoor.case.load import load_case
from floatmoor.simulation.forced import run_forced_motion
from floatmoor.studies import qd_verification as qdv

pytestmark = pytest.mark.benchmark

#: Goal: the 180 quasi-dynamic runs in under a minute on one core [s].
QD_SET_GOAL = 60.0


def _run_set(model: str) -> tuple[float, float, int]:
    """Wall time of the 180 runs, the part spent in the runs themselves, and the steps."""
    total_run, steps = 0.0, 0
    start = time.perf_counter()
    for spec in qdv.design():
        overrides = qdv.motion_overrides(spec.amplitude, spec.period) + [
            f'lines.chain.model="{model}"']
        case = load_case(qdv.case_path(spec.config), overrides)
        t0 = time.perf_counter()
        result = run_forced_motion(case)
        total_run += time.perf_counter() - t0
        steps += result.dataset.sizes["time"] - 1
    return time.perf_counter() - start, total_run, steps


def test_the_180_quasi_dynamic_runs_take_under_a_minute():
    spec = qdv.design()[0]  # compile / load the kernel caches
    run_forced_motion(load_case(qdv.case_path(spec.config),
                                qdv.motion_overrides(spec.amplitude, spec.period)))
    qd_wall, qd_runs, steps = _run_set("quasi-dynamic")
    qs_wall, qs_runs, _ = _run_set("quasi-static")
    print(f"\n180 runs of case B, {steps} steps of 2.5 ms in all:")
    print(f"  quasi-dynamic: {qd_wall:.1f} s ({qd_runs:.1f} s in the runs, "
          f"{qd_runs / steps * 1e6:.2f} us per step with the recording)")
    print(f"  quasi-static:  {qs_wall:.1f} s ({qs_runs:.1f} s in the runs)")
    print(f"  goal: quasi-dynamic set under {QD_SET_GOAL:g} s: "
          f"{'met' if qd_wall < QD_SET_GOAL else 'NOT met'}")
    assert qd_wall < QD_SET_GOAL
