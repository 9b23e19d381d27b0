"""Tests mirror the package and their kinds are markers
(docs/development.md#where-tests-live).

``tests/`` mirrors ``floatmoor/``; a ``.py`` file sits at the top of ``tests/``, in a folder
named in :data:`TEST_EXTRA_FOLDERS`, or in a folder whose path is that of a package of
``floatmoor/`` (``tests/mooring/dg/`` for ``floatmoor/mooring/dg/``). The kind of a test is a
marker, and every marker used is registered in pyproject.toml, whose pytest options keep
``--strict-markers``.
"""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

from tests.package_source import PACKAGE, REPO, TESTS

#: Folders of tests/ that mirror no package: data files, the NumPy oracles of the kernels, and
#: the timings (not in the default run).
TEST_EXTRA_FOLDERS = frozenset({"data", "oracles", "benchmarks"})
#: pytest's own markers, which need no registration.
BUILTIN_MARKERS = frozenset({"parametrize", "skip", "skipif", "xfail", "usefixtures",
                             "filterwarnings"})
#: A marker applied in a test file: ``pytest.mark.<name>``.
MARKER_USE = re.compile(r"\bpytest\.mark\.([A-Za-z_]\w*)")


def _misplaced_tests(tests: Path, package: Path) -> list[str]:
    """The ``.py`` files under ``tests`` in a folder that is neither the top, an extra folder
    nor the mirror of a package (a folder with an ``__init__.py``) under ``package``."""
    misplaced = []
    for path in sorted(tests.rglob("*.py")):
        folder = path.relative_to(tests).parent.parts
        if "__pycache__" in folder or not folder or folder[0] in TEST_EXTRA_FOLDERS:
            continue
        if not package.joinpath(*folder, "__init__.py").is_file():
            misplaced.append(path.relative_to(tests).as_posix())
    return misplaced


def test_misplaced_test_finder_names_planted_files(tmp_path: Path) -> None:
    package, tests = tmp_path / "pkg", tmp_path / "tests"
    for folder in (package, package / "sub", package / "sub" / "inner", package / "loose"):
        folder.mkdir(parents=True, exist_ok=True)
    for folder in (package, package / "sub", package / "sub" / "inner"):
        (folder / "__init__.py").write_text("")
    placed = ["test_top.py", "sub/test_a.py", "sub/inner/test_b.py", "oracles/x_numpy.py",
              "data/bad_cases/make.py", "benchmarks/test_bench.py"]
    planted = ["unit/test_c.py", "loose/test_d.py", "sub/verification/test_e.py",
               "inner/test_f.py"]
    for name in placed + planted:
        (tests / name).parent.mkdir(parents=True, exist_ok=True)
        (tests / name).write_text("")
    assert _misplaced_tests(tests, package) == sorted(planted)


def test_tests_mirror_the_package() -> None:
    """A test of ``floatmoor/<pkg>/<module>.py`` lives in ``tests/<pkg>/``: a folder of tests/
    that mirrors no package (a folder by kind, such as the old ``tests/unit/``) is refused."""
    misplaced = _misplaced_tests(TESTS, PACKAGE)
    assert not misplaced, ("test files in folders that mirror no package of floatmoor/ (move "
                           "them beside the package they test: "
                           "docs/development.md#where-tests-live):\n" + "\n".join(misplaced))


def test_markers_are_strict_and_registered() -> None:
    """pytest refuses an unregistered marker (``--strict-markers``), and every marker the tests
    use is registered in pyproject.toml, the kinds (verification, validation, peer, oracle)
    among them."""
    options = tomllib.loads((REPO / "pyproject.toml").read_text())
    options = options["tool"]["pytest"]["ini_options"]
    assert "--strict-markers" in options["addopts"]
    registered = {line.split(":", 1)[0].strip() for line in options["markers"]}
    assert {"slow", "benchmark", "verification", "validation", "peer", "oracle"} <= registered
    used = {name for path in TESTS.rglob("*.py") if "__pycache__" not in path.parts
            for name in MARKER_USE.findall(path.read_text(encoding="utf-8"))}
    assert used - BUILTIN_MARKERS - registered == set()
