"""The quasi-dynamic verification study (docs/cases/qd_verification.md; quasi-dynamic paper section 4).

The error measures of eqs. (6) to (9) on synthetic signals with known values, the study's
``--quick`` subset through the command line, and (slow) the full 180-run study against the
paper's findings.
"""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from floatmoor.cli import main
from floatmoor.studies import qd_verification as qdv

#: Full study: the paper found RMSE_QD < 20 % in 84 % of its 180 runs and RMSE_S < 20 % in 18 %.
#: Asserted with margin: QD in at least 80 %, QS in at most 30 %.
QD_UNDER_20_MIN = 0.80
QS_UNDER_20_MAX = 0.30


def test_error_measures_on_synthetic_signals():
    """Eqs. (6) to (9) on sinusoids with closed-form answers over exactly one period."""
    n = 400
    t = np.arange(n) * (1.0 / n)  # one period, uniform samples
    t_s0 = 10.0
    dyn = 10.0 + 2.0 * np.sin(2 * np.pi * t)
    # constant offset 0.5 N: RMSE = 0.5 / 10
    assert qdv.rmse(dyn, dyn - 0.5, t_s0) == pytest.approx(0.05, rel=1e-12)
    # sinusoidal difference of amplitude 1 N: RMSE = 1 / sqrt(2) / 10 (mean of sin^2 = 1/2)
    model = dyn + np.cos(2 * np.pi * t)
    assert qdv.rmse(dyn, model, t_s0) == pytest.approx(np.sqrt(0.5) / 10.0, rel=1e-12)
    # peaks: model = 10 + 1.5 sin: min 8.5 against 8 -> 0.5 / 10; max 11.5 against 12 -> 0.5 / 12
    model = 10.0 + 1.5 * np.sin(2 * np.pi * t)
    assert qdv.e_tmin(dyn, model, t_s0) == pytest.approx(0.05, rel=1e-12)
    assert qdv.e_tmax(dyn, model) == pytest.approx(0.5 / 12.0, rel=1e-12)
    assert qdv.rmse(dyn, dyn, t_s0) == 0.0
    # last cycle: T / dt samples ending at t_end
    time = np.arange(0, 7001) * 0.0025
    mask = qdv.last_cycle(time, 2.5)
    assert mask.sum() == 1000 and mask[-1] and not mask[-1001]


def test_periods_follow_eq_5_and_table_4():
    """alpha = w^2 Z_m / g: C22 A3 alpha 0.3 gives the period of s2_d2.toml."""
    spec = qdv.RunSpec("C22", 2, 2)
    assert spec.z_m == 0.0606
    assert spec.period == pytest.approx(0.901615, abs=1e-6)
    assert len(qdv.design()) == 180 and len(qdv.design(quick=True)) == 12
    for config in qdv.CONFIGS:
        assert qdv.case_path(config).is_file()


@pytest.mark.slow  # 88 s of runs at 20 elements: over the default run's time budget
def test_quick_study_through_the_command_line(tmp_path, capsys):
    """``floatmoor study qd-verification --quick``: 6 configurations x A1 x alpha 0.3, 0.6, a
    complete dataset, the summary and the figures; on this subset the quasi-dynamic model is
    closer to the dynamic one than the quasi-static in most runs."""
    status = main(["study", "qd-verification", "-o", str(tmp_path / "out"), "--quick",
                   "--quiet"])
    printed = capsys.readouterr().out
    assert status == 0
    assert "RMSE_QD" in printed
    ds = xr.load_dataset(tmp_path / "out" / "qd_verification.nc")
    assert dict(ds.sizes) == {"config": 6, "amplitude": 1, "alpha": 2, "model": 3,
                              "phase": qdv.PHASE_POINTS}
    assert ds.attrs["failed_runs"] == 0
    for name in ("rmse_qd", "rmse_s", "e_tmin", "e_tmax"):
        assert np.all(np.isfinite(ds[name].values)) and ds[name].attrs["units"] == "1"
    assert np.mean(ds["rmse_qd"].values < ds["rmse_s"].values) >= 0.75
    text = (tmp_path / "out" / "summary.txt").read_text()
    assert "48%" in text and "84%" in text
    for png in ("fig6_cycles_A4.png", "fig7_rmse.png", "fig8_peaks.png"):
        assert (tmp_path / "out" / png).stat().st_size > 1000


