"""Quasi-dynamic verification study (docs/cases/qd_verification.md; quasi-dynamic paper section 4).

Six line configurations (shapes S1 to S3 by anchor position x chains D1, D2; Tables 2, 3), each
with its fairlead in horizontal harmonic motion at five amplitudes A1 to A5 and six dimensionless
accelerations alpha = w^2 Z_m / g = 0.1 to 0.6 (eq. 5, Z_m from Table 4): 180 runs, each with the
quasi-static, quasi-dynamic and dynamic line models. Over one steady cycle (the last of five after
a ramp of two periods) the fairlead tensions of the quasi-dynamic and quasi-static models are
compared with the dynamic one by the paper's error measures:

- RMSE_QD, RMSE_S (eqs. 6, 7): root-mean-square of (T_dyn - T_model) / T_S0,
- e_Tmin (eq. 8): |min T_dyn - min T_QD| / T_S0,
- e_Tmax (eq. 9): |max T_dyn - max T_QD| / max T_dyn,

with T_S0 the initial static fairlead tension (the quasi-static tension at t = 0, the fairlead
at rest before the ramp).

Dynamic discretisation: 20 elements of order 5 (DYNAMIC_ELEMENTS, 120 nodes; the case files
have 10, the paper's dynamic model 31 nodes), settled to its own static equilibrium before the
ramp (DynamicLine.settle: the interpolated catenary rings on undamped in these stiff,
frictionless chains). 20 elements, because refined to 30, at alpha 0.2 the RMSE measures move
by under 0.5 percentage point and the peak errors by under 3, while from 10 to 20 they move by
up to 3.4 and 22 (docs/validation/notes.md#convergence-of-the-stored-dynamic-references); the
RMSE measures at alpha 0.6 move by 0.1 point in the median (3.3 at most) and the peak errors at
alpha 0.6 on S2 and S3 do not converge with any resolution tried. ``discretisation_check``
compares two discretisations on one run, :mod:`qd_convergence` two studies; each run is kept
as it finishes (:mod:`qd_runs`, ``--resume``).

The study's findings against the paper's, and the sensitivity of the dynamic reference behind
them, are in docs/validation/notes.md.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from floatmoor.case.load import load_case
from floatmoor.errors import FloatmoorError
from floatmoor.io.output_files import atomic_target, write_errors
from floatmoor.simulation.forced import run_forced_motion
from floatmoor.studies import qd_runs

#: Folder of the six case files (s1_d1.toml ... s3_d2.toml).
CASE_DIR = Path(__file__).resolve().parents[2] / "cases" / "qd_verification"
#: Configurations in the paper's naming CXY (shape X, chain diameter Y; Table 2).
CONFIGS = ("C11", "C12", "C21", "C22", "C31", "C32")
#: Fairlead amplitudes A1 to A5 [m] (Table 4).
AMPLITUDES = (0.0045, 0.009, 0.018, 0.027, 0.036)
AMPLITUDE_NAMES = ("A1", "A2", "A3", "A4", "A5")
#: Dimensionless accelerations (eq. 5).
ALPHAS = (0.1, 0.2, 0.3, 0.4, 0.5, 0.6)
#: Z_m [m] per shape for A1..A5 (Table 4).
Z_M = {
    1: (0.0280, 0.0560, 0.0840, 0.1399, 0.1959),
    2: (0.0202, 0.0404, 0.0606, 0.1011, 0.1415),
    3: (0.0140, 0.0280, 0.0420, 0.0700, 0.0980),
}
GRAVITY = 9.81  # m/s^2, as in the case files
MODELS = ("quasi-static", "quasi-dynamic", "dynamic")
#: Output step [s]: the paper's time step (Table 3).
OUTPUT_INTERVAL = 0.0025
RAMP_CYCLES = 2
STEADY_CYCLES = 5
#: Phase samples of the stored steady cycle (for the figures).
PHASE_POINTS = 201
#: The paper's published fractions (section 4.2).
PAPER = {"rmse_qd": (0.48, 0.84), "rmse_s": (0.02, 0.18), "peak_qd": (0.67, 0.90)}
#: Reduced design of ``--quick``: A1 at alpha 0.3 and 0.6 for each configuration (the shortest
#: periods: the cheapest runs).
QUICK_AMPLITUDES = (0,)
QUICK_ALPHAS = (2, 5)
#: Elements (order 5) of the dynamic model in the study: converged for the RMSE measures
#: (docs/validation/notes.md#convergence-of-the-stored-dynamic-references; module docstring).
DYNAMIC_ELEMENTS = 20


def case_path(config: str) -> Path:
    """Case file of configuration ``CXY``."""
    return CASE_DIR / f"s{config[1]}_d{config[2]}.toml"


def period(z_m: float, alpha: float, gravity: float = GRAVITY) -> float:
    """Motion period [s] from alpha = w^2 Z_m / g (eq. 5)."""
    return 2.0 * math.pi * math.sqrt(z_m / (alpha * gravity))


def motion_overrides(amplitude: float, period_s: float, dt: float = OUTPUT_INTERVAL) -> list[str]:
    """``--set`` overrides: x-amplitude, period, a ramp of two periods and five steady cycles
    (the duration rounded up onto the output grid)."""
    duration = math.ceil((RAMP_CYCLES + STEADY_CYCLES) * period_s / dt - 1e-9) * dt
    return [f"motion.amplitude=[{amplitude!r}, 0.0, 0.0]", f"motion.period={period_s!r}",
            f"motion.ramp_duration={RAMP_CYCLES * period_s!r}",
            f"simulation.duration={duration!r}", f"simulation.output_interval={dt!r}"]


# --- error measures (eqs. 6 to 9) -----------------------------------------------------------

def last_cycle(time_s: np.ndarray, period_s: float) -> np.ndarray:
    """Mask of the last full cycle: the samples with t > t_end - T (n = T / dt samples)."""
    time_s = np.asarray(time_s, dtype=float)
    return time_s > time_s[-1] - period_s * (1.0 - 1e-9)


def rmse(dynamic: np.ndarray, model: np.ndarray, static_tension: float) -> float:
    """Eqs. (6), (7): sqrt(mean(((T_dyn - T_model) / T_S0)^2))."""
    d = (np.asarray(dynamic, float) - np.asarray(model, float)) / static_tension
    return float(np.sqrt(np.mean(d * d)))


def e_tmin(dynamic: np.ndarray, model: np.ndarray, static_tension: float) -> float:
    """Eq. (8): |min T_dyn - min T_QD| / T_S0."""
    return float(abs(np.min(dynamic) - np.min(model)) / static_tension)


def e_tmax(dynamic: np.ndarray, model: np.ndarray) -> float:
    """Eq. (9): |max T_dyn - max T_QD| / max T_dyn."""
    top = float(np.max(dynamic))
    return float(abs(top - np.max(model)) / top)


# --- runs ---------------------------------------------------------------------------------

@dataclass(frozen=True)
class RunSpec:
    """One of the 180 combinations."""

    config: str
    amplitude_index: int
    alpha_index: int
    dynamic_elements: int | None = DYNAMIC_ELEMENTS  #: None: the case file's

    @property
    def amplitude(self) -> float:
        return AMPLITUDES[self.amplitude_index]

    @property
    def alpha(self) -> float:
        return ALPHAS[self.alpha_index]

    @property
    def z_m(self) -> float:
        return Z_M[int(self.config[1])][self.amplitude_index]

    @property
    def period(self) -> float:
        return period(self.z_m, self.alpha)


def tensions(spec: RunSpec) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """Time and fairlead tension of the three models for one combination."""
    base = motion_overrides(spec.amplitude, spec.period)
    out = {}
    t = None
    for model in MODELS:
        overrides = base + [f'lines.chain.model="{model}"']
        if model == "dynamic" and spec.dynamic_elements is not None:
            overrides.append(f"lines.chain.dynamic.elements={spec.dynamic_elements}")
        ds = run_forced_motion(load_case(case_path(spec.config), overrides)).dataset
        t = ds["time"].values
        out[model] = np.asarray(ds["fairlead_tension"].values[0], dtype=float)
    return t, out


def evaluate(spec: RunSpec) -> dict:
    """Run one combination and return its error measures and its steady cycle (on a phase
    grid of PHASE_POINTS samples, phase 0 at the start of the last cycle)."""
    started, cpu = time.perf_counter(), time.process_time()
    try:
        t, tension = tensions(spec)
    except FloatmoorError as err:  # recorded as a failed run, not fatal to the study
        return {"spec": spec, "error": f"{type(err).__name__}: {err}"}
    t_s0 = float(tension["quasi-static"][0])
    mask = last_cycle(t, spec.period)
    dyn, qd, qs = (tension[m][mask] for m in MODELS[::-1])
    t0 = t[-1] - spec.period
    phase = np.linspace(0.0, 1.0, PHASE_POINTS)
    tc = (t[mask] - t0) / spec.period
    cycle = np.array([np.interp(phase, tc, tension[m][mask]) for m in MODELS])
    return {
        "spec": spec, "error": None, "t_s0": t_s0, "samples": int(mask.sum()),
        "rmse_qd": rmse(dyn, qd, t_s0), "rmse_s": rmse(dyn, qs, t_s0),
        "e_tmin": e_tmin(dyn, qd, t_s0), "e_tmax": e_tmax(dyn, qd),
        "cycle": cycle, "seconds": time.perf_counter() - started,
        "cpu_seconds": time.process_time() - cpu,
    }


def design(quick: bool = False, configs: Sequence[str] = CONFIGS, *,
           dynamic_elements: int | None = DYNAMIC_ELEMENTS,
           amplitudes: Sequence[int] | None = None,
           alphas: Sequence[int] | None = None) -> list[RunSpec]:
    """The 180 combinations (or the quick subset: A1 x alpha 0.3, 0.6 per configuration, or
    the subset of the ``amplitudes`` and ``alphas`` indices given), the dynamic model with
    ``dynamic_elements`` elements of order 5."""
    amps = amplitudes if amplitudes is not None else (
        QUICK_AMPLITUDES if quick else range(len(AMPLITUDES)))
    alpha_idx = alphas if alphas is not None else (
        QUICK_ALPHAS if quick else range(len(ALPHAS)))
    return [RunSpec(c, i, j, dynamic_elements) for c in configs for i in sorted(set(amps))
            for j in sorted(set(alpha_idx))]


def _constants() -> dict:
    """The study's cycle and sampling constants a stored run depends on (qd_runs.identity)."""
    return {"ramp_cycles": RAMP_CYCLES, "steady_cycles": STEADY_CYCLES,
            "output_interval": OUTPUT_INTERVAL, "phase_points": PHASE_POINTS}


