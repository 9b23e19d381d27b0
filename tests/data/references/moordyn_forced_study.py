"""Issue 17 baseline: lines alone on recorded fairlead paths, floatmoor (today) and MoorDyn 2.7.

    python tests/data/references/moordyn_forced_study.py CASE.toml PATHS.nc OUT.json
        [--lines NAME ...] [--start S] [--reference N F SCHEME] [--segments N ...]
        [--fractions F ...] [--schemes RK2 RK4 ...] [--floatmoor]

CASE gives the lines (environment, seabed, line types, anchors); PATHS.nc (make_references.py
fairleads) each line's fairlead position and velocity at the samples, the path both codes
follow (cubic Hermite between samples). Each line alone:

- floatmoor (``--floatmoor``): DynamicLine with the case's settings, settled, then
  ``solve_path``; ``loop`` is solve_path, ``whole`` construction + settling + loop.
- MoorDyn through tests/peer/moordyn_runner.py (``run_moordyn_forced``: its mapping of the
  line, seabed, friction per segment count and internal damping; coupling every 1 ms on the
  Hermite path), N segments, dtM = F l / c (l = L / N, c = sqrt(EA / m)), time scheme SCHEME;
  ``loop`` is moordyn.Step, ``whole`` the whole call (input, creation, initial-condition solve,
  loop). MoorDyn's tension is the force on its coupled fairlead node (end node inertia not
  removed: an O(l) difference that the convergence study sees).

Statistics of each fairlead tension over t >= S: population STD and maximum. A MoorDyn
setting is within 1 % when both are within 1 % of the reference setting's for every line and
the next finer segment count at the same F is too; candidates go in increasing N^2 / F.
"""

from __future__ import annotations

import argparse
import json
import math
import time
from pathlib import Path

import numpy as np
import xarray as xr

from floatmoor.case.load import load_case
from floatmoor.mooring.dg.line import DynamicLine
from tests.peer.moordyn_runner import MoorDynError, MoorDynLine, run_moordyn_forced

TOLERANCE = 0.01
COUPLING = 1e-3  # s, as tests/benchmarks/moordyn_lindahl.py


def stats(t, tension, start):
    sel = t >= start
    return {"std": float(np.std(tension[sel])), "max": float(np.max(tension[sel]))}


def md_line(case, line) -> MoorDynLine:
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


def run_floatmoor(case, lines, paths, start):
    t = paths["time"].values
    out = {"lines": {}, "loop_s": 0.0, "whole_s": 0.0}
    for line in lines:
        p = paths["fairlead_position"].sel(line=line.name).values
        v = paths["fairlead_velocity"].sel(line=line.name).values
        w0 = time.perf_counter()
        dg = DynamicLine.from_case(line, case.environment, case.seabed)
        dg.fairlead = np.array(p[0])  # settle at the path's first point
        if line.dynamic.settle:
            dg.settle()
        n = t.size
        ff = np.zeros((n, 3))
        w1 = time.perf_counter()
        dg.solve_path(t, p, v, ff, np.zeros((n, 3)), np.zeros(n), np.zeros(n))
        w2 = time.perf_counter()
        out["lines"][line.name] = stats(t, np.linalg.norm(ff, axis=1), start)
        out["loop_s"] += w2 - w1
        out["whole_s"] += w2 - w0
    out["loop_per_sim"] = out["loop_s"] / float(t[-1])
    out["whole_per_sim"] = out["whole_s"] / float(t[-1])
    out["settings"] = str(lines[0].dynamic)
    return out


