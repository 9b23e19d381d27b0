"""The one place that imports numba's ``njit``.

Every numerical kernel in floatmoor is decorated with :func:`jit`, which fixes the
project-wide policy: compiled once and cached on disk (``cache=True``), no ``fastmath``
(NaN and infinity checks must keep working, they are how kernels report failure),
``nogil`` so kernels can run in threads.

A private kernel (its name starts with ``_``) is a helper of other kernels: it is compiled
without the CPython and C entry points that only calls from Python need (building them is
about a sixth of the compile time of a first run, docs/validation/performance.md#first-run).
A call from Python (a test, a model's occasional direct call) goes to a twin compiled with
them on first use, cached on disk under its own name; the machine code is the same.

A kernel compiled into the on-disk cache holds the machine code of every kernel it calls, from
whatever module. numba stamps a cached kernel with its own source file only, so a change to a
kernel it calls in another file (``_kernels.py`` under ``_implicit_kernels.py``) would leave the
caller's stale code in use, silently. Every kernel module of the package is therefore cached
under one stamp over all of them (:func:`kernel_sources_stamp`): a change to any kernel source
recompiles every kernel (docs/development.md#2-numerical-kernels-and-their-oracles).
"""

from __future__ import annotations

import functools
import hashlib
import time as _time
import types as _types
from collections.abc import Iterator
from pathlib import Path
from contextlib import contextmanager
from typing import Any, Callable

import numba
from numba.core import event as _event

try:  # numba internals (as of 0.68): without them every kernel keeps its Python entry
    from numba.core.caching import NullCache as _NullCache
    from numba.core.registry import CPUDispatcher as _CPUDispatcher
except ImportError:  # pragma: no cover - a numba that moved them
    _NullCache = _CPUDispatcher = None
try:  # numba internals (as of 0.68): where and under which stamp a kernel is cached
    from numba.core.caching import CacheImpl as _CacheImpl
    from numba.core.caching import _CacheLocator
except ImportError:  # pragma: no cover - a numba that moved them
    _CacheImpl = None
    _CacheLocator = object  # type: ignore[assignment,misc]

__all__ = ["jit", "numba_info", "watch_compilation", "kernel_sources_stamp",
           "KERNEL_ROOTS", "KERNEL_MARK"]

#: Folders whose kernels are cached under :func:`kernel_sources_stamp` (floatmoor's own).
KERNEL_ROOTS: list[Path] = [Path(__file__).resolve().parent]
#: What marks a source file as one that defines kernels (the decorator of this module).
KERNEL_MARK = b"@jit"


@functools.lru_cache(maxsize=None)
def kernel_sources_stamp(root: Path) -> str:
    """SHA-256 over the path and content of every kernel module (a ``.py`` file holding
    :data:`KERNEL_MARK`) under ``root`` and over this module: the source stamp of every kernel
    cached from there. Computed once per process (reading the package's sources takes a few
    milliseconds)."""
    digest = hashlib.sha256(Path(__file__).read_bytes())
    for path in sorted(root.rglob("*.py")):
        source = path.read_bytes()
        if KERNEL_MARK in source:
            digest.update(str(path.relative_to(root)).encode() + b"\0" + source + b"\0")
    return digest.hexdigest()


def _stamped_root(py_file: str) -> Path | None:
    """The entry of :data:`KERNEL_ROOTS` that holds ``py_file``, or None."""
    path = Path(py_file).resolve()
    return next((root for root in KERNEL_ROOTS if path.is_relative_to(root)), None)


class _KernelSourcesLocator(_CacheLocator):  # type: ignore[misc,valid-type]
    """numba's own cache locator for a kernel of :data:`KERNEL_ROOTS` (same folder, same file
    names), with the source stamp of all the kernel modules there besides its own file's."""

    def __init__(self, inner: Any, root: Path) -> None:
        self._inner, self._root = inner, root

    def ensure_cache_path(self) -> None:
        self._inner.ensure_cache_path()

    def get_cache_path(self) -> str:
        return self._inner.get_cache_path()

    def get_disambiguator(self) -> str:
        return self._inner.get_disambiguator()

    def get_source_stamp(self) -> Any:
        return self._inner.get_source_stamp(), kernel_sources_stamp(self._root)

    @classmethod
    def from_function(cls, py_func: Any, py_file: str) -> Any:
        root = _stamped_root(py_file)
        if root is None:
            return None
        for locator in _CacheImpl._locator_classes:
            if locator is not cls:
                inner = locator.from_function(py_func, py_file)
                if inner is not None:
                    return cls(inner, root)
        return None


if _CacheImpl is not None and _KernelSourcesLocator not in _CacheImpl._locator_classes:
    _CacheImpl._locator_classes.insert(0, _KernelSourcesLocator)


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
        return lambda f: _compile(f, settings)
    return _compile(func, settings)


#: Name suffix of the Python-callable twin of a private kernel (its own cache files).
_PYTHON_ENTRY = "__python_entry"
#: Target options of a private kernel that its twin does not take (``njit`` sets nopython).
_KERNEL_ONLY = ("nopython", "no_cpython_wrapper", "no_cfunc_wrapper")


class _KernelOnlyDispatcher(_CPUDispatcher or object):  # type: ignore[misc]
    """Dispatcher of a private kernel, compiled without entry points for Python: kernels
    call it directly; a call from Python goes to :attr:`python_entry`."""

    _python_entry: Any = None

    @property
    def python_entry(self) -> Any:
        """The same kernel compiled with the CPython entry point (built on first use)."""
        if self._python_entry is None:
            func = self.py_func
            twin = _types.FunctionType(func.__code__, func.__globals__, func.__name__,
                                       func.__defaults__, func.__closure__)
            twin.__qualname__ = func.__qualname__ + _PYTHON_ENTRY
            twin.__module__ = func.__module__
            twin.__doc__ = func.__doc__
            options = {k: v for k, v in self.targetoptions.items() if k not in _KERNEL_ONLY}
            cached = not isinstance(self._cache, _NullCache)
            self._python_entry = numba.njit(cache=cached, **options)(twin)
        return self._python_entry

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        # the compiled overloads of this dispatcher have no CPython entry: calling them from
        # Python would jump to a null address
        return self.python_entry(*args, **kwargs)


def _compile(func: Callable[..., Any], settings: dict[str, Any]) -> Any:
    """``numba.njit(**settings)(func)``; a private kernel without its Python entry points."""
    if (not func.__name__.startswith("_") or numba.config.DISABLE_JIT
            or _CPUDispatcher is None):
        return numba.njit(**settings)(func)
    options = dict(settings)
    cache = options.pop("cache")
    options.update(nopython=True, boundscheck=options.get("boundscheck"),
                   no_cpython_wrapper=True, no_cfunc_wrapper=True)
    dispatcher = _KernelOnlyDispatcher(py_func=func, locals={}, targetoptions=options)
    if cache:
        dispatcher.enable_caching()
    return dispatcher


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
