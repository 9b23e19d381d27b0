"""The case-file reference is generated from the readers and cannot drift from them.

Every key the loaders ask for, over every shipped case and study file and the reference
fixtures (tests/data/case_reference), has a description; every description is of a key that
is asked for; every key a loader can read at all (found by reading the loaders' source, and
every key a :class:`~floatmoor.case.setting.SettingTable` declares) is asked for in one of those
files; the committed page is the generator's output; and recording changes nothing about
what is loaded.
"""

from __future__ import annotations

import ast
import dataclasses
import re
import typing
from functools import lru_cache
from importlib import import_module
from pathlib import Path

import numpy as np
import pytest

from floatmoor.case.drag import DragSettings, MorisonCoefficients
from floatmoor.case import key_docs, schema
from floatmoor.case.load import load_case
from floatmoor.case.reader import recording
from floatmoor.case.reference import leaf_of, merge_records, table_of
from floatmoor.case.schema import BODY_DOFS
from floatmoor.case.campaign import CAMPAIGN_TABLES
from floatmoor.case.setting import SettingTable, settings_of
from floatmoor.uq import input_reference
from floatmoor.uq.input_reference import PAGE, ROOT, input_files, record_inputs, reference_page
from floatmoor.uq.inputs import DISTRIBUTIONS
from floatmoor.uq.study import STUDY_TABLES, load_study
from floatmoor.uq.taut_string import BUILTIN_MODELS

#: The modules whose accessor calls make the schema of each kind of file.
CASE_MODULES = sorted((ROOT / "floatmoor" / "case").glob("*.py"))
STUDY_MODULES = [ROOT / "floatmoor" / "uq" / "study.py"]
#: The accessors of TableReader that read a key (``claim``: a key checked by its caller).
ACCESSORS = {"number", "integer", "string", "boolean", "vector", "number_or_vector", "table",
             "tables", "named_tables", "claim"}
#: The methods of a SettingTable that read a key (``TABLE.read(t, "key", ...)``).
TABLE_ACCESSORS = {"read", "table", "tables"}
#: Keyword arguments of an accessor whose value, when computed from other values, the
#: reference cannot print as recorded: the KeyDocs mapping that must word it instead.
COMPUTED = {"default": "defaults", "gt": "allowed", "ge": "allowed", "lt": "allowed",
            "le": "allowed", "choices": "allowed", "size": "types"}

#: Accessor calls whose key is not a literal, by (module, function), with the generic paths
#: they read (each must be read in a shipped or fixture file) and why the key is computed.
DYNAMIC_KEYS: dict[tuple[str, str], tuple[str, ...]] = {
    # a declared setting of kind "strings" (floatmoor.case.setting): every declared key is
    # checked by test_every_declared_setting_is_read
    ("setting.py", "_access"): ("floater.geometry.symmetry",),
    # the swept keys of a campaign: any key path of the case
    ("campaign.py", "read_campaign"): ("campaign.grid", "campaign.zip", "campaign.grid.<key>",
                                       "campaign.zip.<key>"),
    # a SettingTable reads the key its reader names (the keys it declares are checked by
    # test_every_declared_table_key_is_read)
    ("setting.py", "read"): (),
    ("setting.py", "table"): (),
    ("setting.py", "tables"): (),
    # the six harmonic DOF tables of a body motion
    ("motion_body.py", "_harmonic"): tuple(f"motion.{dof}" for dof in BODY_DOFS),
    # resolve_case_file(t, key, ...) only raises errors naming the key
    # the parameters of each distribution
    ("study.py", "_inputs"): tuple(f"inputs[].{p}" for ps in DISTRIBUTIONS.values() for p in ps),
    # the parameters of the built-in models
    ("study.py", "_model"): tuple(f"parameters.{p}" for model in BUILTIN_MODELS.values()
                                  for p in model.parameters),
    # base_overrides, an array of strings
    ("study.py", "_string_list"): ("base_overrides",),
}


@lru_cache(maxsize=1)
def _records():
    return record_inputs(input_files())


@lru_cache(maxsize=1)
def _entries():
    cases, studies = _records()
    return merge_records(cases), merge_records(studies)


