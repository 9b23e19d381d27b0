"""The public API, stated once (docs/development.md#public-api).

Every package's ``__init__`` names its public API in ``__all__``; a package whose names are
imported on first use builds ``__all__`` from one table (``_API``: name -> defining module,
:func:`floatmoor._exports.lazy_exports`), and the top level's ``__all__`` is its own table
(``_LAZY``: name -> the public subpackage) and its errors. Every public name has a numpy-style
docstring. The pages generated from these lists are checked in tests/test_generated_pages.py.
"""

from __future__ import annotations

import ast
import inspect
import re
import subprocess
import sys
import types
from importlib import import_module

import pytest

import floatmoor
from floatmoor._exports import lazy_exports
from tests.conftest import REPO

PACKAGE = REPO / "floatmoor"
#: Every package of floatmoor (a folder with an ``__init__.py``), found without importing.
PACKAGES = sorted(".".join(p.parent.relative_to(REPO).parts) for p in PACKAGE.rglob("__init__.py"))
#: Every module file of floatmoor, as dotted names (what a public name must not shadow).
MODULES = {".".join(p.relative_to(REPO).with_suffix("").parts) for p in PACKAGE.rglob("*.py")}


def _assigns_all(source: str) -> bool:
    """Whether a module's source assigns ``__all__`` at its top level."""
    for node in ast.parse(source).body:
        targets = (node.targets if isinstance(node, ast.Assign)
                   else [node.target] if isinstance(node, ast.AnnAssign) else [])
        for target in targets:
            names = target.elts if isinstance(target, ast.Tuple) else [target]
            if any(isinstance(n, ast.Name) and n.id == "__all__" for n in names):
                return True
    return False


@pytest.mark.parametrize("package", PACKAGES)
def test_every_package_states_its_api_in_all(package: str) -> None:
    init = REPO.joinpath(*package.split("."), "__init__.py")
    assert _assigns_all(init.read_text(encoding="utf-8")), (
        f"{package} has no explicit __all__: list its public names (docs/development.md"
        "#public-api), or `__all__: list[str] = []` for an internal package")
    module = import_module(package)
    names = list(module.__all__)
    assert len(set(names)) == len(names), f"{package}.__all__ repeats a name"
    for name in names:
        value = getattr(module, name)
        # a name imported on first use that is also a submodule's is replaced by that module
        # once the submodule is imported (an eager package binds its names after the import)
        if "_API" in vars(module) and f"{package}.{name}" in MODULES:
            assert value is import_module(f"{package}.{name}"), (
                f"{package}.{name} is both a public name and a submodule")


@pytest.mark.parametrize("package", [p for p in PACKAGES
                                     if "_API" in vars(import_module(p))])
def test_each_table_names_the_module_that_defines_the_name(package: str) -> None:
    table = import_module(package)._API
    assert list(import_module(package).__all__) == list(table)
    for name, module in table.items():
        value = getattr(import_module(module), name) if module != f"{package}.{name}" else None
        if isinstance(value, (type, types.FunctionType)):
            assert value.__module__ == module, (
                f"{package}: {name} is defined in {value.__module__}, not {module}")


def _type_checking_imports() -> dict[str, str]:
    """Name -> module of the top level's ``if TYPE_CHECKING:`` imports."""
    tree = ast.parse((PACKAGE / "__init__.py").read_text(encoding="utf-8"))
    block = next(node for node in tree.body if isinstance(node, ast.If)
                 and "TYPE_CHECKING" in ast.unparse(node.test))
    return {alias.name: node.module for node in block.body if isinstance(node, ast.ImportFrom)
            for alias in node.names}


def test_top_level_all_is_built_from_one_table() -> None:
    assert floatmoor.__all__ == ["__version__", *floatmoor._LAZY, *floatmoor._EAGER]
    assert {"DynamicLine", "read_database", "load_for_case", "rao_for_case"} <= set(
        floatmoor._LAZY)
    for name, package in floatmoor._LAZY.items():
        assert name in import_module(package).__all__, f"{name} is not public in {package}"
        assert getattr(floatmoor, name) is getattr(import_module(package), name)
    hints = _type_checking_imports()
    assert set(hints) == set(floatmoor._LAZY), (
        "the TYPE_CHECKING imports of floatmoor/__init__.py differ from _LAZY: "
        f"{sorted(set(hints) ^ set(floatmoor._LAZY))}")
    for name, module in hints.items():
        assert getattr(import_module(module), name) is getattr(floatmoor, name), name


def test_importing_the_packages_loads_no_numerical_library() -> None:
    """The top level and the lazy packages import only their tables (the ``floatmoor`` command
    imports the package first and must stay quick to answer a Ctrl-C)."""
    lazy = [p for p in PACKAGES if "_API" in vars(import_module(p))]
    code = ("import sys\n" + "".join(f"import {p}\n" for p in lazy)
            + "heavy = sorted({m.split('.')[0] for m in sys.modules} & {'numpy', 'numba', "
              "'scipy', 'xarray', 'matplotlib', 'capytaine', 'openturns'})\n"
              "print(','.join(heavy))\n")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          cwd=REPO, timeout=120, check=True)
    assert done.stdout.strip() == "", f"importing the packages loaded {done.stdout.strip()}"


