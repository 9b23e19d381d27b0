"""The dynamic line against MoorDyn 2.7 run fine, on a forced catenary case without slack.

The Lindahl chain (docs/cases/lindahl.md) with its upper end on a circle of r = 0.1 m every 3 s:
touchdown on the seabed, drag, added mass, the top in air, tension never near zero. Seabed
friction is off in both codes: MoorDyn ramps it linearly, floatmoor with the sine of
docs/theory/cable.md, and this test compares the cable dynamics, not friction models.
"""

from __future__ import annotations

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.simulation.forced import run_forced_motion
from tests.conftest import LINDAHL_CASE


pytestmark = pytest.mark.peer

moordyn_runner = pytest.importorskip("tests.io.moordyn_runner")

#: Required: the fairlead tension history agrees with MoorDyn run fine within 2 % of the
#: tension range (after the ramp).
RANGE_FRACTION = 0.02
#: MoorDyn "run fine": 80 segments at 50 us is within 0.3 % of its 160-segment converged
#: snap maximum on this chain (tests/benchmarks/moordyn_lindahl.py).
MOORDYN_SEGMENTS, MOORDYN_DT = 80, 5e-5

PERIOD, RADIUS = 3.0, 0.1
OVERRIDES = [f"motion.period={PERIOD}", f"motion.radius={RADIUS}",
             f"motion.ramp_duration={2 * PERIOD}", f"simulation.duration={4 * PERIOD}",
             "seabed.friction_coefficient=0.0", "simulation.output_interval=0.001",
             'lines.chain.model="dynamic"']


@pytest.mark.slow  # ~7 s, a peer comparison; the MoorDyn round trips stay in the default run
def test_fairlead_tension_history_matches_moordyn():
    case = load_case(LINDAHL_CASE, OVERRIDES)
    ds = run_forced_motion(case).dataset.sel(line="chain")
    t = ds["time"].values
    ours = ds["fairlead_tension"].values
    position = ds["fairlead_position"].values
    from floatmoor.motion.fairlead import fairlead_state

    _, velocity = fairlead_state(case.motion, case.lines[0], t)
    line = case.lines[0]
    lt = line.line_type
    md_line = moordyn_runner.MoorDynLine(
        line.length, lt.mass_per_length, lt.axial_stiffness, lt.diameter, lt.material_density,
        lt.normal_drag_coefficient, lt.tangential_drag_coefficient, lt.added_mass_coefficient,
        anchor=line.anchor, fairlead=line.fairlead, water_depth=case.environment.water_depth,
        water_density=case.environment.water_density, gravity=case.environment.gravity,
        seabed_stiffness=case.seabed.stiffness, seabed_damping_ratio=case.seabed.damping_ratio,
        friction_coefficient=0.0, slip_speed=case.seabed.slip_speed)
    t_md, theirs, wall = moordyn_runner.run_moordyn_forced(
        md_line, t, position, velocity, segments=MOORDYN_SEGMENTS, dt=MOORDYN_DT)
    np.testing.assert_allclose(t_md, t)
    after = t >= case.motion.ramp_duration
    tension_range = theirs[after].max() - theirs[after].min()
    difference = np.abs(ours[after] - theirs[after])
    print(f"\ntension range {tension_range:.2f} N (min {theirs[after].min():.2f} N); max "
          f"difference {difference.max():.3f} N = {difference.max() / tension_range:.2%} of "
          f"the range, RMS {np.sqrt(np.mean(difference ** 2)) / tension_range:.2%}; "
          f"maxima {ours[after].max():.3f} / {theirs[after].max():.3f} N; MoorDyn {wall:.1f} s")
    assert theirs[after].min() > 0.1 * theirs[after].max()  # no slack: the case's premise
    assert difference.max() <= RANGE_FRACTION * tension_range
