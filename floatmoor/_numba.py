"""The one place that imports numba's ``njit``.

Every numerical kernel in floatmoor is decorated with :func:`jit`, which fixes the
project-wide policy: compiled once and cached on disk (``cache=True``), no ``fastmath``
(NaN and infinity checks must keep working, they are how kernels report failure),
``nogil`` so kernels can run in threads.
"""

from __future__ import annotations

from typing import Any, Callable

import numba

__all__ = ["jit", "numba_info"]


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
