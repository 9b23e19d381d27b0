"""Benchmark: what MoorDyn (v2, lumped mass, the peer code) needs on the Lindahl chain.

Case A (docs/cases/lindahl.md; ``cases/lindahl/lindahl_r0.20_T1.25.toml``, period and ramp overridden):
the 33 m chain with its upper end on a vertical circle, r = 0.2 m, T = 1.25 s (slack and snap)
and T = 3.5 s (smooth), physical seabed (3e9 Pa/m, critical damping, friction 0.3 reached at
0.01 m/s), driven through ``tests/io/moordyn_runner.py``. For each period:

1. a converged reference: ``REFERENCE`` = 160 segments, dt = 25 us (the RK2 step has to shrink
   with the segment length: the highest axial mode, 2 c / l with c = 350 m/s, is undamped and
   RK2 amplifies undamped modes by 1 + (omega dt)^4 / 8 per step);
2. candidate (segments, dt) pairs in increasing cost (segments / dt) until one is accepted:
   its mean cycle maximum of the fairlead tension is within ``TOLERANCE`` = 1 % of the
   reference's, and so is the next finer segment count's at the same dt (``--all`` runs every
   candidate). That one is the cheapest; its wall seconds per simulated second are reported.

At T = 1.25 s the snap maxima scatter by ~1 % (standard deviation) from cycle to cycle and the
scatter is chaotic (any change of the numerics reshuffles it), so a 5-cycle mean carries a
~0.5 % standard error, printed with each result: differences of that size between
configurations are not discretisation error. ``--cycles 15`` narrows it (the reference run then
takes about a minute here). At T = 3.5 s the response is periodic (scatter < 0.1 %).

The fairlead follows the case's motion: a cosine ramp over two periods, then steady cycles;
the mean cycle maximum is taken over the cycles after the ramp (T = 1.25 s: the first one, a
post-ramp transient ~2 % high, skipped, then 5; T = 3.5 s: 4). Cycle windows run from phase
-1/4 to 3/4 (phase 0 at the top of the circle), away from the maxima (phase ~0.13 at T = 1.25 s).
The motion is sampled, and MoorDyn coupled, every 1 ms: piecewise-linear between samples
(< 1e-6 m from the circle), 5 to 40 MoorDyn steps per coupling call, so the Python call overhead
(~7 us per call here) is a few % of the reported wall time at 40 segments.

Wall times are whatever this machine gives at the time (one core, shared): rerun to compare.

Run: ``python -m tests.benchmarks.moordyn_lindahl`` (``--period 1.25``, ``--all``), or
``python -m pytest -m benchmark tests/benchmarks/moordyn_lindahl.py -s`` (T = 1.25 s only).
"""

from __future__ import annotations

import argparse
import math
import time
from dataclasses import dataclass

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.motion.fairlead import fairlead_path
from tests.conftest import LINDAHL_CASE
from tests.io.moordyn_runner import MoorDynError, MoorDynLine, run_moordyn_forced

#: Converged MoorDyn: segments, dt [s]. (80, 50 us) gives the same mean maximum within 0.1 %
#: at T = 1.25 s.
REFERENCE = (160, 2.5e-5)
#: Candidate segment counts and time steps [s]; dt > ~2.7e-4 s is unstable on the seabed
#: spring (critically damped, omega = sqrt(K d / (m + m_a)) = 7.4e3 rad/s, RK2: dt < 2 / omega).
SEGMENTS = (10, 15, 20, 30, 40, 60, 80)
TIME_STEPS = (2e-4, 1e-4, 5e-5)
TOLERANCE = 0.01
RADIUS = 0.2  # m
PERIODS = (1.25, 3.5)  # s
COUPLING_INTERVAL = 1e-3  # s
RAMP_PERIODS = 2
#: Post-ramp cycles skipped and measured, per period.
CYCLES = {1.25: (1, 5), 3.5: (0, 4)}
#: Published measured mean maxima (docs/cases/lindahl.md), for orientation only.
MEASURED = {1.25: 70.3, 3.5: 50.1}