def _setting_tables(path: Path) -> set[str]:
    """The names of the module's SettingTable constants (and of its dicts of them)."""
    module = import_module(".".join(path.relative_to(ROOT).with_suffix("").parts))
    return {name for name, value in vars(module).items()
            if isinstance(value, SettingTable) or (isinstance(value, dict) and value and all(
                isinstance(v, SettingTable) for v in value.values()))}


def _receiver(node: ast.expr) -> str | None:
    """The name a call's receiver starts from (``_PARAMETERS`` of ``_PARAMETERS[name]``)."""
    while isinstance(node, (ast.Subscript, ast.Attribute)):
        node = node.value
    return node.id if isinstance(node, ast.Name) else None


def _calls(path: Path):
    """(function name, accessor call, key argument) of every accessor call in ``path``: a
    TableReader's (the key first) or a declared SettingTable's (the reader, then the key)."""
    tables = _setting_tables(path)
    tree = ast.parse(path.read_text(encoding="utf-8"))
    for function in ast.walk(tree):
        if isinstance(function, (ast.FunctionDef, ast.AsyncFunctionDef)):
            for node in ast.walk(function):
                if not (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)):
                    continue
                if (node.func.attr in TABLE_ACCESSORS and _receiver(node.func.value) in tables
                        and len(node.args) >= 2):
                    yield function.name, node, node.args[1]
                elif node.func.attr in ACCESSORS and node.args:
                    yield function.name, node, node.args[0]


def _literal_key(key: ast.expr) -> str | None:
    return key.value if isinstance(key, ast.Constant) and isinstance(key.value, str) else None


def _static(node: ast.expr) -> bool:
    """A literal, a module constant (UPPER_CASE), or a tuple/list/tuple() of them."""
    if isinstance(node, ast.Constant):
        return True
    if isinstance(node, ast.Name):
        return node.id.isupper() or node.id.lstrip("_").isupper()
    if isinstance(node, ast.UnaryOp):
        return _static(node.operand)
    if isinstance(node, ast.Subscript):
        return _static(node.value) and _static(node.slice)
    if isinstance(node, (ast.Tuple, ast.List)):
        return all(_static(e) for e in node.elts)
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "tuple":
        return all(_static(a) for a in node.args)
    return False


def _docs_and_modules():
    cases, studies = _entries()
    return ((key_docs.CASE, cases, CASE_MODULES),
            (input_reference.STUDY, studies, STUDY_MODULES))


# -- (a), (b): descriptions ------------------------------------------------------------------

@pytest.mark.parametrize("kind", [0, 1], ids=["case", "study"])
def test_every_key_read_is_described(kind):
    docs, entries, _ = _docs_and_modules()[kind]
    missing = [path for path, entry in entries.items()
               if path not in docs.descriptions and not entry.doc]
    assert not missing, ("keys without a description (a setting's doc, or floatmoor/case/"
                         f"key_docs.py): {missing}")
    texts = {**docs.descriptions, **{path: entry.doc for path, entry in entries.items()
                                    if entry.doc}}
    empty = [path for path, text in texts.items() if len(text.split()) < 3]
    assert not empty, f"descriptions too short to say anything: {empty}"
    twice = [path for path, entry in entries.items() if entry.doc and path in docs.descriptions]
    assert not twice, f"keys described both in their declaration and in key_docs: {twice}"


@pytest.mark.parametrize("kind", [0, 1], ids=["case", "study"])
def test_every_description_is_of_a_key_read(kind):
    docs, entries, _ = _docs_and_modules()[kind]
    stale = [path for mapping in (docs.descriptions, docs.defaults, docs.allowed, docs.types)
             for path in mapping if path and path not in entries]
    assert not stale, f"descriptions of keys no reader asks for: {stale}"


# -- (c): keys no shipped file reads -------------------------------------------------------------

