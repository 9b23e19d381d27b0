"""Mooring systems in dynamics against MoorDyn 2.7 run converged on the exported deck (issue 15).

Two lines of tests/data/systems/, each under harmonic fairlead motion (surge 2 m, heave 1 m,
10 s period, ramped in over 10 s): the chain-rope-chain line with a clump weight at its lower
joint, and the lazy-wave-like line held up by a buoy. Both codes model the same physics (the
case files' headers: no friction, only the chain on the seabed, the points off it, all
submerged, the same small internal damping); each starts from its own static state. floatmoor
runs at its defaults (10 elements of order 5 per section); MoorDyn on the deck
``floatmoor export moordyn`` writes, with its segments and dtM refined until converged
(:data:`MOORDYN_SETTINGS`), driven by tests/peer/moordyn_system_runner.py.

Asserted over the whole record after the ramp: the fairlead tension histories agree within
:data:`TENSION_RANGE_FRACTION` of MoorDyn's tension range (the issue's 2 % is not met yet:
see there), and the free points' positions within :data:`POINT_ATOL`. The full runs are slow (minutes); a short run of the lazy-wave line over
the ramp alone checks the harness and the start in the default run.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.simulation.forced import run_forced_motion

moordyn_system_runner = pytest.importorskip("tests.peer.moordyn_system_runner")
pytest.importorskip("moordyn")

SYSTEMS = Path(__file__).parents[1] / "data" / "systems"
#: MoorDyn's finest run (segment multiple of the exported N = elements x order = 50 per
#: section, dtM [s]). From 50 to 100 segments per section the lazy-wave fairlead tension
#: moves by 2.7 % of its range at most (0.5 % RMS): MoorDyn is not converged to the issue's
#: 0.5 % there, and 200 segments (dtM 1.5e-5 s) is ~15 min of MoorDyn per run.
MOORDYN_SETTINGS = {
    "chain_rope_chain_clump": (2.0, 3e-5),
    "lazy_wave_buoy": (2.0, 3e-5),
}
#: Max |floatmoor - MoorDyn| of the fairlead tension after the ramp over MoorDyn's range.
#: The issue asks 2 %; NOT met yet, on either line, against MoorDyn at 100 segments per
#: section (which is itself not converged: 50 -> 100 segments moves it by 2.8 % (clump line)
#: and 2.7 % (lazy wave) of the range at most, 0.5 % RMS). Observed with floatmoor at its
#: defaults: clump line 3.44 % (RMS 0.60 %, the maximum in a trough near 100 kN); lazy wave
#: 4.27 % (RMS 2.2 %; floatmoor at 20 elements 4.25 %, so not floatmoor's discretisation: a
#: systematic ~0.4 kN larger swing in floatmoor on a 13 kN range, 0.4 % of the mean
#: tension). The bounds are the observed gaps, so that they do not grow unnoticed.
TENSION_RANGE_FRACTION = {
    "chain_rope_chain_clump": 0.04,
    "lazy_wave_buoy": 0.05,
}
#: Free points' positions, floatmoor against MoorDyn [m]: observed 0.07 m (buoy) and 0.14 m
#: (the massless chain-rope joint of the lazy wave, 0.05 m with floatmoor at 20 elements).
POINT_ATOL = 0.2
#: The short run: start (tension, relative; points [m]) and the whole 3 s record against the
#: mean tension (observed: see the test's print).
START_RTOL = 5e-3  # observed 2.4e-3 (MoorDyn at 50 segments, TmaxIC 10 s)
START_ATOL = 0.01
SHORT_RTOL = 0.01
#: MoorDyn's coupling: cubic Hermite sub-intervals per output sample, the path floatmoor's
#: DG system follows between its samples.
SUBSTEPS = 4


def _compare(name: str, overrides: list[str], scale: float, dt: float | None, **options):
    case = load_case(SYSTEMS / f"{name}.toml", overrides)
    ds = run_forced_motion(case).dataset
    t = ds["time"].values
    md = moordyn_system_runner.run_moordyn_system(case, t, segment_scale=scale, dt=dt,
                                                  substeps=SUBSTEPS, **options)
    np.testing.assert_allclose(md.time, t)
    return case, ds, md


def _report(name, case, ds, md, after):
    ours = ds["fairlead_tension"].sel(line="line1").values[after]
    theirs = md.fairlead_tension("line1")[after]
    span = theirs.max() - theirs.min()
    error = np.abs(ours - theirs).max() / span
    points = {n: float(np.linalg.norm(ds["point_position"].sel(point=n).values[after]
                                      - md.point_position[n][after], axis=1).max())
              for n in md.point_position}
    print(f"\n{name}: tension range {span / 1e3:.1f} kN ({theirs.min() / 1e3:.1f} to "
          f"{theirs.max() / 1e3:.1f}); max difference {error:.2%} of it; points (m) "
          f"{ {n: round(d, 3) for n, d in points.items()} }; MoorDyn {md.wall:.1f} s")
    return error, points, theirs


@pytest.mark.slow
@pytest.mark.parametrize("name", sorted(MOORDYN_SETTINGS))
def test_fairlead_tension_and_points_match_converged_moordyn(name):
    scale, dt = MOORDYN_SETTINGS[name]
    case, ds, md = _compare(name, [], scale, dt)
    after = ds["time"].values >= case.motion.ramp_duration
    error, points, theirs = _report(name, case, ds, md, after)
    assert theirs.min() > 0.1 * theirs.max()  # taut throughout: the cases' premise
    assert error <= TENSION_RANGE_FRACTION[name]
    assert max(points.values()) <= POINT_ATOL


def test_short_run_starts_at_the_statics_and_follows_moordyn():
    """The first 3 s of the clump line (a 2.5 s ramp) at the exported MoorDyn settings
    and a short MoorDyn start (TmaxIC 10 s is enough from the statics on this line): both codes
    start from the same equilibrium and follow each other within :data:`SHORT_RTOL` of the
    mean tension (a mapping error of the exported deck would show at once)."""
    case, ds, md = _compare("chain_rope_chain_clump", ["simulation.duration=3.0",
                                                       "motion.ramp_duration=2.5"],
                            1.0, None, ic_max_time=10.0)
    ours = ds["fairlead_tension"].sel(line="line1").values
    theirs = md.fairlead_tension("line1")
    np.testing.assert_allclose(theirs[0], ours[0], rtol=START_RTOL)
    for name in ("clump", "line1.joint2"):
        np.testing.assert_allclose(md.point_position[name][0],
                                   ds["point_position"].sel(point=name).values[0],
                                   atol=START_ATOL)
    difference = np.abs(ours - theirs).max() / theirs.mean()
    print(f"\nclump line, 3 s: max difference {difference:.3%} of the mean tension; "
          f"tension {theirs.min() / 1e3:.1f} to {theirs.max() / 1e3:.1f} kN")
    assert difference <= SHORT_RTOL
