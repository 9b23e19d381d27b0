"""Benchmark: peak resident memory of coupled runs: the buoy, and every shipped coupled case.

The moored cylinder of docs/cases/cylinder_buoy.md (``cases/cylinder_buoy/buoy_regular_T1.20.toml``: the
Cummins body from its BEM database, three chains, output every 0.01 s) runs as ``floatmoor
run`` in a child process; the child's peak resident set size (``ru_maxrss`` of its ``wait4``,
what ``/usr/bin/time -v`` prints as "Maximum resident set size") must stay under the project's
limit, with the dynamic DG chains, and must not grow with the simulated duration: with
quasi-static chains (seconds of wall time per simulated minute) a run of ten times the
duration may take only :data:`GROWTH_TOLERANCE_MB` more. First runs warm the kernel cache,
so the figures are those of runs whose numba kernels are cached (a cold cache adds their
compilation). Every shipped coupled case, with either radiation path, stays under the same
limit (measured: 259-269 MB; the first run of a fresh kernel cache peaks near 360 MB while
numba compiles).

What a run holds: about 150 MB of libraries (Python, numpy, numba and llvmlite,
xarray and pandas, scipy), 55 MB when numba loads its first cached kernel, the database, its
checks and the radiation kernel (built in blocks: it peaked at 1.1 GB when its tail operator
was built whole), and a window of output samples (floatmoor.simulation.recorder.WINDOW_BYTES,
2 MB), which is appended to the file as it fills; the run's summary then reads the file one
series at a time.

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
QUASI_STATIC = 'lines.*.model="quasi-static"'
#: The most a shipped coupled run may hold at its peak, whatever its radiation path [MB].
PEAK_LIMIT_MB = 300.0
#: Simulated durations [s]: the dynamic-chain run, the two quasi-static runs, the warm-ups.
DYNAMIC_S, SHORT_S, LONG_S, WARM_S = 20.0, 60.0, 600.0, 0.5
#: How much more the long quasi-static run may take than the short one [MB]. What still
#: grows with the duration is 8 bytes per output sample for each whole series the run's
#: summary holds after the run (the time axis and its index, a line's tension, the window
#: mask, a DOF's displacement: about ten, 4.3 MB for the long run's 54 000 more samples),
#: plus the scatter of the peak between identical runs (under 1 MB here). The samples
#: themselves took 1.6 kB each before they were streamed to the file (87 MB more).
GROWTH_TOLERANCE_MB = 6.0


def _peak_rss_mb(duration: float, output: Path, *overrides: str) -> float:
    """Peak resident set size [MB] of ``floatmoor run`` on the buoy case for ``duration``."""
    settings = ["--set", f"simulation.duration={duration}"]
    for text in overrides:
        settings += ["--set", text]
    return _peak_rss_of(BUOY, output, settings)


def test_coupled_buoy_peak_memory(tmp_path):
    _peak_rss_mb(WARM_S, tmp_path / "warm.nc")
    _peak_rss_mb(WARM_S, tmp_path / "warm_qs.nc", QUASI_STATIC)
    short = _peak_rss_mb(SHORT_S, tmp_path / "short.nc", QUASI_STATIC)
    long = _peak_rss_mb(LONG_S, tmp_path / "long.nc", QUASI_STATIC)
    dynamic = _peak_rss_mb(DYNAMIC_S, tmp_path / "dynamic.nc")
    print(f"\ncylinder buoy, warm kernel cache: peak resident memory with quasi-static chains "
          f"{short:.1f} MB for {SHORT_S:g} s, {long:.1f} MB for {LONG_S:g} s "
          f"(+{long - short:.1f} MB; tolerance {GROWTH_TOLERANCE_MB:g} MB); with dynamic "
          f"chains {dynamic:.1f} MB for {DYNAMIC_S:g} s; limit {PEAK_LIMIT_MB:g} MB")
    assert max(short, long, dynamic) <= PEAK_LIMIT_MB
    assert long - short < GROWTH_TOLERANCE_MB


#: Every shipped coupled case, and the duration a short run needs (a JONSWAP sea needs a
#: frequency step inside its band, the LC43 wind a cut-off above 2 / duration) [s].
SHIPPED_COUPLED = {"cylinder_buoy/buoy_regular_T1.00.toml": 2.0,
                   "cylinder_buoy/buoy_regular_T1.20.toml": 2.0,
                   "cylinder_buoy/buoy_regular_T1.40.toml": 2.0,
                   "deepcwind/deepcwind_free_decay.toml": 2.0,
                   "deepcwind/deepcwind_free_decay_wamit.toml": 2.0,
                   "deepcwind/deepcwind_lc34.toml": 30.0,
                   "deepcwind/deepcwind_lc43.toml": 30.0}
#: The shipped databases without a state-space realisation (convolution only).
CONVOLUTION_ONLY = {"deepcwind/deepcwind_free_decay_wamit.toml"}


@pytest.mark.parametrize("radiation", ["convolution", "state-space"])
@pytest.mark.parametrize("name", sorted(SHIPPED_COUPLED))
def test_every_shipped_coupled_case_peaks_under_the_limit(tmp_path, name, radiation):
    # kernels cached by a first run; the peak does not grow with the duration (test above)
    if radiation == "state-space" and name in CONVOLUTION_ONLY:
        pytest.skip("its database holds no state-space realisation")
    case = CASES / name
    settings = ["--set", f"simulation.duration={SHIPPED_COUPLED[name]}",
                "--set", f'floater.radiation="{radiation}"']
    _peak_rss_of(case, tmp_path / "warm.nc", settings)
    peak = _peak_rss_of(case, tmp_path / "run.nc", settings)
    print(f"\n{name} ({radiation}): peak resident memory {peak:.1f} MB")
    assert peak <= PEAK_LIMIT_MB


def _peak_rss_of(case: Path, output: Path, settings: list[str]) -> float:
    """Peak resident set size [MB] of ``floatmoor run`` of ``case`` with ``settings``."""
    command = [sys.executable, "-m", "floatmoor", "run", str(case), "-o", str(output),
               "--quiet", *settings]
    with open(output.with_suffix(".log"), "wb") as log:
        child = subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT)
        _, status, usage = os.wait4(child.pid, 0)
    assert os.waitstatus_to_exitcode(status) == 0, output.with_suffix(".log").read_text()
    return usage.ru_maxrss / (2 ** 20 if sys.platform == "darwin" else 2 ** 10)