def test_study_rejects_a_file_as_output_folder(tmp_path, capsys):
    target = tmp_path / "file.txt"
    target.write_text("x")
    assert main(["study", "qd-verification", "-o", str(target), "--quick"]) == 2
    assert main(["study", "qd-verification", "-o", str(tmp_path / "o"), "--workers", "0"]) == 2


@pytest.fixture(scope="module")
def full_study(tmp_path_factory):
    """All 180 runs x 3 models against the 20-element reference (2576 s of CPU in all, measured
    run by run: about 22 min with 2 workers on a quiet machine; the 10-element reference took
    25 min with 2 workers on the loaded development machine)."""
    ds = qdv.run_study(tmp_path_factory.mktemp("qd_full"), workers=2)
    print(qdv.summary(ds))
    return ds


@pytest.mark.slow
def test_full_study_quasi_dynamic_beats_quasi_static(full_study):
    """Asserted (all held on the development machine with the 20-element reference, numbers
    observed in brackets): no failed run; RMSE_QD < 20 % in at least 80 % of the runs (91 %;
    paper 84 %); the mean RMSE_QD below the mean RMSE_S for every shape, amplitude and alpha;
    the mean RMSE_QD over each alpha increasing from 0.1 to 0.6 (2.4 % to 17.9 %) and over each
    amplitude from A1 to A5 (5.9 %, 6.8 %, 11.3 %, 12.0 %, 13.8 %); the quasi-static errors
    growing from S3 to S1 (mean RMSE_S 26.1 %, 31.9 %, 44.4 %)."""
    ds = full_study
    assert ds.attrs["failed_runs"] == 0
    assert qdv.fractions(ds)["rmse_qd"][1] >= QD_UNDER_20_MIN
    for dim in ("config", "amplitude", "alpha"):
        others = [d for d in ("config", "amplitude", "alpha") if d != dim]
        assert np.all(ds["rmse_qd"].mean(others).values < ds["rmse_s"].mean(others).values)
    assert np.all(np.diff(ds["rmse_qd"].mean(("config", "amplitude")).values) > 0.0)
    assert np.all(np.diff(ds["rmse_qd"].mean(("config", "alpha")).values) > 0.0)
    by_shape_s = [s for _, _, s in qdv.shape_means(ds)]
    assert by_shape_s[2] < by_shape_s[1] < by_shape_s[0]


# The strict xfail below is a documented deviation from the paper (docs/validation/notes.md): it
# stays until a peer check of the study says otherwise.
@pytest.mark.slow
@pytest.mark.xfail(strict=True, reason="observed RMSE_S < 20 % in 34 % of the runs (paper 18 %) "
                   "with the 10- and the 20-element reference alike; 31-34 % with every dynamic "
                   "discretisation and unspecified input tried (docs/validation/notes.md): not "
                   "an artefact of the reference")
def test_full_study_quasi_static_rarely_within_20_percent(full_study):
    """RMSE_S < 20 % in at most 30 % of the runs."""
    assert qdv.fractions(full_study)["rmse_s"][1] <= QS_UNDER_20_MAX


@pytest.mark.slow
def test_full_study_quasi_dynamic_errors_grow_from_s3_to_s1(full_study):
    """Paper: the lowest errors for S3, then S2, then S1 (mean RMSE_QD per shape). Observed with
    the 20-element reference: S3 8.6 < S2 9.0 < S1 12.3 % (per chain D1 S3 9.0 < S2 10.2 < S1
    14.3 %, D2 S2 7.7 < S3 8.2 < S1 10.2 %). The 10-element reference gave S2 9.4 < S3 10.5 <
    S1 12.3 % (a strict xfail until then): its S3 runs were not converged. The margin of S3
    over S2 is small and rests on S3 runs at alpha 0.5-0.6 whose reference rings axially
    without converging (docs/validation/notes.md)."""
    by_shape = [m for _, m, _ in qdv.shape_means(full_study)]
    assert by_shape[2] < by_shape[1] < by_shape[0]