@pytest.mark.parametrize("kind", [0, 1], ids=["case", "study"])
def test_every_key_a_loader_can_read_is_read(kind):
    """Literal keys by their names (``AST``), computed keys by :data:`DYNAMIC_KEYS`."""
    _, entries, modules = _docs_and_modules()[kind]
    leaves = {leaf_of(path) for path in entries}
    unread, unlisted = [], []
    for module in modules:
        for function, call, key_arg in _calls(module):
            key = _literal_key(key_arg)
            if key is None:
                if (module.name, function) not in DYNAMIC_KEYS:
                    unlisted.append(f"{module.name}:{call.lineno} in {function}")
            elif key not in leaves:
                unread.append(f"{key} ({module.name}:{call.lineno})")
        for (name, _), paths in DYNAMIC_KEYS.items():
            if name == module.name:
                unread += [path for path in paths if path not in entries]
    assert not unlisted, ("accessor calls with a computed key, to list in DYNAMIC_KEYS with "
                          f"the key paths they read: {unlisted}")
    assert not unread, ("keys no shipped case or study reads: add them to a file in "
                        f"tests/data/case_reference: {unread}")


def test_every_declared_setting_is_read():
    """Every key declared on a schema dataclass (floatmoor.case.setting) is read, with its
    description, in a shipped or fixture case file."""
    cases, _ = _entries()
    described = {leaf_of(path) for path, entry in cases.items() if entry.doc}
    unread = [f"{cls.__name__}.{key}" for cls in _declaring_classes()
              for key in settings_of(cls) if key not in described]
    assert _declaring_classes() and not unread, (
        f"declared settings no case file reads: add them to tests/data/case_reference: {unread}")


def test_every_declared_table_key_is_read():
    """Every key a SettingTable declares (a study file's, ``[campaign]``'s) is read, with its
    declared description, in a shipped or fixture file."""
    cases, studies = _entries()
    unread = [path for tables, entries in ((CAMPAIGN_TABLES, cases), (STUDY_TABLES, studies))
              for table in tables for path, spec in table.paths().items()
              if path not in entries or entries[path].doc != spec.doc]
    assert STUDY_TABLES and not unread, (
        f"declared keys no case or study file reads: add them to tests/data/case_reference: "
        f"{unread}")


def _declaring_classes() -> list[type]:
    """The dataclasses whose fields declare case-file settings."""
    from floatmoor.case import coupling, drag, sea, wind

    return [cls for module in (schema, coupling, drag, sea, wind)
            for cls in vars(module).values()
            if dataclasses.is_dataclass(cls) and isinstance(cls, type) and settings_of(cls)]


def test_every_case_table_field_has_its_real_type():
    """No field of a case table's dataclass is typed ``Any`` (``Case.waves`` is the sea's
    :class:`~floatmoor.case.sea.WaveCase`): a reader of the schema sees what each table
    holds."""
    from floatmoor.case import coupling, drag, sea, wind
    from floatmoor.case.sea import WaveCase

    untyped = [f"{module.__name__}.{cls.__name__}.{field.name}"
               for module in (schema, coupling, drag, sea, wind)
               for cls in vars(module).values()
               if dataclasses.is_dataclass(cls) and isinstance(cls, type)
               and cls.__module__ == module.__name__
               for field in dataclasses.fields(cls)
               if typing.get_type_hints(cls)[field.name] is typing.Any]
    assert not untyped, f"case fields typed Any: {untyped}"
    assert typing.get_type_hints(schema.Case)["waves"] == WaveCase | None


def test_drag_keys_are_the_drag_settings():
    """Every field of the drag settings but the coefficients table is a declared key, read
    in [floater.drag] with the preset (floatmoor.case.drag)."""
    cases, _ = _entries()
    declared = set(settings_of(DragSettings)) | set(settings_of(MorisonCoefficients))
    fields = ({f.name for f in dataclasses.fields(DragSettings)} - {"coefficients"}
              | {f.name for f in dataclasses.fields(MorisonCoefficients)})
    assert declared == fields
    assert {leaf_of(p) for p in cases if table_of(p) == "floater.drag"} == declared | {"preset"}


