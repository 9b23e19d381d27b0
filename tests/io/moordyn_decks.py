"""Test helpers for the MoorDyn import/export tests: the decks of tests/data/moordyn with what
import needs and what their cases are, the import and export as files, a comparison of loaded
cases, and MoorDyn 2.7 (the ``moordyn`` package) creating and initialising a deck."""

from __future__ import annotations

import dataclasses
import math
import tempfile
from pathlib import Path
from typing import Any

from floatmoor.case.schema import Case
from floatmoor.io.moordyn.deck import DeckOption
from floatmoor.io.moordyn.exporter import ExportResult, export_case
from floatmoor.io.moordyn.importer import import_deck
from floatmoor.io.moordyn.parser import read_deck
from floatmoor.io.moordyn.writer import deck_text
from floatmoor.mooring.deck_numerics import deck_numerics

REPO = Path(__file__).resolve().parents[2]
DECKS = REPO / "tests" / "data" / "moordyn"
#: Decks floatmoor imports, with the import's keyword arguments (MHK_RM1 is a MoorDyn-F deck:
#: OpenFAST gives its water depth, 50 m in its example).
IMPORTABLE = {
    "oc3_hywind_lines.txt": {},
    "wd0050_chain.txt": {},
    "mhk_rm1_floating.dat": {"water_depth": 50.0},
    "lifting.txt": {},
    "pendulum.txt": {},
    "tripod.txt": {},
}
#: Of those, the decks whose lines are all one section from a fixed to a body point (the
#: runners run them today); the others have free points (systems).
INDEPENDENT = ("oc3_hywind_lines.txt", "wd0050_chain.txt", "mhk_rm1_floating.dat")
SYSTEMS = ("lifting.txt", "pendulum.txt", "tripod.txt")
#: Relative difference of two floats that went through the line-type mapping and back (a
#: product and quotient by d / d_v or pi, a square root): a few ulps, 1e-16 to 3e-16 measured.
ROUND_TRIP_RTOL = 1e-14
#: MoorDyn's initial-condition solve, shortened for tests (MoorDyn's default TmaxIC is 60
#: pseudo-seconds; 25 to 50 s of wall time on the cylinder buoy and tripod decks): the tests
#: check that MoorDyn reads and initialises the deck, not where its relaxation ends.
TEST_IC_TIME = 1.0


def import_file(name: str, folder: Path) -> Path:
    """The case file ``import moordyn`` writes for deck ``name`` (in ``folder``)."""
    out = folder / (Path(name).stem + ".toml")
    out.write_text(import_deck(read_deck(DECKS / name), **IMPORTABLE.get(name, {})).text)
    return out


def exported(case: Case) -> ExportResult:
    """``case``'s MoorDyn deck and notes, with the solvers' numerics (as ``export moordyn``)."""
    return export_case(case, deck_numerics(case))


def export_file(case: Case, path: Path, extra: dict[str, str] | None = None) -> Path:
    """Write ``case``'s MoorDyn deck to ``path`` (``extra`` options appended)."""
    result = exported(case)
    deck = result.deck
    if extra:
        deck = dataclasses.replace(deck, options=deck.options + tuple(
            DeckOption(key, value) for key, value in extra.items()))
    path.write_text(deck_text(deck, result.notes))
    return path


def differences(a: Any, b: Any, path: str = "case") -> list[str]:
    """Where two loaded cases differ: every dataclass field, tuple and dict entry, floats to
    :data:`ROUND_TRIP_RTOL`; the file's provenance (source, text, description) left out."""
    out: list[str] = []
    if dataclasses.is_dataclass(a) and not isinstance(a, type):
        if type(a) is not type(b):
            return [f"{path}: {type(a).__name__} != {type(b).__name__}"]
        for f in dataclasses.fields(a):
            if f.name not in ("source", "text", "description"):
                out += differences(getattr(a, f.name), getattr(b, f.name), f"{path}.{f.name}")
    elif isinstance(a, (tuple, list)):
        if len(a) != len(b):
            return [f"{path}: {len(a)} items != {len(b)}"]
        for i, (x, y) in enumerate(zip(a, b)):
            out += differences(x, y, f"{path}[{i}]")
    elif isinstance(a, dict):
        if list(a) != list(b):
            return [f"{path}: keys {list(a)} != {list(b)}"]
        for key in a:
            out += differences(a[key], b[key], f"{path}[{key!r}]")
    elif isinstance(a, float) and isinstance(b, float):
        if not math.isclose(a, b, rel_tol=ROUND_TRIP_RTOL, abs_tol=0.0) and a != b:
            out.append(f"{path}: {a!r} != {b!r}")
    elif a != b:
        out.append(f"{path}: {a!r} != {b!r}")
    return out


def moordyn_initial_forces(path: Path) -> tuple[int, list[float]]:
    """Create and initialise the deck at ``path`` in MoorDyn, its coupled points held where the
    deck puts them; (Init's status, the forces on the coupled points at t = 0). MoorDyn's
    console output goes to a temporary file."""
    import moordyn

    from floatmoor.io.moordyn.deck import POINT_COUPLED
    from tests.io.moordyn_runner import _stdout_to

    x = [c for p in read_deck(path).points if p.attachment == POINT_COUPLED
         for c in p.position]
    with tempfile.TemporaryDirectory(prefix="floatmoor_moordyn_") as tmp:
        with _stdout_to(Path(tmp) / "console.txt"):
            system = moordyn.Create(str(path))
            try:
                if moordyn.NCoupledDOF(system) != len(x):
                    raise AssertionError(f"MoorDyn has {moordyn.NCoupledDOF(system)} coupled "
                                         f"DOF, the deck {len(x)} coupled coordinates")
                status = moordyn.Init(system, x, [0.0] * len(x))
                forces = list(moordyn.Step(system, x, [0.0] * len(x), 0.0, 0.0)) if x else []
            finally:
                moordyn.Close(system)
    return status, forces

