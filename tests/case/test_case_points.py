"""Points and multi-section lines in case files: the loader's system objects."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from floatmoor.case.load import load_case
from floatmoor.errors import CaseError
from tests.conftest import LINDAHL_CASE

SYSTEM = Path(__file__).parents[1] / "data" / "systems" / "clump_buoy.toml"


def test_short_form_line_is_a_section_between_implicit_points():
    case = load_case(LINDAHL_CASE)
    line = case.lines[0]
    assert [p.name for p in case.points] == ["chain.anchor", "chain.fairlead"]
    assert [p.kind for p in case.points] == ["fixed", "body"]
    assert case.point("chain.anchor").position == line.anchor == (0.0, 0.0, -3.0)
    assert (line.start, line.end) == ("chain.anchor", "chain.fairlead")
    (section,) = line.sections
    assert section.line_type is line.line_type and section.length == line.length == 33.0
    assert section.dynamic == line.dynamic
    assert not case.is_system


def test_sections_points_and_merged_numerics():
    case = load_case(SYSTEM, ["lines.line1.dynamic.order=3",
                              "lines.line1.sections.1.dynamic={elements = 20}"])
    line = case.lines[0]
    assert [(s.start, s.end) for s in line.sections] == [
        ("anchor", "clump"), ("clump", "buoy"), ("buoy", "fairlead")]
    assert [s.line_type.name for s in line.sections] == ["chain", "rope", "chain"]
    assert line.length == 412.0
    # the line's numerics are every section's defaults; a section's own keys override them
    assert [(s.dynamic.elements, s.dynamic.order) for s in line.sections] == [
        (None, 3), (20, 3), (None, 3)]  # None: chosen from the accuracy
    assert case.is_system
    with pytest.raises(ValueError, match="3 sections"):
        line.line_type
    clump = case.point("clump")
    assert (clump.kind, clump.mass, clump.volume, clump.drag_area,
            clump.added_mass_coefficient) == ("free", 2000.0, 0.26, 1.0, 1.0)


def test_points_no_line_uses_are_refused():
    with pytest.raises(CaseError, match="which no line uses"):
        load_case(SYSTEM, ['lines.line1.sections=[{type = "chain", length = 100.0}, '
                           '{type = "rope", length = 340.0}]'])


def test_one_section_line_in_either_form_loads_the_same(tmp_path):
    text = LINDAHL_CASE.read_text()
    long_form = text.replace('type = "chain"\nlength = 33.0                  # m, unstretched',
                             'sections = [{ type = "chain", length = 33.0 }]')
    assert long_form != text
    path = tmp_path / "long.toml"
    path.write_text(long_form)
    a, b = load_case(LINDAHL_CASE).lines[0], load_case(path).lines[0]
    assert a == b


def test_joint_placed_on_the_chord_at_its_length_fraction(tmp_path):
    text = LINDAHL_CASE.read_text().replace(
        'type = "chain"\nlength = 33.0                  # m, unstretched',
        'sections = [{ type = "chain", length = 11.0 }, { type = "chain", length = 22.0 }]')
    path = tmp_path / "two.toml"
    path.write_text(text)
    case = load_case(path)
    joint = case.point("chain.joint1")
    assert joint.kind == "free" and joint.mass == 0.0 and joint.volume == 0.0
    a, b = case.lines[0].anchor, case.lines[0].fairlead
    for c in range(3):
        assert math.isclose(joint.position[c], a[c] + (b[c] - a[c]) / 3.0, abs_tol=1e-12)
    assert [s.label for s in case.sections] == ["chain[0]", "chain[1]"]
    assert case.is_system
