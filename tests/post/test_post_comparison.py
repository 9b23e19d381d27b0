"""Measured-cycle reader, phase averaging and cycle alignment against known answers."""

from __future__ import annotations

import time

import numpy as np
import pytest

from floatmoor.post.comparison import align_cycles, phase_average, read_measured_cycle
from tests.conftest import MEASURED

DATA = MEASURED


def _waveform(t: np.ndarray, period: float) -> np.ndarray:
    """A smooth, asymmetric periodic signal [N] with a single clear best alignment."""
    w = 2.0 * np.pi / period
    return (30.0 + 20.0 * np.sin(w * t) + 8.0 * np.sin(2.0 * w * t + 1.0)
            + 3.0 * np.cos(3.0 * w * t) + 1.5 * np.sin(5.0 * w * t + 0.4))


def _snap(t: np.ndarray, period: float) -> np.ndarray:
    """A narrow periodic pulse on a slack level, like the slack-snap force at T = 1.25 s [N]."""
    phase = (t / period) % 1.0
    return 2.0 + 60.0 * np.exp(-0.5 * ((phase - 0.4) / 0.05) ** 2) + 5.0 * np.sin(2 * np.pi * phase)


# --- read_measured_cycle ---------------------------------------------------------------------

@pytest.mark.parametrize("name, period, peak, peak_time", [
    ("lindahl_measured_cycle_T1.25_r0.20.csv", 1.25, 71.02, 0.459),
    ("lindahl_measured_cycle_T3.50_r0.20.csv", 3.5, 51.41, 0.151),
])
def test_read_measured_cycle_real_files(name, period, peak, peak_time):
    t, mean, std = read_measured_cycle(DATA / name)
    assert t.shape == mean.shape == std.shape == (1000,)
    assert t[0] == 0.0
    np.testing.assert_allclose(np.diff(t), period / 1000, rtol=1e-9)
    assert t[-1] == pytest.approx(period * 999 / 1000, rel=1e-12)  # the t = T row is dropped
    assert np.all(std >= 0.0)
    i = int(np.argmax(mean))
    assert mean[i] == pytest.approx(peak, abs=0.005)
    assert t[i] == pytest.approx(peak_time, abs=0.5e-3 + 0.5 * t[1])  # the validation page rounds to 1 ms


def test_read_measured_cycle_rejects_a_wrong_header(tmp_path):
    path = tmp_path / "bad.csv"
    path.write_text("# comment\ntime,force\n0.0,1.0\n", encoding="utf-8")
    with pytest.raises(ValueError, match="expected the columns"):
        read_measured_cycle(path)


def test_read_measured_cycle_keeps_a_non_repeated_last_row(tmp_path):
    path = tmp_path / "cycle.csv"
    path.write_text("# c\ntime_in_cycle_s,measured_mean_N,measured_std_N\n"
                    "0.0,1.0,0.1\n0.5,2.0,0.2\n1.0,3.0,0.3\n", encoding="utf-8")
    t, mean, std = read_measured_cycle(path)
    np.testing.assert_array_equal(t, [0.0, 0.5, 1.0])
    np.testing.assert_array_equal(mean, [1.0, 2.0, 3.0])


# --- phase_average ---------------------------------------------------------------------------

def test_phase_average_of_a_periodic_signal_returns_it():
    period, dt, start = 1.25, 0.0025, 2.5
    t = np.arange(0.0, 2.5 + 6 * period + 0.3 + dt / 2, dt)  # 6 cycles and a partial one
    y = np.where(t < start, 500.0, _waveform(t, period))  # the transient must be ignored
    phase_time, cycle = phase_average(t, y, period=period, start=start, n_phase=500)
    np.testing.assert_allclose(phase_time, np.arange(500) * period / 500, rtol=0, atol=1e-15)
    # samples coincide with the phase points here: exact up to round-off
    np.testing.assert_allclose(cycle, _waveform(start + phase_time, period), rtol=1e-9)