def lindahl_line(case) -> MoorDynLine:
    """The case's chain as a :class:`MoorDynLine` (physical seabed of the case)."""
    line = case.lines[0]
    lt = line.line_type
    if lt.internal_damping_ratio != 0.0:
        raise ValueError("this benchmark maps no internal damping ratio")
    env, bed = case.environment, case.seabed
    return MoorDynLine(
        line.length, lt.mass_per_length, lt.axial_stiffness, lt.diameter, lt.material_density,
        lt.normal_drag_coefficient, lt.tangential_drag_coefficient, lt.added_mass_coefficient,
        tangential_added_mass_coefficient=lt.tangential_added_mass_coefficient,
        anchor=line.anchor, fairlead=line.fairlead, water_depth=env.water_depth,
        water_density=env.water_density, gravity=env.gravity,
        seabed_stiffness=bed.stiffness, seabed_damping_ratio=bed.damping_ratio,
        friction_coefficient=bed.friction_coefficient, slip_speed=bed.slip_speed)


@dataclass(frozen=True)
class Problem:
    """One forced-motion run: the line and its sampled fairlead path."""

    period: float
    line: MoorDynLine
    time: np.ndarray
    position: np.ndarray
    velocity: np.ndarray
    windows: list[tuple[float, float]]  #: measured cycles [s)

    @property
    def duration(self) -> float:
        return float(self.time[-1])


def lindahl_problem(period: float, radius: float = RADIUS,
                    measured_cycles: int | None = None) -> Problem:
    """The case's line and fairlead path over ``RAMP_PERIODS`` ramp periods, the skipped cycles
    and ``measured_cycles`` (default :data:`CYCLES`) measured ones."""
    skip, measured = CYCLES[period]
    measured = measured if measured_cycles is None else measured_cycles
    case = load_case(LINDAHL_CASE, [f"motion.radius={radius}", f"motion.period={period}",
                                    f"motion.ramp_duration={RAMP_PERIODS * period}"])
    first = RAMP_PERIODS + skip  # index of the first measured cycle
    duration = (first + measured) * period
    n = round(duration / COUPLING_INTERVAL)
    t = np.arange(n + 1) * (duration / n)
    x = fairlead_path(case.motion, case.lines[0], t)
    v = np.gradient(x, t, axis=0, edge_order=2)  # only v[0] = 0 matters (linear coupling)
    windows = [((first + k - 0.25) * period, (first + k + 0.75) * period)
               for k in range(measured)]
    return Problem(period, lindahl_line(case), t, x, v, windows)


def mean_cycle_maximum(problem: Problem, t: np.ndarray, tension: np.ndarray
                       ) -> tuple[float, np.ndarray]:
    maxima = np.array([tension[(t >= a) & (t < b)].max() for a, b in problem.windows])
    return float(maxima.mean()), maxima


@dataclass(frozen=True)
class Result:
    segments: int
    dt: float
    mean_max: float  #: NaN if MoorDyn failed
    maxima: np.ndarray
    wall: float  #: seconds in moordyn.Step
    wall_per_simulated: float
    error: str = ""

    def relative_to(self, reference: float) -> float:
        return self.mean_max / reference - 1.0

    @property
    def standard_error(self) -> float:
        """Of the mean cycle maximum, from the cycle-to-cycle scatter [N]."""
        if self.maxima.size < 2:
            return math.nan
        return float(np.std(self.maxima, ddof=1) / math.sqrt(self.maxima.size))


def run(problem: Problem, segments: int, dt: float) -> Result:
    try:
        t, tension, wall = run_moordyn_forced(problem.line, problem.time, problem.position,
                                              problem.velocity, segments=segments, dt=dt)
    except MoorDynError as exc:
        first_line = str(exc).splitlines()[0]
        return Result(segments, dt, math.nan, np.array([]), math.nan, math.nan, first_line)
    mean_max, maxima = mean_cycle_maximum(problem, t, tension)
    return Result(segments, dt, mean_max, maxima, wall, wall / problem.duration)


