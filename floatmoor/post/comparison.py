"""Comparison of a simulated periodic response with a measured one over a single cycle.

Measured cycles (for example the phase-averaged upper-end force of the Lindahl chain
experiment) come as one cycle sampled on ``0 <= t < T`` with an arbitrary time origin. The
simulated record is reduced to the same form by :func:`phase_average`, and
:func:`align_cycles` finds the circular time shift that best lays the simulated cycle onto the
measured one (least squares over all shifts) before the two are compared.

Time convention of the alignment: the aligned candidate is ``c((t + shift) mod T)``, i.e. the
reference's ``t = 0`` falls at candidate time ``shift``. When the candidate cycle comes from
:func:`phase_average` with ``start`` a whole number of periods, its time is the simulation
time modulo T, so ``2 pi shift / T`` (plus the motion's phase) is the motion phase at which the
reference's time origin lies.

Per-cycle maxima and channel statistics are in :mod:`floatmoor.post.statistics`.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["MeasuredCycle", "AlignmentResult", "read_measured_cycle", "phase_average",
           "align_cycles"]

#: Column names of a measured-cycle CSV file, in order.
MEASURED_COLUMNS = ("time_in_cycle_s", "measured_mean_N", "measured_std_N")

#: Relative slack on times when counting complete cycles, to absorb round-off in t = k * dt [-].
_TIME_EPS = 1e-9

#: Smallest number of points of the common phase grid used by :func:`align_cycles`.
_MIN_ALIGNMENT_GRID = 4096


class MeasuredCycle(NamedTuple):
    """One measured cycle: unpacks as ``time_in_cycle, mean, std``."""

    time_in_cycle: NDArray[np.float64]  #: [s], equally spaced in [0, T)
    mean: NDArray[np.float64]  #: phase mean [N]
    std: NDArray[np.float64]  #: cycle-to-cycle standard deviation [N]


@dataclass(frozen=True)
class AlignmentResult:
    """Best circular alignment of a candidate cycle onto a reference cycle.

    All values are in the unit of the signals (N for forces) unless stated.
    """

    shift: float  #: candidate time at the reference's t = 0, in [0, period) [s]
    period: float  #: cycle length T [s]
    time: NDArray[np.float64]  #: the reference's time grid [s]
    aligned_candidate: NDArray[np.float64]  #: candidate at ``(time + shift) mod period``
    rms_difference: float  #: root mean square of aligned candidate - reference
    rms_relative_to_peak: float  #: rms_difference / reference_peak [-] (NaN if the peak <= 0)
    reference_peak: float  #: max of the reference
    candidate_peak: float  #: max of the candidate samples

    @property
    def shift_deg(self) -> float:
        """The shift as a phase angle, 360 shift / period, in [0, 360) [deg]."""
        return float(360.0 * self.shift / self.period) % 360.0


def read_measured_cycle(path: str | Path) -> MeasuredCycle:
    """Read a phase-averaged measured cycle from its CSV file.

    The file has ``#`` comment lines, then a header ``time_in_cycle_s, measured_mean_N,
    measured_std_N`` and one row per phase point; the last row (t = T) repeats the first and is
    dropped.

    Parameters
    ----------
    path
        The CSV file.

    Returns
    -------
    MeasuredCycle
        ``time_in_cycle`` [s] in [0, T), ``mean`` [N], ``std`` [N].

    Raises
    ------
    ValueError
        When the header is not the expected one, or the times are not increasing.
    """
    path = Path(path)
    lines = [line.strip() for line in path.read_text(encoding="utf-8").splitlines()]
    lines = [line for line in lines if line and not line.startswith("#")]
    if not lines:
        raise ValueError(f"{path}: no header and no data")
    header = tuple(name.strip() for name in lines[0].split(","))
    if header != MEASURED_COLUMNS:
        raise ValueError(f"{path}: expected the columns {', '.join(MEASURED_COLUMNS)}, "
                         f"found {lines[0]!r}")
    data = np.array([[float(x) for x in line.split(",")] for line in lines[1:]], dtype=float)
    if data.ndim != 2 or data.shape[0] < 3 or data.shape[1] != len(MEASURED_COLUMNS):
        raise ValueError(f"{path}: expected at least 3 rows of {len(MEASURED_COLUMNS)} numbers")
    if not np.all(np.isfinite(data)) or not np.all(np.diff(data[:, 0]) > 0.0):
        raise ValueError(f"{path}: the times must be finite and increasing")
    if np.allclose(data[-1, 1:], data[0, 1:], rtol=1e-12, atol=0.0):
        data = data[:-1]  # periodic closure: t = T repeats t = 0
    return MeasuredCycle(data[:, 0].copy(), data[:, 1].copy(), data[:, 2].copy())


def phase_average(time: ArrayLike, values: ArrayLike, *, period: float, start: float,
                  n_phase: int = 1000) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Mean cycle of a periodic signal over the complete cycles from ``start`` on.

    Each cycle ``[start + k T, start + (k + 1) T)`` that the record covers completely is
    linearly interpolated at ``n_phase`` equally spaced times ``start + k T + j T / n_phase``,
    and the cycles are averaged.

    Parameters
    ----------
    time
        Sample times [s], increasing.
    values
        Samples.
    period
        Cycle length T [s].
    start
        Start of the first cycle [s]; phase time 0 corresponds to it.
    n_phase
        Number of phase points per cycle.

    Returns
    -------
    phase_time : ndarray
        ``j T / n_phase`` for j = 0 .. n_phase - 1 [s], time since the start of the cycle.
    mean_cycle : ndarray
        The mean of the cycles at those phase times.

    Raises
    ------
    ValueError
        Without a complete cycle after ``start``, or with bad arguments.
    """
    time = np.asarray(time, dtype=float)
    values = np.asarray(values, dtype=float)
    if time.ndim != 1 or time.shape != values.shape:
        raise ValueError(f"time and values must be 1-D of the same length, found shapes "
                         f"{time.shape} and {values.shape}")
    if not period > 0.0:
        raise ValueError(f"period must be > 0, found {period}")
    if n_phase < 2:
        raise ValueError(f"n_phase must be >= 2, found {n_phase}")
    eps = _TIME_EPS * max(period, 1.0)
    n_cycles = int(np.floor((time[-1] - start) / period + eps)) if time.size else 0
    if n_cycles < 1 or time[0] > start + eps:
        raise ValueError(f"no complete cycle of {period:g} s between t = {start:g} s and the "
                         f"end of the record")
    phase_time = np.arange(n_phase) * (period / n_phase)
    sample_times = start + np.arange(n_cycles)[:, None] * period + phase_time[None, :]
    # round-off may put the last cycle's samples a hair past the record's end: clip them
    sample_times = np.minimum(sample_times, time[-1])
    cycles = np.interp(sample_times.ravel(), time, values).reshape(n_cycles, n_phase)
    return phase_time, cycles.mean(axis=0)


