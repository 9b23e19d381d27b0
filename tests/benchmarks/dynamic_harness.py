"""Shared harness of the dynamic-line benchmarks (``test_bench_*`` beside this file).

What the benchmark files share:

- the stored references of today's code (tests/data/references, README there):
  :func:`load_reference`;
- timing: :class:`Timing` holds a run's *time loop* and *whole run* wall seconds (the whole run
  includes the case loading, the static equilibrium, the settling of the dynamic lines or
  MoorDyn's initial-condition solve, the loop and, for floatmoor's coupled runs, the writing of
  the dataset) and gives both per simulated second;
- statistics after the ramp: :func:`after_ramp` (population STD, maximum, mean of the samples
  from the end of the ramp on: floatmoor.post.statistics.channel_statistics, as the references);
- coupled runs in this process at the case file's own numerics: :func:`run_coupled_case`, after
  :func:`compile_kernels`;
- lines alone on recorded fairlead paths, floatmoor and MoorDyn 2.7 side by side
  (:class:`LinesProblem`, :func:`run_floatmoor_lines`, :func:`run_moordyn_lines`) and the search
  for MoorDyn's cheapest setting within 1 % of its converged reference (:func:`moordyn_study`);
  ``tests/data/references/moordyn_forced_study.py`` (the baseline study) is a command line over
  the same functions;
- printing: :func:`table`.

Quick mode
----------
``FLOATMOOR_BENCH_QUICK=1`` validates the harness without the full cost: shortened durations
(:func:`pick` chooses the quick value), fewer MoorDyn settings, one timing repeat. The
accuracy figures are then printed against references made over other windows, so they are not
asserted; the speed targets still are (their ratios do not depend on the duration much). Run
e.g. ``FLOATMOOR_BENCH_QUICK=1 python -m pytest -m benchmark tests/benchmarks/FILE -s``.

MoorDyn's cost depends on its coupling interval: ``moordyn.Step`` advances at
min(dtM, coupling interval), so a coupling finer than the time step MoorDyn needs makes it pay
for steps it does not need; the studies try several couplings and report the one at which
MoorDyn is cheapest within 1 %.
"""

from __future__ import annotations

import dataclasses
import json
import math
import os
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from floatmoor.case.load import load_case
from floatmoor.case.schema import Case, Line, TableMotion
from floatmoor.mooring.dg.line import DynamicLine
from floatmoor.motion.frequency import fairlead_motion_frequency
from floatmoor.post.statistics import channel_statistics
from floatmoor.simulation.coupled_run import run_coupled
from tests.conftest import REPO
from tests.io.moordyn_runner import MoorDynError, MoorDynLine, run_moordyn_forced

#: Quick mode (module docstring).
QUICK = os.environ.get("FLOATMOOR_BENCH_QUICK", "") == "1"
#: The stored references of today's code.
REFERENCES = REPO / "tests" / "data" / "references"
#: "MoorDyn 2.7 at its cheapest setting within 1 %" (the target): STD and maximum of every line's
#: fairlead tension within 1 % of its converged reference.
MOORDYN_TOLERANCE = 0.01
#: MoorDyn's default coupling interval of the baseline studies [s] (as moordyn_lindahl.py).
COUPLING = 1e-3
#: MoorDyn 2.7's time schemes tried: explicit RK2 (its default) and RK4, and its implicit
#: schemes with three iterations (backward Euler, midpoint, ACA, Wilson).
MOORDYN_SCHEMES = ("RK2", "RK4", "BEuler3", "Midpoint3", "ACA3", "Wilson3")


def pick(full: Any, quick: Any) -> Any:
    """``quick`` in quick mode, else ``full``."""
    return quick if QUICK else full


def load_reference(name: str) -> dict[str, Any]:
    """A JSON reference of tests/data/references."""
    return json.loads((REFERENCES / name).read_text())


@dataclass(frozen=True)
class Timing:
    """Wall seconds of one run: its time loop and the whole run."""

    loop_s: float
    whole_s: float
    simulated_s: float

    @property
    def loop_per_sim(self) -> float:
        return self.loop_s / self.simulated_s

    @property
    def whole_per_sim(self) -> float:
        return self.whole_s / self.simulated_s


def after_ramp(time_s: np.ndarray, values: np.ndarray, start: float) -> dict[str, float]:
    """``std`` (population), ``max`` and ``mean`` of the samples from ``start`` on."""
    s = channel_statistics(np.asarray(time_s, float), np.asarray(values, float), start=start)
    return {"std": float(s["std"]), "max": float(s["max"]), "mean": float(s["mean"])}


