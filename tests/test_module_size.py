"""Modules stay small (docs/development.md#1-package-layout-and-import-order): a module of the
package over :data:`MAX_MODULE_LINES` lines, or a module under tests/ over
:data:`MAX_TEST_MODULE_LINES` lines, must say why in its docstring, on a line starting with
``Size:`` (e.g. ``Size: one numba kernel set that shares its private helpers; split, the
helpers would have to be public``).

Test modules get more room: a test states its case in full (inputs, expected figures and where
they come from), so a file of tests on one module runs longer than the module; past the limit
it is usually two subjects that would read better as two files.
"""

from __future__ import annotations

import ast

from tests.package_source import MODULES, TESTS, relative, source

#: The "about 600 lines" of docs/development.md: past it a module must give its reason.
MAX_MODULE_LINES = 600
#: The limit for a ``.py`` file under tests/ (docs/development.md#where-tests-live).
MAX_TEST_MODULE_LINES = 800
#: The docstring line that gives that reason.
SIZE_REASON_PREFIX = "Size:"


def _size_problem(name: str, text: str, limit: int = MAX_MODULE_LINES) -> str | None:
    """Why the module ``name`` with source ``text`` breaks the size rule for ``limit`` lines,
    or None."""
    lines = len(text.splitlines())
    if lines <= limit:
        return None
    docstring = ast.get_docstring(ast.parse(text)) or ""
    if any(line.strip().startswith(SIZE_REASON_PREFIX) for line in docstring.splitlines()):
        return None
    return (f"{name} has {lines} lines (over {limit}) and its docstring has no "
            f"line starting {SIZE_REASON_PREFIX!r} saying why")


def test_size_rule_wants_a_reason_past_the_limit() -> None:
    body = "x = 1\n" * MAX_MODULE_LINES
    assert _size_problem("short", '"""Short."""\n' + "x = 1\n" * (MAX_MODULE_LINES - 1)) is None
    assert "601 lines" in _size_problem("long", '"""Long."""\n' + body)
    assert _size_problem("long", f'"""Long.\n\n{SIZE_REASON_PREFIX} one kernel set."""\n'
                         + body) is None


def test_size_rule_for_tests_has_its_own_limit() -> None:
    """A test module of 700 lines passes, one of 801 without a ``Size:`` line does not."""
    assert _size_problem("test_x.py", '"""Tests."""\n' + "x = 1\n" * 699,
                         MAX_TEST_MODULE_LINES) is None
    long = '"""Tests."""\n' + "x = 1\n" * MAX_TEST_MODULE_LINES
    assert "801 lines (over 800)" in _size_problem("test_x.py", long, MAX_TEST_MODULE_LINES)
    assert _size_problem("test_x.py", f'"""Tests.\n\n{SIZE_REASON_PREFIX} one oracle."""\n'
                         + "x = 1\n" * MAX_TEST_MODULE_LINES, MAX_TEST_MODULE_LINES) is None


def test_every_long_module_says_why() -> None:
    problems = [_size_problem(relative(path), source(path)) for path, _ in MODULES.values()]
    problems = [p for p in problems if p is not None]
    assert not problems, ("split these modules by what they hold, or say why not:\n"
                          + "\n".join(problems))


def test_every_long_test_module_says_why() -> None:
    """Every ``.py`` file under tests/ (tests, their helpers, oracles and benchmarks)."""
    problems = [_size_problem(relative(path), path.read_text(encoding="utf-8"),
                              MAX_TEST_MODULE_LINES)
                for path in sorted(TESTS.rglob("*.py")) if "__pycache__" not in path.parts]
    problems = [p for p in problems if p is not None]
    assert not problems, ("split these test modules by what they test, or say why not:\n"
                          + "\n".join(problems))
