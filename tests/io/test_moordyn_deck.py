"""MoorDyn decks: the strict parser, the writer, the line-type mapping and the import into
case-file text (floatmoor.io.moordyn), on MoorDyn's own decks (tests/data/moordyn)."""

from __future__ import annotations

import dataclasses
import math
import tomllib
from pathlib import Path

import pytest

from floatmoor.errors import CaseError
from floatmoor.io.moordyn.importer import import_deck
from floatmoor.io.moordyn.line_types import (MoorDynLineType, floatmoor_line_type,
                                             moordyn_line_type, seabed_from_moordyn,
                                             seabed_to_moordyn)
from floatmoor.io.moordyn.parser import parse_deck, read_deck
from floatmoor.io.moordyn.writer import deck_text

DECKS = Path(__file__).parents[1] / "data" / "moordyn"
GOOD = ["oc3_hywind_lines.txt", "wd0050_chain.txt", "lifting.txt", "pendulum.txt",
        "tripod.txt", "mhk_rm1_floating.dat"]


def _strip(items):
    return [dataclasses.replace(i, line_number=0) for i in items]


@pytest.mark.parametrize("name", GOOD)
def test_written_deck_reads_back_the_same(name):
    deck = read_deck(DECKS / name)
    again = parse_deck(deck_text(deck, ["a note"]), "again")
    assert _strip(again.line_types) == _strip(deck.line_types)
    assert [dataclasses.replace(p, line_number=0, attachment_text="") for p in again.points] == \
        [dataclasses.replace(p, line_number=0, attachment_text="") for p in deck.points]
    assert _strip(again.lines) == _strip(deck.lines)
    assert [(o.key, o.value) for o in again.options] == [(o.key, o.value) for o in deck.options]


def test_oc3_deck_values():
    deck = read_deck(DECKS / "oc3_hywind_lines.txt")
    assert [t.name for t in deck.line_types] == ["main"]
    assert deck.line_types[0].axial_stiffness == 384.243e6
    assert [p.attachment for p in deck.points] == ["fixed"] * 3 + ["coupled"] * 3
    assert [(ln.start, ln.end, ln.segments) for ln in deck.lines] == [(1, 4, 20), (2, 5, 20),
                                                                        (3, 6, 20)]
    assert deck.outputs == ("FairTen1", "FairTen2", "FairTen3")


def test_v1_section_names_with_v2_columns():
    deck = read_deck(DECKS / "lifting.txt")  # CONNECTION PROPERTIES
    assert deck.points[1].attachment == "free" and deck.points[1].mass == 1e3


@pytest.mark.parametrize("edit, where, expected", [
    (("902.2     20", "abc       20"), ":19", "LINES, column UnstrLen: expected a number [m], "
                                              "found 'abc'"),
    (("Coupled    5.2", "Floating   5.2"), ":13", "Attachment: expected Fixed, Vessel"),
    (("1     main       1        4", "1     main       1        9"), ":19",
     "AttachB: expected the ID of a POINTS row, found 9"),
    (("1     main       1        4", "1     chain      1        4"), ":19",
     "LineType: expected the name of a LINE TYPES row (main)"),
    (("384.243E6", "tension.txt"), ":6", "tables of nonlinear properties are not supported"),
    (("(#)   (name)     (#)", "ID   (name)     (#)"), ":18", "a row of units in parentheses"),
    (("FairTen3\n", "FairTen3\n--------- need this line ---\nstray\n"), ":39",
     "nothing after the closing line"),
])
def test_malformed_deck_names_file_line_and_finding(tmp_path, edit, where, expected):
    text = (DECKS / "oc3_hywind_lines.txt").read_text().replace(*edit, 1)
    path = tmp_path / "bad.txt"
    path.write_text(text)
    with pytest.raises(CaseError) as err:
        read_deck(path)
    assert f"{path}{where}" in str(err.value) and expected in str(err.value)


def test_deck_with_eleven_line_type_columns_is_refused():
    with pytest.raises(CaseError, match=r"bodies_and_rods.dat:5: LINE TYPES: expected 10 "):
        read_deck(DECKS / "bodies_and_rods.dat")


