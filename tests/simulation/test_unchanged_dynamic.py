"""The dynamic line's new numerics leave the validations unchanged within 0.5 %.

Recomputes, with the case files as shipped, the figures of ``unchanged_dynamic.py`` (the
Lindahl validation, the quasi-dynamic study's figures, the DeepCwind decays) and compares them
with those of the code before them (``tests/data/references/issue17_unchanged.json``, its
provenance inside). What "within 0.5 %" means for each figure:

- Lindahl, each of the 30 runs (r x T): the mean cycle maximum of the fairlead tension within
  0.5 % of the stored one; the **waveform**: the RMS over the cycle of the difference between the
  mean cycle and the stored one (both phase-averaged over the same six cycles, phase 0 at the end
  of the ramp, so no realignment), relative to the stored cycle's range (max - min), within
  0.5 %: a change of the whole shape, not only of the peak, that is 0.5 % of the tension swing.
  With a measured cycle (r = 0.2 m, T = 1.25 s and 3.5 s): the aligned RMS difference to the
  measured cycle, a fraction of the measured peak, within 0.5 % of that peak of the stored
  fraction, and the alignment shift within 0.5 % of the period.
- QD study, each run: the error measures RMSE_QD, RMSE_S, e_Tmin, e_Tmax (fractions of T_S0 or
  of the dynamic maximum, shown in % by the study's figures) within 0.5 percentage points of the
  stored ones (0.5 % of their reference, not of themselves: a relative bound on a 1 % error
  would be a bound on noise); the dynamic model's last cycle (figure 6): its maximum within
  0.5 %, and the RMS of its difference to the stored cycle within 0.5 % of T_S0. The ``--quick``
  subset (12 runs); all 180 with ``FLOATMOOR_UNCHANGED_QD_FULL=1`` (if the reference holds them;
  about 20 minutes).
- DeepCwind decays (quasi-static, quasi-dynamic and dynamic lines): every surge peak, every
  period (release to the first peak, then peak to peak) and every cycle's damping ratio (from
  the logarithmic decrement) within 0.5 %. The damping ratio is the most sensitive: 0.5 % on
  both peaks of a cycle can move it by ~2.5 % at these decrements.

The Lindahl snap runs (T = 1.25 s) scatter by ~1 % from cycle to cycle (chaotically: any change
of the numerics reshuffles it, tests/benchmarks/moordyn_lindahl.py), so their six-cycle means
carry ~0.4 % of noise; the stored per-cycle maxima show it. About 3 minutes in all (8 of the
30 Lindahl runs take 2-3 s each; the dynamic decay half a minute).

Run: ``python -m pytest -m slow tests/simulation/test_unchanged_dynamic.py -s``.
"""

from __future__ import annotations

import functools
import os
import re
from typing import Any

import numpy as np
import pytest

from floatmoor.studies import qd_verification as qdv
from tests.simulation.unchanged_dynamic import (DECAY_MODELS, decay_figures, lindahl_figures,
                                                load_baseline, qd_figures)

pytestmark = [pytest.mark.slow, pytest.mark.validation]

#: The bound: "Unchanged within 0.5 %: the Lindahl validation, the QD study's figures,
#: the DeepCwind decays."
UNCHANGED_RTOL = 0.005

BASELINE = load_baseline()
LINDAHL = {(c["radius"], c["period"]): c for c in BASELINE["lindahl"]["cases"]}
QD_KEY = "qd_full" if os.environ.get("FLOATMOOR_UNCHANGED_QD_FULL") == "1" else "qd_quick"
QD = {r["label"]: r for r in BASELINE[QD_KEY]["runs"]}
#: The dynamic resolution the baseline's QD runs were computed with (its "how"; the study's
#: own reference may since have been refined).
QD_ELEMENTS = int(re.search(r"dynamic (\d+) elements", BASELINE[QD_KEY]["how"]).group(1))


def _relative(now: float, before: float) -> float:
    return now / before - 1.0


def _check(failures: list[str], what: str, change: float, unit: str = "%") -> None:
    """Append ``what`` to ``failures`` when |change| exceeds the bound (change a fraction)."""
    if not abs(change) <= UNCHANGED_RTOL:
        failures.append(f"{what}: {100 * change:+.3f} {unit} (bound {100 * UNCHANGED_RTOL:g} "
                        f"{unit})")


@functools.cache
def _lindahl(radius: float, period: float) -> dict[str, Any]:
    return lindahl_figures(radius, period)


@pytest.mark.parametrize("radius, period", list(LINDAHL), ids=[f"r{r:.3f}-T{t:.2f}"
                                                            for r, t in LINDAHL])
