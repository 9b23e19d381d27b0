"""The one place that imports numba's ``njit``.

Every numerical kernel in floatmoor is decorated with :func:`jit`, which fixes the
project-wide policy: compiled once and cached on disk (``cache=True``), no ``fastmath``
(NaN and infinity checks must keep working, they are how kernels report failure),
``nogil`` so kernels can run in threads.
"""

from __future__ import annotations

import time as _time
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any, Callable

import numba
from numba.core import event as _event

__all__ = ["jit", "numba_info", "watch_compilation"]


def jit(func: Callable[..., Any] | None = None, **options: Any) -> Any:
    """Compile ``func`` with floatmoor's numba policy.

    Parameters
    ----------
    func
        The kernel. Its arguments must be arrays, scalars or tuples of them.
    **options
        Extra ``numba.njit`` options; ``cache``, ``fastmath`` and ``nogil`` are fixed.
    """
    settings = {"cache": True, "fastmath": False, "nogil": True, **options}
    if func is None:
        return lambda f: numba.njit(**settings)(f)
    return numba.njit(**settings)(func)


def numba_info() -> dict[str, str]:
    """Versions and settings of the numba runtime, for result provenance."""
    import llvmlite

    return {
        "numba_version": numba.__version__,
        "llvmlite_version": llvmlite.__version__,
        "numba_disable_jit": str(bool(numba.config.DISABLE_JIT)),
    }


class _CompileListener(_event.Listener):
    """Calls ``on_start`` when the outermost compilation of a kernel begins and ``on_end``
    (with its wall time [s]) when it ends; kernels compiled from inside it are nested."""

    def __init__(self, on_start: Callable[[], None],
                 on_end: Callable[[float], None]) -> None:
        self._on_start, self._on_end = on_start, on_end
        self._depth = 0
        self._began = 0.0

    def on_start(self, event: _event.Event) -> None:
        self._depth += 1
        if self._depth == 1:
            self._began = _time.perf_counter()
            self._on_start()

    def on_end(self, event: _event.Event) -> None:
        self._depth -= 1
        if self._depth == 0:
            self._on_end(_time.perf_counter() - self._began)


@contextmanager
def watch_compilation(on_start: Callable[[], None],
                      on_end: Callable[[float], None]) -> Iterator[None]:
    """Report kernel compilations inside the block.

    numba raises its ``numba:compile`` event only when it compiles a signature, not when it
    loads one from the on-disk cache, so a run whose kernels are all cached reports nothing.

    Parameters
    ----------
    on_start
        Called when an (outermost) kernel compilation starts.
    on_end
        Called with its wall time [s] when it ends.
    """
    with _event.install_listener("numba:compile", _CompileListener(on_start, on_end)):
        yield