def relative(value: float, reference: float) -> float:
    return value / reference - 1.0


def table(headers: Sequence[str], rows: Iterable[Sequence[Any]]) -> str:
    """A plain text table, columns right-aligned but the first."""
    text = [[str(h) for h in headers]] + [[str(c) for c in row] for row in rows]
    widths = [max(len(r[i]) for r in text) for i in range(len(headers))]
    lines = []
    for k, row in enumerate(text):
        cells = [row[0].ljust(widths[0])] + [c.rjust(w) for c, w in zip(row[1:], widths[1:])]
        lines.append("  ".join(cells))
        if k == 0:
            lines.append("  ".join("-" * w for w in widths))
    return "\n".join(lines)


def accuracy_table(figures: Iterable[tuple[str, float, float, float]], *,
                   check: bool = True) -> tuple[str, list[str]]:
    """Figures against their references: (label, value, reference, relative bound) each.

    Returns the table and the failures (labels with their deviation; none unless ``check``).
    """
    rows, failures = [], []
    for label, value, ref, bound in figures:
        dev = relative(value, ref)
        ok = abs(dev) <= bound
        rows.append((label, f"{value:.5g}", f"{ref:.5g}", f"{100 * dev:+.2f} %",
                     f"{100 * bound:g} %", "ok" if ok else ("OUT" if check else "-")))
        if check and not ok:
            failures.append(f"{label}: {value:.5g} against {ref:.5g} ({100 * dev:+.2f} %, "
                            f"bound {100 * bound:g} %)")
    text = table(("figure", "now", "reference", "deviation", "bound", ""), rows)
    return text, failures


def line_tension_figures(ds: xr.Dataset, reference_lines: dict[str, dict[str, float]],
                         start: float, bound: float, *, unit: str = "N",
                         scale: float = 1.0) -> list[tuple[str, float, float, float]]:
    """Each line's fairlead tension STD and maximum after ``start`` beside a reference's
    (``fairlead_tension_std_N``, ``fairlead_tension_max_N`` per line, as the references
    store them), for :func:`accuracy_table`; shown in ``unit`` = N / ``scale``."""
    t = ds["time"].values
    figures = []
    for name, ref in reference_lines.items():
        now = after_ramp(t, ds["fairlead_tension"].sel(line=name).values, start)
        for key in ("std", "max"):
            figures.append((f"{name} tension {key.upper() if key == 'std' else key} [{unit}]",
                            now[key] / scale, ref[f"fairlead_tension_{key}_N"] / scale, bound))
    return figures


def speed_table(timing: Timing, reference: dict[str, Any]) -> str:
    """A coupled run's timings beside today's run of the reference (``wall_time_loop_s``,
    ``wall_time_whole_s``, ``duration_s``): same machine, but not the same moment."""
    ref = Timing(reference["wall_time_loop_s"], reference["wall_time_whole_s"],
                 reference["duration_s"])
    rows = [(label, f"{t.simulated_s:g}", f"{t.loop_s:.1f}", f"{t.whole_s:.1f}",
             f"{t.loop_per_sim:.4f}", f"{t.whole_per_sim:.4f}")
            for label, t in (("now", timing), ("today's reference run", ref))]
    rows.append(("now / today's", "", "", "", f"{timing.loop_per_sim / ref.loop_per_sim:.3f}",
                 f"{timing.whole_per_sim / ref.whole_per_sim:.3f}"))
    return table(("run", "simulated s", "loop s", "whole s", "loop s/s", "whole s/s"), rows)


# --- coupled runs ----------------------------------------------------------------------------

def compile_kernels(case_path: Path, overrides: Sequence[str] = (),
                    duration: float | None = None) -> None:
    """Run the case for ``duration`` seconds (default two output intervals; an irregular sea
    needs a few seconds to hold a wave component) in a subprocess, so that the numba kernels
    it needs are compiled and cached on disk (nothing of it stays in this process: its lines'
    settling is not remembered here)."""
    if duration is None:
        duration = 2 * load_case(case_path, list(overrides)).simulation.output_interval
    with tempfile.TemporaryDirectory(prefix="floatmoor_bench_") as tmp:
        subprocess.run([sys.executable, "-c",
                        "import sys; from floatmoor.cli import main; sys.exit(main(sys.argv[1:]))",
                        "run", str(case_path), "-o", str(Path(tmp) / "warm.nc"), "--quiet",
                        *(a for o in overrides for a in ("--set", o)),
                        "--set", f"simulation.duration={float(duration)!r}"],
                       check=True, cwd=REPO, capture_output=True)