def _store(output: Path | None, res: dict, kept: Callable[[], None] | None) -> None:
    """Write a finished run's result to its run file (a failed run is not stored), then call
    ``kept``."""
    if output is not None and not res["error"]:
        s = res["spec"]
        qd_runs.write_run(qd_runs.run_file(output, s, AMPLITUDE_NAMES[s.amplitude_index]),
                          qd_runs.identity(s, _constants()), res)
        if kept:
            kept()


def _compute(specs: list[RunSpec], output: Path | None, workers: int, done: int, total: int,
             progress: Callable[[int, int], None] | None,
             kept: Callable[[], None] | None) -> list[dict]:
    """Evaluate ``specs``, each result stored as soon as it is finished."""
    results = []

    def finished(res: dict) -> None:
        _store(output, res, kept)
        results.append(res)
        if progress:
            progress(done + len(results), total)

    if workers > 1 and len(specs) > 1:
        pool = ProcessPoolExecutor(max_workers=workers)
        try:
            futures = [pool.submit(evaluate, s) for s in specs]
            for future in as_completed(futures):
                finished(future.result())
        finally:
            pool.shutdown(wait=True, cancel_futures=True)
    else:
        for spec in specs:
            finished(evaluate(spec))
    return results


def run_study(output: str | Path | None = None, workers: int = 1, quick: bool = False,
              progress: Callable[[int, int], None] | None = None, *,
              dynamic_elements: int = DYNAMIC_ELEMENTS, resume: bool = False,
              amplitudes: Sequence[int] | None = None, alphas: Sequence[int] | None = None,
              kept: Callable[[], None] | None = None):
    """Run the study; returns the xarray dataset (written to OUTPUT/qd_verification.nc with
    summary.txt and the figures when ``output`` is given).

    With ``output``, each finished run is written at once to OUTPUT/runs/ (module qd_runs);
    ``resume`` takes the runs stored there instead of computing them again (a fresh study
    removes them first), and the dataset is the one an uninterrupted study gives, except the
    attributes ``wall_time_s`` (this invocation's) and ``resumed_runs``.
    ``dynamic_elements``: elements (order 5) of the dynamic reference; ``amplitudes``,
    ``alphas``: indices of a subset of the design (the full design by default); ``kept``:
    called after each run file is written (the command lists it in its folder's manifest).

    A combination whose run fails is recorded and the study goes on: its error measures are
    NaN, ``run_error`` holds the message, the attribute ``failed_runs`` counts them and
    :func:`failed_runs` lists them (``floatmoor study`` then exits with status 1).

    Raises
    ------
    CaseError
        With ``resume``, when the stored runs were computed otherwise (qd_runs.stored_runs).
    """
    import xarray as xr

    specs = design(quick, dynamic_elements=dynamic_elements, amplitudes=amplitudes,
                   alphas=alphas)
    out = None if output is None else Path(output)
    stored: dict = {}
    if out is not None:
        with write_errors(out):
            out.mkdir(exist_ok=True)  # its parent exists (the command checked)
    if out is not None and resume:
        stored = qd_runs.stored_runs(out, specs, [AMPLITUDE_NAMES[s.amplitude_index]
                                                  for s in specs], _constants())
    elif out is not None:
        qd_runs.clear_runs(out)
    started = time.perf_counter()
    if stored and progress:
        progress(len(stored), len(specs))
    todo = [s for s in specs if s not in stored]
    results = [{**stored[s], "spec": s, "error": None} for s in specs if s in stored]
    results += _compute(todo, out, workers, len(stored), len(specs), progress, kept)
    elapsed = time.perf_counter() - started

    amp_idx = sorted({s.amplitude_index for s in specs})
    alpha_idx = sorted({s.alpha_index for s in specs})
    shape = (len(CONFIGS), len(amp_idx), len(alpha_idx))
    names = ("rmse_qd", "rmse_s", "e_tmin", "e_tmax", "t_s0", "period", "z_m")
    arrays = {n: np.full(shape, np.nan) for n in names}
    run_seconds = sum(r.get("seconds", 0.0) for r in results if not r["error"])
    run_cpu = sum(r.get("cpu_seconds", 0.0) for r in results if not r["error"])
    cycles = np.full(shape + (len(MODELS), PHASE_POINTS), np.nan)
    errors = np.full(shape, "", dtype=object)
    failures = []
    for res in results:
        s = res["spec"]
        ijk = (CONFIGS.index(s.config), amp_idx.index(s.amplitude_index),
               alpha_idx.index(s.alpha_index))
        arrays["period"][ijk], arrays["z_m"][ijk] = s.period, s.z_m
        if res["error"]:
            failures.append(f"{run_label(s)}: {res['error']}")
            errors[ijk] = res["error"]
            continue
        for n in names[:5]:
            arrays[n][ijk] = res[n]
        cycles[ijk] = res["cycle"]

    meta = {
        "rmse_qd": ("RMSE of the quasi-dynamic fairlead tension against the dynamic one over "
                    "one steady cycle, relative to the initial static tension (eq. 6)", "1"),
        "rmse_s": ("RMSE of the quasi-static fairlead tension against the dynamic one over one "
                   "steady cycle, relative to the initial static tension (eq. 7)", "1"),
        "e_tmin": ("error of the quasi-dynamic minimum tension relative to the initial static "
                   "tension (eq. 8)", "1"),
        "e_tmax": ("error of the quasi-dynamic maximum tension relative to the dynamic maximum "
                   "(eq. 9)", "1"),
        "t_s0": ("initial static fairlead tension T_S0", "N"),
        "period": ("fairlead motion period from alpha = w^2 Z_m / g (eq. 5)", "s"),
        "z_m": ("Z_m, maximum static vertical motion of the suspended line (Table 4)", "m"),
    }
    dims = ("config", "amplitude", "alpha")
    data_vars = {n: (dims, arrays[n], {"long_name": meta[n][0], "units": meta[n][1]})
                 for n in names}
    data_vars["run_error"] = (dims, errors.astype(str), {
        "long_name": "why the run failed (empty: the run completed)", "units": "1"})
    data_vars["cycle_tension"] = (
        dims + ("model", "phase"), cycles,
        {"long_name": "fairlead tension over the last (steady) cycle", "units": "N"})
    from floatmoor import __version__
    ds = xr.Dataset(
        data_vars,
        coords={
            "config": ("config", list(CONFIGS), {"long_name": "configuration CXY: shape SX, "
                                                 "chain DY (paper Table 2)"}),
            "amplitude": ("amplitude", [AMPLITUDES[i] for i in amp_idx],
                          {"long_name": "fairlead x-amplitude", "units": "m"}),
            "amplitude_name": ("amplitude", [AMPLITUDE_NAMES[i] for i in amp_idx]),
            "alpha": ("alpha", [ALPHAS[j] for j in alpha_idx],
                      {"long_name": "dimensionless acceleration w^2 Z_m / g", "units": "1"}),
            "model": ("model", list(MODELS)),
            "phase": ("phase", np.linspace(0.0, 1.0, PHASE_POINTS),
                      {"long_name": "time in the last cycle over the period", "units": "1"}),
        },
        attrs={
            "title": "Quasi-dynamic verification study (docs/cases/qd_verification.md)",
            "source": "floatmoor " + __version__ + ", floatmoor.studies.qd_verification",
            "reference": "Trubat, Molins & Gironella, quasi-dynamic mooring model, section 4, "
                         "Tables 2-4, eqs. 5-9",
            "case_files": ", ".join(case_path(c).name for c in CONFIGS),
            "design": _design_name(quick, amp_idx, alpha_idx),
            "cycle": f"ramp {RAMP_CYCLES} periods, {STEADY_CYCLES} steady cycles; measures over "
                     "the last cycle, samples with t > t_end - T at the output step "
                     f"{OUTPUT_INTERVAL} s",
            "static_tension": "T_S0 = quasi-static fairlead tension at t = 0",
            "dynamic_discretisation": f"{dynamic_elements} elements of order 5 (the case "
                                      "files' cfl and seabed contact)",
            "dynamic_elements": dynamic_elements,
            "runs": len(specs), "failed_runs": len(failures),
            "failures": "; ".join(failures) or "none",
            "wall_time_s": round(elapsed, 1), "workers": workers,
            "run_time_s": round(run_seconds, 1), "run_cpu_time_s": round(run_cpu, 1),
            "resumed_runs": len(stored),
        },
    )
    if out is not None:
        out.mkdir(parents=True, exist_ok=True)
        with atomic_target(out / "qd_verification.nc") as tmp:
            ds.to_netcdf(tmp)
        text = summary(ds)
        with write_errors(out / "summary.txt"):
            (out / "summary.txt").write_text(text + "\n")
        figures = {"fig6_cycles_A4.png": lambda p: plot_cycles(ds, p),
                   "fig7_rmse.png": lambda p: plot_errors(ds, p, ("rmse_qd", "rmse_s")),
                   "fig8_peaks.png": lambda p: plot_errors(ds, p, ("e_tmin", "e_tmax"))}
        for name, plot in figures.items():
            with write_errors(out / name):  # disk full: one line naming the file
                plot(out / name)
    return ds


