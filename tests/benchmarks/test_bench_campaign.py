"""Benchmark: campaign overhead. On these machines (about one core of throughput for two
processes) a 2-worker campaign must take no longer than the 1-worker one plus 10 %, and the
per-run compute (CPU) times it records must sum to within 10 % of the serial run's, so that
scaling on a real cluster follows from the worker count.

Run with ``python -m pytest -m benchmark tests/benchmarks/test_bench_campaign.py -s``.
"""

from __future__ import annotations

import time

import pytest

from floatmoor.campaign.design import design_from_options
from floatmoor.campaign.runner import run_campaign
from tests.conftest import LINDAHL_CASE

pytestmark = pytest.mark.benchmark

#: Goal: overhead and compute-time bookkeeping within 10 %.
OVERHEAD_FRACTION = 0.10
#: 8 dynamic Lindahl runs of 10 s (about 0.5 s of compute each).
DESIGN = ["motion.radius=0.1,0.15,0.2,0.25", "motion.period=1.25,2.5"]
BASE = ["simulation.duration=10.0"]


def _timed(workers: int):
    start = time.perf_counter()
    ds = run_campaign(LINDAHL_CASE, design_from_options(DESIGN), base_overrides=BASE,
                      workers=workers)
    return time.perf_counter() - start, float(ds["compute_time_s"].sum())


def test_two_workers_cost_no_more_than_one():
    _timed(1)  # warm the kernel cache
    serial_wall, serial_cpu = _timed(1)
    parallel_wall, parallel_cpu = _timed(2)
    print(f"\n8 runs: 1 worker {serial_wall:.2f} s wall ({serial_cpu:.2f} s compute), "
          f"2 workers {parallel_wall:.2f} s wall ({parallel_cpu:.2f} s compute); "
          f"wall ratio {parallel_wall / serial_wall:.3f}, compute ratio "
          f"{parallel_cpu / serial_cpu:.3f}")
    assert parallel_wall <= (1 + OVERHEAD_FRACTION) * serial_wall
    assert abs(parallel_cpu / serial_cpu - 1.0) <= OVERHEAD_FRACTION
