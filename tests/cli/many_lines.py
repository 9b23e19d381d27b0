"""Test helper: the Lindahl case with N copies of its chain, for the scaling tests of
``floatmoor check`` (a step quadratic in the number of lines shows at a few thousand)."""

from __future__ import annotations

from pathlib import Path

from tests.conftest import LINDAHL_CASE

__all__ = ["many_lines_case"]


def many_lines_case(folder: Path, lines: int, model: str = "quasi-static") -> Path:
    """Write ``folder/many_<lines>.toml``: the Lindahl case with ``lines`` identical chains
    ``chain0``, ``chain1``, ... of ``model``, and return its path."""
    text = LINDAHL_CASE.read_text()
    head, _, rest = text.partition("[[lines]]")
    tail = rest[rest.index("[motion]"):]
    entry = ('[[lines]]\nname = "chain{i}"\ntype = "chain"\nlength = 33.0\n'
             'anchor = [0.0, 0.0, -3.0]\nfairlead = [32.554, 0.0, 0.3]\n'
             f'model = "{model}"\n\n')
    path = folder / f"many_{lines}.toml"
    path.write_text(head + "".join(entry.format(i=i) for i in range(lines)) + tail)
    return path
