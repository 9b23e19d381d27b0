"""
Dynamic similitude: a model chain and its prototype
===================================================

The Lindahl chain scaled to the 1240 m prototype it models (length scale 37.6): the
dimensionless groups of both cases, and their fairlead tensions in dimensionless form, which
coincide when the scaled case keeps every group of the cable equation.
"""

# %%
# The law is the chain-experiment paper's (Bergdahl, Palm, Eskilsson & Lindahl 2016, J. Mar.
# Sci. Eng. 4(1):5, section 3.1): lengths times lambda = 37.6, the diameter 2.2 mm -> 76 mm
# (beta = 34.5), the volume coefficient times phi = 1.296. The water stays fresh here, so
# every group alpha_1 to alpha_5 is kept (with sea water, alpha_3 would change by 0.35 %).
# Both runs start the line from its catenary (``settle = false``), so that they start from
# similar states too, and stop after the ramp and two cycles.
import sys
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import floatmoor as fm
from floatmoor.similitude import ScaleLaw, cable_groups
from floatmoor.similitude.case_scaling import scale_case_file

# The repository, from this script's path (sphinx-gallery runs it without __file__).
REPO = Path(sys.argv[0]).resolve().parents[1]
MODEL = REPO / "cases" / "lindahl" / "lindahl_r0.20_T1.25.toml"
law = ScaleLaw(length=37.6, diameter=76.0 / 2.2, volume_coefficient=1.29578)

model = fm.load_case(MODEL)
period, ramp = model.motion.period, model.motion.ramp_duration
short = ["lines.chain.dynamic.settle=false"]
model = fm.load_case(MODEL, short + [f"simulation.duration={ramp + 2 * period}"])

with tempfile.TemporaryDirectory() as folder:
    path = Path(folder) / "lindahl_prototype.toml"
    scaled = scale_case_file(MODEL, law, output=path)
    path.write_text(scaled.text, encoding="utf-8")
    prototype = fm.load_case(path, short + [
        f"simulation.duration={(ramp + 2 * period) * law.time}"])
print(f"groups kept exactly: {', '.join(scaled.kept)}")
for group, (low, high) in scaled.changed.items():  # new / old over the line's sections
    ratio = f"{low:.4g}" if low == high else f"{low:.4g} to {high:.4g}"
    print(f"not kept: {group}, new / old = {ratio}")

# %%
# The groups of both cases, one row per line section.
groups = {"model": cable_groups(model), "prototype": cable_groups(prototype)}
for name, g in groups.items():
    values = ", ".join(f"{k} = {float(g[k].values[0]):.4g}"
                       for k in ("alpha_1", "alpha_2", "alpha_3", "alpha_4", "alpha_5",
                                 "reynolds_number"))
    print(f"{name}: {values}")


# %%
# Tension over the submerged weight of the line, w L, against time over the period: the two
# curves lie on each other.
fig, ax = plt.subplots(figsize=(8.0, 4.0))
curves = []
for name, case, style in (("model, L = 33 m, T = 1.25 s", model, "-"),
                          ("prototype, L = 1241 m, T = 7.66 s", prototype, "--")):
    dataset = fm.run_forced_motion(case).dataset
    line = case.lines[0]
    weight = line.line_type.weight_in_water(case.environment)  # w [N/m]
    tension = dataset["fairlead_tension"].sel(line=line.name).values / (weight * line.length)
    ax.plot(dataset["time"] / case.motion.period, tension, style, label=name)
    curves.append(tension)
gap = np.max(np.abs(curves[1] - curves[0])) / np.max(curves[0])
print(f"largest difference of the dimensionless tensions: {gap:.1e} of the peak")
ax.axvspan(0.0, ramp / period, color="0.9", label="ramp")
ax.set(xlabel="t / T [-]", ylabel="fairlead tension / (w L) [-]",
       title="Lindahl chain at model and prototype scale")
ax.grid(alpha=0.3)
ax.legend(loc="upper left", fontsize=8)
fig.tight_layout()
