"""Benchmark baseline: lines alone on recorded fairlead paths, floatmoor (today) and MoorDyn 2.7.

    python tests/data/references/moordyn_forced_study.py CASE.toml PATHS.nc OUT.json
        [--lines NAME ...] [--start S] [--reference N F SCHEME] [--segments N ...]
        [--fractions F ...] [--schemes RK2 RK4 ...] [--floatmoor] [--coupling DT]

CASE gives the lines (environment, seabed, line types, anchors); PATHS.nc (make_references.py
fairleads) each line's fairlead position and velocity at the samples, the path both codes
follow (cubic Hermite between samples). Each line alone:

- floatmoor (``--floatmoor``): DynamicLine with the case's settings, settled with its fairlead
  at the path's first point, then ``solve_path``; ``loop`` is solve_path, ``whole``
  construction + settling + loop.
- MoorDyn through tests/io/moordyn_runner.py (``run_moordyn_forced``: its mapping of the
  line, seabed, friction per segment count and internal damping; coupling every 1 ms on the
  Hermite path), N segments, dtM = F l / c (l = L / N, c = sqrt(EA / m)), time scheme SCHEME;
  ``loop`` is moordyn.Step, ``whole`` the whole call (input, creation, initial-condition solve,
  loop). MoorDyn's tension is the force on its coupled fairlead node (end node inertia not
  removed: an O(l) difference that the convergence study sees).

Statistics of each fairlead tension over t >= S: population STD and maximum. A MoorDyn
setting is within 1 % when both are within 1 % of the reference setting's for every line and
the next finer segment count at the same F is too; candidates go in increasing N^2 / F.
The functions are those of tests/benchmarks/dynamic_harness.py (the dynamic-line benchmarks
use them too); this is their command line, which resumes from an existing OUT.json. Run it with
PYTHONPATH = the repository root.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from tests.benchmarks.dynamic_harness import (COUPLING, lines_problem, moordyn_study,
                                              run_floatmoor_lines)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("case")
    p.add_argument("paths")
    p.add_argument("out")
    p.add_argument("--lines", nargs="+", default=None)
    p.add_argument("--start", type=float, default=20.0)
    p.add_argument("--duration", type=float, default=None)
    p.add_argument("--reference", nargs=3, default=["60", "0.5", "RK4"])
    p.add_argument("--segments", nargs="+", type=int, default=[10, 15, 20, 30, 40, 60])
    p.add_argument("--fractions", nargs="+", type=float, default=[1.0, 0.5, 0.25])
    p.add_argument("--schemes", nargs="+", default=["RK2", "RK4"])
    p.add_argument("--floatmoor", action="store_true")
    p.add_argument("--coupling", type=float, default=COUPLING,
                   help="MoorDyn coupling interval [s] (moordyn.Step), default 1 ms")
    a = p.parse_args()
    problem = lines_problem(Path(a.case), Path(a.paths), start=a.start, lines=a.lines,
                            duration=a.duration)
    out = Path(a.out)
    results = json.loads(out.read_text()) if out.exists() else {"runs": []}
    results.update({"case": a.case, "paths": a.paths, "start_s": a.start,
                    "duration_s": problem.duration,
                    "lines": [ln.name for ln in problem.lines]})

    def save():
        out.write_text(json.dumps(results, indent=1) + "\n")

    if a.floatmoor:
        fm = run_floatmoor_lines(problem)
        del fm["tension"]
        results["floatmoor"] = fm
        save()
        print("floatmoor", json.dumps(fm), flush=True)
    if not a.schemes:
        return
    runs = {(r["segments"], r["fraction"], r["scheme"], r.get("coupling_s", COUPLING)): r
            for r in results["runs"]}
    reference = (int(a.reference[0]), float(a.reference[1]), a.reference[2], a.coupling)

    def progress(line):  # print each run and keep it (a rerun resumes from OUT.json)
        print(line, flush=True)
        results["runs"] = list(runs.values())
        save()

    study = moordyn_study(problem, reference=reference, segments=a.segments,
                          fractions=a.fractions, schemes=a.schemes, couplings=[a.coupling],
                          echo=progress, runs=runs)
    results["reference"] = study["reference"]
    results["cheapest"] = {s: r for (s, _), r in study["cheapest"].items()}
    save()


if __name__ == "__main__":
    main()