def _design_name(quick: bool, amp_idx: list[int], alpha_idx: list[int]) -> str:
    """The ``design`` attribute: full, the quick subset, or the amplitudes and alphas run."""
    if len(amp_idx) == len(AMPLITUDES) and len(alpha_idx) == len(ALPHAS):
        return "full (6 x 5 x 6 = 180 runs)"
    if quick and (tuple(amp_idx), tuple(alpha_idx)) == (QUICK_AMPLITUDES, QUICK_ALPHAS):
        return "quick subset"
    return ("subset: amplitudes " + ", ".join(AMPLITUDE_NAMES[i] for i in amp_idx)
            + "; alpha " + ", ".join(f"{ALPHAS[j]:g}" for j in alpha_idx))


def run_label(spec: RunSpec) -> str:
    """A combination as the summaries name it: ``C11 A1 alpha 0.3``."""
    return f"{spec.config} {AMPLITUDE_NAMES[spec.amplitude_index]} alpha {spec.alpha:g}"


def failed_runs(ds) -> list[tuple[str, str]]:
    """(run label, failure message) of every failed combination of a study dataset (a failed
    combination is recorded and the study goes on; its error measures are NaN)."""
    out = []
    for i, config in enumerate(ds["config"].values):
        for j, amplitude in enumerate(ds["amplitude_name"].values):
            for k, alpha in enumerate(ds["alpha"].values):
                error = str(ds["run_error"].values[i, j, k])
                if error:
                    out.append((f"{config} {amplitude} alpha {float(alpha):g}", error))
    return out