def test_study_with_a_failed_run_exits_1_naming_it(tmp_path, capsys, monkeypatch):
    """A combination whose run fails is recorded (NaN measures, its message in run_error) and
    the study completes, but ``floatmoor study`` exits 1 naming it. Two
    combinations; the model runs are replaced by a synthetic steady cycle and a solver
    failure."""
    from floatmoor.errors import SolverError

    specs = [qdv.RunSpec("C11", 0, 2), qdv.RunSpec("C12", 0, 2)]
    monkeypatch.setattr(qdv, "design", lambda *args, **kwargs: specs)

    def tensions(spec):
        if spec.config == "C12":
            raise SolverError("line 'chain' (dynamic): not finite at t = 1.5 s")
        t = np.arange(0.0, 7 * spec.period, qdv.OUTPUT_INTERVAL)
        wave = 100.0 + 10.0 * np.sin(2 * np.pi * t / spec.period)
        return t, {"quasi-static": wave, "quasi-dynamic": wave + 1.0, "dynamic": wave}

    monkeypatch.setattr(qdv, "tensions", tensions)
    out = tmp_path / "out"
    assert main(["study", "qd-verification", "-o", str(out), "--quiet"]) == 1
    captured = capsys.readouterr()
    assert "RMSE_QD" in captured.out
    lines = captured.err.strip().splitlines()
    assert lines[0] == ("floatmoor: study qd-verification failed: 1 of 2 runs failed "
                        "(C12 A1 alpha 0.3)")
    assert lines[1] == "  C12 A1 alpha 0.3: SolverError: line 'chain' (dynamic): not finite " \
                       "at t = 1.5 s"
    ds = xr.load_dataset(out / "qd_verification.nc")
    assert ds.attrs["failed_runs"] == 1
    assert ds["run_error"].sel(config="C11").item() == ""
    assert np.isfinite(ds["rmse_qd"].sel(config="C11").item())
    assert qdv.failed_runs(ds) == [("C12 A1 alpha 0.3", lines[1].split(": ", 1)[1])]


@pytest.fixture
def no_figures(monkeypatch):
    """The study's figures replaced by a small text file (their cost is not under test)."""
    def plot(ds, path, *args):
        path.write_text("figure\n")
        return path

    monkeypatch.setattr(qdv, "plot_cycles", plot)
    monkeypatch.setattr(qdv, "plot_errors", plot)


def _synthetic_tensions(calls):
    """Replacement of qdv.tensions: a steady cycle depending on the combination and on the
    dynamic resolution, each call recorded in ``calls``."""
    def tensions(spec):
        calls.append(spec)
        t = np.arange(0.0, 7 * spec.period, qdv.OUTPUT_INTERVAL)
        w = 2 * np.pi * t / spec.period
        base = 100.0 + 10.0 * spec.amplitude_index + spec.alpha_index
        qs = base + 10.0 * np.sin(w)
        dyn = qs + (1.0 + 0.1 * spec.alpha) * np.sin(2 * w) + 1.0 / spec.dynamic_elements
        return t, {"quasi-static": qs, "quasi-dynamic": qs + 0.3 * np.cos(w), "dynamic": dyn}
    return tensions


