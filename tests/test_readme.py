"""The README and the docs stay true: two quick-start commands, CI runs the second one
verbatim, every row of every validation table names a test that exists, and the case file the
getting-started page writes from scratch is valid and prints what the page shows."""

from __future__ import annotations

import re
import shlex

import pytest

from floatmoor.cli import main
from tests.conftest import REPO

README = (REPO / "README.md").read_text()
VALIDATION_PAGES = sorted((REPO / "docs" / "validation").glob("*.md"))
GETTING_STARTED = (REPO / "docs" / "getting_started.md").read_text()
#: A validation row, test names aside, longer than this is rewritten as a short row and a
#: note below the table (the README once held a row of over 1,000 characters).
MAX_ROW_CHARACTERS = 300
#: The README is what a visitor reads in five minutes (the target).
MAX_README_BYTES = 8000


def _quick_start() -> list[str]:
    section = README.split("## Quick start", 1)[1].split("##", 1)[0]
    block = re.search(r"```bash\n(.*?)```", section, re.S).group(1)
    return [ln for ln in block.splitlines() if ln.strip()]


def test_quick_start_has_two_commands_and_ci_runs_the_test_one():
    commands = _quick_start()
    assert len(commands) == 2
    install_run, install_test = commands
    assert "floatmoor run cases/" in install_run
    case = install_run.split("floatmoor run ", 1)[1].split()[0]
    assert (REPO / case).is_file()
    assert "pytest" in install_test
    ci = (REPO / ".ci" / "run").read_text().splitlines()
    assert install_test in ci  # verbatim


def test_readme_is_short_and_its_links_exist():
    assert len(README.encode()) < MAX_README_BYTES
    for target in re.findall(r"\]\(([^)#]+)(?:#[^)]*)?\)", README):
        if "://" not in target:
            assert (REPO / target).exists(), target


def _table_rows(text: str) -> list[str]:
    """The body rows of every validation table (a header with a `test` column) in a page."""
    rows, in_table = [], False
    for line in text.splitlines():
        if line.startswith("| ") and line.rstrip().endswith("| test |"):
            in_table = True
        elif in_table and line.startswith("|"):
            if not line.startswith("| ---"):
                rows.append(line)
        else:
            in_table = False
    return rows


def test_validation_pages_hold_tables():
    pages_with_rows = [p.name for p in VALIDATION_PAGES if _table_rows(p.read_text())]
    assert len(pages_with_rows) >= 8, pages_with_rows
    assert sum(len(_table_rows(p.read_text())) for p in VALIDATION_PAGES) >= 100


@pytest.mark.parametrize("page", VALIDATION_PAGES, ids=lambda p: p.name)
def test_validation_rows_name_existing_tests(page):
    for row in _table_rows(page.read_text()):
        cells = [c.strip() for c in row.strip().strip("|").split(" | ")]
        assert len(cells) == 6, row
        test_ids = re.findall(r"`(tests/[^`:]+::[^`]+)`", cells[5])
        assert test_ids, row
        for test_id in test_ids:
            path, _, name = test_id.partition("::")
            source = (REPO / path).read_text()
            assert re.search(rf"def {re.escape(name.split('[')[0])}\(", source), test_id
        assert len(" | ".join(cells[:5])) <= MAX_ROW_CHARACTERS, row


def _section(text: str, heading: str) -> str:
    return text.split(heading, 1)[1].split("\n## ", 1)[0]


def test_getting_started_own_case_is_valid_and_prints_what_the_page_shows(tmp_path, capsys,
                                                                           monkeypatch):
    section = _section(GETTING_STARTED, "## First own case")
    case_text = re.search(r"```toml\n(.*?)```", section, re.S).group(1)
    shown = re.search(r"```text\n(.*?)```", section, re.S).group(1).splitlines()
    commands = re.search(r"```bash\n(.*?)```", section, re.S).group(1).splitlines()
    assert commands[0] == "floatmoor check my_line.toml"
    (tmp_path / "my_line.toml").write_text(case_text)
    monkeypatch.chdir(tmp_path)
    for command in commands:
        argv = shlex.split(command)[1:]
        assert main(argv + ["--quiet"] if argv[0] == "run" else argv) == 0
    printed = capsys.readouterr().out.splitlines()
    for line in shown:
        assert line in printed, line  # the statistics, to the printed digits
    assert (tmp_path / "my_line.nc").is_file() and (tmp_path / "my_line.png").is_file()
