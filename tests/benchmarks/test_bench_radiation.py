"""Cost of a body step with each radiation path: the convolution of K(t) and the state-space
realisation.

Run with ``pytest -m benchmark tests/benchmarks/test_bench_radiation.py -s``. Each body, alone
(no lines, no waves), is released from an offset and stepped; the paths are timed alternately,
several repeats, medians reported, after a run-in that fills the convolution's velocity
history (a run's steady cost). The convolution costs a sum over the truncation time per
step (the DeepCwind kernel, 157 s long, is 1571 weights at 0.1 s and 7854 at 0.02 s); the
state-space path four compiled stage calls over its states, whatever the step.
"""

from __future__ import annotations

import statistics
import time
from pathlib import Path

import numpy as np
import pytest

from floatmoor.body.model import build_body
from floatmoor.case.load import load_case
from floatmoor.hydro.database import read_database

REPO = Path(__file__).resolve().parents[2]
CASES = {
    "cylinder_buoy": (REPO / "cases" / "cylinder_buoy" / "buoy_regular_T1.20.toml", (0.01,)),
    "deepcwind": (REPO / "cases" / "deepcwind" / "deepcwind_free_decay.toml", (0.1, 0.02)),
}
STEPS = 2000
REPEATS = 5


def _time_steps(body) -> float:
    zero = np.zeros(6)
    t0 = time.perf_counter()
    for _ in range(STEPS):
        body.step(lambda *a: zero)
    return (time.perf_counter() - t0) / STEPS


@pytest.mark.benchmark
@pytest.mark.parametrize("name", sorted(CASES))
def test_bench_body_step_per_radiation_path(name):
    path, steps = CASES[name]
    case = load_case(path)
    ds = read_database(REPO / "hydrodb" / f"{name}.nc")
    start = np.array([0.01, 0.0, 0.01, 0.0, 0.01, 0.0])
    for dt in steps:
        bodies = {r: build_body(case.floater, ds, case.environment, dt, radiation=r)
                  for r in ("convolution", "state-space")}
        zero = np.zeros(6)
        for body in bodies.values():  # compile, and fill the convolution's whole history
            body.start(0.0, start)
            for _ in range(max(body.weights.shape[0], STEPS)):
                body.step(lambda *a: zero)
        cost = {r: [] for r in bodies}
        for _ in range(REPEATS):
            for r, body in bodies.items():
                cost[r].append(_time_steps(body))
        conv = statistics.median(cost["convolution"])
        stsp = statistics.median(cost["state-space"])
        states = bodies["state-space"].radiation_states
        pairs = len(bodies["convolution"].pairs)
        print(f"\n{name}, dt = {dt} s: convolution {conv * 1e6:.1f} us per step "
              f"({bodies['convolution'].weights.shape[0]} weights x {pairs} pairs), "
              f"state-space {stsp * 1e6:.1f} us per step ({states.n_states} states, "
              f"{states.residualised} fast modes as feedthrough); ratio {conv / stsp:.2f}")
        assert np.isfinite(conv) and np.isfinite(stsp)