# --- summary and figures --------------------------------------------------------------------

def fractions(ds) -> dict[str, tuple[float, float]]:
    """Fractions of the (successful) runs below 10 % and 20 %: RMSE_QD, RMSE_S and the QD peak
    error max(e_Tmin, e_Tmax)."""
    peak = np.fmax(ds["e_tmin"].values, ds["e_tmax"].values)
    out = {}
    for name, v in (("rmse_qd", ds["rmse_qd"].values), ("rmse_s", ds["rmse_s"].values),
                    ("peak_qd", peak)):
        v = v[np.isfinite(v)]
        out[name] = (float(np.mean(v < 0.10)), float(np.mean(v < 0.20))) if v.size else (
            math.nan, math.nan)
    return out


def summary(ds) -> str:
    """The table of fractions beside the paper's, and mean errors by shape and amplitude."""
    fr = fractions(ds)
    n = int(np.isfinite(ds["rmse_qd"].values).sum())
    rows = [f"Quasi-dynamic verification study (docs/cases/qd_verification.md): {n} runs "
            f"({ds.attrs['design']}; failed {ds.attrs['failed_runs']}), "
            f"wall time {ds.attrs['wall_time_s']} s"
            + (f" (runs' own time {ds.attrs['run_time_s']} s, CPU "
               f"{ds.attrs['run_cpu_time_s']} s; {ds.attrs['resumed_runs']} runs resumed)"
               if "run_time_s" in ds.attrs else "")
            + f"; dynamic reference {ds.attrs.get('dynamic_elements', DYNAMIC_ELEMENTS)} "
            "elements of order 5",
            "", f"{'measure':<28}{'< 10 %':>9}{'< 20 %':>9}{'paper < 10 %':>15}"
            f"{'paper < 20 %':>15}"]
    labels = {"rmse_qd": "RMSE_QD (eq. 6)", "rmse_s": "RMSE_S (eq. 7)",
              "peak_qd": "QD peaks max(e_Tmin, e_Tmax)"}
    for key, label in labels.items():
        a, b = fr[key]
        pa, pb = PAPER[key]
        rows.append(f"{label:<28}{a:>9.0%}{b:>9.0%}{pa:>15.0%}{pb:>14.0%}"
                    + ("*" if key == "peak_qd" else ""))
    rows.append("(* paper: 'about 90 %')")
    rows.append("")
    rows.append(f"max RMSE_QD {np.nanmax(ds['rmse_qd'].values):.1%} (paper 37.6 %), max QD peak "
                f"error {np.nanmax(np.fmax(ds['e_tmin'].values, ds['e_tmax'].values)):.1%} "
                "(paper 32.5 %)")
    rows.append("")
    rows.append("mean RMSE_QD / RMSE_S by shape: " + ", ".join(
        f"S{s} {m_qd:.1%} / {m_s:.1%}" for s, m_qd, m_s in shape_means(ds)))
    rows.append("mean RMSE_QD / RMSE_S by amplitude: " + ", ".join(
        f"{name} {float(ds['rmse_qd'].isel(amplitude=i).mean()):.1%} / "
        f"{float(ds['rmse_s'].isel(amplitude=i).mean()):.1%}"
        for i, name in enumerate(ds["amplitude_name"].values)))
    rows.append("mean RMSE_QD / RMSE_S by alpha: " + ", ".join(
        f"{a:.1f} {float(ds['rmse_qd'].isel(alpha=j).mean()):.1%} / "
        f"{float(ds['rmse_s'].isel(alpha=j).mean()):.1%}"
        for j, a in enumerate(ds["alpha"].values)))
    rows.append("RMSE_QD per configuration (mean, max): " + ", ".join(
        f"{c} {float(ds['rmse_qd'].sel(config=c).mean()):.1%}, "
        f"{float(ds['rmse_qd'].sel(config=c).max()):.1%}" for c in ds["config"].values))
    return "\n".join(rows)


