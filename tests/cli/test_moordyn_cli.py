"""``floatmoor import moordyn``: writes the case, prints what it could not map, refuses an
existing output and bad decks (status 2, nothing written)."""

from __future__ import annotations

import tomllib
from pathlib import Path

from floatmoor.cli import main

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