@pytest.mark.parametrize("kind", [0, 1], ids=["case", "study"])
def test_computed_defaults_and_ranges_are_worded(kind):
    """A default, bound, choice or size computed from other values is not printed as the one
    value a file happened to give: key_docs, or the declaration's ``allowed_text``, words
    it."""
    docs, entries, modules = _docs_and_modules()[kind]
    unworded = []
    for module in modules:
        for _, call, key_arg in _calls(module):
            key = _literal_key(key_arg)
            for keyword in call.keywords:
                if keyword.arg in COMPUTED and not _static(keyword.value):
                    mapping = getattr(docs, COMPUTED[keyword.arg])
                    unworded += [f"{path} ({keyword.arg}, {module.name}:{call.lineno})"
                                 for path, entry in entries.items()
                                 if leaf_of(path) == key and path not in mapping
                                 and not (keyword.arg == "default" and entry.default_text)]
    assert not unworded, f"computed values key_docs must word: {unworded}"


def test_shipped_files_are_cases_studies_or_report_references():
    """A TOML file under cases/ the reference leaves out is a report reference file (the
    published values of ``floatmoor report --reference``), not a case without its keys."""
    from floatmoor.report.reference import load_reference

    files = input_files()
    left_out = [p for p in sorted((ROOT / "cases").rglob("*.toml"))
                if p not in files.cases and p not in files.studies]
    assert left_out, "cases/deepcwind/published_*.toml are expected here"
    for path in left_out:
        load_reference(path)


# -- (d): the page -----------------------------------------------------------------------------

def test_page_is_the_generated_one():
    text = (ROOT / PAGE).read_text(encoding="utf-8")
    assert text == reference_page(), (f"{PAGE} is out of date: python -m "
                                      f"floatmoor.cli.case_reference -o {PAGE}")


def test_page_has_every_key_in_its_table():
    text = (ROOT / PAGE).read_text(encoding="utf-8")
    case_part, study_part = text.split("\n## Study files\n")
    for part, entries in zip((case_part, study_part), _entries()):
        sections = dict(re.findall(r"\n### (.+)\n((?:.|\n)*?)(?=\n### |\Z)", part))
        for path, entry in entries.items():
            table = table_of(path)
            header = next(h for h in sections
                          if (not table and h.startswith("Top level"))
                          or h.strip("`[]") == table.replace("[]", "").replace("<name>",
                                                                               "NAME"))
            assert f"\n| `{leaf_of(path)}` |" in sections[header], (path, header)


def test_renderer_words_requirement_and_range():
    """The columns of a made-up table: required, default, optional, bounds, choices."""
    from floatmoor.case.reader import ReadContext, TableReader
    from floatmoor.case.reference import render_section

    with recording() as records:
        t = TableReader({"a": 1.0, "c": "x"}, (), ReadContext("made-up"))
        t.number("a", unit="m", gt=0.0, le=2.0)
        t.number("b", unit="s", default=3.0)
        t.string("c", choices=("x", "y"))
        t.integer("d", ge=1, default=None, auto="chosen")
    docs = key_docs.KeyDocs({k: f"the key {k}" for k in "abcd"})
    text = render_section("", merge_records(records), docs, title="T")
    assert "| `a` | number | m | required | > 0 and <= 2 | the key a |" in text
    assert "| `b` | number | s | default 3 |  | the key b |" in text
    assert '| `c` | string |  | required | one of "x", "y" | the key c |' in text
    assert '| `d` | integer |  | optional | >= 1; or "auto" | the key d |' in text


def test_a_declared_setting_is_read_and_described():
    """One declaration gives the reader's checks and messages and the reference's row."""
    from floatmoor.case.reader import ReadContext, TableReader
    from floatmoor.case.reference import render_section
    from floatmoor.case.setting import read_settings, setting
    from floatmoor.errors import CaseError

    @dataclasses.dataclass(frozen=True)
    class Made:
        a: float = setting("number", unit="m", gt=0.0, doc="The length a of the thing.")
        b: str = setting("string", choices=("x", "y"), default="x", doc="The choice b here.")

    with recording() as records:
        t = TableReader({"a": 2.0}, ("made",), ReadContext("made-up.toml"))
        assert Made(**read_settings(Made, t)) == Made(a=2.0, b="x")
    text = render_section("", merge_records(records), key_docs.KeyDocs({}), title="T")
    assert "| `a` | number | m | required | > 0 | The length a of the thing. |" in text
    assert '| `b` | string |  | default "x" | one of "x", "y" | The choice b here. |' in text
    with pytest.raises(CaseError) as error:
        read_settings(Made, TableReader({"a": -1.0}, ("made",), ReadContext("made-up.toml")))
    assert error.value.key == "made.a" and "a finite number > 0 [m]" in str(error.value)


