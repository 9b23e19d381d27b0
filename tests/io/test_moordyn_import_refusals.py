"""``floatmoor import moordyn`` refuses what the case loader would refuse, naming the deck line
(the importer loads the case text in memory before writing it), and a deck's text cannot make
the case file invalid TOML: status 2, one line, nothing written."""

from __future__ import annotations

import tomllib
from pathlib import Path

import pytest

from floatmoor.case.load import load_case
from floatmoor.cli import main
from floatmoor.errors import CaseError
from floatmoor.io.moordyn.importer import import_deck
from floatmoor.io.moordyn.parser import parse_deck

DECKS = Path(__file__).parents[1] / "data" / "moordyn"
OC3 = (DECKS / "oc3_hywind_lines.txt").read_text()
#: More digits than Python converts to an int (sys.get_int_max_str_digits(), 4300).
HUGE = "1" * 5000


def _import(tmp_path: Path, text: str, capsys, name: str = "deck.txt") -> tuple[int, str, Path]:
    deck = tmp_path / name
    deck.write_text(text)
    out = tmp_path / "case.toml"
    code = main(["import", "moordyn", str(deck), "-o", str(out)])
    return code, capsys.readouterr().err, out


def _refused(code: int, err: str, out: Path) -> None:
    assert code == 2, err
    assert err.count("\n") == 1 and err.startswith("floatmoor: error: "), err
    assert "Traceback" not in err and not out.exists()


@pytest.mark.parametrize("old, new, where", [
    ("1     main       1        4", f"{HUGE}     main       1        4", ":19: LINES, column ID"),
    ("902.2     20      p\n2", f"902.2     {HUGE}      p\n2", ":19: LINES, column NumSegs"),
    ("1     main       1        4", f"1     main       {HUGE}        4",
     ":19: LINES, column AttachA"),
    ("4     Coupled", f"{HUGE}     Coupled", ":13: POINTS, column ID"),
    ("4     Coupled", f"4     Body{HUGE}", ":13: POINTS, column Attachment"),
])
def test_integers_beyond_moordyn_int_are_one_line_errors(tmp_path, capsys, old, new, where):
    code, err, out = _import(tmp_path, OC3.replace(old, new, 1), capsys)
    _refused(code, err, out)
    assert f"deck.txt{where}" in err and "2147483647" in err
    assert len(err) < 400  # the 5000 digits are cut in the message


@pytest.mark.parametrize("old, new, where, expected", [
    ("902.2     20      p\n2", "902.2     2000000000      p\n2",
     ":19: LINES 1 (the case's lines[0].dynamic.elements)", "<= 10000"),
    ("1             disableOutTime", "1e300 TMax",
     ":33: OPTIONS, TMax (the case's simulation.output_interval)", "output samples"),
    ("1             disableOutTime", "1e-300 dtOut",
     ":33: OPTIONS, dtOut (the case's simulation.output_interval)", "output samples"),
    ("1     main       1        4", "1     main       1        1",
     ":19: LINES 1 (the case's lines[0].end)", "a point other than"),
    ("853.87  0       -320.0", "853.87  0       -330.0",
     ":10: POINTS 1 (the case's points[0].position)", "on or above the seabed"),
    ("main       0.09", "main       1e-200", ":6: LINE TYPES 'main'", "ZeroDivisionError"),
])
def test_import_refuses_what_the_case_loader_refuses(tmp_path, capsys, old, new, where,
                                                     expected):
    code, err, out = _import(tmp_path, OC3.replace(old, new, 1), capsys)
    _refused(code, err, out)
    assert f"deck.txt{where}" in err and expected in err


@pytest.mark.parametrize("old, new, line", [
    ("input file of the mooring", "input file\x01 of the mooring", 2),  # title
    ("main       0.09", "ma\x1bin       0.09", 6),  # a line type name
    ("1     Fixed     853.87", "1     Fixed\x7f     853.87", 10),
])
def test_control_characters_are_refused_with_their_line(tmp_path, capsys, old, new, line):
    code, err, out = _import(tmp_path, OC3.replace(old, new, 1), capsys)
    _refused(code, err, out)
    assert f"deck.txt:{line}: expected text without control characters" in err
    assert "\x01" not in err and "\x1b" not in err and "\x7f" not in err


def test_a_newline_in_the_file_name_gives_a_valid_case(tmp_path, capsys):
    text = OC3.replace("MoorDyn input file of the mooring system for OC3-Hywind\n", "", 1)
    code, err, out = _import(tmp_path, text, capsys, name="two\nlines.txt")
    assert code == 0, err
    case = load_case(out)  # valid TOML, and a case the loader accepts
    assert "\n" not in case.title and "two\\x0alines.txt" in case.title
    out.unlink()
    code, err, out = _import(tmp_path, text.replace("902.2", "abc", 1), capsys,
                             name="bad\nname.txt")
    _refused(code, err, out)  # one line: the file name's newline is escaped
    assert "bad\\x0aname.txt:18: LINES, column UnstrLen" in err


def test_a_water_depth_given_on_the_command_line_is_checked_against_the_deck():
    deck = parse_deck(OC3, "d.txt")
    with pytest.raises(CaseError) as err:
        import_deck(deck, water_depth=100.0)  # the anchors are at z = -320 m
    assert str(err.value).startswith("d.txt:10: POINTS 1 (the case's points[0].position): "
                                     "expected a point on or above the seabed (z >= -100 m)")


def test_good_decks_still_import_and_load():
    for name in ("oc3_hywind_lines.txt", "tripod.txt", "lifting.txt"):
        text = import_deck(parse_deck((DECKS / name).read_text(), name)).text
        assert tomllib.loads(text)["lines"]



def test_printed_lists_escape_bidi_controls_of_deck_text(tmp_path, capsys):
    """A right-to-left override in an output flag (a format character, not a control
    character: valid in the case file) is escaped where the import prints it."""
    deck = tmp_path / "deck.txt"
    deck.write_text(OC3.replace("902.2     20      p", "902.2     20      p\u202e", 1))
    out = tmp_path / "case.toml"
    assert main(["import", "moordyn", str(deck), "-o", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "\u202e" not in printed and "output flags 'p\\u202e'" in printed
    assert "output flags 'p\u202e'" in out.read_text()  # the file keeps the text


def test_braces_in_the_deck_title_are_read_as_text(tmp_path, capsys):
    # a title's {...} are placeholders (floatmoor.case.title): the deck's braces are doubled
    text = OC3.replace("MoorDyn input file of the mooring system for OC3-Hywind",
                       "OC3-Hywind {rev 2}", 1)
    code, err, out = _import(tmp_path, text, capsys)
    assert code == 0, err
    assert load_case(out).title == "OC3-Hywind {rev 2}"
