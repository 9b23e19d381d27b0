"""Benchmark: the whole Lindahl quasi-static forced-motion run, against MoorPy solving the same
fairlead path with warm starts in the same process.

Run with ``python -m pytest -m benchmark tests/benchmarks -s``.
"""

from __future__ import annotations

import time

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.motion.fairlead import fairlead_path
from floatmoor.simulation.forced import output_times, run_forced_motion
from tests.conftest import LINDAHL_CASE

pytestmark = pytest.mark.benchmark


def _best_of(func, repeats=5):
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        func()
        times.append(time.perf_counter() - start)
    return min(times)


def test_lindahl_quasi_static_run_against_moorpy():
    catenary = pytest.importorskip("moorpy.Catenary").catenary
    case = load_case(LINDAHL_CASE, ['lines.chain.model="quasi-static"'])
    run_forced_motion(case)  # compile / load the cache
    ours = _best_of(lambda: run_forced_motion(case))

    line = case.lines[0]
    t = output_times(case.simulation)
    path = fairlead_path(case.motion, line, t) - np.asarray(line.anchor)
    w = line.line_type.weight_in_water(case.environment)
    ea, cb, length = line.line_type.axial_stiffness, case.seabed.friction_coefficient, line.length

    def moorpy_run():
        hf = vf = 0.0
        for p in path:
            fah, fav, fbh, fbv, info = catenary(float(np.hypot(p[0], p[1])), float(p[2]), length,
                                                ea, w, CB=cb, HF0=hf, VF0=vf, Tol=1e-10)
            hf, vf = info["HF"], info["VF"]

    theirs = _best_of(moorpy_run, repeats=1)
    n = t.size
    print(f"\nLindahl quasi-static run, {n} samples over {case.simulation.duration:g} s:")
    print(f"  floatmoor run_forced_motion: {ours * 1e3:.1f} ms ({ours / n * 1e6:.2f} us/sample, "
          f"output assembly included)")
    print(f"  MoorPy catenary loop:        {theirs * 1e3:.1f} ms ({theirs / n * 1e6:.2f} us/sample)")
    print(f"  ratio MoorPy / floatmoor:    {theirs / ours:.1f}")
    assert ours < theirs
