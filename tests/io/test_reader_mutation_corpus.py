"""A seeded mutation corpus of the readers of files from elsewhere: WAMIT numeric files, WEC-Sim
BEMIO ``.h5`` files, hull meshes (GDF, STL) and uncertainty study files.

Each reader gets mutants of a valid file (a token set to an extreme or wrong value, a line
dropped or repeated, two tokens swapped; for BEMIO, a dataset replaced by one of another type,
shape or storage). Each must give either a result with no NaN, or one FloatmoorError of one line:
never another exception, a hang (a time bound per mutant), a read of a file the input names
outside itself (a decoy beside it whose reading would show in an audit hook), or a NaN. Slow
(a few minutes): ``pytest -m slow``. The MoorDyn decks have their own corpus
(tests/io/test_moordyn_mutation_corpus.py), the case files theirs (tests/cli).
"""

from __future__ import annotations

import dataclasses
import random
import shutil
import sys
import time
from pathlib import Path

import h5py
import numpy as np
import pytest

from floatmoor.errors import FloatmoorError
from tests.conftest import CASES
from tests.io.text_mutants import text_mutants

pytestmark = pytest.mark.slow

REPO = Path(__file__).resolve().parents[2]
#: Seed of the corpus, so a failure reproduces.
SEED = 20261128
#: Mutants per file.
SAMPLES = 150
#: Longest one mutant may take [s] (valid files take well under a second).
MAX_SECONDS = 20.0
#: Values a token is set to: extremes, signs, zero, non-numbers, huge integers, escapes.
VALUES = ("1e308", "-1e308", "1e-300", "0", "-0", "-1", "1e9", "2e9", "nan", "inf", "-inf",
          "x", "-", "2147483648", "1" * 5000, "\x01", "\u202e", "\x1b]0;t\x07", "1.5.3", "")
#: Names of files the readers must never open (an audit hook watches them).
DECOY = "decoy_secret.txt"


def _text_mutants(text: str, key: str, samples: int = SAMPLES) -> list[tuple[str, str]]:
    """(description, text) of the seeded mutants of ``text``."""
    return text_mutants(text, f"{SEED}-{key}", samples, VALUES)


def _nan_free(value, seen=None) -> bool:
    """Whether ``value`` (arrays, dataclasses, containers, objects' arrays) holds no NaN."""
    seen = set() if seen is None else seen
    if id(value) in seen:
        return True
    seen.add(id(value))
    if isinstance(value, np.ndarray):
        return value.dtype.kind not in "fc" or not np.any(np.isnan(value))
    if isinstance(value, float):
        return value == value
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return all(_nan_free(getattr(value, f.name), seen) for f in dataclasses.fields(value))
    if isinstance(value, dict):
        return all(_nan_free(v, seen) for v in value.values())
    if isinstance(value, (list, tuple)):
        return all(_nan_free(v, seen) for v in value)
    for name in ("vertices", "faces"):  # a mesh
        if hasattr(value, name) and not _nan_free(np.asarray(getattr(value, name)), seen):
            return False
    return True


@pytest.fixture(scope="module")
def opened():
    """Paths opened by the process while the corpus runs (an audit hook; hooks cannot be
    removed, so it records only while ``active``)."""
    record = {"active": False, "paths": []}

    def hook(event, args):
        if record["active"] and event == "open" and args and isinstance(args[0], (str, Path)):
            record["paths"].append(str(args[0]))

    sys.addaudithook(hook)
    return record


def _judge(read, description: str, opened) -> None:
    """Run ``read()``: a result without NaN, or one one-line FloatmoorError, in time, and no
    decoy opened."""
    opened["paths"].clear()
    opened["active"] = True
    started = time.perf_counter()
    try:
        result = read()
    except FloatmoorError as err:
        assert "\n" not in str(err), (description, str(err))
        result = None
    except Exception as err:  # noqa: BLE001 - the corpus's point
        raise AssertionError(f"{description}: {type(err).__name__}: {err}") from err
    finally:
        opened["active"] = False
    assert time.perf_counter() - started < MAX_SECONDS, description
    assert result is None or _nan_free(result), description
    assert not [p for p in opened["paths"] if DECOY in p], (description, opened["paths"])


def _decoy(folder: Path) -> None:
    (folder / DECOY).write_text("secret\n")


@pytest.mark.parametrize("name", ["marin_semi.1", "marin_semi.hst"])
def test_wamit_mutants(tmp_path, name, opened):
    # through the importer's reading (what `hydro import` runs): its overflow checks included
    from floatmoor.hydro.importing import ImportOptions, read_source

    source = REPO / "tests" / "data" / "wamit_oc4" / name
    _decoy(tmp_path)
    other = "marin_semi.hst" if name.endswith(".1") else "marin_semi.1"
    shutil.copy(source.with_name(other), tmp_path / other)
    for k, (description, text) in enumerate(_text_mutants(source.read_text(), name)):
        path = tmp_path / name
        path.write_text(text, encoding="utf-8", errors="surrogateescape")
        _judge(lambda: read_source([str(tmp_path / "marin_semi.1"),
                                    str(tmp_path / "marin_semi.hst")],
                                   ImportOptions(water_density=1025.0, gravity=9.80665,
                                                 water_depth=200.0, disp_volume=1.0e4,
                                                 centre_of_buoyancy=(0.0, 0.0, -10.0))),
               f"{name} mutant {k}: {description}", opened)