def run_coupled_case(case_path: Path, overrides: Sequence[str] = ()
                     ) -> tuple[Case, xr.Dataset, Timing]:
    """The case at its own numerics in this process: whole = load_case + run_coupled (set-up,
    equilibrium, settling, loop, dataset), loop = the run's own time-loop wall time."""
    started = time.perf_counter()
    case = load_case(case_path, list(overrides))
    result = run_coupled(case)
    whole = time.perf_counter() - started
    if result.status != "complete":
        raise RuntimeError(f"{case_path.name}: run {result.status}")
    return case, result.dataset, Timing(result.wall_time_s, whole, result.simulated_time_s)


# --- lines alone on recorded fairlead paths --------------------------------------------------

@dataclass(frozen=True)
class LinesProblem:
    """Lines of a case, each with its fairlead on a recorded path (position and velocity at
    uniform samples; both codes follow the cubic Hermite interpolant), statistics from
    ``start`` on."""

    case: Case
    lines: tuple[Line, ...]
    time: np.ndarray
    position: dict[str, np.ndarray]  #: per line, (n, 3) [m]
    velocity: dict[str, np.ndarray]  #: per line, (n, 3) [m/s]
    start: float  #: [s]

    @property
    def duration(self) -> float:
        return float(self.time[-1])


def lines_problem(case_path: Path, paths_path: Path, *, start: float,
                  lines: Sequence[str] | None = None,
                  duration: float | None = None) -> LinesProblem:
    """The lines of ``case_path`` (all, or those named) on the paths of ``paths_path`` (a
    netCDF file of make_references.py fairleads), cut at ``duration``."""
    case = load_case(case_path)
    with xr.open_dataset(paths_path) as opened:
        paths = opened.load()
    if duration is not None:
        paths = paths.sel(time=slice(0.0, duration))
    chosen = tuple(ln for ln in case.lines if lines is None or ln.name in lines)
    return LinesProblem(case, chosen, paths["time"].values,
                        {ln.name: paths["fairlead_position"].sel(line=ln.name).values
                         for ln in chosen},
                        {ln.name: paths["fairlead_velocity"].sel(line=ln.name).values
                         for ln in chosen}, start)


def _floatmoor_line(problem: LinesProblem, line: Line, offset: float = 0.0) -> DynamicLine:
    """The line at the case's numerics, settled with its fairlead at the path's first point
    (raised by ``offset`` [m]: a warm-up line that is not the one remembered as settled).
    Numerics left to the accuracy see the path's frequency, as from a motion table."""
    first = problem.position[line.name][0] + np.array([0.0, 0.0, offset])
    table = TableMotion(file="(recorded path)", time=problem.time,
                        displacement=problem.position[line.name])
    dynamic = dataclasses.replace(line.dynamic,
                                  motion_frequency=fairlead_motion_frequency(table, None))
    moved = dataclasses.replace(line, fairlead=tuple(float(c) for c in first), dynamic=dynamic)
    return DynamicLine.from_case(moved, problem.case.environment, problem.case.seabed)


def warm_up_floatmoor(problem: LinesProblem, samples: int = 20) -> None:
    """Load (or compile) the kernels the lines need, on a line whose settled state is not the
    one the timed runs use (so they settle it themselves)."""
    for line in problem.lines:
        dg = _floatmoor_line(problem, line, offset=1e-3 * line.length)
        n = min(samples, problem.time.size)
        dg.solve_path(problem.time[:n], problem.position[line.name][:n] + dg.fairlead
                      - problem.position[line.name][0], problem.velocity[line.name][:n],
                      np.zeros((n, 3)), np.zeros((n, 3)), np.zeros(n), np.zeros(n))


