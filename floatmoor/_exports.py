"""The public names of a package, each imported from its module on first use (PEP 562).

A package's ``__init__`` states its public API once, as one table: each public name and the
module that defines it (docs/development.md#public-api). :func:`lazy_exports` turns the table
into the package's ``__all__``, ``__getattr__`` and ``__dir__``: importing the package imports
none of those modules, so a package's import cost (and the order in which its modules are
first imported) is that of the modules a caller actually uses. ``docs/reference/api.md`` is
generated from the ``__all__`` lists (``python docs/tools/api_page.py``).

A table entry whose module is ``package.name`` itself exports that submodule.
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Mapping
from importlib import import_module
from typing import Any


def lazy_exports(package: str, table: Mapping[str, str]
                 ) -> tuple[list[str], Callable[[str], Any], Callable[[], list[str]]]:
    """``__all__``, ``__getattr__`` and ``__dir__`` of ``package`` from its table of names.

    Parameters
    ----------
    package
        The package's dotted name (its ``__name__``); it must be imported (being imported).
    table
        Public name -> dotted name of the module that defines it, in the order the API
        reference lists them.

    Returns
    -------
    tuple
        ``__all__`` (the table's names, in order), the module ``__getattr__`` that imports a
        name's module on first use and keeps the value in the package's namespace, and the
        module ``__dir__``.
    """
    namespace = sys.modules[package].__dict__

    def __getattr__(name: str) -> Any:
        module = table.get(name)
        if module is None:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        if module == f"{package}.{name}":
            value = import_module(module)
        else:
            value = getattr(import_module(module), name)
        namespace[name] = value
        return value

    def __dir__() -> list[str]:
        return sorted(set(namespace) | set(table))

    return list(table), __getattr__, __dir__