def test_lazy_exports_imports_on_first_use_and_refuses_other_names() -> None:
    package = types.ModuleType("made_up_package")
    sys.modules["made_up_package"] = package
    try:
        names, getattr_, dir_ = lazy_exports("made_up_package", {
            "sqrt": "math", "loads": "json", "decoder": "made_up_package.decoder"})
        package.__getattr__ = getattr_
        assert names == ["sqrt", "loads", "decoder"]
        import json
        import math
        assert package.sqrt is math.sqrt and vars(package)["sqrt"] is math.sqrt
        assert package.loads is json.loads
        assert "loads" in dir_()
        with pytest.raises(AttributeError, match="'made_up_package' has no attribute 'nope'"):
            package.nope  # noqa: B018
        with pytest.raises(ModuleNotFoundError):
            package.decoder  # noqa: B018 (a submodule export imports the submodule)
    finally:
        del sys.modules["made_up_package"]


# -- numpy-style docstrings of every public name ------------------------------------------------

#: A numpy section heading that lists names: a parameter's or an attribute's.
_NAMES_SECTION = re.compile(r"^(Parameters|Other Parameters|Attributes)\n-{3,}\n", re.M)
#: Headings of the other docstring styles (Google, reST fields), which napoleon's numpy
#: reader does not read.
_OTHER_STYLES = re.compile(r"^(Args|Arguments|Returns|Raises|Yields):\s*$|^:(param|returns?|"
                           r"raises?|type|rtype)\b", re.M)

def _parameters(obj: object) -> list[str]:
    """The names a docstring must describe: a callable's parameters (a class's ``__init__``'s,
    a NamedTuple's or dataclass's fields); none for exceptions, modules and data."""
    if inspect.ismodule(obj) or (inspect.isclass(obj) and issubclass(obj, BaseException)):
        return []
    if not callable(obj):
        return []
    try:
        signature = inspect.signature(obj)
    except (TypeError, ValueError):
        return []
    return [p.name for p in signature.parameters.values()
            if p.name not in ("self", "cls") and not p.name.startswith("_")
            and p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD)]


def docstring_problem(obj: object) -> str | None:
    """Why ``obj``'s docstring is not a numpy-style one describing its parameters, or None.

    Parameters
    ----------
    obj
        A public function, class, module or data object.

    Returns
    -------
    str or None
        The problem, in words.
    """
    doc = obj.__doc__ if inspect.isclass(obj) or inspect.ismodule(obj) else inspect.getdoc(obj)
    if inspect.isclass(obj) and doc and doc.startswith(f"{obj.__name__}("):
        doc = None  # the signature a dataclass or NamedTuple writes when it has no docstring
    doc = inspect.cleandoc(doc) if doc else ""
    if not doc.strip() or not doc.splitlines()[0].strip():
        return "no docstring, or no summary on its first line"
    if _OTHER_STYLES.search(doc):
        return "sections in another style than numpy's (Args:, :param ...)"
    parameters = _parameters(obj)
    if not parameters:
        return None
    section = _NAMES_SECTION.search(doc)
    if section is None:
        return "no Parameters (or Attributes) section"
    described = doc[section.end():]
    missing = [name for name in parameters
               if not re.search(rf"^\**{name}\b|, \**{name}\b", described, re.M)]
    return f"parameters not described: {', '.join(missing)}" if missing else None


def _public_objects() -> dict[str, object]:
    """Every public object, under the first public name it has (top level first)."""
    found: dict[int, tuple[str, object]] = {}
    for package in PACKAGES:
        module = import_module(package)
        for name in module.__all__:
            if name != "__version__":
                found.setdefault(id(getattr(module, name)), (f"{package}.{name}",
                                                             getattr(module, name)))
    return dict(found.values())


def test_docstring_rule_on_made_up_functions() -> None:
    def described(a, b, *, c=1):
        """Sum.

        Parameters
        ----------
        a, b
            Terms.
        c
            Third.
        """

    def google(a):
        """Sum.

        Args:
            a: a term.
        """

    def half(a, b):
        """Sum.

        Parameters
        ----------
        a
            A term.
        """

    assert docstring_problem(described) is None
    assert "another style" in docstring_problem(google)
    assert docstring_problem(half) == "parameters not described: b"
    assert docstring_problem(lambda: None).startswith("no docstring")


def test_every_public_name_has_a_numpy_docstring() -> None:
    """No exceptions: every public name describes each of its parameters (or fields)."""
    problems = {name: docstring_problem(obj) for name, obj in _public_objects().items()}
    failing = {name: problem for name, problem in problems.items() if problem}
    assert not failing, "public names without numpy-style docstrings:\n" + "\n".join(
        f"{name}: {problem}" for name, problem in sorted(failing.items()))
