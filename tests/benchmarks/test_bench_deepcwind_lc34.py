"""Benchmark: DeepCwind LC34, 3 hours with dynamic lines, against today's 10 x p5 run
and against the same case with quasi-static lines.

``cases/deepcwind/deepcwind_lc34.toml --set 'lines.*.model="dynamic"'`` at the dynamic line's
defaults (the case has no ``[lines.dynamic]`` table: the accuracy rule's numerics, probed as
the run goes and raised if the probe finds them over the accuracy), in this process after its
kernels are compiled in a subprocess. Compared with ``deepcwind_lc34_dynamic_10xp5.json``
(today's code, 10 elements of order 5): every line's fairlead-tension STD and maximum after
the 60 s ramp. Then the case as it is (quasi-static lines), in the same process through the
same harness, its kernels compiled first too.

Targets: the whole run (case loading, equilibrium, line settling, radiation kernel, loop,
dataset) at most 1.2 times the whole run with quasi-static lines (CPU time of this process:
the machine's other load does not count), and the line figures within 2 %. The earlier 2-minute
target (90 x real time) was replaced by that ratio (its 147 s accepted): it is printed, not
asserted.

Quick mode (``FLOATMOOR_BENCH_QUICK=1``): 300 s; the accuracy figures are printed, not
asserted, and the time target is scaled to the duration.

Run: ``python -m pytest -m benchmark tests/benchmarks/test_bench_deepcwind_lc34.py -s``
(about 5 minutes on an idle machine: the dynamic run and the quasi-static one).
"""

from __future__ import annotations

import time

import pytest

from tests.benchmarks.dynamic_harness import (QUICK, accuracy_table, compile_kernels,
                                              line_tension_figures, load_reference, pick,
                                              run_coupled_case, speed_table)
from tests.conftest import CASES

pytestmark = pytest.mark.benchmark

CASE = CASES / "deepcwind" / "deepcwind_lc34.toml"
REFERENCE = "deepcwind_lc34_dynamic_10xp5.json"
#: The earlier target of the whole run, 2 minutes for 3 hours (90 x real time): printed only.
WALL_MAX_S = 120.0
#: "dynamic lines at most 1.2 times the cost of quasi-static ones" (the target): whole runs.
QS_RATIO_MAX = 1.2
DURATION_S = 10800.0
#: "fairlead tension STD and maximum within 2 % of today's 10 x p5 run" (the target).
LINE_RTOL = 0.02
QUICK_DURATION = 300.0  # s
#: Duration of the kernels' warm-up run [s]: the JONSWAP sea of a shorter run has no wave
#: component in the case's band (its frequency step is 2 pi / duration).
WARM_UP_S = 20.0


def _timed(overrides: list[str]):
    """The case run by the harness, and the CPU time of this process it took [s]."""
    cpu = time.process_time()
    case, ds, timing = run_coupled_case(CASE, overrides)
    return case, ds, timing, time.process_time() - cpu


def test_lc34_three_hours_dynamic_lines():
    duration = pick([], [f"simulation.duration={QUICK_DURATION}"])
    overrides = ['lines.*.model="dynamic"', *duration]
    compile_kernels(CASE, overrides, duration=WARM_UP_S)
    compile_kernels(CASE, duration, duration=WARM_UP_S)
    case, ds, timing, cpu = _timed(overrides)
    _, _, qs_timing, qs_cpu = _timed(duration)
    ref = load_reference(REFERENCE)
    start = case.waves.ramp_duration
    text, failures = accuracy_table(
        line_tension_figures(ds, ref["lines"], start, LINE_RTOL, unit="kN", scale=1e3),
        check=not QUICK)
    print(f"\n{case.title}, dynamic lines at the defaults: {case.lines[0].dynamic}")
    print("line accuracy: " + str(ds.attrs.get("line_accuracy", "-")).replace("\n", "\n  "))
    print(f"after the ramp (t >= {start:g} s) against today's 10 x p5 run of 3 h"
          + (" (quick: other window, not asserted)" if QUICK else ""))
    print(text)
    print(speed_table(timing, ref))
    limit = WALL_MAX_S * timing.simulated_s / DURATION_S
    print(f"earlier target (printed only): whole run <= {limit:.1f} s ({DURATION_S / WALL_MAX_S:g}"
          f" x real time); now {timing.simulated_s / timing.whole_s:.1f} x real time")
    ratio = cpu / qs_cpu
    print(f"quasi-static lines: whole run {qs_timing.whole_s:.1f} s wall, {qs_cpu:.1f} s CPU "
          f"(time loop {qs_timing.loop_s:.1f} s); dynamic: {timing.whole_s:.1f} s wall, "
          f"{cpu:.1f} s CPU (time loop {timing.loop_s:.1f} s)")
    print(f"target: whole run dynamic / quasi-static <= {QS_RATIO_MAX:g}; now {ratio:.2f} "
          f"(CPU), {timing.whole_s / qs_timing.whole_s:.2f} (wall)")
    if not ratio <= QS_RATIO_MAX:
        failures.append(f"whole run dynamic / quasi-static {ratio:.2f} in CPU time ({cpu:.1f} "
                        f"s / {qs_cpu:.1f} s; target <= {QS_RATIO_MAX:g})")
    assert not failures, "\n".join(failures)