def _row(r: Result, reference: float | None = None) -> str:
    if r.error:
        return f"  {r.segments:4d} seg  dt {r.dt * 1e6:6.1f} us   failed: {r.error}"
    rel = "" if reference is None else f"  {100 * r.relative_to(reference):+6.2f} %"
    return (f"  {r.segments:4d} seg  dt {r.dt * 1e6:6.1f} us  mean max {r.mean_max:7.3f}"
            f" +- {r.standard_error:5.3f} N{rel}  {r.wall_per_simulated:7.4f} wall s / sim s"
            f"  (cycles {np.array2string(r.maxima, precision=2, separator=' ')})")


def study(period: float, *, all_candidates: bool = False, measured_cycles: int | None = None,
          echo=print) -> dict:
    """Reference and the cheapest accepted candidate for one period.

    A candidate is accepted when its mean cycle maximum is within :data:`TOLERANCE` of the
    reference's and so is that of the next finer segment count at the same dt (which guards
    against a coarse discretisation landing within the tolerance by a cancellation of errors:
    at T = 1.25 s, 15 segments do, 20 are 3 % low).
    """
    problem = lindahl_problem(period, measured_cycles=measured_cycles)
    echo(f"Lindahl r = {RADIUS} m, T = {period} s: {problem.duration:g} s simulated, "
         f"{len(problem.windows)} cycles measured from t = {problem.windows[0][0]:g} s; "
         f"mean cycle maximum +- its standard error from the cycle-to-cycle scatter")
    start = time.perf_counter()
    ref = run(problem, *REFERENCE)
    if ref.error:
        raise RuntimeError(f"reference run failed: {ref.error}")
    echo("reference:" + _row(ref) + f"  [measured {MEASURED.get(period)} N]")
    results: dict[tuple[int, float], Result] = {}

    def result(n: int, dt: float) -> Result:
        if (n, dt) not in results:
            results[n, dt] = r = run(problem, n, dt)
            within = not r.error and abs(r.relative_to(ref.mean_max)) <= TOLERANCE
            echo(_row(r, ref.mean_max) + ("   within" if within else ""))
        return results[n, dt]

    def within(r: Result) -> bool:
        return not r.error and abs(r.relative_to(ref.mean_max)) <= TOLERANCE

    candidates = sorted(((n, dt) for n in SEGMENTS for dt in TIME_STEPS),
                        key=lambda c: (c[0] / c[1], c[0]))
    cheapest = None
    for n, dt in candidates:
        r = result(n, dt)
        if cheapest is None and within(r):
            finer = [m for m in SEGMENTS if m > n]
            if not finer or within(result(finer[0], dt)):
                cheapest = r
                echo(f"  -> accepted ({finer[:1] or 'no'} finer segments also within)")
        if cheapest is not None and not all_candidates:
            break
    echo(f"  ({time.perf_counter() - start:.0f} s for this study)")
    if cheapest is not None:
        echo(f"cheapest within {100 * TOLERANCE:g} %: {cheapest.segments} segments, "
             f"dt = {cheapest.dt * 1e6:g} us, {cheapest.wall_per_simulated:.4f} wall s per "
             f"simulated s")
    return {"period": period, "reference": ref, "results": results, "cheapest": cheapest}


@pytest.mark.benchmark
def test_moordyn_lindahl_snap_benchmark():
    pytest.importorskip("moordyn")
    out = study(1.25)
    assert out["cheapest"] is not None


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--period", type=float, nargs="+", default=list(PERIODS),
                        choices=PERIODS)
    parser.add_argument("--all", action="store_true", help="run every candidate")
    parser.add_argument("--cycles", type=int, default=None,
                        help="measured cycles (default: 5 at T = 1.25 s, 4 at T = 3.5 s)")
    args = parser.parse_args(argv)
    for period in args.period:
        study(period, all_candidates=args.all, measured_cycles=args.cycles,
              echo=lambda s: print(s, flush=True))


if __name__ == "__main__":
    main()
