"""Citations point at the project's own pages: no file cites the team-internal reference files
(they are not in the repository), and every page under ``docs/`` the package, the cases or the
tests cite exists, down to the section anchor when one is given."""

from __future__ import annotations

import re
import subprocess

import pytest

from tests.conftest import REPO

#: The internal reference files whose content now lives in docs/ (theory/, cases/ and
#: development.md), and the folder that held them.
RETIRED = re.compile(rb"physics\.md|cases\.md|capytaine_notes\.md|\bstyle\.md|shared[/]reference")
#: Run logs under tests/data are records of past runs, kept as they were written.
UNCHECKED_LOGS = re.compile(r"tests/data/.*\.log")
#: A documentation page cited by path, e.g. ``docs/theory/cable.md``.
DOC_PAGE = re.compile(r"docs/[A-Za-z0-9_./-]+?\.md\b")
#: A section of a page cited by its anchor, e.g. ``docs/development.md#case-513-axial-waves``.
DOC_ANCHOR = re.compile(r"(docs/[A-Za-z0-9_./-]+?\.md)#([A-Za-z0-9_-]+)")
#: Folders whose files cite documentation pages.
CITING = ("floatmoor", "cases", "tests")
#: The deepest heading level that gets an anchor: MyST's ``myst_heading_anchors`` in docs/conf.py.
ANCHOR_LEVELS = int(re.search(r"^myst_heading_anchors\s*=\s*(\d+)",
                              (REPO / "docs" / "conf.py").read_text(encoding="utf-8"),
                              re.MULTILINE).group(1))
#: A Markdown heading (ATX style) and a code fence, which hides headings.
HEADING = re.compile(r"^(#{1,6})\s+(.+?)\s*#*\s*$")
FENCE = re.compile(r"^\s*(```|~~~|:::)")


def _repository_files() -> list[str]:
    """Files git knows (tracked or new, not ignored): what a clone of the repository holds."""
    try:
        out = subprocess.run(["git", "ls-files", "--cached", "--others", "--exclude-standard"],
                             cwd=REPO, capture_output=True, check=True, text=True).stdout
    except (OSError, subprocess.CalledProcessError):
        pytest.skip("not a git checkout: the repository's file list is unknown")
    return [name for name in out.splitlines() if (REPO / name).is_file()]


def _citing_texts() -> dict[str, str]:
    """Text of every file under :data:`CITING` (binary files cite no page)."""
    texts = {}
    for name in _repository_files():
        if not name.startswith(CITING):
            continue
        try:
            texts[name] = (REPO / name).read_text(encoding="utf-8")
        except UnicodeDecodeError:
            continue
    return texts


def slug(title: str) -> str:
    """MyST's heading anchor (GitHub style): lower case, spaces to '-', other punctuation
    dropped (``myst_parser.slugs.github_slugify``)."""
    return re.sub(r"[^\w\- ]", "", title.lower().replace(" ", "-"))


def heading_anchors(markdown: str) -> set[str]:
    """Anchors MyST gives the headings of a page, levels 1 to :data:`ANCHOR_LEVELS`; a repeated
    slug gets ``-1``, ``-2``, ... as MyST numbers it."""
    anchors: set[str] = set()
    fenced = False
    for line in markdown.splitlines():
        if FENCE.match(line):
            fenced = not fenced
            continue
        match = None if fenced else HEADING.match(line)
        if match and len(match.group(1)) <= ANCHOR_LEVELS:
            base = anchor = slug(match.group(2))
            count = 0
            while anchor in anchors:
                count += 1
                anchor = f"{base}-{count}"
            anchors.add(anchor)
    return anchors


def test_slug_follows_the_myst_rule():
    assert slug("Case 5.1.3: axial waves") == "case-513-axial-waves"
    assert slug("5.4 Kernel-oracle tolerance") == "54-kernel-oracle-tolerance"
    assert heading_anchors("# A\n```\n# B\n```\n## A\n#### C\n") == {"a", "a-1"}


def test_no_file_cites_the_internal_reference_files():
    """Text and binary files alike (a netCDF attribute can carry a case file's comments)."""
    offenders = [name for name in _repository_files()
                 if not UNCHECKED_LOGS.fullmatch(name)
                 and RETIRED.search((REPO / name).read_bytes())]
    assert not offenders, f"cite docs/ pages instead, in: {offenders}"


def test_cited_documentation_pages_exist():
    cited: dict[str, set[str]] = {}
    for name, text in _citing_texts().items():
        for page in DOC_PAGE.findall(text):
            cited.setdefault(page, set()).add(name)
    assert cited, "no docs/ page is cited: the pattern is broken"
    missing = {page: sorted(names) for page, names in cited.items() if not (REPO / page).is_file()}
    assert not missing, f"cited pages that do not exist: {missing}"


def test_cited_section_anchors_exist():
    cited: dict[tuple[str, str], set[str]] = {}
    for name, text in _citing_texts().items():
        for page, anchor in DOC_ANCHOR.findall(text):
            cited.setdefault((page, anchor), set()).add(name)
    assert cited, "no docs/ section is cited: the pattern is broken"
    anchors = {page: heading_anchors((REPO / page).read_text(encoding="utf-8"))
               for page, _ in cited if (REPO / page).is_file()}
    missing = {f"{page}#{anchor}": sorted(names) for (page, anchor), names in cited.items()
               if anchor not in anchors.get(page, set())}
    assert not missing, f"cited sections that do not exist (MyST heading anchors): {missing}"
