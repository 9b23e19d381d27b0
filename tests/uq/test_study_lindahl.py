"""Case F through ``floatmoor uq``: the Lindahl chain's fairlead tension with uncertain drag
coefficients (gpc paper section 4.2).

Default run: a quick variant (one cycle after the ramp, p = 2, two inputs, 9 runs) checked
for physical sense, a quadrature study with a failed run (exit 1 naming it, no surrogate) and
a regression that drops a failed run (results written without it, exit 1 naming it). Slow:
the shipped full studies.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import floatmoor.campaign.runner as runner
from floatmoor.cli import main
from tests.conftest import CASES, LINDAHL_CASE
from tests.uq.case_f_findings import PUBLISHED_PEAK_N, SCENARIOS, all_figures

#: Sobol indices are variance fractions: sum_i S_i <= 1 exactly and S_i <= S_T,i; the
#: coefficients' squares summed in double precision carry round-off of ~1e-12 relative.
SOBOL_TOLERANCE = 1e-9
#: How far the surrogate's mean may lie outside the range of the runs' values, relative to
#: that range: a mean is a weighted average of the runs with positive Gauss weights, so it
#: lies inside exactly (up to round-off).
MEAN_RANGE_TOLERANCE = 1e-9

QUICK = f"""
title = "Lindahl chain, quick: uncertain drag coefficients"
case = "{LINDAHL_CASE}"
base_overrides = ["simulation.duration=3.75"]   # the 2.5 s ramp, then one cycle

[[inputs]]
key = "line_types.chain.normal_drag_coefficient"
distribution = "uniform"
lower = 1.25
upper = 3.75

[[inputs]]
key = "line_types.chain.tangential_drag_coefficient"
distribution = "uniform"
lower = 0.25
upper = 0.75

[method]
kind = "quadrature"
order = 2

[[quantities]]
name = "cycle_max"
line = "chain"
statistic = "mean_cycle_max"

