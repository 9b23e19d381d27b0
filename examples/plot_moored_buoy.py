"""
A moored buoy in regular waves
==============================

A 0.515 m cylinder buoy on three chains (case C) run coupled in regular waves for a few
seconds: the floater's motions (translations in m, rotations in degrees) and the tension at
both ends of each line, drawn with the same views as ``floatmoor run --plot``.
"""

# %%
# The case and its hydrodynamic database ship with floatmoor (``cases/cylinder_buoy``,
# ``hydrodb/cylinder_buoy.nc``). To keep the example short, the lines are quasi-static
# catenaries instead of the case's dynamic lines (whose explicit steps, set by the axial wave
# speed of the stiff chain, make a run take minutes), the wave ramp is cut to 2 s and the run
# to 8 s: the response is still settling, as the first periods of a run do.
import sys
from pathlib import Path

import floatmoor as fm
from floatmoor.plots.motions import draw_body_motions
from floatmoor.plots.tensions import draw_tensions

# The repository, from this script's path (sphinx-gallery runs it without __file__).
REPO = Path(sys.argv[0]).resolve().parents[1]
RAMP = 2.0  # s, cosine ramp of the wave excitation

case = fm.load_case(REPO / "cases" / "cylinder_buoy" / "buoy_regular_T1.00.toml",
                    ["simulation.duration=8.0", f"waves.ramp_duration={RAMP}",
                     'lines.*.model="quasi-static"'])
result = fm.run_coupled(case)
dataset = result.dataset
print(case.title)
print(f"simulated {dataset.attrs['simulated_time_s']} s in {dataset.attrs['wall_time_s']:.2f} s")

# %%
# Surge, heave and pitch move; sway, roll and yaw stay at rest (waves along x on an
# axisymmetric buoy) and are named in the title instead of drawn.
draw_body_motions(dataset, ramp_duration=RAMP)

# %%
# Line 3 points down-wave (+x), lines 1 and 2 up-wave at 120 and 240 degrees.
draw_tensions(dataset, ramp_duration=RAMP)
