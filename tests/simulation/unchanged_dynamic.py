"""The "unchanged" figures of the dynamic line: what the validations judge, computed.

The dynamic (DG) line's numerics changed (accuracy-chosen discretisation, implicit time
integration) on the condition that three validations stay within 0.5 %: the Lindahl validation, the
quasi-dynamic (QD) study's figures and the DeepCwind decays. This module computes the figures
those validations judge, with the case files as shipped; ``issue17_unchanged.json`` in
tests/data/references holds them from the code before the change, and
``test_unchanged_dynamic.py`` recomputes and compares them.

- **Lindahl** (tests/simulation/lindahl.py, test_lindahl.py, test_lindahl_robustness.py): the
  30 experiment runs, radii 0.075-0.2 m x periods 1.25-3.5 s (docs/cases/lindahl.md), each as the
  validation runs it (:func:`run_lindahl`: two ramp periods, six cycles): the mean of the
  per-cycle maxima of the fairlead tension, the maxima, and the mean cycle (phase time 0 at the
  end of the ramp) at :data:`WAVEFORM_POINTS` phase points; for the two runs with a measured
  cycle (r = 0.2 m, T = 1.25 s and 3.5 s) the alignment onto it (RMS difference relative to the
  measured peak, shift). The robustness grid's maxima are judged only for order and bounds,
  not for values, and its per-order test pins the discretisation: neither is stored.
- **QD study** (floatmoor/studies/qd_verification.py): every figure involves the dynamic model,
  the study's reference (figure 6 draws its cycles, figures 7 and 8 and the summary are the
  error measures against it). Per run: T_S0, RMSE_QD, RMSE_S, e_Tmin, e_Tmax and the dynamic
  model's last cycle (the stored :data:`qdv.PHASE_POINTS` phase samples). The ``--quick``
  subset (12 runs) always; the full 180 with ``--qd-full`` (about 20 minutes in one process).
- **DeepCwind decays** (test_deepcwind_decay.py, deepcwind_decay.py): surge free decay from
  16.58 m with quasi-static, quasi-dynamic and dynamic lines: the positive surge peaks and their
  times, the period (time to each return peak from the previous one, the first from the release)
  and the damping ratio of each cycle from the logarithmic decrement of successive peaks (the
  first from the release offset).

Write the reference (today's code; about 2 minutes, 20 more with ``--qd-full``)::

    PYTHONPATH=. python -m tests.simulation.unchanged_dynamic --write [--qd-full]

Without ``--write`` the figures are only printed.
"""

from __future__ import annotations

import argparse
import datetime
import json
import math
import platform
import re
import subprocess
import sys
import time
from collections.abc import Iterable, Sequence
from importlib.metadata import version
from typing import Any

import numpy as np

from floatmoor.post.comparison import phase_average
from floatmoor.post.statistics import cycle_maxima
from floatmoor.studies import qd_verification as qdv
from tests.conftest import REPO
from tests.simulation.deepcwind_decay import DURATION as DECAY_DURATION
from tests.simulation.deepcwind_decay import OFFSET as DECAY_OFFSET
from tests.simulation.deepcwind_decay import surge_decay
from tests.simulation.lindahl import DEFAULT_CYCLES, RAMP_PERIODS, run_lindahl

#: The stored figures of the code before those numerics.
BASELINE = REPO / "tests" / "data" / "references" / "issue17_unchanged.json"
#: The 30 Lindahl experiment runs (docs/cases/lindahl.md): radii [m] x periods [s].
LINDAHL_RADII = (0.075, 0.100, 0.125, 0.150, 0.200)
LINDAHL_PERIODS = (1.25, 1.5, 2.0, 2.5, 3.0, 3.5)
#: Phase points of the stored Lindahl mean cycles (500 samples per cycle at T = 1.25 s: every
#: other one, enough to follow the snap, small enough to store 30 of them).
WAVEFORM_POINTS = 250
#: Significant digits of the stored histories and lists (1e-8 relative: far below the 0.5 %
#: compared; the single figures keep all theirs).
STORED_DIGITS = 8
#: Line models of the DeepCwind decays.
DECAY_MODELS = ("quasi-static", "quasi-dynamic", "dynamic")


