"""Benchmark: peak resident memory of a coupled buoy run (issue 17, item 3).

The moored cylinder of cases.md C (``cases/cylinder_buoy/buoy_regular_T1.20.toml``: the
Cummins body from its BEM database, three dynamic DG chains, output every 0.01 s) runs as
``floatmoor run`` in a child process for two durations; the child's peak resident set size
(``ru_maxrss`` of its ``wait4``, what ``/usr/bin/time -v`` prints as "Maximum resident set
size") must stay under the issue's limit and must not grow with the duration beyond the
output samples the run holds. A first short run warms the kernel cache, so the figures are
those of a run whose numba kernels are cached (a cold cache adds their compilation).

What a run holds (issue 17): about 150 MB of libraries (Python, numpy, numba and llvmlite,
xarray and pandas, scipy), 55 MB when numba loads its first cached kernel, the database, its
checks and the radiation kernel (built in blocks: it peaked at 1.1 GB when its tail operator
was built whole), then the output samples until the file is written.

Run with ``python -m pytest -m benchmark tests/benchmarks/test_bench_memory.py -s`` (about
three minutes here: the dynamic chains take some 5 wall seconds per simulated second).
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from tests.conftest import CASES

pytestmark = pytest.mark.benchmark

BUOY = CASES / "cylinder_buoy" / "buoy_regular_T1.20.toml"
#: Issue 17: a coupled buoy run's peak resident memory at most 300 MB [MB].
PEAK_LIMIT_MB = 300.0
#: Simulated durations of the two measured runs [s], and of the run that warms the cache.
SHORT_S, LONG_S, WARM_S = 5.0, 20.0, 0.5
#: How much more the long run may take than the short one [MB]: the run keeps its output
#: samples until it writes its file, with the file's derived series and scipy's copy of the
#: whole dataset while writing (1.6 kB per sample of this case, 0.16 MB per simulated second:
#: 2.4 MB for the long run's 15 s more), plus the scatter of the peak between identical runs
#: (under 0.5 MB here).
GROWTH_TOLERANCE_MB = 6.0


def _peak_rss_mb(duration: float, output: Path) -> float:
    """Peak resident set size [MB] of ``floatmoor run`` on the buoy case for ``duration``."""
    command = [sys.executable, "-m", "floatmoor", "run", str(BUOY), "-o", str(output),
               "--quiet", "--set", f"simulation.duration={duration}"]
    with open(output.with_suffix(".log"), "wb") as log:
        child = subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT)
        _, status, usage = os.wait4(child.pid, 0)
    child.returncode = os.waitstatus_to_exitcode(status)  # reaped here, not by Popen
    assert child.returncode == 0, output.with_suffix(".log").read_text()
    # ru_maxrss: kilobytes on Linux, bytes on macOS
    return usage.ru_maxrss / (2 ** 20 if sys.platform == "darwin" else 2 ** 10)


def test_coupled_buoy_peak_memory(tmp_path):
    _peak_rss_mb(WARM_S, tmp_path / "warm.nc")
    short = _peak_rss_mb(SHORT_S, tmp_path / "short.nc")
    long = _peak_rss_mb(LONG_S, tmp_path / "long.nc")
    print(f"\ncylinder buoy, dynamic chains, warm kernel cache: peak resident memory "
          f"{short:.1f} MB for {SHORT_S:g} s, {long:.1f} MB for {LONG_S:g} s "
          f"(+{long - short:.1f} MB); limit {PEAK_LIMIT_MB:g} MB, growth tolerance "
          f"{GROWTH_TOLERANCE_MB:g} MB")
    assert max(short, long) <= PEAK_LIMIT_MB
    assert long - short < GROWTH_TOLERANCE_MB