def run_floatmoor_lines(problem: LinesProblem) -> dict[str, Any]:
    """floatmoor's dynamic lines at the case's numerics, one after the other.

    Returns
    -------
    dict
        ``lines``: per line :func:`after_ramp` of the fairlead tension; ``loop_s`` (solve_path),
        ``whole_s`` (construction, settling and loop), summed over the lines, and per simulated
        second ``loop_per_sim``, ``whole_per_sim``; ``settings`` (the first line's numerics);
        ``tension``: per line the fairlead tension history [N].
    """
    t = problem.time
    n = t.size
    out: dict[str, Any] = {"lines": {}, "loop_s": 0.0, "whole_s": 0.0, "tension": {}}
    for line in problem.lines:
        w0 = time.perf_counter()
        dg = _floatmoor_line(problem, line)
        ff = np.zeros((n, 3))
        w1 = time.perf_counter()
        dg.solve_path(t, problem.position[line.name], problem.velocity[line.name], ff,
                      np.zeros((n, 3)), np.zeros(n), np.zeros(n))
        w2 = time.perf_counter()
        tension = np.linalg.norm(ff, axis=1)
        out["tension"][line.name] = tension
        out["lines"][line.name] = after_ramp(t, tension, problem.start)
        out["loop_s"] += w2 - w1
        out["whole_s"] += w2 - w0
    out["loop_per_sim"] = out["loop_s"] / problem.duration
    out["whole_per_sim"] = out["whole_s"] / problem.duration
    out["settings"] = str(problem.lines[0].dynamic)
    return out


def moordyn_line(case: Case, line: Line) -> MoorDynLine:
    """A case's one-section line as MoorDyn's (tests/io/moordyn_runner.py), its internal
    damping ratio mapped as floatmoor's exporter does."""
    lt, env, bed = line.line_type, case.environment, case.seabed
    c_int = 2.0 * lt.internal_damping_ratio * line.length * math.sqrt(
        lt.axial_stiffness * lt.mass_per_length) / math.pi  # floatmoor's (exporter note)
    return MoorDynLine(
        line.length, lt.mass_per_length, lt.axial_stiffness, lt.diameter, lt.material_density,
        lt.normal_drag_coefficient, lt.tangential_drag_coefficient, lt.added_mass_coefficient,
        tangential_added_mass_coefficient=lt.tangential_added_mass_coefficient,
        internal_damping=c_int, anchor=line.anchor, fairlead=line.fairlead,
        water_depth=env.water_depth, water_density=env.water_density, gravity=env.gravity,
        seabed_stiffness=bed.stiffness, seabed_damping_ratio=bed.damping_ratio,
        friction_coefficient=bed.friction_coefficient, slip_speed=bed.slip_speed)


def run_moordyn_lines(problem: LinesProblem, segments: int, fraction: float, scheme: str,
                      coupling: float = COUPLING) -> dict[str, Any]:
    """MoorDyn 2.7 on the lines, one after the other: ``segments`` segments, dtM = ``fraction``
    l / c (l = L / segments, c = sqrt(EA / m)), time scheme ``scheme``, coupled every
    ``coupling`` s (sub-points of the Hermite path between samples).

    Returns
    -------
    dict
        ``segments``, ``fraction``, ``scheme``, ``coupling_s``, ``dt`` (the last line's);
        ``lines``: per line :func:`after_ramp`; ``loop_s`` (moordyn.Step), ``whole_s`` (the
        whole call: input, creation, initial-condition solve, loop), per simulated second
        ``loop_per_sim``, ``whole_per_sim``; or ``error`` (the first failure's message).
    """
    t = problem.time
    res: dict[str, Any] = {"segments": segments, "fraction": fraction, "scheme": scheme,
                           "coupling_s": coupling, "lines": {}, "loop_s": 0.0, "whole_s": 0.0}
    substeps = max(1, round(float(t[1] - t[0]) / coupling))
    for line in problem.lines:
        lt = line.line_type
        dt = fraction * (line.length / segments) / math.sqrt(lt.axial_stiffness
                                                             / lt.mass_per_length)
        res["dt"] = dt
        w0 = time.perf_counter()
        try:
            tt, ten, wall = run_moordyn_forced(
                moordyn_line(problem.case, line), t, problem.position[line.name],
                problem.velocity[line.name], segments=segments, dt=dt, substeps=substeps,
                time_scheme=scheme)
        except MoorDynError as exc:
            res["error"] = str(exc).splitlines()[0][:200]
            return res
        res["whole_s"] += time.perf_counter() - w0
        res["loop_s"] += wall
        s = after_ramp(tt, ten, problem.start)
        if not (np.isfinite(s["max"]) and s["max"] < 1e3 * np.abs(ten[0]) + 1e3):
            res["error"] = "diverged (tension out of bounds)"
            return res
        res["lines"][line.name] = s
    res["loop_per_sim"] = res["loop_s"] / problem.duration
    res["whole_per_sim"] = res["whole_s"] / problem.duration
    return res


