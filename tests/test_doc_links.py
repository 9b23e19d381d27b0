"""Citations point at the project's own pages: no file cites the team-internal reference files
(they are not in the repository), and every page under ``docs/`` the package, the cases or the
tests cite exists (issue 19)."""

from __future__ import annotations

import re
import subprocess

import pytest

from tests.conftest import REPO

#: The internal reference files whose content now lives in docs/ (theory/ and cases/ pages).
RETIRED = re.compile(rb"physics\.md|cases\.md|capytaine_notes\.md")
#: A documentation page cited by path, e.g. ``docs/theory/cable.md``.
DOC_PAGE = re.compile(r"docs/[A-Za-z0-9_./-]+?\.md\b")
#: Folders whose files cite documentation pages.
CITING = ("floatmoor", "cases", "tests")


def _repository_files() -> list[str]:
    """Files git knows (tracked or new, not ignored): what a clone of the repository holds."""
    try:
        out = subprocess.run(["git", "ls-files", "--cached", "--others", "--exclude-standard"],
                             cwd=REPO, capture_output=True, check=True, text=True).stdout
    except (OSError, subprocess.CalledProcessError):
        pytest.skip("not a git checkout: the repository's file list is unknown")
    return [name for name in out.splitlines() if (REPO / name).is_file()]


def test_no_file_cites_the_internal_reference_files():
    """Text and binary files alike (a netCDF attribute can carry a case file's comments)."""
    offenders = [name for name in _repository_files()
                 if RETIRED.search((REPO / name).read_bytes())]
    assert not offenders, f"cite docs/ pages instead, in: {offenders}"


def test_cited_documentation_pages_exist():
    cited: dict[str, set[str]] = {}
    for name in _repository_files():
        if not name.startswith(CITING):
            continue
        try:
            text = (REPO / name).read_text(encoding="utf-8")
        except UnicodeDecodeError:
            continue
        for page in DOC_PAGE.findall(text):
            cited.setdefault(page, set()).add(name)
    assert cited, "no docs/ page is cited: the pattern is broken"
    missing = {page: sorted(names) for page, names in cited.items() if not (REPO / page).is_file()}
    assert not missing, f"cited pages that do not exist: {missing}"
