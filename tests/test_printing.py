"""Only the command line prints (docs/development.md#1-package-layout-and-import-order).

Library code returns values, takes a ``progress`` callback or warns; the commands in
``floatmoor/cli/`` print. No module outside it may call ``print(`` or use ``sys.stdout`` or
``sys.stderr``: read from the syntax tree (tests/package_source.py), so that text in strings
and comments does not count. A module whose text holds none of :data:`PRINTING_WORDS` has
none of those (short of spelling a name in other Unicode characters) and is not parsed.
"""

from __future__ import annotations

import ast

from tests.package_source import MODULES, PACKAGE, relative, source, tree

#: The package of the commands, their progress display and their printing: the only code that
#: may print (docs/development.md#1-package-layout-and-import-order).
PRINTING_PACKAGE = PACKAGE / "cli"
#: Words every way of printing that :func:`_printing` finds has in its source text.
PRINTING_WORDS = ("print", "stdout", "stderr")


def _printing(name: str, code: str | ast.Module) -> list[str]:
    """``name:line: what`` of every ``print(`` call and every use of ``sys.stdout`` or
    ``sys.stderr`` in the source (or syntax tree) ``code`` (read with :mod:`ast`: text in
    strings and comments does not count)."""
    found = []
    for node in ast.walk(ast.parse(code) if isinstance(code, str) else code):
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) \
                and node.func.id == "print":
            found.append((node.lineno, "print(...)"))
        elif isinstance(node, ast.Attribute) and node.attr in ("stdout", "stderr") \
                and isinstance(node.value, ast.Name) and node.value.id == "sys":
            found.append((node.lineno, f"sys.{node.attr}"))
        elif isinstance(node, ast.ImportFrom) and node.module == "sys" \
                and any(alias.name in ("stdout", "stderr") for alias in node.names):
            found.append((node.lineno, "from sys import ..."))
    return [f"{name}:{line}: {what}" for line, what in sorted(found)]


def test_printing_finder_names_planted_prints() -> None:
    planted = ("import sys\n"
               "from sys import stderr\n"
               "def f(x):\n"
               "    print(x)\n"
               "    sys.stderr.write('print(x)')  # print(x)\n"
               "    return sys.stdout\n"
               "    self.print(x)\n")
    assert _printing("planted.py", planted) == [
        "planted.py:2: from sys import ...", "planted.py:4: print(...)",
        "planted.py:5: sys.stderr", "planted.py:6: sys.stdout"]
    lines = planted.splitlines()
    for found in _printing("planted.py", planted):  # what lets a module be skipped unread
        line = lines[int(found.split(":")[1]) - 1]
        assert any(word in line for word in PRINTING_WORDS), line


def test_only_the_command_line_prints() -> None:
    """Library code returns values, takes a ``progress`` callback or warns (a
    :class:`floatmoor.errors.FloatmoorWarning`); :mod:`floatmoor.cli` prints."""
    problems = []
    for path, _ in MODULES.values():
        if PRINTING_PACKAGE in path.parents:
            continue
        if any(word in source(path) for word in PRINTING_WORDS):
            problems += _printing(relative(path), tree(path))
    assert not problems, ("library code must not print: return the text, take a progress "
                          "callback or warn, and let floatmoor/cli/ print it:\n"
                          + "\n".join(problems))