def test_line_type_mapping_inverts_exactly():
    md = MoorDynLineType(diameter=0.252, mass_per_length=390.0, axial_stiffness=1.674e9,
                         internal_damping=-1.0, normal_drag_coefficient=1.37,
                         added_mass_coefficient=1.0, tangential_drag_coefficient=0.64,
                         tangential_added_mass_coefficient=0.3)
    fm = floatmoor_line_type(md)
    desc = type("Desc", (), fm)
    back = moordyn_line_type(desc, -1.0)
    for f in dataclasses.fields(md):
        assert getattr(back, f.name) == pytest.approx(getattr(md, f.name), rel=1e-14)
    k, c = seabed_to_moordyn(*seabed_from_moordyn(1e5, 1e4, desc), desc)
    assert (k, c) == (pytest.approx(1e5, rel=1e-14), pytest.approx(1e4, rel=1e-14))


def _case(name, **kw):
    result = import_deck(read_deck(DECKS / name), **kw)
    return tomllib.loads(result.text), result.unmapped


def test_import_maps_the_oc3_deck():
    case, unmapped = _case("oc3_hywind_lines.txt")
    lt = case["line_types"]["main"]
    assert lt["diameter"] == 0.09
    assert lt["material_density"] * math.pi * 0.09 ** 2 / 4 == pytest.approx(77.7066)
    assert lt["tangential_drag_coefficient"] == pytest.approx(0.1 * math.pi)
    # MoorDyn: c = 0.8 (L/20) sqrt(EA m); floatmoor: c = 2 zeta L sqrt(EA m) / pi
    assert lt["internal_damping_ratio"] == pytest.approx(0.8 * math.pi / 40, rel=1e-14)
    assert [p["kind"] for p in case["points"]] == ["fixed"] * 3 + ["body"] * 3
    assert [(ln["start"], ln["end"]) for ln in case["lines"]][0] == ("point1", "point4")
    assert case["lines"][0]["dynamic"] == {"elements": 4, "order": 5}
    assert case["environment"] == {"water_density": 1025.0, "water_depth": 320.0,
                                   "gravity": 9.80665}
    assert case["seabed"]["stiffness"] == 3e6
    text = "\n".join(unmapped)
    assert "option dtM = 0.002" in text and "OUTPUTS FairTen1" in text
    assert "output flags 'p'" in text


def test_import_splits_a_type_whose_lines_need_different_damping_ratios(tmp_path):
    text = (DECKS / "oc3_hywind_lines.txt").read_text().replace(
        "902.2     20      p\n3", "902.2     40      p\n3", 1)
    path = tmp_path / "two.txt"
    path.write_text(text)
    case = tomllib.loads(import_deck(read_deck(path)).text)
    assert [ln["type"] for ln in case["lines"]] == ["main", "main_2", "main"]
    assert case["line_types"]["main_2"]["internal_damping_ratio"] == pytest.approx(
        0.8 * math.pi / 80, rel=1e-14)


def test_import_lists_what_changes_the_physics():
    _, unmapped = _case("tripod.txt")
    text = "\n".join(unmapped)
    assert "EI = 9.32126e+07" in text and "[physics, approximate]" in text
    assert "option Currents = 0 (line" in text and "off, no effect" in text


def test_import_of_a_moordyn_f_deck_needs_a_water_depth():
    with pytest.raises(CaseError, match="WtrDpth: expected a water depth"):
        _case("mhk_rm1_floating.dat")
    case, unmapped = _case("mhk_rm1_floating.dat", water_depth=50.0)
    assert case["environment"]["water_depth"] == 50.0
    assert any("EI = 0.8" in item for item in unmapped)


def test_import_keeps_free_point_mass_and_friction():
    case, _ = _case("wd0050_chain.txt")
    assert case["seabed"]["friction_coefficient"] == 0.5
    # FricDamp (MoorDyn's default 200 N s/m) = w l / v_c on a resting node
    lt = case["line_types"]["chain"]
    w = lt["mass_per_length"] * 9.80665 * (1 - 1025.0 / lt["material_density"])
    assert case["seabed"]["slip_speed"] == pytest.approx(w * 410 / 82 / 200.0, rel=1e-14)
    case, _ = _case("pendulum.txt")
    free = case["points"][1]
    assert (free["kind"], free["mass"], free["volume"]) == ("free", 1e5, 0.0)