def test_lindahl_run_unchanged(radius, period):
    before, now = LINDAHL[radius, period], _lindahl(radius, period)
    name = f"Lindahl r = {radius:.3f} m, T = {period:.2f} s"
    failures: list[str] = []
    change = _relative(now["mean_cycle_max_N"], before["mean_cycle_max_N"])
    _check(failures, f"{name}: mean cycle maximum {now['mean_cycle_max_N']:.3f} N against "
           f"{before['mean_cycle_max_N']:.3f} N", change)
    difference = np.asarray(now["mean_cycle_N"]) - np.asarray(before["mean_cycle_N"])
    waveform = float(np.sqrt(np.mean(difference**2))) / before["cycle_range_N"]
    _check(failures, f"{name}: mean cycle, RMS difference to the stored one relative to its "
           f"range {before['cycle_range_N']:.2f} N", waveform, "% of the range")
    print(f"\n{name}: mean cycle max {now['mean_cycle_max_N']:.3f} N ({100 * change:+.3f} %), "
          f"waveform RMS change {100 * waveform:.3f} % of the range")
    assert not failures, "\n".join(failures)


@pytest.mark.parametrize("radius, period", [k for k, c in LINDAHL.items() if "measured" in c],
                         ids=lambda v: f"{v:g}")
def test_lindahl_measured_cycle_comparison_unchanged(radius, period):
    before = LINDAHL[radius, period]["measured"]
    now = _lindahl(radius, period)["measured"]
    name = f"Lindahl r = {radius:.3f} m, T = {period:.2f} s against the measured cycle"
    failures: list[str] = []
    _check(failures, f"{name}: aligned RMS difference {100 * now['rms_relative_to_peak']:.2f} % "
           f"of the measured peak against {100 * before['rms_relative_to_peak']:.2f} %",
           now["rms_relative_to_peak"] - before["rms_relative_to_peak"], "% of the peak")
    shift = (now["shift_s"] - before["shift_s"] + 0.5 * period) % period - 0.5 * period
    _check(failures, f"{name}: alignment shift {now['shift_s']:.4f} s against "
           f"{before['shift_s']:.4f} s", shift / period, "% of the period")
    print(f"\n{name}: RMS {100 * now['rms_relative_to_peak']:.2f} % of the peak (stored "
          f"{100 * before['rms_relative_to_peak']:.2f} %), shift {now['shift_s']:.4f} s "
          f"(stored {before['shift_s']:.4f} s)")
    assert not failures, "\n".join(failures)


@pytest.mark.parametrize("label", list(QD))
def test_qd_study_run_unchanged(label):
    before = QD[label]
    spec = qdv.RunSpec(before["config"], before["amplitude_index"], before["alpha_index"],
                       QD_ELEMENTS)
    now = qd_figures(spec)
    name = f"QD study {label}"
    failures: list[str] = []
    for key in ("rmse_qd", "rmse_s", "e_tmin", "e_tmax"):
        _check(failures, f"{name}: {key} {100 * now[key]:.3f} % against "
               f"{100 * before[key]:.3f} %", now[key] - before[key], "percentage points")
    cycle_now, cycle_before = (np.asarray(r["dynamic_cycle_N"]) for r in (now, before))
    _check(failures, f"{name}: dynamic cycle maximum {cycle_now.max():.4f} N against "
           f"{cycle_before.max():.4f} N", _relative(cycle_now.max(), cycle_before.max()))
    rms = float(np.sqrt(np.mean((cycle_now - cycle_before) ** 2))) / before["t_s0_N"]
    _check(failures, f"{name}: dynamic cycle, RMS difference to the stored one relative to "
           f"T_S0 = {before['t_s0_N']:.4f} N", rms, "% of T_S0")
    print(f"\n{name}: " + ", ".join(f"{k} {100 * now[k]:.2f} % ({100 * before[k]:.2f} %)"
                                    for k in ("rmse_qd", "rmse_s", "e_tmin", "e_tmax"))
          + f"; dynamic cycle RMS change {100 * rms:.3f} % of T_S0")
    assert not failures, "\n".join(failures)


@pytest.mark.parametrize("model", DECAY_MODELS)
def test_deepcwind_decay_unchanged(model):
    before = BASELINE["decays"]["models"][model]
    now = decay_figures(model)
    name = f"DeepCwind surge decay, {model} lines"
    failures: list[str] = []
    if len(now["peaks_m"]) != len(before["peaks_m"]):
        failures.append(f"{name}: {len(now['peaks_m'])} surge peaks against "
                        f"{len(before['peaks_m'])}")
    for key, label in (("peaks_m", "peak [m]"), ("periods_s", "period [s]"),
                       ("damping_ratios", "damping ratio")):
        for k, (a, b) in enumerate(zip(now[key], before[key]), 1):
            _check(failures, f"{name}: cycle {k} {label} {a:.5g} against {b:.5g}",
                   _relative(a, b))
    print(f"\n{name}: periods {np.round(now['periods_s'], 3)} s (stored "
          f"{np.round(before['periods_s'], 3)}), damping ratios "
          f"{np.round(now['damping_ratios'], 4)} (stored {np.round(before['damping_ratios'], 4)})")
    assert not failures, "\n".join(failures)
