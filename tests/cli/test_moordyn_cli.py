"""``floatmoor import moordyn`` and ``export moordyn``: write the file, print what they could not
map or represent, refuse an existing output and bad input (status 2, one line, nothing
written)."""

from __future__ import annotations

import shutil
import tomllib
from pathlib import Path

import pytest

from floatmoor.cli import main
from floatmoor.io.moordyn.parser import read_deck
from tests.conftest import LINDAHL_CASE

DECKS = Path(__file__).parents[1] / "data" / "moordyn"


def test_import_writes_the_case_and_lists_what_it_could_not_map(tmp_path, capsys):
    out = tmp_path / "oc3.toml"
    assert main(["import", "moordyn", str(DECKS / "oc3_hywind_lines.txt"), "-o", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "not mapped (11):" in printed and "option dtM = 0.002" in printed
    text = out.read_text()
    assert "# - option dtM = 0.002" in text  # the same list, as comments
    assert len(tomllib.loads(text)["lines"]) == 3


def test_import_refuses_an_existing_output_without_force(tmp_path, capsys):
    out = tmp_path / "case.toml"
    out.write_text("keep me\n")
    args = ["import", "moordyn", str(DECKS / "wd0050_chain.txt"), "-o", str(out)]
    assert main(args) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--force replaces an existing one" in err
    assert out.read_text() == "keep me\n"
    # --force replaces only a case file, never another file
    assert main([*args, "--force"]) == 2
    assert "which is not a TOML file" in capsys.readouterr().err
    assert out.read_text() == "keep me\n"
    out.write_text(LINDAHL_CASE.read_text())
    assert main([*args, "--force"]) == 0
    assert "[[lines]]" in out.read_text()


def test_bad_deck_is_status_2_and_writes_nothing(tmp_path, capsys):
    out = tmp_path / "case.toml"
    assert main(["import", "moordyn", str(DECKS / "bodies_and_rods.dat"), "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert "bodies_and_rods.dat:5: LINE TYPES: expected 10 columns" in err
    assert "Traceback" not in err and not out.exists()
    assert main(["import", "moordyn", str(DECKS / "mhk_rm1_floating.dat"), "-o", str(out)]) == 2
    assert "--water-depth" in capsys.readouterr().err and not out.exists()


# -- export moordyn ----------------------------------------------------------------------------

SYSTEM = Path(__file__).parents[1] / "data" / "systems" / "clump_buoy.toml"


def test_export_writes_the_deck_and_prints_its_notes(tmp_path, capsys):
    out = tmp_path / "system.dat"
    assert main(["export", "moordyn", str(SYSTEM), "-o", str(out)]) == 0
    printed = capsys.readouterr().out
    assert f"wrote {out} from {SYSTEM}" in printed
    assert "notes (also in the file's title block) (" in printed
    assert "  - line line1 is quasi-static in floatmoor" in printed
    text = out.read_text()
    assert "# line line1 is quasi-static in floatmoor" in text  # the same notes, as comments
    assert text.count("Free ") == 2 and "Coupled " in text


def test_export_applies_the_set_overrides(tmp_path):
    out = tmp_path / "system.dat"
    assert main(["export", "moordyn", str(SYSTEM), "-o", str(out),
                 "--set", "environment.water_depth=120.0"]) == 0
    assert read_deck(out).option("WtrDpth").value == "120.0"


def test_export_refuses_an_existing_output_without_force(tmp_path, capsys):
    out = tmp_path / "deck.dat"
    out.write_text("keep me\n")
    args = ["export", "moordyn", str(SYSTEM), "-o", str(out)]
    assert main(args) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--force replaces an existing one" in err
    assert out.read_text() == "keep me\n"
    # --force replaces only a MoorDyn input file, never another file
    assert main([*args, "--force"]) == 2
    assert "not a MoorDyn input file" in capsys.readouterr().err
    assert out.read_text() == "keep me\n"
    shutil.copy(DECKS / "wd0050_chain.txt", out)
    assert main([*args, "--force"]) == 0
    assert "MoorDyn Input File" in out.read_text()


@pytest.mark.parametrize("args, message", [
    (["--set", "environment.water_depth=-1.0"], "environment.water_depth: expected"),
    (["--set", "points.9.mass=1.0"], "points"),
])
def test_export_of_a_bad_case_is_status_2_and_writes_nothing(tmp_path, capsys, args, message):
    out = tmp_path / "deck.dat"
    assert main(["export", "moordyn", str(SYSTEM), "-o", str(out), *args]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err and message in err
    assert err.startswith("floatmoor: error: ") and not out.exists()


def test_export_refuses_an_output_in_a_missing_folder(tmp_path, capsys):
    out = tmp_path / "missing" / "deck.dat"
    assert main(["export", "moordyn", str(SYSTEM), "-o", str(out)]) == 2
    assert "a file in an existing folder" in capsys.readouterr().err and not out.exists()
