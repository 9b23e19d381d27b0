"""Reference (published) columns, ``floatmoor compare`` and bad input of the report commands."""

from __future__ import annotations

import argparse
from pathlib import Path

import pytest

from floatmoor.errors import ModelValidityWarning
from floatmoor.io.netcdf import read_dataset
from floatmoor.post.statistics import time_statistics
from floatmoor.cli.report import compare_command, report_command
from floatmoor.report.reference import load_reference
from floatmoor.simulation.forced import run_forced_motion
from floatmoor.case.load import load_case
from tests.conftest import CASES, LINDAHL_CASE
from tests.report.test_report import TABLE_RTOL, assert_png_not_blank, cell, table_rows

#: Published LC34 / LC43 files (docs/cases/deepcwind.md, quasi-dynamic paper Tables 8 to 10).
PUBLISHED = {"lc34": CASES / "deepcwind" / "published_lc34.toml",
             "lc43": CASES / "deepcwind" / "published_lc43.toml"}


def _ns(**kwargs) -> argparse.Namespace:
    base = dict(start=None, reference=None, nominal_diameter=[], html=False)
    base.update(kwargs)
    return argparse.Namespace(**base)


@pytest.fixture(scope="module")
def lindahl_run(tmp_path_factory) -> Path:
    path = tmp_path_factory.mktemp("lindahl") / "lindahl.nc"
    run_forced_motion(load_case(LINDAHL_CASE), output=path)
    return path


def test_published_files_hold_cases_md_values() -> None:
    lc34 = {c.key: c for c in load_reference(PUBLISHED["lc34"]).columns}
    lc43 = {c.key: c for c in load_reference(PUBLISHED["lc43"]).columns}
    assert all(c.label.startswith("published") for c in [*lc34.values(), *lc43.values()])
    assert lc34["quasi-static"].lines["line2"] == {"mean": 1193e3, "std": 119.6e3,
                                                   "min": 909.6e3, "max": 2299e3,
                                                   "damage": 1.752e-7}
    assert lc34["experiment"].lines["line1"]["damage"] == 1.764e-6
    assert lc43["quasi-dynamic"].lines["line2"]["max"] == 5246e3
    assert lc43["dynamic"].lines["line1"]["std"] == 37.8e3
    # the published ordering the LC34 comparison is to show
    qs, qd, dyn = (lc34[k].lines["line2"] for k in ("quasi-static", "quasi-dynamic", "dynamic"))
    assert qs["std"] < 0.5 * min(qd["std"], dyn["std"])
    assert qs["damage"] < 1e-2 * min(qd["damage"], dyn["damage"])
    assert 0.5 < qd["damage"] / dyn["damage"] < 2.0
    assert load_reference(PUBLISHED["lc34"]).default_nominal_diameter == 0.0779


def test_reference_column_beside_the_runs(lindahl_run, tmp_path) -> None:
    ref = tmp_path / "ref.toml"
    ref.write_text('title = "Published values (test)"\nsource = "a test"\n'
                   "nominal_diameter = 0.003\n"
                   '[values.paper]\nlabel = "published: paper"\n'
                   "[values.paper.chain]\nmean = 27.5\nstd = 20.25\ndamage = 3.5e-8\n")
    out = tmp_path / "r"
    assert report_command(_ns(runs=[str(lindahl_run)], output=str(out),
                              reference=str(ref))) == 0
    md = (out / "summary.md").read_text()
    rows = table_rows(md, "Fairlead tension statistics, line chain")
    assert rows[0] == ["statistic", "unit", "lindahl", "published: paper"]
    assert cell(rows, "mean", "published: paper") == "27.5"
    assert cell(rows, "max", "published: paper") == "–"
    ds = read_dataset(lindahl_run)
    mean = float(time_statistics(ds["fairlead_tension"], start=2.5)["mean"].sel(line="chain"))
    assert float(cell(rows, "mean", "lindahl")) == pytest.approx(mean, rel=TABLE_RTOL)
    damage = table_rows(md, "Fatigue damage (Miner) of the fairlead tension")
    assert cell(damage, "chain", "published: paper") == "3.5e-08"
    # the reference file's nominal diameter is used, and said so
    d_rows = table_rows(md, "Chain nominal diameters used for the damage")
    assert d_rows[1][2:] == ["0.003", "reference file"]
    assert "**Published values (test)**" in md and "not results of these runs" in md


def test_compare_lindahl_models_side_by_side(tmp_path, capsys) -> None:
    out = tmp_path / "cmp"
    status = compare_command(_ns(case=str(LINDAHL_CASE), models="quasi-static,dynamic",
                                 overrides=[], workers=1, quiet=True, output=str(out)))
    assert status == 0, capsys.readouterr().err
    md = (out / "summary.md").read_text()
    rows = table_rows(md, "Fairlead tension statistics, line chain")
    assert rows[0][2:] == ["quasi-static", "dynamic"]
    for model in ("quasi-static", "dynamic"):
        ds = read_dataset(out / "runs" / f"{model}.nc")
        assert str(ds["model"].values[0]) == model
        std = float(time_statistics(ds["fairlead_tension"], start=2.5)["std"].sel(line="chain"))
        assert float(cell(rows, "std", model)) == pytest.approx(std, rel=TABLE_RTOL)
    # the dynamic chain's snap loads: a larger tension STD than the quasi-static catenary
    assert float(cell(rows, "std", "dynamic")) > float(cell(rows, "std", "quasi-static"))
    assert_png_not_blank(out / "tension_psd.png")


def _bad(handler, capsys, out: Path, **kwargs) -> str:
    assert handler(_ns(output=str(out), **kwargs)) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "Traceback" not in err
    assert not out.exists()
    return err


