"""The full-scale cases on which the accuracy defaults of the dynamic line are judged
(docs/validation/dynamic_line.md#the-accuracy-defaults-on-full-scale-lines), built in a
folder of the test's: a test helper, not a test file (test_fullscale_accuracy.py uses it).

- OC4: OpenFAST's MoorDyn r-test md_5MW_OC4Semi (three 835 m chains in 200 m of water),
  imported with its driver, under its own 60 s platform motion (a transient: no period), or
  the first 40 s of it (a table shorter than the check's probe of 60 s's);
- DeepCwind: the three LC34 lines alone (tests/data/references/deepcwind_lines_forced.toml)
  each under its recorded fairlead path (deepcwind_lc34_fairleads_600s.nc, 600 s of an
  irregular sea) as a motion table of its own;
- N20: the r-test md_Node_Check_N20 chain (1800 m in 600 m of water, a FAST.Farm deck with no
  motion of its own), its top point surged 5 m at 10 s after a 20 s ramp, 6 cycles.

The statistics judged (:func:`judged_statistics`): each line's fairlead-tension STD and mean
of per-cycle maxima from the window start on, the cycles being the motion's period or, for a
table (no period), windows of the period 2 pi / omega the rule and the check use (omega the
table's mean zero-crossing frequency, :mod:`floatmoor.motion.frequency`).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import xarray as xr

from floatmoor.case.schema import Case
from floatmoor.cli import main
from floatmoor.post.statistics import channel_statistics
from tests.conftest import REPO

RTEST = REPO / "tests" / "data" / "moordyn" / "rtest"
REFERENCES = REPO / "tests" / "data" / "references"
#: The overrides that leave a line's numerics to its accuracy (the default 1 %).
AUTO = ['lines.*.dynamic.elements="auto"', 'lines.*.dynamic.order="auto"']
#: Where the judged window starts [s]: OC4 from its first sample (no ramp: the lines start in
#: the motion's first pose), DeepCwind after the first 60 s of the record (as
#: tests/data/references/deepcwind_lines_forced_study.json), N20 after its ramp.
WINDOW_START = {"oc4": 0.0, "deepcwind": 60.0, "n20": 20.0}

N20_MOTION = """
[motion]  # the deck's top point surged 5 m at 10 s (the deck itself has no motion)
kind = "body"
reference_point = [0.0, 0.0, 0.0]
ramp_duration = 20.0

[motion.surge]
amplitude = 5.0
period = 10.0
"""


def _import(folder: Path, deck: str, name: str) -> Path:
    out = folder / f"{name}.toml"
    code = main(["import", "moordyn", str(RTEST / deck / ("test.dat" if deck ==
                 "md_Node_Check_N20" else "moordyn.dat")), "--driver",
                 str(RTEST / deck / "md_driver.inp"), "-o", str(out)])
    assert code == 0
    return out


def oc4_case(folder: Path, end: float | None = None) -> Path:
    """The OC4 r-test case, imported into ``folder``; with ``end``, its motion table and run
    cut at the last row at or before ``end`` [s]."""
    path = _import(folder, "md_5MW_OC4Semi", "oc4")
    if end is None:
        return path
    table = folder / "oc4_motion.csv"
    rows = table.read_text().splitlines()
    kept = [r for r in rows if not r[:1].isdigit() or float(r.split(",")[0]) <= end]
    table.write_text("\n".join(kept) + "\n")
    last = float(kept[-1].split(",")[0])
    text = path.read_text()
    assert "duration = 60.0  #" in text
    path.write_text(text.replace("duration = 60.0  #", f"duration = {last!r}  #"))
    return path


def n20_case(folder: Path) -> Path:
    """The md_Node_Check_N20 case, imported into ``folder``, its top point driven."""
    path = _import(folder, "md_Node_Check_N20", "n20")
    text = path.read_text()
    fixed = 'name = "point1"  # POINTS 1 (line 11): Fixed\nkind = "fixed"'
    assert fixed in text
    text = text.replace(fixed, 'name = "point1"  # POINTS 1: driven here\nkind = "body"')
    text = text.replace("duration = 60.0225", "duration = 80.0")
    text = text.replace("output_interval = 0.2  #", "output_interval = 0.05  #")
    path.write_text(text + N20_MOTION)
    return path


def deepcwind_line_case(folder: Path, line: str) -> Path:
    """DeepCwind ``line`` alone under its recorded LC34 fairlead path, a case in ``folder``
    (its fairlead at the path's first point, the table its displacement from there)."""
    base = (REFERENCES / "deepcwind_lines_forced.toml").read_text()
    head, *blocks = base.split("[[lines]]")
    block = next(b for b in blocks if f'name = "{line}"' in b).split("[simulation]")[0]
    with xr.open_dataset(REFERENCES / "deepcwind_lc34_fairleads_600s.nc") as ds:
        time = ds["time"].values
        path = ds["fairlead_position"].sel(line=line).values
    rows = "\n".join(f"{t:.4f},{dx:.9g},{dy:.9g},{dz:.9g}"
                     for t, (dx, dy, dz) in zip(time, path - path[0]))
    (folder / f"{line}_path.csv").write_text("time,x,y,z\n" + rows + "\n")
    start = ", ".join(repr(float(c)) for c in path[0])
    block = "\n".join(f"fairlead = [{start}]" if row.startswith("fairlead") else row
                      for row in block.splitlines())
    case = folder / f"{line}.toml"
    case.write_text(head + "[[lines]]" + block + f"""
[simulation]
duration = 600.0
output_interval = 0.1

[motion]
kind = "table"
file = "{line}_path.csv"
ramp_duration = 0.0
""")
    return case


def judged_statistics(case: Case, dataset: xr.Dataset, start: float
                      ) -> dict[str, tuple[float, float]]:
    """Per line, the fairlead tension's (STD, mean per-cycle maximum) [N] from ``start`` on
    (module docstring)."""
    period = case.motion.cycle_period or 2.0 * math.pi / case.lines[0].dynamic.motion_frequency
    time = dataset["time"].values
    out = {}
    for line in case.lines:
        tension = dataset["fairlead_tension"].sel(line=line.name).values
        stats = channel_statistics(time, np.asarray(tension), start=start, period=period)
        out[line.name] = (float(stats["std"]), float(stats["mean_cycle_max"]))
    return out