def test_wamit_out_mutants(tmp_path, opened):
    from floatmoor.io.wamit import read_wamit_out

    text = ("  WAMIT  Release 7.3\n\n Gravity:     9.80665                Length scale:"
            "        1.00000\n Water depth:        200.000000    Water density:      "
            "1025.00000\n")
    _decoy(tmp_path)
    for k, (description, mutant) in enumerate(_text_mutants(text, "out", 80)):
        path = tmp_path / "run.out"
        path.write_text(mutant)
        _judge(lambda: read_wamit_out(path), f".out mutant {k}: {description}", opened)


def test_mesh_mutants(tmp_path, opened):
    from floatmoor.hydro.mesh_file import read_mesh_file

    gdf = (REPO / "tests" / "data" / "bad_cases" / "mesh_box_hull.gdf").read_text()
    stl = ("solid box\n" + "".join(
        f" facet normal 0 0 -1\n  outer loop\n   vertex {a}\n   vertex {b}\n   vertex {c}\n"
        "  endloop\n endfacet\n" for a, b, c in (
            ("0 0 -1", "1 0 -1", "1 1 -1"), ("0 0 -1", "1 1 -1", "0 1 -1"),
            ("0 0 -1", "0 1 -1", "0 1 0"), ("0 0 -1", "0 1 0", "0 0 0"))) + "endsolid box\n")
    _decoy(tmp_path)
    for fmt, text in (("gdf", gdf), ("stl", stl)):
        for k, (description, mutant) in enumerate(_text_mutants(text, fmt)):
            path = tmp_path / f"hull.{fmt}"
            path.write_text(mutant, encoding="utf-8", errors="surrogateescape")
            _judge(lambda: read_mesh_file(str(path), fmt), f"{fmt} mutant {k}: {description}",
                   opened)


def test_study_file_mutants(tmp_path, opened):
    from floatmoor.uq.study import load_study

    # the study beside a copy of its case, as in cases/uq and cases/lindahl
    shutil.copytree(CASES / "lindahl", tmp_path / "lindahl")
    (tmp_path / "uq").mkdir()
    _decoy(tmp_path / "uq")
    source = CASES / "uq" / "lindahl_T1.25_all.toml"
    for k, (description, text) in enumerate(_text_mutants(source.read_text(), "study")):
        path = tmp_path / "uq" / "study.toml"
        path.write_text(text, encoding="utf-8", errors="surrogateescape")
        _judge(lambda: load_study(path), f"study mutant {k}: {description}", opened)


def _bemio_file(path: Path, rng) -> None:
    """A valid one-body BEMIO file (the layout of tests/io/test_bemio.py)."""
    from tests.io.test_bemio import _hydro, _write

    _write(path, _hydro(rng, 1))


#: Replacements of a dataset: another type, another shape, empty, a string, external storage
#: pointing at the decoy, a soft link to itself, a huge declared shape.
def _bemio_edits(folder: Path):
    decoy = str(folder / DECOY)

    def retype(f, name):
        data = np.asarray(f[name][()])
        del f[name]
        numeric = data.dtype.kind in "fiu" and data.size
        f[name] = data.astype(np.int64) if numeric else np.int64(1)

    def reshape(f, name):
        del f[name]
        f[name] = np.zeros((3, 2))

    def empty(f, name):
        del f[name]
        f.create_dataset(name, data=h5py.Empty("f8"))

    def text(f, name):
        del f[name]
        f[name] = "1.0e308"

    def external(f, name):
        shape = f[name].shape or (1,)
        del f[name]
        f.create_dataset(name, shape, "f8", external=[(decoy, 0, 8 * int(np.prod(shape)))])

    def loop(f, name):
        del f[name]
        f[name] = h5py.SoftLink(name)

    def huge(f, name):
        del f[name]
        f.create_dataset(name, (6, 6, 2_000_000_000), "f8", chunks=(1, 1, 1024),
                         compression="gzip")

    def nan(f, name):
        data = np.asarray(f[name][()])
        del f[name]
        f[name] = np.full(data.shape if data.dtype.kind in "fiu" else (), np.nan)

    return (retype, reshape, empty, text, external, loop, huge, nan)


def test_bemio_mutants(tmp_path, opened, rng):
    from floatmoor.io.bemio import read_bemio

    _decoy(tmp_path)
    (tmp_path / DECOY).write_bytes(np.arange(64, dtype=float).tobytes())
    valid = tmp_path / "valid.h5"
    _bemio_file(valid, rng)
    with h5py.File(valid, "r") as f:
        names = []
        f.visititems(lambda n, obj: names.append(n) if isinstance(obj, h5py.Dataset) else None)
    pick = random.Random(f"{SEED}-bemio")
    edits = _bemio_edits(tmp_path)
    for k in range(min(SAMPLES, 8 * len(names))):
        name, edit = pick.choice(names), pick.choice(edits)
        path = tmp_path / "mutant.h5"
        shutil.copy(valid, path)
        with h5py.File(path, "r+") as f:
            edit(f, name)
        _judge(lambda: read_bemio(path, water_density=1025.0),
               f"BEMIO mutant {k}: {edit.__name__} {name}", opened)
