"""The run-time validity monitor: a floater's rotations and heave, a quasi-dynamic line's
dimensionless acceleration; one warning per condition per run, recorded in the output file
and printed in the run's summary."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.cli import main
from floatmoor.errors import ModelValidityWarning
from floatmoor.io.netcdf import read_dataset
from floatmoor.simulation.forced import run_forced_motion
from floatmoor.simulation.validity import QD_ALPHA_LIMIT, ROTATION_LIMIT, ValidityMonitor
from tests.conftest import CASES, LINDAHL_CASE

BUOY_CASE = CASES / "cylinder_buoy" / "buoy_regular_T1.20.toml"
#: The Lindahl chain with the quasi-dynamic model at T = 1.25 s (alpha ~1.3, the docs'
#: example of a run outside the model's range), shortened to 1.5 s after the ramp.
QD_LINDAHL = ['lines.chain.model="quasi-dynamic"', "simulation.duration=4.0",
              "simulation.output_interval=0.01"]


def _pitching(n: int, peak_deg: float) -> np.ndarray:
    x = np.zeros((n, 6))
    x[:, 4] = np.radians(peak_deg) * np.sin(np.linspace(0.0, 2.0 * np.pi, n))
    return x


def test_rotation_beyond_the_bound_warns_once_per_run_with_its_largest_value() -> None:
    case = load_case(BUOY_CASE)
    monitor = ValidityMonitor(case, body=True)
    t = np.linspace(0.0, 1.0, 101)
    lines = np.zeros((len(case.lines), t.size, 3))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        monitor.check(t, lines, _pitching(t.size, 10.0))  # within: nothing
        assert caught == [] and monitor.messages() == []
        monitor.check(t + 1.0, lines, _pitching(t.size, 95.0))
        monitor.check(t + 2.0, lines, _pitching(t.size, 120.0))  # again: no second warning
    assert [w.category for w in caught] == [ModelValidityWarning]
    assert str(caught[0].message).startswith("floater pitch: 95 deg from equilibrium at t = ")
    assert "beyond the 15 deg of linear hydrostatics and radiation" in str(caught[0].message)
    (message,) = monitor.messages()
    assert message.startswith("floater pitch: 120 deg") and ROTATION_LIMIT == math.radians(15)


def test_heave_beyond_the_draft_of_a_cylinder_warns() -> None:
    case = load_case(BUOY_CASE)
    draft = case.floater.geometry.draft
    monitor = ValidityMonitor(case, body=True)
    x = np.zeros((3, 6))
    x[1, 2] = 1.5 * draft
    with pytest.warns(ModelValidityWarning, match="floater heave up: .* beyond the draft"):
        monitor.check(np.arange(3.0), np.zeros((len(case.lines), 3, 3)), x)


def test_forced_quasi_dynamic_run_beyond_alpha_warns_once_and_records_it(tmp_path) -> None:
    case = load_case(LINDAHL_CASE, QD_LINDAHL)
    with pytest.warns(ModelValidityWarning) as caught:
        result = run_forced_motion(case, output=tmp_path / "qd.nc")
    ours = [w for w in caught if issubclass(w.category, ModelValidityWarning)]
    assert len(ours) == 1
    text = str(ours[0].message)
    assert text.startswith("line 'chain' (quasi-dynamic): dimensionless acceleration ")
    assert "(alpha = omega^2 Z_m / g)" in text
    assert f"beyond the {QD_ALPHA_LIMIT:g} of the model's verification" in text
    recorded = read_dataset(tmp_path / "qd.nc").attrs["validity_warnings"]
    alpha = float(recorded.split("acceleration ")[1].split()[0])
    assert 1.1 < alpha < 1.6  # the docs' 1.3 (docs/theory/quasi_dynamic.md)
    assert result.dataset.attrs["validity_warnings"] == recorded


def test_quasi_dynamic_run_within_its_range_does_not_warn() -> None:
    case = load_case(LINDAHL_CASE, QD_LINDAHL + ["motion.period=3.5", "motion.ramp_duration=1"])
    with warnings.catch_warnings():
        warnings.simplefilter("error", ModelValidityWarning)
        ds = run_forced_motion(case).dataset
    assert ds.attrs["validity_warnings"] == ""


def test_run_summary_prints_the_validity_warnings(tmp_path, capsys) -> None:
    out = tmp_path / "buoy.nc"
    status = main(["run", str(BUOY_CASE), "-o", str(out), "--quiet",
                   "--set", "simulation.duration=0.4", "--set", "simulation.output_interval=0.02",
                   "--set", 'lines.*.model="quasi-static"', "--set", "initial.pitch_deg=20"])
    captured = capsys.readouterr()
    assert status == 0
    rows = [r for r in captured.out.splitlines() if r.startswith("warning: outside")]
    assert len(rows) == 1 and "floater pitch: 20 deg from equilibrium at t = 0 s" in rows[0]
    assert "floater pitch" not in captured.err  # printed once, in the summary
    assert read_dataset(out).attrs["validity_warnings"] == rows[0].split("validity: ", 1)[1]


def test_a_resumed_run_keeps_the_messages_its_file_holds_and_does_not_warn_again(tmp_path):
    """The interrupted run's file holds its validity messages; the recorder that continues it
    reads them back, and a monitor given them keeps them without warning again."""
    from floatmoor.simulation.recorder import Recorder

    case = load_case(BUOY_CASE)
    times = np.arange(5) * 0.1
    message = "floater pitch: 95 deg from equilibrium at t = 0.1 s, beyond the 15 deg"
    first = Recorder(case, times, tmp_path / "run.nc", body=True, equilibrium=np.zeros(6))
    first.reserve(3)
    first.advance(3)
    first.validity_warnings = [message]
    first.write("running")
    first.close()
    resumed = Recorder(case, times, tmp_path / "run.nc", body=True, equilibrium=np.zeros(6))
    resumed.continue_file(3)
    assert resumed.validity_warnings == [message]
    monitor = ValidityMonitor(case, body=True, carried=resumed.validity_warnings)
    with warnings.catch_warnings():
        warnings.simplefilter("error", ModelValidityWarning)
        monitor.check(times, np.zeros((len(case.lines), 5, 3)), _pitching(5, 40.0))
    assert monitor.messages() == [message]  # the larger, from before the interruption
    monitor.check(times + 1.0, np.zeros((len(case.lines), 5, 3)), _pitching(5, 120.0))
    (kept,) = monitor.messages()
    assert kept.startswith("floater pitch: 120 deg")  # the resumed run's, now the larger
    resumed.close()