def run_md(case, lines, paths, segments, fraction, scheme, start, coupling=COUPLING):
    t = paths["time"].values
    res = {"segments": segments, "fraction": fraction, "scheme": scheme, "lines": {},
           "loop_s": 0.0, "whole_s": 0.0}
    substeps = max(1, round(float(t[1] - t[0]) / coupling))
    for line in lines:
        lt = line.line_type
        dt = fraction * (line.length / segments) / math.sqrt(lt.axial_stiffness
                                                             / lt.mass_per_length)
        res["dt"] = dt
        p = paths["fairlead_position"].sel(line=line.name).values
        v = paths["fairlead_velocity"].sel(line=line.name).values
        w0 = time.perf_counter()
        try:
            tt, ten, wall = run_moordyn_forced(md_line(case, line), t, p, v, segments=segments,
                                               dt=dt, substeps=substeps, time_scheme=scheme)
        except MoorDynError as exc:
            res["error"] = str(exc).splitlines()[0][:200]
            return res
        res["whole_s"] += time.perf_counter() - w0
        res["loop_s"] += wall
        s = stats(tt, ten, start)
        if not (np.isfinite(s["max"]) and s["max"] < 1e3 * np.abs(ten[0]) + 1e3):
            res["error"] = "diverged (tension out of bounds)"
            return res
        res["lines"][line.name] = s
    res["loop_per_sim"] = res["loop_s"] / float(t[-1])
    res["whole_per_sim"] = res["whole_s"] / float(t[-1])
    return res


def within(r, ref):
    if "error" in r:
        return False
    return all(abs(r["lines"][k][q] / ref["lines"][k][q] - 1.0) <= TOLERANCE
               for k in ref["lines"] for q in ("std", "max"))


def rel(r, ref):
    if "error" in r:
        return r["error"]
    return "  ".join(f"{k} std {100 * (r['lines'][k]['std'] / ref['lines'][k]['std'] - 1):+6.2f}%"
                     f" max {100 * (r['lines'][k]['max'] / ref['lines'][k]['max'] - 1):+6.2f}%"
                     for k in ref["lines"])


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
    case = load_case(a.case)
    paths = xr.open_dataset(a.paths).load()
    if a.duration is not None:
        paths = paths.sel(time=slice(0.0, a.duration))
    lines = [ln for ln in case.lines if a.lines is None or ln.name in a.lines]
    out = Path(a.out)
    results = json.loads(out.read_text()) if out.exists() else {"runs": []}
    results.update({"case": a.case, "paths": a.paths, "start_s": a.start,
                    "duration_s": float(paths["time"].values[-1]),
                    "lines": [ln.name for ln in lines]})

    def save():
        out.write_text(json.dumps(results, indent=1) + "\n")

    if a.floatmoor:
        results["floatmoor"] = fm = run_floatmoor(case, lines, paths, a.start)
        save()
        print("floatmoor", json.dumps(fm), flush=True)
    done = {(r["segments"], r["fraction"], r["scheme"]): r for r in results["runs"]}

    def get(n, f, s):
        key = (n, f, s)
        if key not in done:
            w0 = time.perf_counter()
            r = run_md(case, lines, paths, n, f, s, a.start, a.coupling)
            r["coupling_s"] = a.coupling
            r["call_s"] = time.perf_counter() - w0
            done[key] = r
            results["runs"].append(r)
            save()
            ref = results.get("reference")
            extra = "" if ref is None or r is ref else rel(r, ref)
            print(f"{s:10s} {n:4d} seg f {f:5.3f} dt {r['dt']:.3g} s  "
                  + (f"loop {r['loop_per_sim']:.4f} whole {r['whole_per_sim']:.4f} s/s  "
                     if "error" not in r else "") + extra, flush=True)
        return done[key]

    if not a.schemes:
        return
    results["reference"] = ref = get(int(a.reference[0]), float(a.reference[1]), a.reference[2])
    save()
    print("reference", json.dumps(ref["lines"]), flush=True)
    cheapest = results.setdefault("cheapest", {})
    for s in a.schemes:
        cands = sorted(((n, f) for n in a.segments for f in a.fractions),
                       key=lambda c: (c[0] ** 2 / c[1], c[0]))
        for n, f in cands:
            r = get(n, f, s)
            if within(r, ref):
                finer = [m for m in a.segments if m > n]
                if not finer or within(get(finer[0], f, s), ref):
                    cheapest[s] = r
                    print(f"  -> {s}: cheapest within 1 %: {n} segments, f = {f}", flush=True)
                    break
        save()


if __name__ == "__main__":
    main()
