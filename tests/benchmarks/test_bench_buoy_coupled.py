"""Benchmark: the moored buoy at T = 1.2 s, dynamic lines at the accuracy default,
against the explicit 10 x p5 run of today.

``cases/cylinder_buoy/buoy_regular_T1.20.toml`` with its lines' reference numerics (10 x p5,
explicit, which the file names) set to "auto" (tests/conftest.py ACCURACY_DEFAULT), 60 s of
regular waves after a 20 s ramp, in this process after its kernels are compiled in a
subprocess. Compared with ``buoy_T1.20_dynamic_10xp5.json`` (today's
code, 10 elements of order 5): every line's fairlead-tension STD and maximum after the ramp, and
the heave and pitch STD.

Targets: at most 0.3 wall s per simulated second (asserted on the whole run: case
loading, equilibrium, line settling, loop, dataset; the time loop alone is reported too); the
line figures within 2 %, heave and pitch STD within 1 % of today's. The maxima after the ramp
are single snap events (README of the references: lines 1 and 2, mirror images, peak at 5.37 N
and 6.93 N in the same run).

Quick mode (``FLOATMOOR_BENCH_QUICK=1``): 24 s (4 s after the ramp); the accuracy figures are
printed, not asserted.

Run: ``python -m pytest -m benchmark tests/benchmarks/test_bench_buoy_coupled.py -s``
(about 7 minutes with today's numerics, 18 s at the target).
"""

from __future__ import annotations

import pytest

from tests.benchmarks.dynamic_harness import (QUICK, accuracy_table, after_ramp, compile_kernels,
                                              line_tension_figures, load_reference, pick,
                                              run_coupled_case, speed_table)
from tests.conftest import ACCURACY_DEFAULT, CASES

pytestmark = pytest.mark.benchmark

CASE = CASES / "cylinder_buoy" / "buoy_regular_T1.20.toml"
REFERENCE = "buoy_T1.20_dynamic_10xp5.json"
#: "at most 0.3 wall s per simulated second" (the target).
WALL_PER_SIMULATED_MAX = 0.3
#: "every line's fairlead-tension STD and maximum after the ramp within 2 %" (the target).
LINE_RTOL = 0.02
#: "heave and pitch STD within 1 %" (the target).
MOTION_RTOL = 0.01
QUICK_DURATION = 24.0  # s


def test_buoy_coupled_as_shipped():
    # the accuracy default: the file names its reference numerics (10 x p5, explicit), the
    # run this is compared with
    overrides = [*ACCURACY_DEFAULT, *pick([], [f"simulation.duration={QUICK_DURATION}"])]
    compile_kernels(CASE, overrides)
    case, ds, timing = run_coupled_case(CASE, overrides)
    ref = load_reference(REFERENCE)
    start = case.waves.ramp_duration
    figures = line_tension_figures(ds, ref["lines"], start, LINE_RTOL)
    for dof, key, unit in (("Heave", "heave_std_m", "m"), ("Pitch", "pitch_std_rad", "rad")):
        now = after_ramp(ds["time"].values, ds["body_displacement"].sel(dof=dof).values, start)
        figures.append((f"{dof.lower()} STD [{unit}]", now["std"], ref[key], MOTION_RTOL))
    text, failures = accuracy_table(figures, check=not QUICK)
    print(f"\n{case.title}, dynamic lines at the accuracy default: {case.lines[0].dynamic}")
    print(f"after the ramp (t >= {start:g} s) against today's 10 x p5 run"
          + (" (quick: other window, not asserted)" if QUICK else ""))
    print(text)
    print(speed_table(timing, ref))
    print(f"target: whole run <= {WALL_PER_SIMULATED_MAX} wall s per simulated s")
    if not timing.whole_per_sim <= WALL_PER_SIMULATED_MAX:
        failures.append(f"whole run {timing.whole_per_sim:.3f} wall s per simulated s "
                        f"(target <= {WALL_PER_SIMULATED_MAX}; time loop "
                        f"{timing.loop_per_sim:.3f})")
    assert not failures, "\n".join(failures)
