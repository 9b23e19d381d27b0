"""The README stays true: two quick-start commands, CI runs the second one verbatim, every row
of the validation table names a test that exists, and the cases it mentions exist."""

from __future__ import annotations

import re

from tests.conftest import REPO

README = (REPO / "README.md").read_text()


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


def test_validation_rows_name_existing_tests():
    section = README.split("## Validation", 1)[1].split("\n## ", 1)[0]
    lines = section.strip().splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith("| "))
    end = next((i for i in range(start, len(lines)) if not lines[i].startswith("|")), len(lines))
    rows = [r for r in lines[start:end] if "---" not in r][1:]  # the validation table
    assert len(rows) >= 8
    for row in rows:
        test_ids = re.findall(r"`(tests/[^`:]+::[^`]+)`", row)
        assert test_ids, row
        for test_id in test_ids:
            path, _, name = test_id.partition("::")
            source = (REPO / path).read_text()
            assert re.search(rf"def {re.escape(name.split('[')[0])}\(", source), test_id
