"""``floatmoor report`` and ``floatmoor compare`` are reachable from the command line."""

from __future__ import annotations

from floatmoor.cli import main
from tests.conftest import LINDAHL_CASE


def test_report_and_compare_through_main(tmp_path, capsys) -> None:
    run = tmp_path / "lindahl.nc"
    assert main(["run", str(LINDAHL_CASE), "-o", str(run), "--quiet",
                 "--set", "simulation.duration=5.0"]) == 0
    assert main(["report", str(run), "-o", str(tmp_path / "rep")]) == 0
    assert (tmp_path / "rep" / "summary.md").stat().st_size > 200
    assert main(["report", str(tmp_path / "missing.nc"), "-o", str(tmp_path / "r2")]) == 2
    assert "missing.nc" in capsys.readouterr().err
    assert not (tmp_path / "r2").exists()
    assert main(["compare", str(LINDAHL_CASE), "--models", "quasi-static,nonsense", "-o",
                 str(tmp_path / "c")]) == 2
