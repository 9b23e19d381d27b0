"""What a campaign, study or uq run says of its cost while it runs (floatmoor.cli.campaign):
how many runs and on what before the first finishes, the estimated wall time to finish once
the first runs give one (said once), and what is left after each run."""

from __future__ import annotations

import math

from floatmoor.cli.campaign import campaign_reporters, duration_text, workers_text


def _lines(capsys) -> list[str]:
    return capsys.readouterr().err.strip().splitlines()


def test_the_count_then_the_estimate_once_then_what_is_left(capsys):
    progress, _ = campaign_reporters(False, workers_text(2, None))
    progress(0, 450, math.nan)
    assert _lines(capsys) == ["floatmoor: 450 runs on 2 local workers; the wall-time estimate "
                              "follows the first finished run"]
    progress(1, 450, math.nan)  # the run that compiled the kernels: no estimate from it
    assert _lines(capsys) == ["floatmoor: 1 / 450 runs done"]
    progress(2, 450, 5.0 * 3600 + 7 * 60)
    assert _lines(capsys) == [
        "floatmoor: estimated wall time to finish the 448 runs left: 5 h 07 min",
        "floatmoor: 2 / 450 runs done, ~5 h 07 min left"]
    progress(3, 450, 90.0)
    assert _lines(capsys) == ["floatmoor: 3 / 450 runs done, ~90 s left"]


def test_a_resumed_study_says_what_it_already_holds(capsys):
    progress, _ = campaign_reporters(False, workers_text(1, "tcp://10.0.0.5:8786"))
    progress(148, 150, math.nan)
    assert _lines(capsys) == [
        "floatmoor: 150 runs (148 already done) on the workers of the Dask scheduler at "
        "tcp://10.0.0.5:8786; the wall-time estimate follows the first finished run",
        "floatmoor: 148 / 150 runs done"]


def test_quiet_says_nothing(capsys):
    progress, compiling = campaign_reporters(True, "1 local worker")
    progress(0, 3, math.nan)
    progress(1, 3, 10.0)
    compiling()
    assert capsys.readouterr().err == ""


def test_durations_read_as_an_engineer_reads_them():
    assert [duration_text(s) for s in (0.4, 119.0, 121.0, 7139.0, 7200.0, 90061.0)] == [
        "0 s", "119 s", "2 min", "119 min", "2 h 00 min", "25 h 01 min"]
    assert workers_text(1, None) == "1 local worker"
