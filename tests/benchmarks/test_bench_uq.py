"""Benchmark: the wall time of the gpc paper's studies on this machine, local and
with 2 workers.

- Case F, T = 1.25 s, all three coefficients (``cases/uq/lindahl_T1.25_all.toml``: 216 dynamic
  Lindahl runs of 15 s at MooDy's 10 x p5), the whole study through ``floatmoor uq`` with 1 and
  2 local workers.
- Case G (``cases/uq/buoy_T1.20_anchors.toml``: 150 coupled buoy runs of 60 s with dynamic
  lines, for each of three wave periods): the first :data:`G_RUNS` runs of its design with 1
  and 2 workers, the 450 runs of the three studies extrapolated from them (the whole study takes
  hours here at the coupled buoy's speed).

This machine gives about one core of throughput to two busy processes, so 2 workers are not
expected to be faster here: the figures say what a run costs and that the campaign adds no
overhead. Nothing but completion is asserted.

Run: ``python -m pytest -m benchmark tests/benchmarks/test_bench_uq.py -s`` (about 20 min).
"""

from __future__ import annotations

import time

import pytest

from floatmoor.campaign.design import Axis, CampaignDesign
from floatmoor.campaign.runner import run_campaign
from floatmoor.cli import main
from floatmoor.uq.run import study_design
from floatmoor.uq.study import load_study
from tests.conftest import CASES

pytestmark = pytest.mark.benchmark

CASE_F = CASES / "uq" / "lindahl_T1.25_all.toml"
CASE_G = CASES / "uq" / "buoy_T1.20_anchors.toml"
#: Runs of case G's design timed (one per worker with 2 workers; ~4 min each here).
G_RUNS = 2
#: Case G: three wave periods of 150 runs each.
G_TOTAL_RUNS = 3 * 150


def test_case_f_wall_time(tmp_path) -> None:
    walls = {}
    for workers in (1, 2):
        start = time.perf_counter()
        assert main(["uq", str(CASE_F), "-o", str(tmp_path / f"w{workers}"), "--quiet",
                     "--workers", str(workers)]) == 0
        walls[workers] = time.perf_counter() - start
    print(f"\ncase F, T = 1.25 s, all three coefficients (216 runs): 1 worker {walls[1]:.1f} s, "
          f"2 workers {walls[2]:.1f} s (ratio {walls[2] / walls[1]:.3f}); "
          f"{walls[1] / 216:.2f} s per run")


def test_case_g_wall_time(tmp_path) -> None:
    study = load_study(CASE_G)
    _, _, full = study_design(study)
    axis = full.axes[0]
    design = CampaignDesign((Axis(axis.keys, tuple(v[:G_RUNS] for v in axis.values)),))
    walls, cpu = {}, {}
    for workers in (1, 2):
        start = time.perf_counter()
        ds = run_campaign(study.case, design, base_overrides=list(study.base_overrides),
                          timeseries=True, workers=workers)
        walls[workers] = time.perf_counter() - start
        cpu[workers] = float(ds["compute_time_s"].sum())
        assert (ds["status"].values == "complete").all()
    per_run = walls[1] / G_RUNS
    print(f"\ncase G, T = 1.2 s, {G_RUNS} of the 150 coupled runs (60 s, dynamic lines): "
          f"1 worker {walls[1]:.1f} s ({per_run:.1f} s per run, {per_run / 60.0:.2f} wall s "
          f"per simulated s), 2 workers {walls[2]:.1f} s (ratio {walls[2] / walls[1]:.3f}); "
          f"compute {cpu[1]:.1f} / {cpu[2]:.1f} s; the three studies ({G_TOTAL_RUNS} runs) "
          f"extrapolated: {G_TOTAL_RUNS * per_run / 3600.0:.1f} h on one process")
