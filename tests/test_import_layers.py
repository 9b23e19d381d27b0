"""Imports run down the layers (docs/development.md#1-package-layout-and-import-order): the
project layers its code one way (base -> case -> io -> models -> simulation ->
campaigns/reports -> CLI).

The layer table of that section is the one declaration of the layers, lowest first
(:func:`_layer_table` reads it); a module may import modules of its own layer and of lower
layers only. Every import counts here: module-level, function-level and ``if TYPE_CHECKING:``
ones alike (an annotation that names a higher layer's class still couples the lower layer to
it). A module's layer is that of the most specific pattern of the table it matches
(:func:`_layer_of`). The imports are read from the source (tests/package_source.py).
"""

from __future__ import annotations

import re

from tests.package_source import (FUNCTION_LEVEL, MODULE_LEVEL, MODULES, REPO,
                                  TYPE_CHECKING_ONLY, import_statements, imports, relative,
                                  statements_of)

#: The page whose section 1 table declares the layers.
DEVELOPMENT_PAGE = REPO / "docs" / "development.md"
#: The heading of that section.
LAYER_SECTION = "## 1. Package layout and import order"


def _layer_table(text: str) -> list[tuple[str, tuple[str, ...]]]:
    """(layer, path patterns) of each row of the layer table in :data:`LAYER_SECTION` of
    ``text``, lowest layer first: the patterns are the backquoted ``floatmoor/...`` paths of
    the row's second cell (a folder ends with ``/``; ``*`` matches within a name, ``**/`` any
    folders)."""
    section = text.split(LAYER_SECTION, 1)[1].split("\n## ", 1)[0]
    rows = [line for line in section.splitlines() if line.startswith("|")]
    layers = []
    for row in rows[2:]:  # after the header and its rule
        cells = [cell.strip() for cell in row.strip().strip("|").split("|")]
        layers.append((cells[0], tuple(re.findall(r"`(floatmoor/[^`]*)`", cells[1]))))
    return layers


def _pattern(pattern: str) -> re.Pattern[str]:
    """The regular expression of a layer-table path pattern (see :func:`_layer_table`)."""
    if pattern.endswith("/"):
        return re.compile(re.escape(pattern) + ".*")
    parts = {"**/": "(?:[^/]+/)*", "*": "[^/]*"}
    return re.compile("".join(parts.get(part, re.escape(part))
                              for part in re.split(r"(\*\*/|\*)", pattern)))


def _layer_of(path: str, layers: list[tuple[str, tuple[str, ...]]]) -> int:
    """Index in ``layers`` of the layer of the file ``path`` (``floatmoor/...``): that of the
    most specific pattern it matches (a file pattern before a folder, a longer folder before a
    shorter one). Raises AssertionError when no pattern, or patterns of two layers equally
    specific, match it."""
    matches = [((not pattern.endswith("/"), len(pattern) if pattern.endswith("/") else 0),
                index, pattern)
               for index, (_, patterns) in enumerate(layers) for pattern in patterns
               if _pattern(pattern).fullmatch(path)]
    assert matches, (f"{path} is in no layer of {DEVELOPMENT_PAGE.name}'s table: add it to "
                     "the row of its layer")
    best = max(key for key, _, _ in matches)
    found = {(index, pattern) for key, index, pattern in matches if key == best}
    assert len({index for index, _ in found}) == 1, (
        f"{path} matches patterns of several layers equally: "
        + ", ".join(f"{pattern} ({layers[index][0]})" for index, pattern in sorted(found)))
    return found.pop()[0]


def _upward_imports(layers: list[tuple[str, tuple[str, ...]]],
                    statements: dict[str, tuple[tuple[str, str, int], ...]],
                    paths: dict[str, str]) -> list[tuple[str, str, str]]:
    """(importer, imported, description) of each import, of any kind, from a lower layer to a
    higher one, one per (importer, imported) pair (its first statement)."""
    layer = {module: _layer_of(path, layers) for module, path in paths.items()}
    found: dict[tuple[str, str], str] = {}
    for module in sorted(statements):
        for target, kind, line in statements[module]:
            if layer[target] > layer[module] and (module, target) not in found:
                found[(module, target)] = (
                    f"{module} ({layers[layer[module]][0]}) imports {target} "
                    f"({layers[layer[target]][0]}): {paths[module]}:{line}, {kind}")
    return [(module, target, text) for (module, target), text in found.items()]


def _package_layers() -> list[tuple[str, tuple[str, ...]]]:
    return _layer_table(DEVELOPMENT_PAGE.read_text(encoding="utf-8"))


def _package_upward_imports() -> list[tuple[str, str, str]]:
    paths = {module: relative(path) for module, (path, _) in MODULES.items()}
    return _upward_imports(_package_layers(),
                           {module: statements_of(module) for module in MODULES}, paths)


