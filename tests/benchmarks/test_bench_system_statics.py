"""Timing of the statics of a mooring system along a body path: floatmoor against MoorPy.

Run with ``pytest -m benchmark tests/benchmarks/test_bench_system_statics.py -s``. The
three-line system of the statics tests (a chain-rope line with a clump weight, a rope to a
bridle held by two chains, a chain-rope-chain line with a clump and a buoy: 12 unknowns)
has its three body points moved along a surge-heave path; each sample's equilibrium starts
from the previous one, in floatmoor (``SystemStatics.solve_path``, one compiled loop) and in
MoorPy 1.3 (``System.solveEquilibrium`` after moving its coupled points), at the tolerance
the peer test uses for MoorPy (converged to 1e-12 of the forces) and at MoorPy's default.
"""

from __future__ import annotations

import contextlib
import io
import time

import numpy as np
import pytest

from floatmoor.mooring.statics_solver import SystemStatics, build_static_system
from tests.mooring.test_statics_moorpy import MOORPY_TOL, _moorpy
from tests.mooring.statics_systems import ENVIRONMENT, SEABED, three_lines

#: The project's goal for a system: a warm-started sample at least 20 times faster than
#: MoorPy's at the tolerance that makes MoorPy's answer agree with ours.
MIN_SPEEDUP = 20.0
N_SAMPLES = 4000
N_MOORPY = 60


def body_path(rest: np.ndarray, n: int) -> np.ndarray:
    """(n, bodies, 3): surge 8 m (period 400 samples) and heave 2 m (period 260 samples)."""
    i = np.arange(n)
    offset = np.zeros((n, 3))
    offset[:, 0] = 8.0 * np.sin(2 * np.pi * i / 400)
    offset[:, 2] = 2.0 * np.sin(2 * np.pi * i / 260)
    return rest[None, :, :] + offset[:, None, :]


@pytest.mark.benchmark
def test_system_statics_series_against_moorpy():
    pytest.importorskip("moorpy")
    points, lines = three_lines()
    system = build_static_system(points, lines, ENVIRONMENT, SEABED)
    rest = system.positions[system.body_index]
    path = body_path(rest, N_SAMPLES)
    n_pts, n_sec = len(system.point_names), len(system.section_names)

    def run(statics: SystemStatics, k: int) -> None:
        statics.solve_path(np.arange(k, dtype=float), path[:k], np.zeros_like(path[:k]),
                           np.zeros((k, n_sec, 3)), np.zeros((k, n_sec, 3)),
                           np.zeros((k, n_sec)), np.zeros((k, n_pts, 3)), np.zeros(k))

    run(SystemStatics(system), 10)  # compile
    statics = SystemStatics(system)
    statics.solve()
    t0 = time.perf_counter()
    run(statics, N_SAMPLES)
    ours = (time.perf_counter() - t0) / N_SAMPLES

    timings = {}
    for label, tol in (("converged", MOORPY_TOL), ("default", None)):
        ms, number = _moorpy(points, lines, body="coupled")
        coupled = [number[n] - 1 for n in system.body_point_names]
        t0 = time.perf_counter()
        with contextlib.redirect_stdout(io.StringIO()):
            for k in range(N_MOORPY):
                for b, p in enumerate(coupled):
                    ms.pointList[p].setPosition(path[k, b])
                if tol is None:
                    ms.solveEquilibrium()
                else:
                    ms.solveEquilibrium(tol=tol, maxIter=2000)
        timings[label] = (time.perf_counter() - t0) / N_MOORPY
    print(f"\nsystem statics per sample: floatmoor {ours * 1e6:.1f} us; MoorPy "
          f"{timings['converged'] * 1e3:.2f} ms converged (x{timings['converged'] / ours:.0f}),"
          f" {timings['default'] * 1e3:.2f} ms at its default tolerance "
          f"(x{timings['default'] / ours:.0f})")
    assert timings["converged"] / ours >= MIN_SPEEDUP