[[quantities]]
name = "cycle"
line = "chain"
statistic = "history"
window = [2.5, 3.75]
"""


CDT_INPUT = """[[inputs]]
key = "line_types.chain.tangential_drag_coefficient"
distribution = "uniform"
lower = 0.25
upper = 0.75
"""
assert CDT_INPUT in QUICK


def _write(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "study.toml"
    path.write_text(text, encoding="utf-8")
    return path


def test_quick_case_f_makes_physical_sense(tmp_path, capsys):
    out = tmp_path / "f"
    assert main(["uq", str(_write(tmp_path, QUICK)), "-o", str(out), "--json",
                 "--quiet"]) == 0
    summary = json.loads(capsys.readouterr().out)
    with xr.open_dataset(out / "uq.nc", engine="scipy") as ds:
        ds.load()
    runs = ds["cycle_max_runs"].values
    assert runs.shape == (9,) and np.all(np.isfinite(runs))
    spread = runs.max() - runs.min()
    mean = float(ds["cycle_max_mean"])
    assert runs.min() - MEAN_RANGE_TOLERANCE * spread <= mean \
        <= runs.max() + MEAN_RANGE_TOLERANCE * spread
    # the measured mean maximum is 70.3 N (docs/cases/lindahl.md): the chain's snap loads stay near it
    assert 60.0 < mean < 85.0
    assert summary["quantities"]["cycle_max"]["mean"] == pytest.approx(mean, rel=1e-12)
    for name in ("cycle_max", "cycle"):
        first = ds[f"{name}_sobol_first"].values
        total = ds[f"{name}_sobol_total"].values
        assert np.all(first >= -SOBOL_TOLERANCE)
        assert np.all(first.sum(axis=0) <= 1.0 + SOBOL_TOLERANCE)
        assert np.all(first <= total + SOBOL_TOLERANCE)
        assert np.all(total <= 1.0 + SOBOL_TOLERANCE)
    # the history: one cycle of output samples, mean inside its band, band inside the runs'
    # range widened by the surrogate's reach
    time = ds["cycle_time"].values
    assert time[0] == pytest.approx(2.5) and time[-1] == pytest.approx(3.75)
    assert ds["cycle_runs"].shape == (9, time.size)
    assert np.all(ds["cycle_lower"].values <= ds["cycle_mean"].values + 1e-9)
    assert np.all(ds["cycle_mean"].values <= ds["cycle_upper"].values + 1e-9)
    # the mean cycle maximum of each run is the maximum of its one cycle's history
    assert np.allclose(ds["cycle_runs"].max(axis=1).values, runs, rtol=1e-12)
    for var in (*ds.data_vars.values(), *ds.coords.values()):
        assert var.attrs.get("units") and var.attrs.get("long_name"), var.name
    for figure in ("cycle_max_pdf", "cycle_max_sobol", "cycle_band", "cycle_density",
                   "cycle_sobol_time", "cycle_sobol"):
        assert (out / "report" / f"{figure}.png").is_file(), figure
    # resumed: a second run into the folder runs nothing again
    assert main(["uq", str(_write(tmp_path, QUICK)), "-o", str(out), "--json"]) == 0
    err = capsys.readouterr().err
    assert "9 / 9 runs done" in err and "1 / 9" not in err


def _failing(bad_value: float):
    """run_one, but the run whose Cdn is ``bad_value`` fails as a diverging run would."""
    original = runner.run_one

    def run_one(case_path, overrides, timeseries=False, run_file=None):
        if f"line_types.chain.normal_drag_coefficient={bad_value!r}" in overrides:
            return {"status": "failed: SolverError: diverged (test)", "statistics": {},
                    "compute_time_s": 0.0, "wall_time_s": 0.0, "compile_time_s": 0.0}
        return original(case_path, overrides, timeseries, run_file)

    return run_one


def test_quadrature_with_a_failed_run_exits_1_naming_it(tmp_path, capsys, monkeypatch):
    text = QUICK.replace("order = 2", "order = 1").replace(CDT_INPUT, "")
    upper_node = 2.5 + 1.25 / np.sqrt(3.0)  # the Gauss-Legendre node above the mean
    monkeypatch.setattr(runner, "run_one", _failing(float(upper_node)))
    out = tmp_path / "f"
    assert main(["uq", str(_write(tmp_path, text)), "-o", str(out), "--quiet"]) == 1
    err = capsys.readouterr().err
    assert "uq failed: 1 of 2 runs failed" in err
    assert f"line_types.chain.normal_drag_coefficient={float(upper_node)!r}" in err
    assert "diverged (test)" in err
    assert (out / "runs.nc").is_file() and not (out / "uq.nc").exists()


def test_regression_drops_a_failed_run_and_records_it(tmp_path, capsys, monkeypatch):
    text = QUICK.replace('kind = "quadrature"\norder = 2', 'kind = "regression"\norder = 1\n'
                         "q_norm = 1.0\nsamples = 6\nseed = 3")
    study = _write(tmp_path, text)
    from floatmoor.uq.run import study_design
    from floatmoor.uq.study import load_study

    nodes, _, _ = study_design(load_study(study))
    bad = float(nodes[2, 0])
    monkeypatch.setattr(runner, "run_one", _failing(bad))
    out = tmp_path / "f"
    assert main(["uq", str(study), "-o", str(out), "--quiet"]) == 1  # loud, results written
    captured = capsys.readouterr()
    assert "1 of 6 runs failed or gave non-finite values and were dropped" in captured.err
    assert f"normal_drag_coefficient={bad!r}" in captured.err
    with xr.open_dataset(out / "uq.nc", engine="scipy") as ds:
        assert list(ds["run_used"].values) == [1, 1, 0, 1, 1, 1]
        assert str(ds["run_status"].values[2]).startswith("failed: SolverError")
        assert f"normal_drag_coefficient={bad!r}" in ds.attrs["runs_dropped"]
        assert np.isfinite(ds["cycle_max_mean"].values).all()


#: Published peaks against ours: the two DG codes' deterministic runs differ (ours: 72.7 N mean
#: cycle maximum at r = 0.2 m, T = 1.25 s; the measurement 70.3 N, docs/cases/lindahl.md), and the paper's
#: figures are read to ~1 N of their 80 N scale: 5 %.
PEAK_TOLERANCE = 0.05
#: "Equal to, or only slightly lower than": the averaged peak of 20 sets of 3000 samples moves
#: by 1.4 % with the seed (79.5 and 80.6 N at T = 1.25 s, all varied).
SAMPLING_TOLERANCE = 0.015
#: "C_dn dominates almost the entire time" (T = 3.5 s): share of the cycle's instants.
CDN_SHARE_3_5 = 0.8
#: "Varying C_dt causes no noticeable changes" (T = 3.5 s): its spread against C_dn's.
NO_CHANGE = 0.1
#: The published 3.5 s peaks with C_dn varied that this model does not reach (explained in
#: docs/validation/uq.md, case F): (period, scenario) -> our figure when last run.
NOT_REPRODUCED = {("3.50", "all"): "56.1 N", ("3.50", "cdn"): "56.1 N"}


@pytest.fixture(scope="module", params=["1.25", "3.50"])
def case_f(request, tmp_path_factory):
    """The shipped p = 5 studies of one period, four scenarios (216 + 3 x 6 runs; ~4 min at
    1.25 s, ~7 min at 3.5 s on one process), and their figures (case_f_findings.py)."""
    period, root = request.param, tmp_path_factory.mktemp(f"case_f_{request.param}")
    for sc in SCENARIOS:
        study = CASES / "uq" / f"lindahl_T{period}_{sc}.toml"
        assert main(["uq", str(study), "-o", str(root / f"lindahl_T{period}_{sc}"),
                     "--quiet"]) == 0
    fig = all_figures(root, period)
    print(f"\ncase F, T = {period} s:", json.dumps(fig, indent=1))
    return period, fig


@pytest.mark.slow
@pytest.mark.parametrize("scenario", SCENARIOS)
def test_case_f_peak_tensions(case_f, scenario, request):
    """The largest tension the density reaches against the paper's (section 4.2): 79 / 69 N
    with all varied, C_dn alone 75 / 69 N, C_dt or C_m alone 73-74 / 52 N (1.25 / 3.5 s)."""
    period, fig = case_f
    published = PUBLISHED_PEAK_N.get((period, scenario))
    if published is None:
        pytest.skip("the paper gives no peak: C_dt changes nothing at 3.5 s")
    if (period, scenario) in NOT_REPRODUCED:
        request.applymarker(pytest.mark.xfail(strict=True, reason=(
            f"published {published:g} N, ours {NOT_REPRODUCED[period, scenario]}: our tension "
            "rises by ~4 N per unit of C_dn at 3.5 s (46.2 to 55.9 N over the design), so "
            "69 N would need C_dn ~ 7, outside U(1.25, 3.75); the measured mean maximum is "
            "50.1 N (docs/validation/uq.md, case F)")))
    assert fig[scenario]["peak"] == pytest.approx(published, rel=PEAK_TOLERANCE)


@pytest.mark.slow
def test_case_f_spread_and_sensitivities(case_f):
    """The spread largest with all varied, then C_dn alone, C_dt and C_m lower; the peak with
    all varied equal to or slightly above C_dn's, above C_dt's and C_m's; C_dn leading the
    high-tension part; at 1.25 s C_dt leading the low-tension part and more dispersion rising
    from slack than falling from the maximum; at 3.5 s C_dn leading almost the whole cycle and
    C_dt changing nothing."""
    period, fig = case_f
    assert fig["all"]["peak"] >= fig["cdn"]["peak"] * (1.0 - SAMPLING_TOLERANCE)
    assert fig["cdn"]["peak"] > max(fig["cdt"]["peak"], fig["cm"]["peak"])
    assert fig["all"]["spread"] > fig["cdn"]["spread"]
    assert fig["cdn"]["spread"] > max(fig["cdt"]["spread"], fig["cm"]["spread"])
    assert fig["all"]["leader_high"] == "cdn"
    if period == "1.25":
        assert fig["all"]["leader_low"] == "cdt"
        assert fig["all"]["rising_std"] > fig["all"]["falling_std"]
    else:
        assert fig["all"]["leader_share"]["cdn"] > CDN_SHARE_3_5
        assert fig["cdt"]["spread"] < NO_CHANGE * fig["cdn"]["spread"]


@pytest.mark.slow
@pytest.mark.parametrize("period", ["1.00", "1.20", "1.40"])
def test_full_case_g_anchor_positions(tmp_path, capsys, period):
    """The shipped buoy studies (150 LHS runs, LAR): heave and pitch barely change while
    surge and tension change noticeably (gpc paper 4.3)."""
    study = CASES / "uq" / f"buoy_T{period}_anchors.toml"
    out = tmp_path / "g"
    assert main(["uq", str(study), "-o", str(out), "--json", "--quiet", "--workers", "2"]) == 0
    q = json.loads(capsys.readouterr().out)["quantities"]
    for name in ("surge", "heave", "pitch", "tension_line1", "tension_line3"):
        assert np.isfinite(q[name]["max_std"]), name
    # relative spread: the band's width against the quantity's own swing over the window
    def relative(name: str) -> float:
        swing = q[name]["max_mean"] - q[name]["min_mean"]
        return q[name]["max_std"] / swing
    assert relative("surge") > relative("heave")
    assert relative("tension_line3") > relative("pitch")


@pytest.mark.slow
def test_quick_case_g_floater_quantities(tmp_path, capsys):
    """The buoy study on quasi-static lines, 4 s, 10 LHS runs at p = 1 (about 30 s): the
    floater DOF quantities (a scalar and histories) go through, and the anchors move surge
    far more than heave, relative to their swing (gpc paper 4.3)."""
    text = (CASES / "uq" / "buoy_T1.20_anchors.toml").read_text()
    text = text.replace('case = "../cylinder_buoy/', f'case = "{CASES}/cylinder_buoy/')
    text = text.replace("surrogate_samples = 3000", "surrogate_samples = 3000\nbase_overrides"
                        " = ['lines.*.model=\"quasi-static\"', \"simulation.duration=4.0\", "
                        "\"waves.ramp_duration=1.0\"]")
    text = text.replace("samples = 150", "samples = 10").replace("order = 5", "order = 1")
    text = text.replace("window = [55.0, 60.0]", "window = [2.8, 4.0]")
    text += '\n[[quantities]]\nname = "surge_max"\ndof = "Surge"\nstatistic = "max"\n'
    out = tmp_path / "g"
    assert main(["uq", str(_write(tmp_path, text)), "-o", str(out), "--json", "--quiet"]) == 0
    q = json.loads(capsys.readouterr().out)["quantities"]
    assert q["surge_max"]["units"] == "m" and q["pitch"]["units"] == "rad"
    assert np.isfinite(q["surge_max"]["mean"])

    def relative(name: str) -> float:
        return q[name]["max_std"] / (q[name]["max_mean"] - q[name]["min_mean"])
    assert relative("surge") > 10.0 * relative("heave")