def test_a_setting_table_reads_and_describes_its_keys():
    """A SettingTable's keys: read with the accessor's checks and messages, computed options
    replacing the declared ones, sub-tables and arrays of tables, each recorded with its
    description; the allowed column words computed choices from the declaration."""
    from floatmoor.case.reader import MISSING, ReadContext, TableReader
    from floatmoor.case.reference import render_section
    from floatmoor.case.setting import Setting
    from floatmoor.errors import CaseError

    top = SettingTable("", {
        "a": Setting("integer", ge=1, default=2, doc="The count a of the thing."),
        "b": Setting("string", allowed_text="a name of the case", doc="The name b here."),
        "items": Setting("tables", doc="The items of the thing."),
        "opt": Setting("table", default={}, doc="Optional settings of it."),
        "<key>": Setting("array", doc="Any key and its values."),
    })
    item = SettingTable("items[]", {"x": Setting("vector", size=2, unit="s", ge=0.0,
                                                 doc="The window x of an item.")})
    data = {"b": "n", "items": [{"x": [0.0, 1.0]}], "k.1": [1, 2]}
    with recording() as records:
        t = TableReader(data, (), ReadContext("made-up.toml"))
        assert top.read(t, "a") == 2
        assert top.read(t, "b", choices=("n", "m")) == "n"
        assert [item.read(e, "x") for e in top.tables(t, "items")] == [(0.0, 1.0)]
        assert top.table(t, "opt").data == {}
        assert top.read(t, "k.1", declared="<key>") == [1, 2]
        t.finish()
    entries = merge_records(records)
    assert {p: e.doc for p, e in entries.items()} == {
        "a": "The count a of the thing.", "b": "The name b here.",
        "items": "The items of the thing.", "items[].x": "The window x of an item.",
        "opt": "Optional settings of it.", "<key>": "Any key and its values."}
    docs = key_docs.KeyDocs({}, allowed={p: s.allowed_text for p, s in top.paths().items()
                                         if s.allowed_text})
    text = render_section("", entries, docs, title="T")
    assert "| `b` | string |  | required | a name of the case | The name b here. |" in text
    assert render_section("items[]", entries, docs).startswith(
        "### `[[items]]`\n\nThe items of the thing.\n")
    for bad, key, expected in (({"a": 0}, "a", "an integer >= 1"),
                               ({"b": "z"}, "b", 'one of "n", "m"'),
                               ({"b": "n", "items": [{"x": [-1.0, 1.0]}]}, "items[0].x[0]",
                                "a finite number >= 0")):
        with pytest.raises(CaseError) as error:
            t = TableReader(bad, (), ReadContext("made-up.toml"))
            top.read(t, "a")
            top.read(t, "b", choices=("n", "m"))
            for e in top.tables(t, "items"):
                item.read(e, "x")
        assert error.value.key == key and expected in str(error.value), str(error.value)
    with pytest.raises(TypeError):
        top.table(TableReader({}, (), ReadContext("made-up.toml")), "items")
    assert MISSING is top.settings["b"].default


