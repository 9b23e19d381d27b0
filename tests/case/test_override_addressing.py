"""``--set`` addressing: entries of [[lines]] by name or all by ``*``, never by a bare index."""

from __future__ import annotations

import pytest

from floatmoor.case.load import load_case
from floatmoor.errors import CaseError
from tests.conftest import CASES, LINDAHL_CASE

LC34 = CASES / "deepcwind" / "deepcwind_lc34.toml"


def test_wildcard_sets_every_line_and_a_name_one_line():
    case = load_case(LC34, ['lines.*.model="quasi-dynamic"', 'lines.line2.model="dynamic"',
                            "lines.*.dynamic.elements=4"])
    assert [line.model for line in case.lines] == ["quasi-dynamic", "dynamic", "quasi-dynamic"]
    # a missing sub-table is created in every line
    assert [line.dynamic.elements for line in case.lines] == [4, 4, 4]


def test_digit_segment_is_an_error_naming_the_entries():
    """The trap: LC34's lines are line1..line3, so ``lines.1`` read as line1 but
    set line2. Now it is bad input that lists the names and the wildcard."""
    with pytest.raises(CaseError) as info:
        load_case(LC34, ['lines.1.model="dynamic"'])
    err = info.value
    assert err.key == "lines.1" and err.found == "'1'"
    assert "line1, line2, line3" in err.expected and "'*'" in err.expected
    assert "(--set lines.1.model=\"dynamic\")" in err.source


def test_unknown_name_and_misplaced_wildcard_are_errors():
    with pytest.raises(CaseError) as info:
        load_case(LC34, ['lines.line4.model="dynamic"'])
    assert info.value.key == "lines.line4" and "line1, line2, line3" in info.value.expected
    with pytest.raises(CaseError) as info:
        load_case(LINDAHL_CASE, ["motion.*=1.0"])
    assert info.value.key == "motion.*"


def test_index_still_addresses_entries_without_names():
    """A vector (or an array of unnamed tables) has no names to confuse an index with."""
    case = load_case(LINDAHL_CASE, ["lines.chain.anchor.0=0.5"])
    assert case.lines[0].anchor == (0.5, 0.0, -3.0)
    with pytest.raises(CaseError) as info:
        load_case(LINDAHL_CASE, ["lines.chain.anchor.3=0.5"])
    assert info.value.key == "lines.chain.anchor.3" and "0..2" in info.value.expected


def test_error_of_a_wildcard_override_names_the_override():
    """Validation errors of values set by ``*`` still say they came from the command line."""
    with pytest.raises(CaseError) as info:
        load_case(LC34, ["lines.*.length=-1.0"])
    assert info.value.key == "lines[0].length"
    assert "(--set lines.*.length=-1.0)" in info.value.source