def test_bad_input_exits_2_with_one_message(lindahl_run, tmp_path, capsys) -> None:
    out = tmp_path / "out"
    err = _bad(report_command, capsys, out, runs=[str(tmp_path / "missing.nc")])
    assert "missing.nc" in err and "no such file" in err
    junk = tmp_path / "junk.nc"
    junk.write_text("not netcdf")
    assert "junk.nc" in _bad(report_command, capsys, out, runs=[str(junk)])
    assert "--start" in _bad(report_command, capsys, out, runs=[str(lindahl_run)], start="-1")
    err = _bad(report_command, capsys, out, runs=[str(lindahl_run)], start="100")
    assert "--start" in err and "0 to 15 s" in err
    err = _bad(report_command, capsys, out, runs=[str(lindahl_run)],
               nominal_diameter=["line9=0.1"])
    assert "--nominal-diameter" in err and "line9" in err
    ref = tmp_path / "ref.toml"
    ref.write_text('[values.a.line7]\nmean = 1.0\n')
    assert "line7" in _bad(report_command, capsys, out, runs=[str(lindahl_run)],
                           reference=str(ref))
    assert "nope.toml" in _bad(report_command, capsys, out, runs=[str(lindahl_run)],
                               reference=str(tmp_path / "nope.toml"))
    err = _bad(compare_command, capsys, out, case=str(LINDAHL_CASE), models="static,dynamic",
               overrides=[], workers=1, quiet=True)
    assert "--models" in err and "'static'" in err
    err = _bad(compare_command, capsys, out, case=str(tmp_path / "none.toml"),
               models="dynamic", overrides=[], workers=1, quiet=True)
    assert "none.toml" in err
    a_file = tmp_path / "file.txt"
    a_file.write_text("x")
    assert report_command(_ns(runs=[str(lindahl_run)], output=str(a_file))) == 2
    assert "-o/--output" in capsys.readouterr().err


#: Short quasi-static and dynamic Lindahl runs (ramp 2.5 s + 2 cycles).
SHORT_COMPARE = ["simulation.duration=5.0"]


def _compare(out: Path, models: str, overrides: list[str] = SHORT_COMPARE) -> int:
    return compare_command(_ns(case=str(LINDAHL_CASE), models=models, overrides=overrides,
                               workers=1, quiet=True, output=str(out)))


def test_compare_resumes_models_already_run(tmp_path, capsys, monkeypatch) -> None:
    from floatmoor.campaign import runner as campaign_runner
    from floatmoor.campaign import worker

    out = tmp_path / "cmp"
    assert _compare(out, "quasi-static,dynamic") == 0, capsys.readouterr().err
    first = (out / "summary.md").read_text()
    calls = []
    original = worker.run_one
    monkeypatch.setattr(campaign_runner, "run_one",
                        lambda *a: calls.append(a[1][-1]) or original(*a))
    # the same comparison again: nothing runs, the same report
    assert _compare(out, "quasi-static,dynamic") == 0
    assert calls == []
    assert table_rows((out / "summary.md").read_text(), "Fairlead tension statistics, line "
                      "chain") == table_rows(first, "Fairlead tension statistics, line chain")
    # a model whose run file went missing runs again, and only it
    (out / "runs" / "dynamic.nc").unlink()
    assert _compare(out, "quasi-static,dynamic") == 0
    assert calls == ['lines.*.model="dynamic"']
    # other models (or overrides) in the same folder: a new comparison, not an error
    calls.clear()
    with pytest.warns(ModelValidityWarning, match="run quasi-dynamic: line 'chain'"):
        # T = 1.25 s: the quasi-dynamic line outside its range (alpha ~1.3), as the report says
        assert _compare(out, "quasi-static,quasi-dynamic") == 0, capsys.readouterr().err
    assert "**Run quasi-dynamic is outside its model's validity**" in \
        (out / "summary.md").read_text()
    assert calls == ['lines.*.model="quasi-static"', 'lines.*.model="quasi-dynamic"']
    rows = table_rows((out / "summary.md").read_text(), "Fairlead tension statistics, line chain")
    assert rows[0][2:] == ["quasi-static", "quasi-dynamic"]


def test_compare_reports_a_failing_model_and_exits_1(tmp_path, capsys) -> None:
    """A catenary that cannot converge fails the quasi-static and quasi-dynamic runs at the
    first step; the dynamic run still runs; the message names the failed models."""
    out = tmp_path / "cmp"
    failing = [*SHORT_COMPARE, "lines.chain.quasi_static.max_iterations=1",
               "lines.chain.quasi_static.tolerance=1e-16"]
    assert _compare(out, "quasi-static,dynamic", failing) == 1
    err = capsys.readouterr().err
    assert "run failed: 1 of 2 model runs failed" in err
    assert "quasi-static: SolverError: line 'chain' (quasi-static)" in err
    assert "dynamic:" not in err.replace("quasi-static", "")
    assert "Traceback" not in err and not (out / "summary.md").exists()
    assert read_dataset(out / "runs" / "dynamic.nc").attrs["status"] == "complete"
    assert read_dataset(out / "runs" / "quasi-static.nc").attrs["status"].startswith("failed")


def test_interrupted_compare_exits_130_without_traceback(tmp_path, capsys, monkeypatch) -> None:
    import floatmoor.report.compare as compare

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(compare, "compare_models", interrupted)
    assert _compare(tmp_path / "cmp", "quasi-static,dynamic") == 130
    err = capsys.readouterr().err
    assert err.startswith("floatmoor: interrupted;") and "re-run to resume" in err
