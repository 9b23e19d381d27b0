"""Benchmark: wall time of the coupled runs: the 3-hour DeepCwind LC34 sea state with
each line model on one core (goals: dynamic lines under 10 minutes, quasi-dynamic under 1
minute), and the moored cylinder of docs/cases/cylinder_buoy.md with its dynamic chains.

Each run is a whole ``floatmoor run`` in this process (start-up, equilibrium, line settling,
the radiation kernel and the writing of the output included), with the case's own numerics.
The timings print; the goals are asserted.

Run with ``python -m pytest -m benchmark tests/benchmarks/test_bench_coupled.py -s``
(about 15 minutes on the development machine).
"""

from __future__ import annotations

import time

import pytest

from floatmoor.case.load import load_case
from floatmoor.simulation.coupled_run import run_coupled
from tests.conftest import CASES

pytestmark = pytest.mark.benchmark

LC34 = CASES / "deepcwind" / "deepcwind_lc34.toml"
BUOY = CASES / "cylinder_buoy" / "buoy_regular_T1.20.toml"
#: The goals for the 3-hour LC34 run on one core [s]; quasi-static has none (it is
#: the floor the others are measured against).
GOALS = {"dynamic": 600.0, "quasi-dynamic": 60.0, "quasi-static": None}


def _all_lines(model: str) -> list[str]:
    return [f'lines.*.model="{model}"']


@pytest.mark.parametrize("model", ["quasi-static", "quasi-dynamic", "dynamic"])
def test_lc34_three_hours(model, tmp_path):
    case = load_case(LC34, _all_lines(model))
    start = time.perf_counter()
    result = run_coupled(case, output=tmp_path / "lc34.nc")
    wall = time.perf_counter() - start
    goal = GOALS[model]
    print(f"\nLC34, 3 h, {model} lines: {wall:.1f} s wall ({result.simulated_time_s / wall:.0f} x "
          f"real time); goal {'-' if goal is None else f'{goal:g} s'}")
    assert result.status == "complete"
    if goal is not None:
        assert wall <= goal


@pytest.mark.parametrize("model", ["quasi-static", "quasi-dynamic", "dynamic"])
def test_cylinder_buoy(model, tmp_path):
    """The shipped case as it is (60 s of regular waves, 0.01 s body steps); its dynamic chains
    (EA 1.6 MN on 6.95 m, c = 3325 m/s) take steps of about 0.1 ms."""
    case = load_case(BUOY, _all_lines(model))
    start = time.perf_counter()
    result = run_coupled(case, output=tmp_path / "buoy.nc")
    wall = time.perf_counter() - start
    print(f"\ncylinder buoy (T = 1.2 s, {result.simulated_time_s:g} s), {model} lines: "
          f"{wall:.1f} s wall ({wall / result.simulated_time_s:.3f} s per simulated second)")
    assert result.status == "complete"
