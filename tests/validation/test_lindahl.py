"""Validation against the Lindahl (1985) chain experiment, r = 0.20 m (cases.md case A).

The upper end of a 33 m chain moves on a circle of radius 0.2 m with period 1.25 s (the chain
goes slack and snaps) and 3.5 s (smooth response). With the dynamic line model we check

- the mean of the per-cycle maxima of the upper-end tension after the ramp against the
  published measured mean maxima, 70.3 N and 50.1 N;
- the simulated mean cycle, shifted onto the phase-averaged measured cycle (whose time origin
  is arbitrary), against that cycle: RMS difference relative to the measured peak.

Run with ``python -m pytest -m slow tests/validation -s``; set ``FLOATMOOR_PLOT_DIR`` to keep
the comparison plot (otherwise it goes to a temporary folder).
"""

from __future__ import annotations

import functools
import os
from pathlib import Path
from typing import Any

import pytest

from tests.validation.lindahl import (PUBLISHED_MEAN_MAX_N, describe, plot_lindahl_comparison,
                                      run_lindahl)

pytestmark = pytest.mark.slow

#: The line model validated here.
MODEL = "dynamic"
#: Extra ``--set`` overrides of the dynamic model's numerics; the case file's defaults if empty.
EXTRA_OVERRIDES: tuple[str, ...] = ()
#: Circle radius [m] and periods [s] with published maxima and measured cycles.
RADIUS = 0.2
PERIODS = (1.25, 3.5)

#: Relative tolerance on the mean per-cycle maximum against the published measured mean
#: maximum. 4 % is the acceptance bar set by the dynamic-model issue; it lies inside the
#: +/- 5 % measurement error of the maxima (cases.md case A; chain-experiment paper).
MEAN_MAX_RTOL = 0.04
#: Largest RMS difference between the aligned simulated mean cycle and the measured mean
#: cycle, relative to the measured cycle's peak (71.02 N at T = 1.25 s, 51.41 N at 3.5 s): 8 %.
ALIGNED_RMS_REL_TOL = 0.08


@functools.cache
def _result(period: float) -> dict[str, Any]:
    """One run per period, shared by the tests of this module."""
    return run_lindahl(period, radius=RADIUS, model=MODEL, extra_overrides=EXTRA_OVERRIDES)


@pytest.mark.parametrize("period", PERIODS)
def test_mean_cycle_maximum(period):
    result = _result(period)
    print("\n" + describe(result))
    published = PUBLISHED_MEAN_MAX_N[(RADIUS, period)]
    assert result["cycle_maxima_count"] >= 6
    assert result["mean_cycle_max"] == pytest.approx(published, rel=MEAN_MAX_RTOL), (
        f"mean cycle maximum {result['mean_cycle_max']:.2f} N vs measured {published} N "
        f"(tolerance {100 * MEAN_MAX_RTOL:g} %)")


@pytest.mark.parametrize("period", PERIODS)
def test_aligned_mean_cycle(period):
    result = _result(period)
    alignment = result["alignment"]
    print("\n" + describe(result))
    assert alignment is not None, "no measured cycle for this case"
    assert alignment.rms_relative_to_peak < ALIGNED_RMS_REL_TOL, (
        f"aligned RMS difference {alignment.rms_difference:.2f} N = "
        f"{100 * alignment.rms_relative_to_peak:.1f} % of the measured peak "
        f"{alignment.reference_peak:.2f} N (tolerance {100 * ALIGNED_RMS_REL_TOL:g} %)")


def test_comparison_plot(tmp_path):
    results = [_result(period) for period in PERIODS]
    folder = Path(os.environ.get("FLOATMOOR_PLOT_DIR") or tmp_path)
    path = plot_lindahl_comparison(results, folder / f"lindahl_r{RADIUS:.2f}_{MODEL}.png")
    print(f"\ncomparison plot: {path}")
    for result in results:
        print(describe(result))
    assert path.is_file() and path.stat().st_size > 10_000
