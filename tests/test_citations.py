"""Citations name pages, not tracker numbers (docs/development.md#8-citations-in-code).

Code and tests cite docs pages and papers, never a numbered issue of a tracker the reader of
the code does not have: no line of a ``.py`` file under ``floatmoor/`` or ``tests/`` may match
:data:`TRACKER_REFERENCE` (the word, one space or hyphen, an optional ``#``, a number). The
documentation tells the project's history in words too ("the first accuracy-targeted
defaults", not a number): no line of a file under ``docs/``, nor of README.md, may match it
either. Data file names such as ``issue17_unchanged.json`` do not match; the records under
``tests/data/`` (reference READMEs, logs, decks) are what was written when they were made and
are not read.
"""

from __future__ import annotations

import re
from pathlib import Path

from tests.package_source import PACKAGE, REPO, TESTS, relative

#: Folders whose ``.py`` files must not cite tracker issue numbers.
CODE_ROOTS = (PACKAGE, TESTS)
#: The documentation: every text file of docs/ (pages, their generators, the Sphinx
#: configuration) and the README.
DOCS = REPO / "docs"
README = REPO / "README.md"
#: Suffixes of the documentation files that are text.
DOC_SUFFIXES = frozenset({".md", ".py", ".txt", ".rst"})
#: Folders of docs/ that a build makes (git ignores them): not the documentation's source.
BUILT = frozenset({"_build", "auto_examples"})
#: A numbered tracker reference; built from pieces so that this file's source does not match.
TRACKER_REFERENCE = re.compile(r"\b[Ii]ssue" + r"s?[ -]#?\d+")


def _tracker_references(name: str, text: str) -> list[str]:
    """``name:line: text`` of every line of ``text`` that cites a numbered tracker issue."""
    return [f"{name}:{number}: {line.strip()}"
            for number, line in enumerate(text.splitlines(), start=1)
            if TRACKER_REFERENCE.search(line)]


def _references_in(paths: list[Path]) -> list[str]:
    return [found for path in paths
            for found in _tracker_references(relative(path), path.read_text(encoding="utf-8"))]


def test_tracker_reference_pattern() -> None:
    """The pattern flags the word with a number after a space, a hyphen or ``#``, not data
    file names."""
    word = "Issue"
    planted = (f"# {word} 17: 1 %\n"
               f"x = 1  # see {word.lower()}s 6 and 7\n"
               f'"""Fixed ({word.lower()} #5)."""\n'
               f"BASELINE = '{word.lower()}17_unchanged.json'\n"
               f"# the {word.lower()}'s targets\n"
               f"| 2 % ({word.lower()}-15) |\n")
    assert _tracker_references("planted.py", planted) == [
        f"planted.py:1: # {word} 17: 1 %",
        f"planted.py:2: x = 1  # see {word.lower()}s 6 and 7",
        f'planted.py:3: """Fixed ({word.lower()} #5)."""',
        f"planted.py:6: | 2 % ({word.lower()}-15) |"]


def test_code_cites_no_tracker_issue_numbers() -> None:
    """Comments, docstrings and messages say what they mean or cite a docs page instead."""
    problems = _references_in([path for root in CODE_ROOTS
                               for path in sorted(root.rglob("*.py"))])
    assert not problems, ("cite the docs page (with its anchor) or paper that holds the "
                          "decision, not the tracker's issue number:\n" + "\n".join(problems))


def test_docs_cite_no_tracker_issue_numbers() -> None:
    """The pages say what a change was ("the first accuracy-targeted defaults", "when the
    references were reviewed") instead of which issue it was."""
    pages = [path for path in sorted(DOCS.rglob("*"))
             if path.is_file() and path.suffix in DOC_SUFFIXES
             and not BUILT & set(path.relative_to(DOCS).parts)] + [README]
    assert len(pages) > 50, "the documentation was not found"
    problems = _references_in(pages)
    assert not problems, ("say what the change or decision was, not its issue number "
                          "(docs/development.md#8-citations-in-code):\n" + "\n".join(problems))