def lindahl_figures(radius: float, period: float, overrides: Sequence[str] = ()
                    ) -> dict[str, Any]:
    """One Lindahl run as the validation runs it (dynamic line, the case file's numerics
    unless ``overrides`` change them).

    Returns
    -------
    dict
        ``radius`` [m], ``period`` [s], ``mean_cycle_max_N``, ``cycle_maxima_N``,
        ``mean_cycle_N`` (:data:`WAVEFORM_POINTS` phase points from the end of the ramp),
        ``cycle_range_N`` (its max - min), ``wall_time_s``; with a measured cycle also
        ``measured``: ``rms_relative_to_peak``, ``rms_N``, ``shift_s``, ``measured_peak_N``.
    """
    result = run_lindahl(period, radius=radius, model="dynamic", extra_overrides=overrides)
    _, cycle = phase_average(result["time"], result["tension"], period=result["period"],
                             start=result["ramp"], n_phase=WAVEFORM_POINTS)
    maxima = cycle_maxima(result["time"], result["tension"], start=result["ramp"],
                          period=result["period"])  # those behind mean_cycle_max
    out: dict[str, Any] = {
        "radius": float(radius), "period": float(period),
        "mean_cycle_max_N": float(result["mean_cycle_max"]),
        "cycle_maxima_N": [float(m) for m in maxima],
        "mean_cycle_N": [float(v) for v in cycle],
        "cycle_range_N": float(cycle.max() - cycle.min()),
        "wall_time_s": float(result["wall_time_s"]),
    }
    alignment = result["alignment"]
    if alignment is not None:
        out["measured"] = {"rms_relative_to_peak": float(alignment.rms_relative_to_peak),
                           "rms_N": float(alignment.rms_difference),
                           "shift_s": float(alignment.shift),
                           "measured_peak_N": float(alignment.reference_peak)}
    return out


def qd_figures(spec: qdv.RunSpec) -> dict[str, Any]:
    """One run of the QD study (:func:`qdv.evaluate`: the three models, the study's numerics).

    Returns
    -------
    dict
        ``label`` (``C11 A1 alpha 0.3``), ``config``, ``amplitude_index``, ``alpha_index``,
        ``t_s0_N``, ``rmse_qd``, ``rmse_s``, ``e_tmin``, ``e_tmax`` (fractions, as the study),
        ``dynamic_cycle_N`` (the dynamic tension over the last cycle at the study's phase
        points), ``seconds``.
    """
    res = qdv.evaluate(spec)
    if res["error"]:
        raise RuntimeError(f"QD study run {qdv.run_label(spec)} failed: {res['error']}")
    dynamic = res["cycle"][qdv.MODELS.index("dynamic")]
    return {"label": qdv.run_label(spec), "config": spec.config,
            "amplitude_index": spec.amplitude_index, "alpha_index": spec.alpha_index,
            "t_s0_N": res["t_s0"], "rmse_qd": res["rmse_qd"], "rmse_s": res["rmse_s"],
            "e_tmin": res["e_tmin"], "e_tmax": res["e_tmax"],
            "dynamic_cycle_N": [float(v) for v in dynamic], "seconds": res["seconds"]}


def decay_figures(model: str) -> dict[str, Any]:
    """The DeepCwind surge decay with ``model`` lines (tests/simulation/deepcwind_decay.py).

    Returns
    -------
    dict
        ``model``, ``peak_times_s``, ``peaks_m``, ``periods_s`` (from the release to the first
        peak, then between successive peaks), ``damping_ratios`` (per cycle, from the
        logarithmic decrement delta = ln(a_k / a_k+1) of successive peaks, the first from the
        release offset: zeta = delta / sqrt(4 pi^2 + delta^2)), ``wall_time_s``.
    """
    decay = surge_decay(model)
    amplitudes = np.concatenate(([DECAY_OFFSET], decay.peaks))
    delta = np.log(amplitudes[:-1] / amplitudes[1:])
    return {"model": model,
            "peak_times_s": [float(t) for t in decay.peak_times],
            "peaks_m": [float(p) for p in decay.peaks],
            "periods_s": [float(p) for p in np.diff(np.concatenate(([0.0], decay.peak_times)))],
            "damping_ratios": [float(z) for z in delta / np.sqrt(4.0 * math.pi**2 + delta**2)],
            "wall_time_s": decay.wall_time_s}


def load_baseline() -> dict[str, Any]:
    """The stored figures (:data:`BASELINE`)."""
    return json.loads(BASELINE.read_text())


def _commit() -> str:
    run = subprocess.run(["git", "rev-parse", "HEAD"], cwd=REPO, capture_output=True, text=True)
    dirty = subprocess.run(["git", "status", "--porcelain", "floatmoor"], cwd=REPO,
                           capture_output=True, text=True).stdout.strip()
    return run.stdout.strip() + (" (floatmoor/ modified)" if dirty else "")


