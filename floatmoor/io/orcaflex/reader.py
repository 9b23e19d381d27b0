"""A strict, safe reader of OrcaFlex text data files (YAML).

Only :class:`OrcaFlexLoader`, a subclass of PyYAML's ``SafeLoader``, ever reads the text (no
Python objects can be built from tags). On top of the safe loader it refuses:

- anchors and aliases: an alias repeats a node without repeating its text, so a few hundred
  bytes of nested aliases ("billion laughs") expand to gigabytes in memory; OrcaFlex does not
  write them;
- merge keys (``<<``), which copy mappings by alias; OrcaFlex does not write them either;
- a key given twice in one mapping (YAML keeps the last silently);
- files over :data:`MAX_MODEL_FILE_BYTES`, before parsing.

Numbers are not resolved by YAML (whose 1.1 rules read ``1e6`` as text, ``1:30`` as 90 and
``0x1F`` as 31): every plain scalar stays text except null (``~``) and the booleans
(OrcaFlex's ``Yes``/``No``), and :mod:`.values` reads numbers with one strict pattern.
"""

from __future__ import annotations

import os
import stat
from typing import Any

import yaml

from floatmoor.errors import CaseError
from floatmoor.terminal_text import shown

__all__ = ["OrcaFlexLoader", "MAX_MODEL_FILE_BYTES", "read_model", "parse_model"]

#: Largest OrcaFlex text data file read [bytes]. The mooring part of a model is a few kB; a
#: model carrying vessel-type RAO and QTF tables runs to a few MB. PyYAML's pure-Python
#: parser reads about 1 MB/s and holds some 50 times the text in memory, so 16 MiB bounds a
#: read to well under a minute and a GB of memory; a larger file is refused before parsing.
MAX_MODEL_FILE_BYTES = 16 * 1024 * 1024

_DROPPED_RESOLVERS = ("tag:yaml.org,2002:int", "tag:yaml.org,2002:float",
                      "tag:yaml.org,2002:timestamp")


class OrcaFlexLoader(yaml.SafeLoader):
    """PyYAML's safe loader without anchors, aliases, merge keys, duplicate keys, or
    implicit numbers and dates (plain scalars other than null and booleans stay text)."""

    yaml_implicit_resolvers = {
        first: [(tag, rx) for tag, rx in resolvers if tag not in _DROPPED_RESOLVERS]
        for first, resolvers in yaml.SafeLoader.yaml_implicit_resolvers.items()}

    def compose_node(self, parent: Any, index: Any) -> Any:  # noqa: D102
        event = self.peek_event()
        if isinstance(event, yaml.AliasEvent) or getattr(event, "anchor", None) is not None:
            raise yaml.MarkedYAMLError(
                None, None, "anchors and aliases are not read (an alias can expand a small "
                "file to gigabytes; OrcaFlex writes none)", event.start_mark)
        return super().compose_node(parent, index)

    def flatten_mapping(self, node: Any) -> None:  # noqa: D102
        for key_node, _ in node.value:
            if key_node.tag == "tag:yaml.org,2002:merge":
                raise yaml.MarkedYAMLError(None, None, "merge keys (<<) are not read "
                                           "(OrcaFlex writes none)", key_node.start_mark)
        seen: dict[Any, Any] = {}
        for key_node, _ in node.value:
            if isinstance(key_node, yaml.ScalarNode):
                if key_node.value in seen:
                    raise yaml.MarkedYAMLError(
                        None, None, f"each key once in a mapping: '{key_node.value}' is also "
                        f"on line {seen[key_node.value].line + 1}", key_node.start_mark)
                seen[key_node.value] = key_node.start_mark
        super().flatten_mapping(node)


def parse_model(text: str, source: str = "<model>") -> dict[str, Any]:
    """The data of an OrcaFlex text data file.

    Raises
    ------
    CaseError
        Malformed YAML, anchors, aliases, merge keys, a repeated key, or a document that is
        not a mapping of OrcaFlex's sections, naming ``source`` and the line.
    """
    try:
        data = yaml.load(text, Loader=OrcaFlexLoader)  # noqa: S506 - a SafeLoader subclass
    except yaml.MarkedYAMLError as err:
        mark = err.problem_mark or err.context_mark
        where = f"{source}:{mark.line + 1}" if mark is not None else source
        raise CaseError(where, "", "an OrcaFlex text data file (YAML)",
                        shown(err.problem or err.context or "malformed YAML")) from None
    except yaml.YAMLError as err:
        raise CaseError(source, "", "an OrcaFlex text data file (YAML)", shown(err)) from None
    except RecursionError:
        raise CaseError(source, "", "an OrcaFlex text data file (YAML)",
                        "nesting too deep to read") from None
    if not isinstance(data, dict):
        raise CaseError(source, "", "an OrcaFlex text data file (a mapping of sections: "
                        "General, Environment, LineTypes, Lines, ...)",
                        "an empty document" if data is None else type(data).__name__)
    return data


def read_model(path: str | os.PathLike[str]) -> dict[str, Any]:
    """Read and parse the OrcaFlex text data file at ``path`` (see the module docstring).

    Parameters
    ----------
    path
        The ``.yml`` file.

    Returns
    -------
    dict
        The model's data, as plain dicts, lists, strings and numbers.

    Raises
    ------
    CaseError
        The file cannot be read, is not a regular file, is larger than
        :data:`MAX_MODEL_FILE_BYTES`, is not UTF-8, or is malformed.
    """
    source = shown(path)
    try:
        mode = os.stat(path).st_mode
        if not stat.S_ISREG(mode):
            raise CaseError(source, "", "an OrcaFlex text data file (a regular file)",
                            "a folder" if stat.S_ISDIR(mode) else "not a regular file")
        with open(path, "rb") as stream:
            data = stream.read(MAX_MODEL_FILE_BYTES + 1)
    except OSError as err:
        raise CaseError(source, "", "a readable OrcaFlex text data file",
                        shown(err.strerror or err)) from None
    if len(data) > MAX_MODEL_FILE_BYTES:
        raise CaseError(source, "", f"an OrcaFlex text data file of at most "
                        f"{MAX_MODEL_FILE_BYTES} bytes", "a larger file")
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError:
        raise CaseError(source, "", "an OrcaFlex text data file (UTF-8 text)",
                        "bytes that are not UTF-8") from None
    return parse_model(text, source)
