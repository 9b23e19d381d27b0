"""The pages generated from the package are the ones in docs/: the API reference (from the
packages' ``__all__``, docs/tools/api_page.py) and the layout page (from the modules and their
imports, docs/tools/layout_page.py). A page that differs fails with the command that remakes
it."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path
from types import ModuleType

import pytest

from tests.conftest import REPO

TOOLS = REPO / "docs" / "tools"


def _tool(name: str) -> ModuleType:
    """A generator of docs/tools, imported from its file (docs/ is no package)."""
    spec = importlib.util.spec_from_file_location(f"docs_tools_{name}", TOOLS / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


api_page = _tool("api_page")
layout_page = _tool("layout_page")


@pytest.mark.parametrize(("page", "tool", "make"), [
    ("docs/reference/api.md", "api_page", lambda: api_page.api_page()),
    ("docs/guide/layout.md", "layout_page", lambda: layout_page.layout_page()),
], ids=["api", "layout"])
def test_page_is_the_generated_one(page: str, tool: str, make) -> None:
    text = (REPO / page).read_text(encoding="utf-8")
    assert text == make(), f"{page} is out of date: python docs/tools/{tool}.py -o {page}"


def test_api_page_documents_every_public_name_once() -> None:
    import floatmoor

    text = api_page.api_page()
    assert "## `floatmoor.hydro`" in text and "## `floatmoor.mooring.dg`" in text
    top = text.split("\n## `floatmoor.")[0]
    for name in floatmoor.__all__[1:]:
        assert f":: {name}\n" in top, name
    # DynamicLine is documented at the top level and linked from the packages that export it
    assert text.count(".. autoclass:: DynamicLine\n") == 1
    dg_section = text.split("## `floatmoor.mooring.dg`")[1]
    assert ":obj:`DynamicLine <floatmoor.DynamicLine>`" in dg_section


def test_layout_page_lists_every_module_with_its_summary(tmp_path: Path) -> None:
    """A made-up package: a module appears with its first sentence, a folder with the other
    parts it imports, and a new module changes the page."""
    package = tmp_path / "floatmoor"
    (package / "lines").mkdir(parents=True)
    (package / "__init__.py").write_text('"""The package."""\n')
    (package / "errors.py").write_text('"""Errors (e.g. bad input). More."""\n')
    (package / "lines" / "__init__.py").write_text('"""Line models."""\n')
    (package / "lines" / "model.py").write_text(
        '"""A line (see eq. 3). Details."""\nfrom typing import TYPE_CHECKING\n'
        'from floatmoor.errors import CaseError\nif TYPE_CHECKING:\n'
        '    from floatmoor.case import Case\n')
    text = layout_page.layout_page(package)
    assert "| `errors.py` | Errors (e.g. bad input). Depends on: nothing else" in text
    assert "## `floatmoor/lines/`\n\nLine models.\n\nDepends on: `errors`.\n" in text
    assert "| `model.py` | A line (see eq. 3). |" in text
    (package / "lines" / "solver.py").write_text('"""The solver."""\n')
    assert "| `solver.py` | The solver. |" in layout_page.layout_page(package)


def test_first_sentence_stops_at_a_full_stop_outside_code_and_parentheses() -> None:
    first = layout_page.first_sentence
    assert first("One (a. b). Two.") == "One (a. b)."
    assert first("``x ... -o y``: the file. Two.") == "``x ... -o y``: the file."
    assert first("See :mod:`~floatmoor.io.netcdf`. Two.") == "See `floatmoor.io.netcdf`."
    assert first("No full stop\n\nSecond paragraph.") == "No full stop"
    assert first(None) == ""
    assert first("Runs (docs/guide/running.md#outside-the-models-validity). Two.") == (
        "Runs ([docs/guide/running.md#outside-the-models-validity]"
        "(../guide/running.md#outside-the-models-validity)).")
