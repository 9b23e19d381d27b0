"""Timing of one warm-started catenary solve: floatmoor's kernel against MoorPy.

Run with ``pytest -m benchmark tests/benchmarks/test_bench_catenary.py -s``. The fairlead of
a chain with touchdown (850 m, 200 m water depth) moves a small step between calls, as in a
time-domain simulation, and each solve starts from the previous solution.
"""

from __future__ import annotations

import math
import time

import numpy as np
import pytest

from floatmoor._numba import jit
from floatmoor.mooring import _catenary_kernels as k
from floatmoor.mooring.catenary import DEFAULT_TOL

#: The project's goal: one warm solve from Python at least 50 times faster than MoorPy's.
MIN_SPEEDUP = 50.0
N_CALLS = 20000
N_MOORPY = 400

ANCHOR = np.array([-800.0, 0.0, -200.0])
L, EA, W, CB, SEABED_Z = 850.0, 7.5e8, 1100.0, 0.0, -200.0


def fairlead_path(n: int) -> np.ndarray:
    """Surge 5 m, heave 2 m, sway 1 m around (0, 0, -10): steps of ~0.06 m per call."""
    i = np.arange(n)
    return np.column_stack([5.0 * np.sin(2 * np.pi * i / 500), 1.0 * np.sin(2 * np.pi * i / 700),
                            -10.0 + 2.0 * np.sin(2 * np.pi * i / 370)])


@jit
def _solve_path(anchor, path, L, EA, W, CB, seabed_z, tol, out, iterations):
    h0 = math.nan
    v0 = math.nan
    failures = 0
    for i in range(path.shape[0]):
        if k.catenary_solve_3d(anchor, path[i], L, EA, W, CB, seabed_z, h0, v0, tol, 100,
                               out) != k.CAT_OK:
            failures += 1
        h0 = out[k.I3_HF]
        v0 = out[k.I3_VF]
        iterations[i] = out[k.I3_ITER]
    return failures


@pytest.mark.benchmark
def test_warm_solve_is_at_least_50x_faster_than_moorpy():
    catenary = pytest.importorskip("moorpy.Catenary").catenary
    path = fairlead_path(N_CALLS)
    out = np.zeros(k.N_OUT_3D)
    assert k.catenary_solve_3d(ANCHOR, path[0], L, EA, W, CB, SEABED_Z, math.nan, math.nan,
                               DEFAULT_TOL, 100, out) == k.CAT_OK
    solve = k.catenary_solve_3d

    # --- from Python: one call per position, preallocated out, previous solution as warm start
    times = np.empty(N_CALLS, dtype=np.int64)
    iterations = np.empty(N_CALLS)
    for i in range(N_CALLS):
        fairlead = path[i]
        h0 = out[k.I3_HF]
        v0 = out[k.I3_VF]
        t0 = time.perf_counter_ns()
        status = solve(ANCHOR, fairlead, L, EA, W, CB, SEABED_Z, h0, v0, DEFAULT_TOL, 100, out)
        times[i] = time.perf_counter_ns() - t0
        assert status == k.CAT_OK
        iterations[i] = out[k.I3_ITER]
    ours = float(np.median(times)) * 1e-9

    # --- the same loop inside a jitted driver (amortised per solve; first call compiles)
    its = np.empty(N_CALLS)
    _solve_path(ANCHOR, path[:10], L, EA, W, CB, SEABED_Z, DEFAULT_TOL, out, its)
    t0 = time.perf_counter_ns()
    assert _solve_path(ANCHOR, path, L, EA, W, CB, SEABED_Z, DEFAULT_TOL, out, its) == 0
    jitted = (time.perf_counter_ns() - t0) * 1e-9 / N_CALLS

    # --- MoorPy, warm-started with its previous (HF, VF), default and tight tolerance
    def moorpy_median(tol: float) -> float:
        hf = vf = 0.0
        spent = []
        for i in range(N_MOORPY):
            span = path[i] - ANCHOR
            xf, zf = math.hypot(span[0], span[1]), span[2]
            t0 = time.perf_counter_ns()
            *_, info = catenary(xf, zf, L, EA, W, CB=CB, HF0=hf, VF0=vf, Tol=tol, MaxIter=100)
            spent.append(time.perf_counter_ns() - t0)
            hf, vf = info["HF"], info["VF"]
        return float(np.median(spent[10:])) * 1e-9

    theirs = moorpy_median(1e-6)  # MoorPy's default Tol [m]
    theirs_tight = moorpy_median(1e-10)
    ratio = theirs / ours
    print(f"\nwarm catenary solve (850 m chain with touchdown, fairlead steps ~0.06 m):"
          f"\n  floatmoor catenary_solve_3d from Python: {ours * 1e6:8.2f} us median "
          f"({iterations.mean():.2f} Newton iterations on average, tol {DEFAULT_TOL:g} L)"
          f"\n  floatmoor in a jitted loop:              {jitted * 1e6:8.2f} us per solve"
          f"\n  MoorPy catenary, Tol = 1e-6 m:           {theirs * 1e6:8.1f} us median"
          f"\n  MoorPy catenary, Tol = 1e-10 m:          {theirs_tight * 1e6:8.1f} us median"
          f"\n  ratio MoorPy / floatmoor (from Python):  {ratio:8.0f} x (Tol 1e-6), "
          f"{theirs_tight / ours:.0f} x (Tol 1e-10); jitted loop {theirs / jitted:.0f} x")
    assert ratio >= MIN_SPEEDUP
