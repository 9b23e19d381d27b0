"""Mooring systems in dynamics against MoorDyn 2.7 run converged on the exported deck.

Two lines of tests/data/systems/, each under harmonic fairlead motion (surge 2 m, heave 1 m,
10 s period, ramped in over 10 s): the chain-rope-chain line with a clump weight at its lower
joint, and the lazy-wave-like line held up by a buoy. Both codes model the same physics (the
case files' headers: no friction, only the chain on the seabed, the points off it, all
submerged, the same small internal damping); each starts from its own static state. floatmoor
runs at its defaults (10 elements of order 5 per section). MoorDyn's finest record
(:data:`tests.io.moordyn_system_reference.REFERENCE_SETTINGS`) is stored in
tests/data/systems/NAME_moordyn.nc (tests/io/moordyn_system_reference.py says how it was
produced and regenerates it), so the
slow tests run floatmoor only; a short run of the clump line checks the harness, the exported
deck and the start against a fresh MoorDyn run (slow too); the default run checks the stored
records.

Asserted over the whole record after the ramp: the fairlead tension histories agree within
:data:`TENSION_RANGE_FRACTION` of MoorDyn's tension range, their wave-frequency content
(harmonics of the motion up to 1 Hz) within :data:`LOW_FREQUENCY_RANGE_FRACTION`, and the
free points' positions within :data:`POINT_ATOL`.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.simulation.forced import run_forced_motion
from tests.io.moordyn_system_reference import (REFERENCE_SETTINGS, read_reference,
                                               reference_path)


pytestmark = pytest.mark.peer

SYSTEMS = Path(__file__).parents[1] / "data" / "systems"
#: Max |floatmoor - MoorDyn| of the fairlead tension after the ramp over MoorDyn's range, per
#: line (2 % required). Observed, floatmoor at its defaults against the stored records:
#: - lazy wave (MoorDyn 200 segments per section): 1.47 % (RMS 0.37 %), 1.46 % against the
#:   Richardson estimate of converged MoorDyn (its wave-frequency content moves 0.13 % then
#:   0.03 % of the range RMS from 50 to 100 to 200 segments: order 2.1); floatmoor at 20
#:   elements 0.54 %, at 40 0.23 %. Met.
#: - clump line (MoorDyn 200 segments): 2.16 % (RMS 0.42 %; 2.10 % against the Richardson
#:   estimate); NOT met at floatmoor's defaults (1.82 % at 20 elements). The wave-frequency
#:   content agrees within 0.25 %; the rest is the ringing (2-9 Hz, ~3 kN RMS in both codes)
#:   that each tension trough (t = 14-16 s, 24-26 s) sets off, whose phase neither code has
#:   converged: MoorDyn moves 2.9 % of the range from 100 to 200 segments, floatmoor 1.6 % from
#:   10 to 20 elements. The bound is the observed gap, so that it does not grow unnoticed.
TENSION_RANGE_FRACTION = {
    "chain_rope_chain_clump": 0.025,
    "lazy_wave_buoy": 0.02,
}
#: The required bound [-], met by both lines with floatmoor's sections at 20 elements (a
#: numerics choice, not a physical input: the clump line's ringing is not converged at the
#: default 10; floatmoor chooses numerics from an accuracy).
ISSUE_RANGE_FRACTION = 0.02
REFINED = ["lines.*.dynamic.elements=20"]
#: The same for the wave-frequency content: the least-squares fit of the harmonics of the
#: motion's period up to :data:`LOW_PASS_FREQUENCY` of both records (observed 0.25 % clump
#: line, 0.49 % lazy wave).
LOW_FREQUENCY_RANGE_FRACTION = 0.01
LOW_PASS_FREQUENCY = 1.0  # Hz: ten harmonics of the 10 s motion
#: Free points' positions, floatmoor against MoorDyn [m]: observed 0.016 m (clump), 0.018 m
#: (its chain-rope joint), 0.072 m (buoy) and 0.145 m (the lazy wave's massless chain-rope
#: joint, which moves 1 m; 0.038 m with floatmoor at 20 elements, 0.011 m at 40).
POINT_ATOL = 0.2
#: The short run: start (tension, relative; points [m]) and the whole 3 s record against the
#: mean tension.
START_RTOL = 5e-3  # observed 2.4e-3 (MoorDyn at 50 segments, TmaxIC 10 s)
START_ATOL = 0.01
SHORT_RTOL = 5e-3  # observed 0.16 % (coupling interval 0.4 ms)


def _low_pass(t: np.ndarray, y: np.ndarray, period: float) -> np.ndarray:
    """Least-squares fit of the harmonics of ``period`` up to :data:`LOW_PASS_FREQUENCY`."""
    w = 2.0 * np.pi / period
    n = int(round(LOW_PASS_FREQUENCY * period))
    basis = [np.ones_like(t)] + [f(k * w * t) for k in range(1, n + 1) for f in (np.cos, np.sin)]
    X = np.column_stack(basis)
    coef, *_ = np.linalg.lstsq(X, y, rcond=None)
    return X @ coef


@pytest.mark.slow
@pytest.mark.parametrize("name, overrides, bound", [
    *((name, [], TENSION_RANGE_FRACTION[name]) for name in sorted(REFERENCE_SETTINGS)),
    ("chain_rope_chain_clump", REFINED, ISSUE_RANGE_FRACTION),
], ids=["clump-defaults", "lazy-wave-defaults", "clump-20-elements"])
def test_fairlead_tension_and_points_match_converged_moordyn(name, overrides, bound):
    case = load_case(SYSTEMS / f"{name}.toml", overrides)
    ds = run_forced_motion(case).dataset
    ref = read_reference(name)
    t = ds["time"].values
    np.testing.assert_allclose(ref["time"].values, t)
    after = t >= case.motion.ramp_duration
    ours = ds["fairlead_tension"].sel(line="line1").values[after]
    theirs = ref["fairlead_tension"].values[after].astype(float)
    span = theirs.max() - theirs.min()
    error = np.abs(ours - theirs).max() / span
    period = case.motion.period[0]
    low = np.abs(_low_pass(t[after], ours, period)
                 - _low_pass(t[after], theirs, period)).max() / span
    points = {str(n): float(np.linalg.norm(
        ds["point_position"].sel(point=str(n)).values[after]
        - ref["point_position"].sel(point=n).values[after], axis=1).max())
        for n in ref["point"].values}
    print(f"\n{name}: tension range {span / 1e3:.1f} kN ({theirs.min() / 1e3:.1f} to "
          f"{theirs.max() / 1e3:.1f}); max difference {error:.2%} of it, "
          f"<= {LOW_PASS_FREQUENCY:g} Hz {low:.2%}; points (m) "
          f"{ {n: round(d, 3) for n, d in points.items()} }")
    assert theirs.min() > 0.1 * theirs.max()  # taut throughout: the cases' premise
    assert error <= bound
    assert low <= LOW_FREQUENCY_RANGE_FRACTION
    assert max(points.values()) <= POINT_ATOL


@pytest.mark.parametrize("name", sorted(REFERENCE_SETTINGS))
def test_stored_moordyn_records_say_how_they_were_made(name):
    """The stored records carry units and their provenance, and start at the statics both
    codes share (the mean tension before the motion, within the start tolerance)."""
    ref = read_reference(name)
    for var in ref.data_vars.values():
        assert var.attrs["units"] and var.attrs["long_name"]
    assert "moordyn_system_reference" in ref.attrs["regenerate"]
    scale = REFERENCE_SETTINGS[name][0]
    assert ref.attrs["segments_per_section"] == str(int(50 * scale))
    case = load_case(SYSTEMS / f"{name}.toml")
    from floatmoor.mooring.statics_solver import case_statics

    at_rest = case_statics(case).solve()
    fairlead = at_rest.forces_on("fairlead")
    tension = float(np.linalg.norm(sum(fairlead.values())))
    assert float(ref["fairlead_tension"].values[0]) == pytest.approx(tension, rel=START_RTOL)
    assert reference_path(name).stat().st_size < 200_000


@pytest.mark.slow  # a fresh MoorDyn run (16 s); the stored records are checked in the default run
def test_short_run_starts_at_the_statics_and_follows_moordyn():
    """The first 3 s of the clump line (a 2.5 s ramp) at the exported MoorDyn settings
    and a short MoorDyn start (TmaxIC 10 s is enough from the statics on this line): both codes
    start from the same equilibrium and follow each other within :data:`SHORT_RTOL` of the
    mean tension (a mapping error of the exported deck would show at once)."""
    pytest.importorskip("moordyn")
    from tests.io.moordyn_system_runner import run_moordyn_system

    case = load_case(SYSTEMS / "chain_rope_chain_clump.toml",
                     ["simulation.duration=3.0", "motion.ramp_duration=2.5"])
    ds = run_forced_motion(case).dataset
    t = ds["time"].values
    md = run_moordyn_system(case, t, ic_max_time=10.0)
    np.testing.assert_allclose(md.time, t)
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
