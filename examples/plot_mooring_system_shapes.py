"""
Line shapes of a mooring system
===============================

Three chain-rope-chain lines with a clump weight and a subsurface buoy each, held by a vessel
that surges, heaves and pitches: the quasi-static line shapes at rest and at three instants of
the motion, in side and plan views with the seabed, the still water line, the anchors and the
touchdown points.
"""

# %%
# The system ships as ``cases/systems/three_line_clump_buoy.toml`` (100 m of water, 76 mm chain
# and 160 mm polyester rope). Every line is quasi-static: at each instant the clump weights
# and buoys take the positions where the catenary sections between them balance their weight
# and buoyancy. The run stops after the 12 s ramp and the first 12 s cycle.
import sys
from pathlib import Path

import floatmoor as fm
from floatmoor.io.shape_samples import nearest_shape_samples
from floatmoor.plots.context import run_context
from floatmoor.plots.shapes import draw_line_shapes

# The repository, from this script's path (sphinx-gallery runs it without __file__).
REPO = Path(sys.argv[0]).resolve().parents[1]

case = fm.load_case(REPO / "cases" / "systems" / "three_line_clump_buoy.toml",
                    ["simulation.duration=24.0"])
result = fm.run_case(case)
dataset = result.dataset

# %%
# The shapes are stored every ``simulation.shape_output_interval`` (3 s here); draw the rest
# position and a quarter, a half and three quarters of the first cycle after the ramp.
samples = nearest_shape_samples(dataset, [0.0, 15.0, 18.0, 21.0])
draw_line_shapes(dataset, samples, run_context(dataset))

# %%
# The fairlead tensions over the same run, in kN.
tension = dataset["fairlead_tension"] / 1e3
for line in tension["line"].values:
    t = tension.sel(line=line)
    print(f"{line}: fairlead tension {float(t.min()):.0f} to {float(t.max()):.0f} kN")
