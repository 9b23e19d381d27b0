"""
The Lindahl chain against the measured force cycle
==================================================

The dynamic line model of a 33 m chain whose upper end moves on a circle (Lindahl's 1985
experiment, case A), run for three motion cycles after the ramp and compared, once phase
averaged and aligned, with the measured mean fairlead force and its cycle-to-cycle scatter.
"""

# %%
# The case file ships in ``cases/lindahl``; the measured cycle, phase-averaged from the
# published records of Bergdahl, Palm, Eskilsson & Lindahl (2016, J. Mar. Sci. Eng. 4(1):5,
# doi:10.3390/jmse4010005), in ``tests/data/lindahl``. Three cycles after the two-period ramp
# keep the run short; ``floatmoor run`` runs the case's ten.
import sys
from pathlib import Path

import matplotlib.pyplot as plt

import floatmoor as fm
from floatmoor.post.comparison import align_cycles, phase_average, read_measured_cycle

# The repository, from this script's path (sphinx-gallery runs it without __file__).
REPO = Path(sys.argv[0]).resolve().parents[1]
PERIOD = 1.25    # s, the motion period of the case
CYCLES = 3       # cycles averaged after the ramp

case = fm.load_case(REPO / "cases" / "lindahl" / "lindahl_r0.20_T1.25.toml")
ramp = case.motion.ramp_duration
case = fm.load_case(case.source, [f"simulation.duration={ramp + CYCLES * PERIOD}"])
result = fm.run_forced_motion(case)
tension = result.dataset["fairlead_tension"].sel(line="chain")

# %%
# Phase averaging from the end of the ramp (a whole number of periods), then the circular
# time shift that best lays the simulated cycle onto the measured one.
measured = read_measured_cycle(
    REPO / "tests" / "data" / "lindahl" / "lindahl_measured_cycle_T1.25_r0.20.csv")
phase_time, simulated = phase_average(tension["time"].values, tension.values,
                                      period=PERIOD, start=ramp)
fit = align_cycles(measured.time_in_cycle, measured.mean, phase_time, simulated,
                   period=PERIOD)
print(f"peak: simulated {fit.candidate_peak:.1f} N, measured {fit.reference_peak:.1f} N; "
      f"RMS difference {100 * fit.rms_relative_to_peak:.1f} % of the measured peak")

fig, (history, cycle) = plt.subplots(2, 1, figsize=(8.0, 7.0))
history.plot(tension["time"], tension, lw=0.9)
history.axvspan(0.0, ramp, color="0.9", label="ramp")
history.set(xlabel="time [s]", ylabel="fairlead tension [N]",
            title="simulated fairlead tension, r = 0.20 m, T = 1.25 s")
history.legend(loc="upper left")
cycle.fill_between(measured.time_in_cycle, measured.mean - measured.std,
                   measured.mean + measured.std, color="0.8",
                   label="measured, mean $\\pm$ 1 std")
cycle.plot(measured.time_in_cycle, measured.mean, color="k", lw=1.2, label="measured mean")
cycle.plot(fit.time, fit.aligned_candidate, color="C3", lw=1.2,
           label=f"simulated, {CYCLES}-cycle mean, aligned")
cycle.set(xlabel="time in cycle [s]", ylabel="fairlead tension [N]",
          title=f"one cycle: RMS difference {100 * fit.rms_relative_to_peak:.1f} % of the peak")
cycle.legend(loc="upper right")
for ax in (history, cycle):
    ax.grid(alpha=0.3)
fig.tight_layout()