def test_resumed_study_skips_finished_runs_and_gives_the_same_dataset(tmp_path, capsys,
                                                                       monkeypatch, no_figures):
    """Interrupted after 3 of the 12 quick runs: 3 run files kept, exit 130 naming them;
    ``--resume`` computes only the other 9 and writes the dataset an uninterrupted study
    writes (but for its own wall time and count of resumed runs). The model runs are
    replaced by synthetic cycles."""
    calls = []
    monkeypatch.setattr(qdv, "tensions", _synthetic_tensions(calls))
    whole = tmp_path / "whole"
    assert main(["study", "qd-verification", "-o", str(whole), "--quick", "--quiet",
                 "--dynamic-elements", "7"]) == 0
    assert len(calls) == 12 and {s.dynamic_elements for s in calls} == {7}
    assert len(list((whole / "runs").glob("*.json"))) == 12

    real_evaluate = qdv.evaluate

    def evaluate(spec):
        if len(calls) == 15:
            raise KeyboardInterrupt
        return real_evaluate(spec)

    monkeypatch.setattr(qdv, "evaluate", evaluate)
    out = tmp_path / "out"
    args = ["study", "qd-verification", "-o", str(out), "--quick", "--quiet",
            "--dynamic-elements", "7"]
    capsys.readouterr()
    assert main(args) == 130
    err = capsys.readouterr().err
    assert err.startswith(f"floatmoor: interrupted; 3 finished runs kept in {out / 'runs'}")
    assert "Traceback" not in err and not (out / "qd_verification.nc").exists()
    kept = sorted(p.name for p in (out / "runs").glob("*.json"))
    assert kept == ["C11_A1_alpha0.3.json", "C11_A1_alpha0.6.json", "C12_A1_alpha0.3.json"]
    del calls[:]
    assert main(args + ["--resume"]) == 0
    assert len(calls) == 9 and all(s.config != "C11" for s in calls)
    assert ("C12", 0, 2) not in {(s.config, s.amplitude_index, s.alpha_index) for s in calls}
    a = xr.load_dataset(whole / "qd_verification.nc")
    b = xr.load_dataset(out / "qd_verification.nc")
    assert b.attrs["resumed_runs"] == 3 and a.attrs["resumed_runs"] == 0
    assert a.attrs["dynamic_elements"] == 7
    for ds in (a, b):
        for name in ("wall_time_s", "resumed_runs", "run_time_s", "run_cpu_time_s"):
            del ds.attrs[name]
    xr.testing.assert_identical(a, b)
    # the stored run is the fresh one, value for value
    assert (out / "runs" / "C11_A1_alpha0.3.json").read_text().split('"seconds"')[0] == (
        whole / "runs" / "C11_A1_alpha0.3.json").read_text().split('"seconds"')[0]
    # a run file that is not a whole one of this format is computed again, and replaced
    (out / "runs" / "C12_A1_alpha0.3.json").write_text('{"format": "floatmoor qd-verif')
    del calls[:]
    assert main(args + ["--resume"]) == 0
    assert [(s.config, s.alpha_index) for s in calls] == [("C12", 2)]
    assert xr.load_dataset(out / "qd_verification.nc")["rmse_qd"].equals(a["rmse_qd"])