def shape_means(ds) -> list[tuple[int, float, float]]:
    """(shape, mean RMSE_QD, mean RMSE_S) for S1, S2, S3."""
    out = []
    for s in (1, 2, 3):
        sel = [c for c in ds["config"].values if c[1] == str(s)]
        out.append((s, float(ds["rmse_qd"].sel(config=sel).mean()),
                    float(ds["rmse_s"].sel(config=sel).mean())))
    return out


def plot_cycles(ds, path: Path, amplitude: str = "A4") -> Path | None:
    """Figure 6: fairlead tension over the steady cycle in the six configurations for one
    amplitude, all accelerations in the dataset (dynamic solid, QD dashed, QS dotted)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    names = list(ds["amplitude_name"].values)
    if amplitude not in names:
        amplitude = names[-1]
    i = names.index(amplitude)
    fig, axes = plt.subplots(3, 2, figsize=(10, 10), sharex=True)
    colours = plt.cm.viridis(np.linspace(0.0, 0.9, ds.sizes["alpha"]))
    phase = ds["phase"].values
    for ax, config in zip(axes.ravel(), ds["config"].values):
        for j, a in enumerate(ds["alpha"].values):
            cyc = ds["cycle_tension"].sel(config=config).isel(amplitude=i, alpha=j).values
            ax.plot(phase, cyc[2], "-", color=colours[j], label=f"alpha {a:.1f} dynamic")
            ax.plot(phase, cyc[1], "--", color=colours[j], label="QD" if j == 0 else None)
            if j == 0:
                ax.plot(phase, cyc[0], ":", color="k", label="QS")
        ax.set_title(f"{config}, {amplitude}")
        ax.set_ylabel("fairlead tension [N]")
        ax.grid(alpha=0.3)
    for ax in axes[-1]:
        ax.set_xlabel("t / T over the last cycle")
    axes[0, 0].legend(fontsize=7)
    fig.suptitle("Dynamic (solid), quasi-dynamic (dashed), quasi-static (dotted, lowest alpha)")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


def plot_errors(ds, path: Path, measures: Sequence[str]) -> Path:
    """Figures 7, 8: the error measures per configuration against alpha, one line per
    amplitude; one column per measure."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(ds.sizes["config"], len(measures), sharex=True, sharey=True,
                             figsize=(5 * len(measures), 2.2 * ds.sizes["config"]),
                             squeeze=False)
    colours = plt.cm.plasma(np.linspace(0.0, 0.85, ds.sizes["amplitude"]))
    for r, config in enumerate(ds["config"].values):
        for c, name in enumerate(measures):
            ax = axes[r, c]
            for i, a in enumerate(ds["amplitude_name"].values):
                ax.plot(ds["alpha"].values, 100 * ds[name].sel(config=config).isel(
                    amplitude=i).values, "o-", color=colours[i], label=str(a))
            for level in (10, 20):
                ax.axhline(level, color="grey", lw=0.7, ls="--")
            ax.set_title(f"{config}: {name}", fontsize=9)
            ax.set_ylabel("%")
            ax.grid(alpha=0.3)
    for ax in axes[-1]:
        ax.set_xlabel("alpha = w^2 Z_m / g")
    axes[0, 0].legend(fontsize=7, ncol=5)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)
    return path


