"""Case titles: placeholders filled from the final values, unshown overrides appended."""

from __future__ import annotations

import pytest

from floatmoor.case.load import load_case
from floatmoor.cli import main
from floatmoor.errors import CaseError
from tests.conftest import LINDAHL_CASE

TEMPLATE = "Lindahl chain, circular motion r = {motion.radius:.2f} m, T = {motion.period:.2f} s"


def _case_with_title(tmp_path, title: str):
    text = LINDAHL_CASE.read_text().replace(f'title = "{TEMPLATE}"', f'title = "{title}"')
    assert title in text
    path = tmp_path / "case.toml"
    path.write_text(text)
    return path


def test_placeholders_read_the_file_values_by_default():
    case = load_case(LINDAHL_CASE)
    assert case.title == "Lindahl chain, circular motion r = 0.20 m, T = 1.25 s"
    assert case.title_template == TEMPLATE


def test_placeholders_follow_the_overrides_and_nothing_is_appended_for_them():
    """The bug: after --set motion.period=3.5 --set motion.radius=0.15 the title still
    read 'r = 0.20 m, T = 1.25 s'."""
    case = load_case(LINDAHL_CASE, ["motion.period=3.5", "motion.radius=0.15"])
    assert case.title == "Lindahl chain, circular motion r = 0.15 m, T = 3.50 s"


def test_a_formatted_placeholder_takes_an_array_an_override_sets():
    """A valid override may turn a scalar the title formats into an array (per-axis harmonic
    motion): the spec applies to each element, the case still loads."""
    qd = LINDAHL_CASE.parents[1] / "qd_verification" / "s2_d2.toml"
    case = load_case(qd, ['motion={kind = "harmonic", amplitude = [0.05, 0.1, 0.03], '
                          'period = [1.3, 1.7, 1.1]}'])
    assert "x amplitude 0.05 m, T = [1.3, 1.7, 1.1] s" in case.title


def test_overrides_the_title_does_not_show_are_appended_in_order():
    case = load_case(LINDAHL_CASE, ['lines.*.model="quasi-static"', "motion.period=3.5",
                                    "simulation.duration=20.0"])
    assert case.title == ("Lindahl chain, circular motion r = 0.20 m, T = 3.50 s "
                          "[lines.*.model=quasi-static, simulation.duration=20.0]")


def test_a_key_an_override_removed_reads_n_a_and_the_override_is_appended():
    case = load_case(LINDAHL_CASE, ['motion={kind = "harmonic", amplitude = [0.1, 0.0, 0.0], '
                                    "period = 2.0}"])
    assert case.title.startswith("Lindahl chain, circular motion r = n/a m, T = 2.00 s [motion=")


def test_literal_braces_and_unformatted_values(tmp_path):
    case = load_case(_case_with_title(tmp_path, "{{x}} {motion.sense}, {lines.chain.model}"))
    assert case.title == "{x} away-from-anchor-at-top, dynamic"


@pytest.mark.parametrize("title, found", [
    ("T = {motion.periode} s", "periode"),        # no such key
    ("T = {motion.period:d} s", "motion.period:d"),  # a spec that does not fit a float
    ("{lines.0.model}", "'0'"),                   # entries by name
    ("{lines.*.model}", "no '*'"),
    ("{motion}", "a table"),
    ("T = {motion.period", "T = {motion.period"),  # unbalanced brace
])
def test_bad_placeholder_is_a_case_error_at_title(tmp_path, title, found):
    with pytest.raises(CaseError) as info:
        load_case(_case_with_title(tmp_path, title))
    assert info.value.key == "title"
    assert found in info.value.found + info.value.expected


def test_bad_placeholder_is_status_2_without_output(tmp_path, capsys):
    path = _case_with_title(tmp_path, "T = {motion.periode} s")
    out = tmp_path / "out.nc"
    assert main(["run", str(path), "-o", str(out), "--quiet"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "title" in err[0] and "motion.periode" in err[0]
    assert not out.exists()


def test_an_overridden_title_is_filled_and_not_appended_to_itself():
    case = load_case(LINDAHL_CASE, ['title="chain at T = {motion.period:g} s"',
                                    "motion.period=2.0"])
    assert case.title == "chain at T = 2 s"