def test_phase_average_interpolates_and_averages_the_cycles():
    period, dt, start = 3.5, 0.0025, 1.1  # start not on a sample, nor a whole period
    t = np.arange(0.0, 30.0 + dt / 2, dt)
    cycle_index = np.floor((t - start) / period)
    alternating = np.where(cycle_index % 2 == 0, 4.0, -4.0)  # cancels over an even count
    y = _waveform(t, period) + alternating
    n_cycles = int((t[-1] - start) // period)
    assert n_cycles == 8
    phase_time, cycle = phase_average(t, y, period=period, start=start)
    assert phase_time.size == 1000
    # linear interpolation error of the smooth waveform ~ dt^2 / 8 * max|f''| ~ 1e-3 N
    np.testing.assert_allclose(cycle, _waveform(start + phase_time, period), atol=5e-3)


def test_phase_average_needs_a_complete_cycle():
    t = np.linspace(0.0, 2.0, 201)
    with pytest.raises(ValueError, match="no complete cycle"):
        phase_average(t, np.sin(t), period=1.5, start=1.0)


# --- align_cycles ----------------------------------------------------------------------------

#: Noise added to both cycles in the shift-recovery test [N]: 0.1 N on a ~50 N range.
NOISE_N = 0.1
#: Shift error allowed with that noise [reference steps]. The error is noise-limited: over 200
#: random shifts its standard deviation was 0.042 (smooth waveform) and 0.021 (snap) steps,
#: so 0.25 is about 6 standard deviations; without noise the error is below 1e-6 steps.
NOISY_SHIFT_TOL_STEPS = 0.25
#: Shift error allowed without noise [reference steps] (parabolic refinement bias).
CLEAN_SHIFT_TOL_STEPS = 1e-3


def _shift_error(found: float, true: float, period: float) -> float:
    """Circular difference found - true, in (-period / 2, period / 2] [s]."""
    return (found - true + period / 2) % period - period / 2


@pytest.mark.parametrize("signal", [_waveform, _snap])
@pytest.mark.parametrize("true_shift_fraction", [0.2371, 0.99973, 0.00041])
@pytest.mark.parametrize("noise, tolerance", [(NOISE_N, NOISY_SHIFT_TOL_STEPS),
                                              (0.0, CLEAN_SHIFT_TOL_STEPS)])
def test_align_cycles_recovers_the_shift(rng, signal, true_shift_fraction, noise, tolerance):
    period = 1.25
    ref_t = np.arange(1000) * period / 1000
    step = ref_t[1]
    true_shift = true_shift_fraction * period  # near 0 and near T too: wrap-around
    reference = signal(ref_t, period) + noise * rng.standard_normal(ref_t.size)
    # the candidate is the same cycle delayed: c(t) = f(t - shift), on its own coarser grid
    cand_t = np.arange(700) * period / 700
    candidate = signal(cand_t - true_shift, period) + noise * rng.standard_normal(cand_t.size)
    result = align_cycles(ref_t, reference, cand_t, candidate, period=period)
    error = _shift_error(result.shift, true_shift, period)
    print(f"{signal.__name__}, noise {noise} N: shift error {error / step:+.2e} steps")
    assert 0.0 <= result.shift < period
    assert abs(error) < tolerance * step
    assert result.shift_deg == pytest.approx(360.0 * result.shift / period)
    # only the noise is left: rms ~ sqrt(2) * noise (+ interpolation error ~ 1e-2 N)
    assert result.rms_difference == pytest.approx(np.sqrt(2.0) * noise, rel=0.15, abs=0.01)


def test_align_cycles_of_identical_shifted_signals_gives_zero_rms():
    period = 3.5
    ref_t = np.arange(1000) * period / 1000
    true_shift = 1.23456
    reference = _waveform(ref_t, period)
    cand_t = np.arange(4000) * period / 4000
    candidate = _waveform(cand_t - true_shift, period)
    result = align_cycles(ref_t, reference, cand_t, candidate, period=period)
    assert result.shift == pytest.approx(true_shift, abs=1e-3 * ref_t[1])
    np.testing.assert_array_equal(result.time, ref_t)
    np.testing.assert_allclose(result.aligned_candidate, reference, atol=1e-3)
    assert result.rms_difference < 1e-3
    assert result.rms_relative_to_peak == pytest.approx(result.rms_difference / reference.max())
    assert result.reference_peak == reference.max()
    assert result.candidate_peak == candidate.max()


def test_align_cycles_of_a_signal_with_itself_gives_zero_shift():
    period = 1.0
    t = np.arange(1000) * period / 1000
    y = _snap(t, period)
    result = align_cycles(t, y, t, y, period=period)
    assert min(result.shift, period - result.shift) < 1e-6
    assert result.rms_difference < 1e-9


def test_align_cycles_rejects_mismatched_input():
    t = np.linspace(0.0, 0.9, 10)
    with pytest.raises(ValueError, match="same length"):
        align_cycles(t, np.ones(9), t, np.ones(10), period=1.0)
    with pytest.raises(ValueError, match="period"):
        align_cycles(t, np.ones(10), t, np.ones(10), period=0.0)


# --- the validation runner, with the quasi-static model as a fast stand-in ---------------------

def test_run_lindahl_quasi_static_runs_and_plots(tmp_path):
    """The plumbing of tests/simulation/lindahl.py: a short quasi-static run (under 5 s)."""
    from tests.simulation.lindahl import describe, plot_lindahl_comparison, run_lindahl

    start = time.perf_counter()
    result = run_lindahl(1.25, model="quasi-static", n_cycles=2)
    print(describe(result), f"[{time.perf_counter() - start:.2f} s]")
    assert result["model"] == "quasi-static" and result["sense"] == "away-from-anchor-at-top"
    assert result["ramp"] == 2.5 and result["duration"] == 5.0
    assert result["cycle_maxima_count"] == 2
    assert result["published_mean_max"] == 70.3
    # quasi-static tension has no inertia or drag: its maxima are well below the measured ones
    assert 20.0 < result["mean_cycle_max"] < 70.3
    alignment = result["alignment"]
    assert alignment.time.size == 1000
    assert alignment.reference_peak == pytest.approx(71.02, abs=0.005)
    assert 0.0 < alignment.rms_relative_to_peak < 1.0
    assert 0.0 <= result["measured_origin_phase_deg"] < 360.0
    assert result["mean_cycle"].max() == pytest.approx(result["mean_cycle_max"], rel=1e-3)
    path = plot_lindahl_comparison([result], tmp_path / "sub" / "lindahl.png")
    assert path.is_file() and path.stat().st_size > 10_000
