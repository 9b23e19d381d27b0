"""A kernel cached on disk is recompiled when a kernel it calls changes in another file.

numba stamps a cached kernel with its own source file only; floatmoor caches every kernel
under a stamp over all its kernel modules (floatmoor/_numba.py, docs/development.md section 2).
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from floatmoor._numba import KERNEL_ROOTS, kernel_sources_stamp
from tests.conftest import REPO

#: A kernel module (the callee) and one that calls it from another file.
_CALLEE = """from floatmoor._numba import jit


@jit
def _inner(x):
    return x + {value}
"""
_CALLER = """from floatmoor._numba import jit
from kernels_pkg._inner_kernels import _inner


@jit
def outer(x):
    return _inner(x) * 10.0
"""
#: Run in a fresh process: the folder is a kernel root, as floatmoor's own is.
_CALL = """import sys
from pathlib import Path
import floatmoor._numba as nb
nb.KERNEL_ROOTS.append(Path(sys.argv[1]).resolve() / "kernels_pkg")
sys.path.insert(0, sys.argv[1])
from kernels_pkg._outer_kernels import outer
print(outer(1.0), sum(outer.stats.cache_hits.values()))
"""


def _call(folder: Path) -> tuple[float, int]:
    out = subprocess.run([sys.executable, "-c", _CALL, str(folder)], capture_output=True,
                         text=True, check=True, cwd=REPO,
                         env={**os.environ, "PYTHONPATH": str(REPO)})
    value, hits = out.stdout.split()
    return float(value), int(hits)  # signatures loaded from the on-disk cache


def test_a_cached_caller_sees_a_change_of_its_callee_in_another_file(tmp_path: Path):
    package = tmp_path / "kernels_pkg"
    package.mkdir()
    (package / "__init__.py").write_text("")
    (package / "_inner_kernels.py").write_text(_CALLEE.format(value=1.0))
    (package / "_outer_kernels.py").write_text(_CALLER)
    assert _call(tmp_path) == (20.0, 0)  # compiled and cached
    assert _call(tmp_path) == (20.0, 1)  # loaded from the cache
    (package / "_inner_kernels.py").write_text(_CALLEE.format(value=2.0))
    value, hits = _call(tmp_path)  # numba alone: 20.0 from the stale cache of outer
    assert (value, hits) == (30.0, 0)


def test_the_stamp_covers_each_kernel_module_and_only_those(tmp_path: Path):
    (tmp_path / "_a_kernels.py").write_text("@jit\ndef f(x):\n    return x\n")
    (tmp_path / "model.py").write_text("X = 1\n")
    before = kernel_sources_stamp(tmp_path)
    kernel_sources_stamp.cache_clear()
    (tmp_path / "model.py").write_text("X = 2\n")
    assert kernel_sources_stamp(tmp_path) == before
    kernel_sources_stamp.cache_clear()
    (tmp_path / "_a_kernels.py").write_text("@jit\ndef f(x):\n    return x + 1\n")
    assert kernel_sources_stamp(tmp_path) != before
    kernel_sources_stamp.cache_clear()


def test_floatmoor_kernels_are_cached_under_the_package_stamp():
    from floatmoor.mooring.dg import _kernels

    stamp = _kernels.dg_run_path._cache._cache_file._source_stamp
    assert stamp[1] == kernel_sources_stamp(KERNEL_ROOTS[0])