def test_layer_table_is_read_and_places_files() -> None:
    """The table reader and the pattern rules on a made-up page: rows lowest first, a file
    pattern before a folder, ``**/`` for any folders, no layer and a tie are errors."""
    page = (f"# Dev\n\n{LAYER_SECTION}\n\ntext\n\n"
            "| layer | packages | holds |\n| --- | --- | --- |\n"
            "| base | `floatmoor/errors.py`, `floatmoor/x.py` | errors |\n"
            "| models | `floatmoor/hydro/` (with `sub/`), `floatmoor/hydro/deep/` | models |\n"
            "| top | `floatmoor/**/cli.py` and `floatmoor/**/*_cli.py` | commands |\n"
            "| tie | `floatmoor/x.py` | wrong |\n\n## 2. Next\n\n| a | `floatmoor/no.py` |\n")
    layers = _layer_table(page)
    assert layers == [("base", ("floatmoor/errors.py", "floatmoor/x.py")),
                      ("models", ("floatmoor/hydro/", "floatmoor/hydro/deep/")),
                      ("top", ("floatmoor/**/cli.py", "floatmoor/**/*_cli.py")),
                      ("tie", ("floatmoor/x.py",))]
    assert _layer_of("floatmoor/errors.py", layers) == 0
    assert _layer_of("floatmoor/hydro/rao.py", layers) == 1
    assert _layer_of("floatmoor/hydro/deep/a.py", layers) == 1
    assert _layer_of("floatmoor/hydro/rao_cli.py", layers) == 2
    assert _layer_of("floatmoor/hydro/deep/cli.py", layers) == 2
    assert _layer_of("floatmoor/cli.py", layers) == 2
    for path, message in (("floatmoor/other.py", "in no layer"),
                          ("floatmoor/x.py", "several layers")):
        try:
            _layer_of(path, layers)
        except AssertionError as err:
            assert message in str(err)
        else:
            raise AssertionError(f"{path}: no error")


def test_direction_finder_names_a_planted_upward_import() -> None:
    """Downward and same-layer imports pass; an upward one is named with both layers, where
    and of which kind it is, whatever its kind (TYPE_CHECKING included)."""
    layers = [("base", ("floatmoor/errors.py",)), ("models", ("floatmoor/hydro/",)),
              ("reports", ("floatmoor/plots/",))]
    paths = {"floatmoor.errors": "floatmoor/errors.py", "floatmoor.hydro.a": "floatmoor/hydro/a.py",
             "floatmoor.hydro.b": "floatmoor/hydro/b.py",
             "floatmoor.plots.style": "floatmoor/plots/style.py"}
    statements = {"floatmoor.errors": (), "floatmoor.plots.style": (),
                  "floatmoor.hydro.a": (("floatmoor.errors", MODULE_LEVEL, 3),
                                        ("floatmoor.hydro.b", MODULE_LEVEL, 4)),
                  "floatmoor.hydro.b": ()}
    assert _upward_imports(layers, statements, paths) == []
    for kind in (MODULE_LEVEL, FUNCTION_LEVEL, TYPE_CHECKING_ONLY):
        planted = dict(statements, **{"floatmoor.hydro.b": (("floatmoor.plots.style", kind, 9),)})
        assert _upward_imports(layers, planted, paths) == [(
            "floatmoor.hydro.b", "floatmoor.plots.style",
            f"floatmoor.hydro.b (models) imports floatmoor.plots.style (reports): "
            f"floatmoor/hydro/b.py:9, {kind}")]


def test_type_checking_imports_are_read_for_the_direction() -> None:
    """``if TYPE_CHECKING:`` imports (also inside a function) are statements of their kind;
    the ``else`` branch runs and is not."""
    source = ("from floatmoor.errors import CaseError\n"
              "if TYPE_CHECKING:\n    from floatmoor.case.schema import Case\n"
              "else:\n    import floatmoor.io.netcdf\n"
              "def f():\n    from floatmoor.hydro import radiation\n"
              "    if TYPE_CHECKING:\n        from floatmoor.plots import style\n")
    assert import_statements(source, "floatmoor.made_up", False) == [
        ("floatmoor.errors", MODULE_LEVEL, 1), ("floatmoor.case.schema", TYPE_CHECKING_ONLY, 3),
        ("floatmoor.io.netcdf", MODULE_LEVEL, 5), ("floatmoor.hydro.radiation", FUNCTION_LEVEL, 7),
        ("floatmoor.plots.style", TYPE_CHECKING_ONLY, 9)]


def test_every_module_is_in_one_layer() -> None:
    """Each module of the package falls in exactly one row of the layer table."""
    layers = _package_layers()
    assert len(layers) >= 2 and all(patterns for _, patterns in layers), layers
    for path, _ in MODULES.values():
        _layer_of(relative(path), layers)


def test_imports_run_down_the_layers() -> None:
    """No module imports a module of a higher layer, by any kind of import
    (docs/development.md#1-package-layout-and-import-order); none is excused."""
    upward = [text for module, target, text in _package_upward_imports()]
    assert not upward, ("imports from a lower layer to a higher one (move the code to the layer "
                        "it belongs to, or pass the higher layer's answer in):\n"
                        + "\n".join(upward))


def test_nothing_below_the_command_line_imports_it() -> None:
    """The command line is the top layer: only its own modules and ``python -m floatmoor``
    (floatmoor/__main__.py, the program's entry) import :mod:`floatmoor.cli`."""
    entry = {"floatmoor.cli", "floatmoor.__main__"}
    upward = []
    for module in MODULES:
        if module in entry or module.startswith("floatmoor.cli."):
            continue
        top, lazy = imports(module)
        cli = sorted(target for target in top | lazy
                     if target == "floatmoor.cli" or target.startswith("floatmoor.cli."))
        if cli:
            upward.append(f"{module} imports {', '.join(cli)}")
    assert not upward, "the command line is imported from below:\n" + "\n".join(upward)
