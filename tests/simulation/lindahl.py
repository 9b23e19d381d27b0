"""Runner and comparison plot of the Lindahl chain validation (docs/cases/lindahl.md).

The upper end of the 33 m chain moves on a circle of radius r with period T. We run the case
for a two-period ramp and then ``n_cycles`` full cycles, and compare with the measured data of
``tests/data/lindahl`` (copies of the reference's ``data``) (phase-averaged upper-end force over one cycle, r = 0.20 m only):

- the mean of the per-cycle maxima after the ramp, against the published measured mean maxima
  (70.3 N at T = 1.25 s and 50.1 N at T = 3.5 s);
- the simulated mean cycle, circularly shifted onto the measured one (the measured time origin
  is arbitrary), and the RMS difference between them.

Used by ``tests/simulation/test_lindahl.py``; also usable by hand::

    from tests.simulation.lindahl import run_lindahl, plot_lindahl_comparison
    results = [run_lindahl(1.25, model="quasi-static"), run_lindahl(3.5, model="quasi-static")]
    plot_lindahl_comparison(results, "lindahl.png")
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from floatmoor.case.load import load_case
from floatmoor.post.comparison import align_cycles, phase_average, read_measured_cycle
from floatmoor.post.statistics import channel_statistics
from floatmoor.simulation.forced import run_forced_motion
from tests.conftest import LINDAHL_CASE, MEASURED

__all__ = ["PUBLISHED_MEAN_MAX_N", "MEASURED_PEAK_N", "measured_cycle_path", "run_lindahl",
           "describe", "plot_lindahl_comparison"]

#: Published measured mean maximum upper-end tension [N], by (radius [m], period [s])
#: (chain-experiment paper Tables 7-8; docs/cases/lindahl.md). Measurement error about +/- 5 %.
PUBLISHED_MEAN_MAX_N: dict[tuple[float, float], float] = {(0.20, 1.25): 70.3, (0.20, 3.5): 50.1}

#: Peak of the phase-averaged measured cycle [N] (data/README.md), by (radius, period).
MEASURED_PEAK_N: dict[tuple[float, float], float] = {(0.20, 1.25): 71.02, (0.20, 3.5): 51.41}

#: Ramp length [periods] and default number of full cycles after it.
RAMP_PERIODS = 2
DEFAULT_CYCLES = 6

#: Phase points per cycle of the simulated mean cycle (the measured cycles have 1000).
N_PHASE = 1000


def _key(radius: float, period: float) -> tuple[float, float]:
    return round(radius, 3), round(period, 3)


def measured_cycle_path(period: float, radius: float = 0.2) -> Path:
    """The measured-cycle CSV for (r, T); it may not exist (only r = 0.20 m is provided)."""
    return MEASURED / f"lindahl_measured_cycle_T{period:.2f}_r{radius:.2f}.csv"


def run_lindahl(period: float, radius: float = 0.2, sense: str | None = None,
                model: str = "dynamic", extra_overrides: Sequence[str] = (), *,
                n_cycles: int = DEFAULT_CYCLES) -> dict[str, Any]:
    """Run the Lindahl case at (r, T) and compare it with the measurement.

    Parameters
    ----------
    period
        Motion period T [s].
    radius
        Circle radius r [m].
    sense
        ``"away-from-anchor-at-top"`` or ``"toward-anchor-at-top"``; None keeps the case file's.
    model
        Line model of the chain (``lines.chain.model``).
    extra_overrides
        More ``--set``-style overrides, applied after these (so they win).
    n_cycles
        Full cycles simulated after the ramp of two periods (>= 1; validation uses >= 6).

    Returns
    -------
    dict
        ``period``, ``radius``, ``sense``, ``model``, ``phase_deg`` (motion phase at t = 0),
        ``ramp``, ``duration`` [s]; ``time``, ``tension`` (the fairlead tension history [N]);
        ``statistics`` (:func:`channel_statistics` after the ramp), ``mean_cycle_max`` [N],
        ``cycle_maxima_count``; ``phase_time``, ``mean_cycle`` (simulated mean cycle, phase
        time 0 = end of the ramp = motion phase ``phase_deg``); ``published_mean_max``
        (None if not published); ``measured`` (a :class:`MeasuredCycle` or None),
        ``alignment`` (:class:`AlignmentResult` or None) and ``measured_origin_phase_deg``
        (the motion phase at the measured t = 0 after alignment, or None); ``wall_time_s``.
    """
    if n_cycles < 1:
        raise ValueError(f"n_cycles must be >= 1, found {n_cycles}")
    ramp = RAMP_PERIODS * period
    duration = ramp + n_cycles * period
    overrides = [f"motion.radius={float(radius)!r}", f"motion.period={float(period)!r}",
                 f"motion.ramp_duration={float(ramp)!r}",
                 f"simulation.duration={float(duration)!r}",
                 f'lines.chain.model="{model}"']
    if sense is not None:
        overrides.append(f'motion.sense="{sense}"')
    overrides.extend(extra_overrides)
    case = load_case(LINDAHL_CASE, overrides)
    result = run_forced_motion(case)
    if result.status != "complete":
        raise RuntimeError(f"Lindahl run T = {period} s did not complete: {result.status}")
    ds = result.dataset
    time = ds["time"].values
    tension = ds["fairlead_tension"].sel(line="chain").values
    motion = case.motion
    ramp = motion.ramp_duration
    period = motion.cycle_period
    stats = channel_statistics(time, tension, start=ramp, period=period)
    phase_time, mean_cycle = phase_average(time, tension, period=period, start=ramp,
                                           n_phase=N_PHASE)
    # phase time 0 is t = ramp; it is a whole number of periods unless overridden
    phase_deg = float(np.degrees(motion.phase) + 360.0 * ramp / period) % 360.0

    key = _key(motion.radius, period)
    measured = alignment = origin_deg = None
    path = measured_cycle_path(period, motion.radius)
    if path.is_file():
        measured = read_measured_cycle(path)
        alignment = align_cycles(measured.time_in_cycle, measured.mean, phase_time, mean_cycle,
                                 period=period)
        origin_deg = (alignment.shift_deg + phase_deg) % 360.0
    return {
        "period": period,
        "radius": motion.radius,
        "sense": motion.sense,
        "model": case.lines[0].model,
        "phase_deg": phase_deg,
        "ramp": ramp,
        "duration": case.simulation.duration,
        "time": time,
        "tension": tension,
        "statistics": stats,
        "mean_cycle_max": stats["mean_cycle_max"],
        "cycle_maxima_count": stats["n_cycles"],
        "phase_time": phase_time,
        "mean_cycle": mean_cycle,
        "published_mean_max": PUBLISHED_MEAN_MAX_N.get(key),
        "measured": measured,
        "alignment": alignment,
        "measured_origin_phase_deg": origin_deg,
        "wall_time_s": result.wall_time_s,
    }


def describe(result: Mapping[str, Any]) -> str:
    """One line of numbers for a :func:`run_lindahl` result (for test output)."""
    text = (f"T = {result['period']:g} s, r = {result['radius']:g} m, {result['model']}, "
            f"{result['sense']}: mean cycle max {result['mean_cycle_max']:.2f} N")
    published = result["published_mean_max"]
    if published is not None:
        text += (f" (published {published:g} N, "
                 f"{100.0 * (result['mean_cycle_max'] / published - 1.0):+.1f} %)")
    alignment = result["alignment"]
    if alignment is not None:
        text += (f"; aligned: shift {alignment.shift:.4f} s ({alignment.shift_deg:.1f} deg), "
                 f"measured t = 0 at motion phase {result['measured_origin_phase_deg']:.1f} deg, "
                 f"RMS {alignment.rms_difference:.2f} N = "
                 f"{100.0 * alignment.rms_relative_to_peak:.1f} % of the measured peak "
                 f"{alignment.reference_peak:.2f} N")
    return text


def plot_lindahl_comparison(results: Sequence[Mapping[str, Any]], path: str | Path) -> Path:
    """Measured and simulated mean cycles side by side, one panel per result.

    Each panel shows the measured phase mean with a +/- one standard deviation band and the
    simulated mean cycle shifted onto it (:func:`align_cycles`); the legend gives the mean
    per-cycle maxima (simulated and published) and the RMS difference.

    Parameters
    ----------
    results
        :func:`run_lindahl` results, e.g. for T = 1.25 s and 3.5 s; drawn left to right in
        order of increasing period.
    path
        Image file (.png, .pdf or .svg); its folder is created.

    Returns
    -------
    Path
        The file written.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    ordered = sorted(results, key=lambda r: r["period"])
    fig, axes = plt.subplots(1, len(ordered), figsize=(6.2 * len(ordered), 5.6), squeeze=False)
    for ax, res in zip(axes[0], ordered):
        measured, alignment = res["measured"], res["alignment"]
        published = res["published_mean_max"]
        if measured is not None and alignment is not None:
            t, mean, std = measured
            ax.fill_between(t, mean - std, mean + std, color="0.8", lw=0,
                            label="measured, $\\pm$ 1 std (cycle to cycle)")
            pub = f", published mean max {published:g} N" if published is not None else ""
            ax.plot(t, mean, color="k", lw=1.4,
                    label=f"measured phase mean (peak {alignment.reference_peak:.2f} N{pub})")
            ax.plot(t, alignment.aligned_candidate, color="C3", lw=1.4,
                    label=(f"floatmoor {res['model']}, aligned (mean cycle max "
                           f"{res['mean_cycle_max']:.2f} N)"))
            ax.plot([], [], " ", label=(f"shift {alignment.shift:.3f} s; RMS diff. "
                                        f"{alignment.rms_difference:.2f} N = "
                                        f"{100.0 * alignment.rms_relative_to_peak:.1f} % of peak"))
            ax.set_xlabel("time in the measured cycle [s]")
        else:
            ax.plot(res["phase_time"], res["mean_cycle"], color="C3", lw=1.4,
                    label=(f"floatmoor {res['model']} (mean cycle max "
                           f"{res['mean_cycle_max']:.2f} N)"))
            ax.set_xlabel("time after the ramp, modulo T [s]")
        title = (f"T = {res['period']:g} s, r = {res['radius']:g} m: mean cycle max "
                 f"{res['mean_cycle_max']:.1f} N")
        if published is not None:
            title += f" (measured {published:g} N)"
        ax.set_title(title, fontsize=10)
        ax.set_xlim(0.0, res["period"])
        ax.set_ylabel("upper-end tension [N]")
        ax.grid(alpha=0.3)
        ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.14), fontsize=7.5, frameon=False)
    senses = sorted({str(r["sense"]) for r in ordered})
    fig.suptitle(f"Lindahl chain: measured vs simulated upper-end force ({', '.join(senses)})",
                 fontsize=11)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path