def within(result: dict[str, Any], reference: dict[str, Any],
           tolerance: float = MOORDYN_TOLERANCE) -> bool:
    """Every line's tension STD and maximum within ``tolerance`` of the reference's."""
    if "error" in result:
        return False
    return all(abs(relative(result["lines"][k][q], reference["lines"][k][q])) <= tolerance
               for k in reference["lines"] for q in ("std", "max"))


def deviations(result: dict[str, Any], reference: dict[str, Any]) -> str:
    """Each line's STD and maximum relative to the reference's, or the error."""
    if "error" in result:
        return result["error"]
    return "  ".join(
        f"{k} std {100 * relative(result['lines'][k]['std'], reference['lines'][k]['std']):+6.2f}%"
        f" max {100 * relative(result['lines'][k]['max'], reference['lines'][k]['max']):+6.2f}%"
        for k in reference["lines"])


def setting_name(result: dict[str, Any]) -> str:
    """``RK2 20 seg dt = 1 l/c (17.1 ms), coupling 20 ms``."""
    return (f"{result['scheme']} {result['segments']} seg dt = {result['fraction']:g} l/c "
            f"({1e3 * result['dt']:.3g} ms), coupling {1e3 * result['coupling_s']:g} ms")


def moordyn_study(problem: LinesProblem, *, reference: tuple[int, float, str, float],
                  segments: Sequence[int], fractions: Sequence[float],
                  schemes: Sequence[str], couplings: Sequence[float],
                  check: tuple[int, float, str, float] | None = None,
                  echo: Callable[[str], None] = print,
                  runs: dict[tuple, dict[str, Any]] | None = None) -> dict[str, Any]:
    """MoorDyn's reference and, per coupling interval and scheme, its cheapest setting within
    :data:`MOORDYN_TOLERANCE` of the reference.

    Candidates (segments N, dtM fraction F) go in increasing N^2 / F (cost ~ nodes / step); a
    candidate is accepted when it is within the tolerance *and* so is the next finer segment
    count at the same F (a coarse mesh landing within it by a cancellation of errors is not
    accepted).

    Parameters
    ----------
    reference
        (segments, fraction, scheme, coupling) of the converged reference.
    check
        A coarser setting that must be within the tolerance of the reference for the
        reference to count as converged; if it is not, no candidate is searched (within 1 %
        of an unconverged reference means nothing). None: the reference is taken as converged.
    runs
        Results already computed, by (segments, fraction, scheme, coupling); filled in.

    Returns
    -------
    dict
        ``reference`` (a :func:`run_moordyn_lines` result), ``check`` (or None),
        ``converged``, ``cheapest``: {(scheme, coupling): result} of the accepted settings,
        ``runs`` (all results).
    """
    runs = {} if runs is None else runs

    def get(n: int, f: float, s: str, c: float) -> dict[str, Any]:
        if (n, f, s, c) not in runs:
            runs[n, f, s, c] = r = run_moordyn_lines(problem, n, f, s, c)
            ref = runs.get(reference)
            extra = "" if ref is None or r is ref else deviations(r, ref)
            cost = ("" if "error" in r else f"loop {r['loop_per_sim']:.4f} whole "
                    f"{r['whole_per_sim']:.4f} s/s  ")
            echo(f"  MoorDyn {setting_name(r)}: {cost}{extra}")
        return runs[n, f, s, c]

    ref = get(*reference)
    if "error" in ref:
        raise RuntimeError(f"MoorDyn reference {reference} failed: {ref['error']}")
    checked = None if check is None else get(*check)
    converged = checked is None or within(checked, ref)
    cheapest: dict[tuple[str, float], dict[str, Any]] = {}
    if not converged:
        echo(f"  MoorDyn's reference is not converged: {setting_name(checked)} is not within "
             f"{100 * MOORDYN_TOLERANCE:g} % of it; no candidate searched")
        couplings = ()
    candidates = sorted(((n, f) for n in segments for f in fractions),
                        key=lambda c: (c[0] ** 2 / c[1], c[0]))
    for c in couplings:
        for s in schemes:
            for n, f in candidates:
                r = get(n, f, s, c)
                if within(r, ref):
                    finer = [m for m in segments if m > n]
                    if not finer or within(get(finer[0], f, s, c), ref):
                        cheapest[s, c] = r
                        echo(f"  -> cheapest within {100 * MOORDYN_TOLERANCE:g} %: "
                             f"{setting_name(r)}")
                        break
    return {"reference": ref, "check": checked, "converged": converged, "cheapest": cheapest,
            "runs": runs}


