"""The quick start's first run compiles each kernel it uses once, and nothing else.

A first run after an install spends most of its time compiling numba kernels
(docs/validation/performance.md#first-run). Waste creeps in silently: a kernel compiled for a
second argument type (an int literal beside an int, a read-only array beside a writable one), a
private kernel called from Python (which builds its twin with the Python entry points), a
kernel of a path the run does not take. The tests run the README's quick-start case on an
empty numba cache, in a child process, and list every compilation (about 10 s: it compiles);
then once more on the same cache, which must compile nothing and say nothing of compiling
(the one empty-cache compilation of the default run that the message check shares).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from floatmoor._numba import jit
from floatmoor.cli.progress import COMPILING_MESSAGE
from tests.conftest import REPO

QUICK_START_CASE = REPO / "cases" / "lindahl" / "lindahl_r0.20_T1.25.toml"

#: The modules whose kernels the quick start (a forced dynamic line, explicit steps, its
#: initial shape from the catenary) compiles; a kernel from any other (the implicit or coupled
#: DG paths, the quasi-static series, the body) is compiled for a path the run does not take.
QUICK_START_KERNEL_MODULES = {
    "floatmoor.mooring._catenary_kernels",
    "floatmoor.mooring._catenary_equations",
    "floatmoor.mooring._catenary_profile",
    "floatmoor.mooring.dg._kernels",
}

#: The child: runs the CLI with a listener on numba's compile event and writes every compiled
#: (module, kernel, argument types) to the file named by its first argument.
_CHILD = """
import json, sys
from numba.core import event
compiled = []
class Listener(event.Listener):
    def on_start(self, ev):
        pass
    def on_end(self, ev):
        func = ev.data["dispatcher"].py_func
        compiled.append([func.__module__, func.__qualname__, str(ev.data["args"])])
event.register("numba:compile", Listener())
from floatmoor.cli import main
status = main(sys.argv[2:])
with open(sys.argv[1], "w") as out:
    json.dump({"status": status, "compiled": compiled}, out)
"""


def _quick_start_run(folder: Path, name: str) -> tuple[int, list[list[str]], str]:
    """The quick start on the numba cache in ``folder``: (status, compilations, stderr)."""
    env = {**os.environ, "NUMBA_CACHE_DIR": str(folder / "numba"), "MPLBACKEND": "Agg",
           "PYTHONPATH": os.pathsep.join([str(REPO), os.environ.get("PYTHONPATH", "")])}
    record = folder / f"{name}.json"
    # the quick start's case and numerics, 0.5 s simulated: compiling does not depend on it;
    # not --quiet, so that the progress reporter says whether it compiles
    command = [sys.executable, "-c", _CHILD, str(record), "run", str(QUICK_START_CASE),
               "--set", "simulation.duration=0.5", "--set", "motion.ramp_duration=0.25",
               "-o", str(folder / f"{name}.nc")]
    done = subprocess.run(command, env=env, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    result = json.loads(record.read_text())
    return result["status"], result["compiled"], done.stderr


@pytest.fixture(scope="module")
def quick_start_runs(tmp_path_factory: pytest.TempPathFactory) -> dict[str, tuple]:
    """The quick start run twice on one empty numba cache: "first" compiles, "again" loads
    every kernel from the cache."""
    folder = tmp_path_factory.mktemp("quick_start")
    return {name: _quick_start_run(folder, name) for name in ("first", "again")}


def test_quick_start_compiles_each_kernel_once_and_only_its_own(quick_start_runs):
    status, compiled, _ = quick_start_runs["first"]
    assert status == 0
    ours = [c for c in compiled if c[0].startswith("floatmoor.")]
    names = [f"{module}.{kernel}" for module, kernel, _ in ours]
    assert "floatmoor.mooring.dg._kernels.dg_run_path" in names  # the dynamic line compiled
    twice = {name: [args for m, k, args in ours if f"{m}.{k}" == name]
             for name in set(names) if names.count(name) > 1}
    assert not twice, f"kernels compiled for more than one signature: {twice}"
    python_entries = [name for name in names if name.endswith("__python_entry")]
    assert not python_entries, f"private kernels called from Python: {python_entries}"
    others = sorted({m for m, _, _ in ours} - QUICK_START_KERNEL_MODULES)
    assert not others, f"kernels of paths the quick start does not take: {others}"


def test_first_run_says_it_compiles_and_a_cached_run_does_not(quick_start_runs):
    """On an empty numba cache (a fresh install) the run says it compiles kernels, once; the
    next run loads them from the cache, compiles nothing and says nothing of it."""
    status, _, first = quick_start_runs["first"]
    again_status, again_compiled, again = quick_start_runs["again"]
    assert status == 0 and again_status == 0
    assert first.count(COMPILING_MESSAGE) == 1
    assert "left" not in first  # no estimate from the chunk that compiled
    assert COMPILING_MESSAGE not in again
    assert not again_compiled, f"compiled again on a warm cache: {again_compiled}"


@jit
def _doubled(x):
    return 2.0 * x


@jit
def doubled_plus_one(x):
    return _doubled(x) + 1.0


def test_a_private_kernel_has_no_python_entry_and_python_calls_reach_its_twin():
    # private kernels are compiled for calls from kernels only (no CPython wrapper, which a
    # call from Python would jump through): from Python they go to a twin that has one
    assert doubled_plus_one(1.5) == 4.0
    assert _doubled._python_entry is None  # a kernel's call needs no twin
    assert _doubled.targetoptions["no_cpython_wrapper"]
    assert "no_cpython_wrapper" not in doubled_plus_one.targetoptions
    assert _doubled(1.5) == 3.0
    assert _doubled._python_entry is not None
    assert "no_cpython_wrapper" not in _doubled.python_entry.targetoptions