def discretisation_check(spec: RunSpec, coarse: int = 6, fine: int = 10) -> dict:
    """Dynamic tension with ``coarse`` and ``fine`` elements (order 5) on one combination:
    RMSE of the difference over the last cycle relative to T_S0, and the relative difference
    of the cycle maxima."""
    out = {}
    for n in (coarse, fine):
        s = RunSpec(spec.config, spec.amplitude_index, spec.alpha_index, n)
        base = motion_overrides(s.amplitude, s.period)
        case = load_case(case_path(s.config), base + ['lines.chain.model="dynamic"',
                                                      f"lines.chain.dynamic.elements={n}"])
        started = time.perf_counter()
        ds = run_forced_motion(case).dataset
        out[n] = (ds["time"].values, ds["fairlead_tension"].values[0],
                  time.perf_counter() - started)
    t, tc, _ = out[coarse]
    mask = last_cycle(t, spec.period)
    tf = out[fine][1]
    qs = load_case(case_path(spec.config), motion_overrides(spec.amplitude, spec.period)
                   + ['lines.chain.model="quasi-static"'])
    t_s0 = float(run_forced_motion(qs).dataset["fairlead_tension"].values[0][0])
    return {"rmse": rmse(tf[mask], tc[mask], t_s0),
            "max": abs(tc[mask].max() - tf[mask].max()) / tf[mask].max(),
            "seconds": (out[coarse][2], out[fine][2])}
