"""A seeded mutation corpus of MoorDyn's decks (tests/data/moordyn) for ``import moordyn``.

Each deck is mutated (a token set to an extreme or wrong value, a line dropped or repeated, two
tokens swapped) for a seeded sample; the import must then give either a case the loader
accepts, with finite numbers only, or one CaseError of one line: never another exception, a
hang (a time bound per deck) or a NaN. A few mutants go through the command line too (status 0
or 2, one line, no traceback). Slow (a minute): ``pytest -m slow``.
"""

from __future__ import annotations

import math
import os
import subprocess
import sys
import time
import tomllib
from pathlib import Path

import pytest

from floatmoor.errors import CaseError
from floatmoor.io.moordyn.importer import import_deck
from floatmoor.io.moordyn.parser import parse_deck
from tests.io.moordyn_decks import DECKS, IMPORTABLE, REPO
from tests.io.text_mutants import text_mutants

#: A mutant's value may be valid but implausible (a diameter of 1e-9 m): the loader then warns,
#: naming the key (floatmoor.case.plausibility), which is an outcome the corpus accepts.
pytestmark = [pytest.mark.slow,
              pytest.mark.filterwarnings("ignore::floatmoor.errors.ImplausibleInputWarning")]

#: Seed of the corpus, so a failure reproduces.
SEED = 20261128
#: Mutants per deck.
SAMPLES = 300
#: Mutants per deck also run through ``floatmoor import moordyn``.
CLI_SAMPLES = 3
#: Longest an import of one mutant may take [s] (they take ~10 ms; the loader's statics of
#: a system included).
MAX_SECONDS = 10.0
#: Values a token is set to: extremes, signs, zero, non-numbers, huge integers, names.
VALUES = ("1e308", "-1e308", "1e-300", "-1e-300", "0", "-0", "-1", "1e9", "2e9", "1e-9",
          "1e-200", "1e200", "nan", "inf", "x", "-", "2147483648", "1" * 5000, "Body1",
          "Body99", "Fixed", "Free", "Coupled", "main", "\x01", "\u202e")


def _mutants(name: str) -> list[tuple[str, str]]:
    """(description, text) of the seeded mutants of deck ``name``."""
    return text_mutants((DECKS / name).read_text(), f"{SEED}-{name}", SAMPLES, VALUES)


def _finite(value) -> bool:
    if isinstance(value, float):
        return math.isfinite(value)
    if isinstance(value, dict):
        return all(_finite(v) for v in value.values())
    if isinstance(value, list):
        return all(_finite(v) for v in value)
    return True


@pytest.mark.parametrize("name", sorted(IMPORTABLE))
def test_mutated_decks_import_or_give_one_line(name: str):
    kwargs = IMPORTABLE[name]
    imported = refused = 0
    for what, text in _mutants(name):
        start = time.perf_counter()
        try:
            result = import_deck(parse_deck(text, "mutant.dat"), **kwargs)
        except CaseError as err:
            assert "\n" not in str(err) and str(err).startswith("mutant.dat"), what
            refused += 1
        else:
            assert _finite(tomllib.loads(result.text)), what
            imported += 1
        assert time.perf_counter() - start < MAX_SECONDS, what
    assert imported and refused  # the corpus exercises both outcomes


@pytest.mark.parametrize("name", sorted(IMPORTABLE))
def test_mutated_decks_through_the_command_line(name: str, tmp_path: Path):
    depth = IMPORTABLE[name].get("water_depth")
    for k, (what, text) in enumerate(_mutants(name)[:CLI_SAMPLES]):
        deck = tmp_path / f"mutant{k}.dat"
        deck.write_text(text)
        out = tmp_path / f"mutant{k}.toml"
        args = ["import", "moordyn", str(deck), "-o", str(out)]
        if depth is not None:
            args += ["--water-depth", str(depth)]
        result = subprocess.run([sys.executable, "-m", "floatmoor.cli", *args],
                                capture_output=True, text=True, timeout=120, cwd=REPO,
                                env={**os.environ, "PYTHONPATH": str(REPO)})
        assert result.returncode in (0, 2), f"{what}: {result.stderr[-2000:]}"
        assert "Traceback" not in result.stderr, what
        if result.returncode == 2:
            lines = result.stderr.strip().splitlines()
            assert len(lines) == 1 and lines[0].startswith("floatmoor: error: "), what
            assert not out.exists(), what