def compute(parts: Iterable[str], qd_full: bool = False, echo=print) -> dict[str, Any]:
    """The figures of ``parts`` (``lindahl``, ``qd``, ``decays``) with the current code."""
    out: dict[str, Any] = {}
    parts = set(parts)
    if "lindahl" in parts:
        started = time.perf_counter()
        cases = []
        for radius in LINDAHL_RADII:
            for period in LINDAHL_PERIODS:
                cases.append(fig := lindahl_figures(radius, period))
                echo(f"Lindahl r = {radius:.3f} m, T = {period:.2f} s: mean cycle max "
                     f"{fig['mean_cycle_max_N']:.3f} N ({fig['wall_time_s']:.1f} s)")
        out["lindahl"] = {
            "how": "tests/simulation/lindahl.py run_lindahl(period, radius, model='dynamic'): "
                   f"the case file as shipped, a {RAMP_PERIODS}-period ramp, "
                   f"{DEFAULT_CYCLES} cycles; mean cycle on {WAVEFORM_POINTS} phase points",
            "wall_time_s": round(time.perf_counter() - started, 1),
            "cases": cases}
    if "qd" in parts:
        started = time.perf_counter()
        runs = []
        for spec in qdv.design(quick=not qd_full):
            runs.append(fig := qd_figures(spec))
            echo(f"QD {fig['label']}: RMSE_QD {fig['rmse_qd']:.4f}, RMSE_S {fig['rmse_s']:.4f}, "
                 f"e_Tmin {fig['e_tmin']:.4f}, e_Tmax {fig['e_tmax']:.4f} "
                 f"({fig['seconds']:.1f} s)")
        out["qd_full" if qd_full else "qd_quick"] = {
            "how": "floatmoor.studies.qd_verification.evaluate on design(quick="
                   f"{not qd_full}): the study's numerics (dynamic {qdv.DYNAMIC_ELEMENTS} "
                   "elements of order 5, the case files' other settings)",
            "wall_time_s": round(time.perf_counter() - started, 1),
            "runs": runs}
    if "decays" in parts:
        started = time.perf_counter()
        models = {}
        for model in DECAY_MODELS:
            models[model] = fig = decay_figures(model)
            echo(f"decay {model}: period {fig['periods_s'][0]:.3f} s, peaks "
                 f"{np.round(fig['peaks_m'], 3)} m, damping ratios "
                 f"{np.round(fig['damping_ratios'], 4)} ({fig['wall_time_s']:.1f} s)")
        out["decays"] = {
            "how": "tests/simulation/deepcwind_decay.py surge_decay(model): "
                   f"cases/deepcwind/deepcwind_free_decay.toml, surge {DECAY_OFFSET} m, "
                   f"{DECAY_DURATION:g} s, body step 0.1 s, output 0.5 s",
            "wall_time_s": round(time.perf_counter() - started, 1),
            "models": models}
    return out


def provenance(command: str) -> dict[str, Any]:
    """Where and how the figures were made."""
    return {"floatmoor_commit": _commit(),
            "date": datetime.date.today().isoformat(),
            "command": command,
            "versions": {name: version(name) for name in ("numpy", "numba", "scipy")},
            "python": platform.python_version()}


def _rounded(data: Any) -> Any:
    """``data`` with the numbers of its lists rounded to :data:`STORED_DIGITS` digits."""
    if isinstance(data, dict):
        return {k: _rounded(v) for k, v in data.items()}
    if isinstance(data, list):
        return [float(f"{v:.{STORED_DIGITS}g}") if isinstance(v, float) else _rounded(v)
                for v in data]
    return data


def _dumps(data: dict[str, Any]) -> str:
    """JSON with each list of numbers rounded (:func:`_rounded`) and on one line (the cycles
    are long)."""
    text = json.dumps(_rounded(data), indent=1)
    return re.sub(r"\[[-+0-9.eE,\s]+\]", lambda m: " ".join(m.group(0).split()), text) + "\n"


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--write", action="store_true",
                        help=f"store the figures in {BASELINE.name} (merged into it)")
    parser.add_argument("--only", nargs="+", choices=("lindahl", "qd", "decays"),
                        default=["lindahl", "qd", "decays"])
    parser.add_argument("--qd-full", action="store_true",
                        help="the full 180-run QD study instead of the --quick subset")
    args = parser.parse_args(argv)
    figures = compute(args.only, qd_full=args.qd_full, echo=lambda s: print(s, flush=True))
    if args.write:
        stored = load_baseline() if BASELINE.is_file() else {}
        command = "PYTHONPATH=. python -m tests.simulation.unchanged_dynamic " + " ".join(
            sys.argv[1:] if argv is None else argv)
        for key, value in figures.items():
            value["provenance"] = provenance(command)
            stored[key] = value
        BASELINE.write_text(_dumps(stored))
        print(f"written: {BASELINE}")


if __name__ == "__main__":
    main()