def cheapest_by(study: dict[str, Any], key: str) -> dict[str, Any] | None:
    """The accepted setting with the smallest ``key`` (``loop_s`` or ``whole_s``), or None."""
    accepted = list(study["cheapest"].values())
    return min(accepted, key=lambda r: r[key]) if accepted else None


def report_lines_comparison(problem: LinesProblem, floatmoor: dict[str, Any],
                            study: dict[str, Any]) -> dict[str, tuple[dict[str, Any], float]]:
    """Print floatmoor's run and MoorDyn's reference and accepted settings (each line's tension
    STD and maximum against MoorDyn's reference, loop and whole wall s per simulated s), and the
    wall-time ratios floatmoor / MoorDyn against MoorDyn's cheapest accepted setting by time
    loop and by whole run.

    Returns
    -------
    dict
        ``loop`` and ``whole``: (MoorDyn's cheapest accepted setting by that measure, the ratio
        floatmoor / MoorDyn); empty if no MoorDyn setting was accepted.
    """
    ref = study["reference"]
    rows = [("floatmoor, the case's numerics", deviations(floatmoor, ref),
             f"{floatmoor['loop_per_sim']:.4f}", f"{floatmoor['whole_per_sim']:.4f}"),
            (f"MoorDyn reference {setting_name(ref)}", "", f"{ref['loop_per_sim']:.4f}",
             f"{ref['whole_per_sim']:.4f}")]
    if study["check"] is not None:
        c = study["check"]
        rows.append((f"MoorDyn check {setting_name(c)}", deviations(c, ref),
                     *((f"{c['loop_per_sim']:.4f}", f"{c['whole_per_sim']:.4f}")
                       if "error" not in c else ("-", "-"))))
    for r in study["cheapest"].values():
        rows.append((f"MoorDyn 1 %: {setting_name(r)}", deviations(r, ref),
                     f"{r['loop_per_sim']:.4f}", f"{r['whole_per_sim']:.4f}"))
    print(f"\n{', '.join(ln.name for ln in problem.lines)} alone on the recorded fairlead path, "
          f"{problem.duration:g} s, statistics from t = {problem.start:g} s; floatmoor at "
          f"{floatmoor['settings']}")
    print("MoorDyn's reference: " + "  ".join(
        f"{k} STD {v['std']:.6g} N max {v['max']:.6g} N" for k, v in ref["lines"].items()))
    print(table(("run", "tension vs MoorDyn's reference", "loop s/s", "whole s/s"), rows))
    ratios: dict[str, tuple[dict[str, Any], float]] = {}
    for measure, key in (("loop", "loop_s"), ("whole", "whole_s")):
        best = cheapest_by(study, key)
        if best is not None:
            ratios[measure] = (best, floatmoor[key] / best[key])
    if ratios:
        print(table(("measure", "MoorDyn's cheapest within 1 %", "floatmoor / MoorDyn"),
                    [(m, setting_name(r), f"{x:.3f}") for m, (r, x) in ratios.items()]))
    else:
        why = ("its reference is not converged" if not study["converged"]
               else "none in the range tried")
        print(f"MoorDyn: no setting within {100 * MOORDYN_TOLERANCE:g} % ({why}); floatmoor / "
              f"MoorDyn's reference: loop {floatmoor['loop_s'] / ref['loop_s']:.3f}, whole "
              f"{floatmoor['whole_s'] / ref['whole_s']:.3f}"
              + ("" if study["converged"] else " (MoorDyn within 1 % would need a finer, "
                 "costlier setting than its reference)"))
    return ratios


def lines_against_moordyn(problem: LinesProblem, **study: Any
                          ) -> tuple[dict[str, Any], dict[str, tuple[dict[str, Any], float]]]:
    """floatmoor's lines at the case's numerics (after a warm-up), then :func:`moordyn_study`
    with the options ``study``, reported (:func:`report_lines_comparison`).

    Returns
    -------
    tuple
        floatmoor's run (:func:`run_floatmoor_lines`) and the ratios of
        :func:`report_lines_comparison`.
    """
    warm_up_floatmoor(problem)
    ours = run_floatmoor_lines(problem)
    return ours, report_lines_comparison(problem, ours, moordyn_study(problem, **study))