def align_cycles(reference_time: ArrayLike, reference: ArrayLike, candidate_time: ArrayLike,
                 candidate: ArrayLike, *, period: float,
                 n_grid: int | None = None) -> AlignmentResult:
    """Best circular time shift of a candidate cycle onto a reference cycle.

    Both cycles are interpolated (linearly, periodically) onto a common fine grid of
    ``n_grid`` phase points. The least-squares misfit ``sum_t (c(t + s) - r(t))^2`` of a
    circular shift ``s`` is ``sum r^2 + sum c^2 - 2 sum_t r(t) c(t + s)``, so the best shift
    maximises the circular cross-correlation, computed for all shifts at once by FFT; the peak
    is refined below the grid step by a parabola through it and its two neighbours. The
    candidate is then evaluated at ``(reference_time + shift) mod period`` from its own samples.

    Parameters
    ----------
    reference_time
        Times of the reference cycle [s], within one period (taken modulo ``period``).
    reference
        The reference cycle (e.g. measured).
    candidate_time
        Times of the candidate cycle [s], within one period (taken modulo ``period``).
    candidate
        The candidate cycle (e.g. simulated).
    period
        Cycle length T [s].
    n_grid
        Points of the common phase grid; default: the next power of two at or above
        ``max(4096, 4 * max(len(reference), len(candidate)))``.

    Returns
    -------
    AlignmentResult
        The shift in [0, period) [s], the aligned candidate on the reference grid and the
        RMS difference (also relative to the reference's peak).

    Raises
    ------
    ValueError
        With mismatched, non-finite or too short inputs, or a period <= 0.
    """
    ref_t, ref = _cycle_arrays(reference_time, reference, "reference")
    cand_t, cand = _cycle_arrays(candidate_time, candidate, "candidate")
    if not period > 0.0:
        raise ValueError(f"period must be > 0, found {period}")
    if n_grid is None:
        n_grid = 1 << int(np.ceil(np.log2(max(_MIN_ALIGNMENT_GRID, 4 * max(ref.size, cand.size)))))
    if n_grid < 3:
        raise ValueError(f"n_grid must be >= 3, found {n_grid}")
    step = period / n_grid
    grid = np.arange(n_grid) * step
    r = np.interp(grid, ref_t, ref, period=period)
    c = np.interp(grid, cand_t, cand, period=period)
    r -= r.mean()  # constant offsets do not change the argmax; they only cost precision
    c -= c.mean()
    # correlation[k] = sum_j r[j] c[j + k] (indices modulo n_grid)
    correlation = np.fft.irfft(np.conj(np.fft.rfft(r)) * np.fft.rfft(c), n=n_grid)
    k = int(np.argmax(correlation))
    y0, y1, y2 = correlation[k - 1], correlation[k], correlation[(k + 1) % n_grid]
    curvature = y0 - 2.0 * y1 + y2
    delta = 0.5 * (y0 - y2) / curvature if curvature < 0.0 else 0.0
    shift = float(((k + float(np.clip(delta, -0.5, 0.5))) * step) % period)
    if shift >= period:  # (k + delta) * step % period can round up to period
        shift = 0.0

    aligned = np.interp((ref_t + shift) % period, cand_t, cand, period=period)
    rms = float(np.sqrt(np.mean((aligned - ref) ** 2)))
    reference_peak = float(ref.max())
    return AlignmentResult(
        shift=shift,
        period=float(period),
        time=ref_t,
        aligned_candidate=aligned,
        rms_difference=rms,
        rms_relative_to_peak=rms / reference_peak if reference_peak > 0.0 else float("nan"),
        reference_peak=reference_peak,
        candidate_peak=float(cand.max()),
    )


def _cycle_arrays(time: ArrayLike, values: ArrayLike,
                  name: str) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Validated float copies of one cycle's times and values."""
    t = np.array(time, dtype=float)
    v = np.array(values, dtype=float)
    if t.ndim != 1 or t.shape != v.shape or t.size < 3:
        raise ValueError(f"{name}: time and values must be 1-D of the same length >= 3, found "
                         f"shapes {t.shape} and {v.shape}")
    if not (np.all(np.isfinite(t)) and np.all(np.isfinite(v))):
        raise ValueError(f"{name}: times and values must be finite")
    return t, v