def test_a_declared_angle_is_read_in_degrees_into_radians():
    """A field holding radians declares the file's ``*_deg`` key; its row, value and
    errors are the key's; ``{table}`` in a description names the table it is read in."""
    import math

    from floatmoor.case.reader import ReadContext, TableReader
    from floatmoor.case.reference import render_section
    from floatmoor.case.setting import read_settings, setting, settings_of
    from floatmoor.errors import CaseError

    @dataclasses.dataclass(frozen=True)
    class Made:
        phase: float = setting("number", key="phase_deg", radians=True, unit="deg",
                               default=0.0, doc="Phase of the {table} motion.")
        period: tuple[float, ...] = setting("number_or_vector", size=3, unit="s", gt=0.0,
                                            doc="Periods of the {table} motion.")

    assert list(settings_of(Made)) == ["phase_deg", "period"]
    with recording() as records:
        t = TableReader({"phase_deg": 90.0, "period": 2.0}, ("motion", "roll"),
                        ReadContext("made-up.toml"), generic="motion.roll")
        made = Made(**read_settings(Made, t))
    assert made == Made(phase=math.radians(90.0), period=(2.0, 2.0, 2.0))
    text = render_section("motion.roll", merge_records(records), key_docs.KeyDocs({}), title="T")
    assert "| `phase_deg` | number | deg | default 0 |  | Phase of the roll motion. |" in text
    assert read_settings(Made, TableReader({"period": 1.0}, ("m",), ReadContext("x")))[
        "phase"] == 0.0
    with pytest.raises(CaseError) as error:
        read_settings(Made, TableReader({"phase_deg": "x", "period": 1.0}, ("m",),
                                        ReadContext("made-up.toml")))
    assert error.value.key == "m.phase_deg"


def test_a_bound_computed_from_other_values_is_worded_on_its_declaration():
    """A bound passed when reading is the declaration's wording on the page, not the one
    file's value; without a wording the read is refused (the page would be wrong)."""
    from floatmoor.case.reader import ReadContext, TableReader
    from floatmoor.case.reference import render_section
    from floatmoor.case.setting import setting, settings_of
    from floatmoor.errors import CaseError

    @dataclasses.dataclass(frozen=True)
    class Made:
        low: float = setting("number", unit="m", doc="The low end of it.")
        high: float = setting("number", unit="m", allowed_text="> low",
                              doc="The high end of it.")

    declared = settings_of(Made)
    with recording() as records:
        t = TableReader({"low": 1.0, "high": 2.0}, ("made",), ReadContext("made-up.toml"))
        low = declared["low"].read(t, "low")
        assert declared["high"].read(t, "high", gt=low) == 2.0
    text = render_section("", merge_records(records), key_docs.KeyDocs({}), title="T")
    assert "| `high` | number | m | required | > low | The high end of it. |" in text
    with pytest.raises(CaseError) as error:
        declared["high"].read(TableReader({"high": 0.5}, ("made",), ReadContext("made-up.toml")),
                              "high", gt=1.0)
    assert "a finite number > 1 [m]" in str(error.value)
    with pytest.raises(TypeError, match="allowed_text"):
        declared["low"].read(TableReader({"low": 1.0}, (), ReadContext("x")), "low", lt=2.0)


# -- (e): recording changes nothing ---------------------------------------------------------------

def _same(a, b) -> bool:
    if dataclasses.is_dataclass(a) and not isinstance(a, type):
        return type(a) is type(b) and all(_same(getattr(a, f.name), getattr(b, f.name))
                                          for f in dataclasses.fields(a))
    if isinstance(a, np.ndarray):
        return isinstance(b, np.ndarray) and np.array_equal(a, b, equal_nan=True)
    if isinstance(a, (tuple, list)):
        return type(a) is type(b) and len(a) == len(b) and all(map(_same, a, b))
    if isinstance(a, dict):
        return a.keys() == b.keys() and all(_same(a[k], b[k]) for k in a)
    if isinstance(a, float) and isinstance(b, float) and np.isnan(a):
        return bool(np.isnan(b))
    return a == b


def test_recording_changes_nothing_loaded():
    files = input_files()
    for path in files.cases:
        plain = load_case(path)
        with recording() as records:
            recorded = load_case(path)
        assert records and _same(plain, recorded), path
    for path in files.studies:
        plain = load_study(path)
        with recording() as records:
            recorded = load_study(path)
        assert records and _same(plain, recorded), path


def test_recording_is_off_outside_the_block():
    with recording() as records:
        pass
    load_case(input_files().cases[0])
    assert records == []