def test_resume_refuses_runs_of_another_dynamic_resolution(tmp_path, capsys, monkeypatch,
                                                           no_figures):
    """A folder whose runs were computed with 7 elements is not resumed at 9: status 2 before
    any run, naming the option, the file and both resolutions; a fresh study (no --resume)
    replaces those runs."""
    calls = []
    monkeypatch.setattr(qdv, "tensions", _synthetic_tensions(calls))
    out = tmp_path / "out"
    base = ["study", "qd-verification", "-o", str(out), "--quiet", "--amplitudes", "A2",
            "--alphas", "0.4"]
    assert main(base + ["--dynamic-elements", "7"]) == 0
    assert len(calls) == 6
    capsys.readouterr()
    assert main(base + ["--dynamic-elements", "9", "--resume"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("floatmoor: error: --resume: expected the runs of the same study in "
                          "the output folder (dynamic_elements 9 (--dynamic-elements))")
    assert "C11_A2_alpha0.4.json computed with dynamic_elements 7" in err
    assert len(calls) == 6 and "\n" not in err
    assert main(base + ["--dynamic-elements", "9"]) == 0
    assert len(calls) == 12
    ds = xr.load_dataset(out / "qd_verification.nc")
    assert ds.attrs["dynamic_elements"] == 9 and dict(ds.sizes)["alpha"] == 1
    assert ds.attrs["design"] == "subset: amplitudes A2; alpha 0.4"


def test_study_killed_without_cleanup_resumes(tmp_path, capsys, monkeypatch, no_figures):
    """A study killed outright (no exit handler runs: SIGKILL, a power cut) has listed each
    run file in its folder's manifest as it wrote it: ``--resume`` accepts the folder and
    computes only the missing runs."""
    from floatmoor.io import output_folders

    calls = []
    monkeypatch.setattr(qdv, "tensions", _synthetic_tensions(calls))
    real_evaluate, real_exit = qdv.evaluate, output_folders.OwnedFolder.__exit__

    class Killed(BaseException):
        pass

    def evaluate(spec):
        if len(calls) == 2:
            raise Killed
        return real_evaluate(spec)

    monkeypatch.setattr(qdv, "evaluate", evaluate)
    monkeypatch.setattr(output_folders.OwnedFolder, "__exit__", lambda *args: None)
    out = tmp_path / "out"
    args = ["study", "qd-verification", "-o", str(out), "--quiet", "--amplitudes", "A1",
            "--alphas", "0.3"]
    with pytest.raises(Killed):
        main(args)
    monkeypatch.setattr(qdv, "evaluate", real_evaluate)
    monkeypatch.setattr(output_folders.OwnedFolder, "__exit__", real_exit)
    del calls[:]
    assert main(args + ["--resume"]) == 0
    assert len(calls) == 4 and {s.config for s in calls} == {"C21", "C22", "C31", "C32"}


def test_reference_change_between_two_resolutions():
    """Largest and median change of each judged statistic over the runs both datasets hold,
    and the runs that change class (10 %, 20 %), on hand-made datasets."""
    from floatmoor.studies.qd_convergence import reference_change

    def dataset(rmse_qd, e_tmin, alphas):
        shape = (len(qdv.CONFIGS), 1, len(alphas))
        zero = np.zeros(shape)
        return xr.Dataset(
            {"rmse_qd": (("config", "amplitude", "alpha"), np.reshape(rmse_qd, shape)),
             "rmse_s": (("config", "amplitude", "alpha"), zero + 0.3),
             "e_tmin": (("config", "amplitude", "alpha"), np.reshape(e_tmin, shape)),
             "e_tmax": (("config", "amplitude", "alpha"), zero + 0.05)},
            coords={"config": list(qdv.CONFIGS), "amplitude": [0.018],
                    "amplitude_name": ("amplitude", ["A3"]), "alpha": list(alphas)})

    coarse = dataset(np.linspace(0.05, 0.30, 12), np.full(12, 0.09), [0.2, 0.6])
    rmse = np.linspace(0.05, 0.30, 12).copy()
    rmse[3] += 0.004  # C12 alpha 0.6: 0.1182 -> 0.1222, same class
    rmse[1] -= 0.03   # C11 alpha 0.6: 0.0727 -> 0.0427, same class
    e_tmin = np.full((6, 3), 0.09)
    e_tmin[0, 0] = 0.105  # C11 alpha 0.2 crosses 10 %
    # the finer one also holds alpha 0.4, which the coarse one lacks: left out
    fine = dataset(np.insert(rmse.reshape(6, 2), 1, 1.0, axis=1), e_tmin, [0.2, 0.4, 0.6])
    change = reference_change(coarse, fine)
    assert change["rmse_qd"]["runs"] == 12
    assert change["rmse_qd"]["max"] == pytest.approx(0.03, abs=1e-12)
    assert change["rmse_qd"]["max_run"] == "C11 A3 alpha 0.6"
    assert change["rmse_qd"]["median"] == pytest.approx(0.0, abs=1e-12)
    assert change["rmse_qd"]["class_changes"] == []
    assert change["e_tmin"]["max"] == pytest.approx(0.015, abs=1e-12)
    assert change["e_tmin"]["class_changes"] == ["C11 A3 alpha 0.2"]
    assert change["peak_qd"]["class_changes"] == ["C11 A3 alpha 0.2"]
    assert change["rmse_s"]["max"] == 0.0


@pytest.mark.parametrize("option, value", [
    ("--dynamic-elements", "0"), ("--dynamic-elements", "-3"), ("--dynamic-elements", "2.5"),
    ("--dynamic-elements", "ten"), ("--dynamic-elements", ""), ("--amplitudes", "A6"),
    ("--amplitudes", "A1,A1"), ("--amplitudes", ""), ("--alphas", "0.7"),
    ("--alphas", "0.1,,0.2"), ("--alphas", "nan"),
])
def test_study_refuses_bad_option_values(tmp_path, capsys, option, value):
    """Strict options: status 2, one line naming the option and the value, nothing written."""
    out = tmp_path / "out"
    assert main(["study", "qd-verification", "-o", str(out), option, value]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"floatmoor: error: {option}: expected ") and repr(value) in err
    assert len(err.strip().splitlines()) == 1 and not out.exists()


def test_interrupted_study_exits_130_without_traceback(tmp_path, capsys, monkeypatch):
    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(qdv, "run_study", interrupted)
    assert main(["study", "qd-verification", "-o", str(tmp_path / "out"), "--quiet"]) == 130
    assert capsys.readouterr().err.startswith("floatmoor: interrupted; nothing written")
