"""The accuracy defaults (``elements``, ``order`` = "auto" at ``accuracy`` 1 %, with the
a-posteriori check) on full-scale lines beyond the rule's three calibration references
(docs/validation/dynamic_line.md#the-accuracy-defaults-on-full-scale-lines): the three cases of
tests/simulation/fullscale_cases.py, every line's fairlead-tension STD and mean per-cycle
maximum within 1 % of a converged run of the same code; and a motion table ending before
the probe's window is probed over its own span, not past its end.

The converged figures below were computed with this code (floatmoor 0.1.0, branch fullscale):
16, 24 and 32 elements of order 5 with explicit time steps, the next refinement moving both
statistics by < 0.2 % (24 -> 32 x p5: <= 0.07 %), the 32 x p5 figure stored; beside them
MoorDyn-C 2.7 (the ``moordyn`` package) with the deck's segments doubled until < 0.2 %, its
internal damping held at the deck's value in N s (BA = -1 is a damping ratio per segment,
which refining would change), dtM = 0.5 l / c over the segment's damping ratio when above 1.

Run: ``python -m pytest -m slow tests/simulation/test_fullscale_accuracy.py -s`` (about 2 min
of CPU: the check's probes, then 60 s of OC4, 3 x 600 s of DeepCwind lines, 80 s of N20).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.simulation import line_accuracy as la
from floatmoor.simulation.forced import run_forced_motion
from tests.conftest import CASES
from tests.simulation.fullscale_cases import (AUTO, WINDOW_START, deepcwind_line_case,
                                              judged_statistics, n20_case, oc4_case)


pytestmark = pytest.mark.validation

#: The accuracy asked (the default): the defaults' statistics within this of converged.
ACCURACY = 0.01

#: OC4 r-test, (STD, mean per-cycle maximum) of each fairlead tension [N] over the whole 60 s
#: (the lines start in the motion's first pose), cycles of 2 pi / omega = 14.68 s (omega the
#: table's mean zero-crossing frequency, 0.428 rad/s; 4 cycles). floatmoor 32 x p5 explicit;
#: MoorDyn-C 160 segments (dtM 0.127 ms): line1 23481.7 / 998329.8, line2 87233.4 /
#: 1536563.1, line3 24445.7 / 999398.5 (-0.04 % to +0.006 % from floatmoor's).
OC4_CONVERGED = {"line1": (23482.5, 998342.2), "line2": (87230.0, 1536502.3),
                 "line3": (24454.9, 999337.1)}
#: The same with the motion table cut at 40 s (its omega 0.504 rad/s, 3 cycles of 12.47 s):
#: floatmoor 32 x p5 explicit. The defaults (19, 8, 14 x p3) are -0.98, +0.57, -0.11 % off in
#: STD: line 1's 19 x p3 is -0.85 % with explicit steps, the rest the implicit steps' (which
#: the check does not estimate), and its estimate 0.93 %: the thinnest margin of these cases.
OC4_CUT_CONVERGED = {"line1": (14288.6, 984718.8), "line2": (50822.1, 1586675.2),
                     "line3": (14370.9, 985646.7)}
#: DeepCwind LC34 lines, each under its recorded path, from 60 s to 600 s, cycles of 2 pi /
#: omega of its path (13.598 s for lines 1 and 3, 13.600 s for line 2; 39 cycles). floatmoor
#: 32 x p5 explicit (line 3 mirrors line 1: same figures); MoorDyn-C 160 segments RK4, dtM
#: 0.35 ms, line1 100195.1 / 1245674.6 (-0.03 %, -0.003 %), line 2 (cycles of 13.598 s) in
#: the validation page.
DEEPCWIND_CONVERGED = {"line1": (100228.3, 1245709.5), "line2": (306657.8, 1508912.1),
                       "line3": (100228.3, 1245709.5)}
#: md_Node_Check_N20's chain, its top surged 5 m at 10 s, after the 20 s ramp (6 cycles).
#: floatmoor 32 x p5 explicit; MoorDyn-C in the validation page.
N20_CONVERGED = {"line1": (1119511.0, 5442654.2)}


def _assert_within(case, dataset, start, converged):
    stats = judged_statistics(case, dataset, start)
    for line, (std, maxima) in converged.items():
        got_std, got_max = stats[line]
        print(f"\n{line}: STD {got_std:.1f} N ({got_std / std - 1:+.3%}), mean cycle maximum "
              f"{got_max:.1f} N ({got_max / maxima - 1:+.3%})")
        assert abs(got_std / std - 1.0) < ACCURACY, (line, "std", got_std, std)
        assert abs(got_max / maxima - 1.0) < ACCURACY, (line, "maxima", got_max, maxima)


def _run_checked(path, lines):
    case = load_case(path, AUTO)
    result = run_forced_motion(case)
    assert [a.line for a in result.line_accuracy] == lines
    for checked in result.line_accuracy:
        print(f"\n{la.describe(checked)}")
        assert checked.estimated_error <= ACCURACY
    return case, result


@pytest.mark.slow
def test_oc4_rtest_defaults_meet_the_accuracy(tmp_path):
    # the rule's 8 x p3 put the STD of lines 1 and 3 5.5-5.6 % off; the check raises them to
    # 15 elements (line 2 stays at 8: +0.5 %)
    case, result = _run_checked(oc4_case(tmp_path), ["line1", "line2", "line3"])
    assert [a.refinements >= 1 for a in result.line_accuracy] == [True, False, True]
    _assert_within(case, result.dataset, WINDOW_START["oc4"], OC4_CONVERGED)


@pytest.mark.slow
def test_oc4_rtest_cut_at_40_s_defaults_meet_the_accuracy(tmp_path):
    # its table (omega 0.504 rad/s: probe of 3 x 12.47 s = 37.4 s) fits the probe; judged
    # over the last two cycles only (before the start-up was judged), the check kept line 3 at
    # 19 x p3, 1.20 % low in STD; judged from the start, 14 x p3 (-0.11 %)
    case, result = _run_checked(oc4_case(tmp_path, end=40.0), ["line1", "line2", "line3"])
    _assert_within(case, result.dataset, WINDOW_START["oc4"], OC4_CUT_CONVERGED)


@pytest.mark.slow
@pytest.mark.parametrize("line", ["line1", "line2", "line3"])
def test_deepcwind_lines_defaults_meet_the_accuracy(tmp_path, line):
    case, result = _run_checked(deepcwind_line_case(tmp_path, line), [line])
    _assert_within(case, result.dataset, WINDOW_START["deepcwind"],
                   {line: DEEPCWIND_CONVERGED[line]})


@pytest.mark.slow
def test_n20_chain_defaults_meet_the_accuracy(tmp_path):
    case, result = _run_checked(n20_case(tmp_path), ["line1"])
    _assert_within(case, result.dataset, WINDOW_START["n20"], N20_CONVERGED)


# -- a line the check cannot probe says so ------------------------------------------------------

S3 = CASES / "qd_verification" / "s3_d1.toml"
#: S3's motion period [s] (s3_d1.toml): the tables below are its x-harmonic, sampled.
S3_PERIOD = 0.750601


def _s3_table_case(tmp_path, table_end: float):
    """S3 (dynamic, numerics from its accuracy) under its harmonic surge given as a table
    ending at ``table_end`` [s], no ramp, a 0.2 s run."""
    rows = [(k * 0.01, 0.018 * math.sin(2.0 * math.pi * k * 0.01 / S3_PERIOD))
            for k in range(int(round(table_end / 0.01)) + 1)]
    (tmp_path / "surge.csv").write_text(
        "time,x,y,z\n" + "".join(f"{t:.2f},{x:.9g},0,0\n" for t, x in rows))
    text = "\n".join('title = "S3 under a table"' if row.startswith("title = ") else row
                     for row in S3.read_text().split("[motion]")[0].splitlines())
    case = tmp_path / "s3_table.toml"
    case.write_text(text + '[motion]\nkind = "table"\nfile = "surge.csv"\n'
                    'ramp_duration = 0.0\n\n[simulation]\nduration = 0.2\n'
                    'output_interval = 0.01\n')
    return load_case(case, ['lines.*.model="dynamic"', *AUTO,
                            'lines.*.dynamic.time_integration="explicit"'])


def _recording_estimate(calls):
    """An ``estimate_error`` recording the probe's period and the times it asks the path
    at, estimating 0.2 % and 0.1 %."""
    def estimate(line, environment, seabed, path_state, ramp):
        period = 2.0 * math.pi / line.dynamic.motion_frequency
        time = np.arange(int(math.ceil(ramp / period * la.SAMPLES_PER_CYCLE))
                         + la.PROBE_CYCLES * la.SAMPLES_PER_CYCLE + 1) * (
            period / la.SAMPLES_PER_CYCLE)  # the probe's samples (estimate_error)
        calls.append((period, float(time[-1])))
        return 0.002, 0.001
    return estimate


def test_a_table_ending_before_the_probe_is_probed_over_its_own_span(tmp_path, monkeypatch):
    # S3's table at 0.75 s asks for a probe of 3 cycles, 2.25 s; a 1.5 s table would leave
    # the last 0.75 s of it on a fairlead held at its last row: the cycles are shortened to
    # 0.5 s, so the probe ends with the table
    calls = []
    monkeypatch.setattr(la, "estimate_error", _recording_estimate(calls))
    case = _s3_table_case(tmp_path, 1.5)
    omega = case.lines[0].dynamic.motion_frequency
    assert la.probe_end(0.0, omega) > 2.0
    result = run_forced_motion(case)
    ((period, end),) = calls
    assert period == pytest.approx(0.5) and end == pytest.approx(1.5)
    (record,) = result.line_accuracy
    assert record.std_error == 0.002 and record.refinements == 0


def test_a_table_covering_the_probe_is_probed_at_its_frequency(tmp_path, monkeypatch):
    calls = []
    monkeypatch.setattr(la, "estimate_error", _recording_estimate(calls))
    case = _s3_table_case(tmp_path, 2.4)
    run_forced_motion(case)
    ((period, end),) = calls
    assert period == pytest.approx(2.0 * math.pi / case.lines[0].dynamic.motion_frequency)
    assert end < 2.4

