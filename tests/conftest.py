"""Shared test configuration: strict floating point, a non-interactive matplotlib, paths."""

from __future__ import annotations

from pathlib import Path

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")

REPO = Path(__file__).resolve().parents[1]
CASES = REPO / "cases"
LINDAHL_CASE = CASES / "lindahl" / "lindahl_r0.20_T1.25.toml"
#: Overrides giving every dynamic line MooDy's reference numerics (10 elements of order 5,
#: explicit steps), which the shipped cases name in comments: for tests written at them.
REFERENCE_NUMERICS = ["lines.*.dynamic.elements=10", "lines.*.dynamic.order=5",
                      'lines.*.dynamic.time_integration="explicit"']
#: Overrides giving every dynamic line the numerics chosen from its accuracy (what a case
#: that names none gets), whatever the case file names.
ACCURACY_DEFAULT = ['lines.*.dynamic.elements="auto"', 'lines.*.dynamic.order="auto"',
                    'lines.*.dynamic.time_integration="auto"']
#: The measured Lindahl cycles: copies of the project reference's data folder (CC BY 4.0; see
#: the README there), kept in the repository so that a clean clone runs its tests alone.
MEASURED = REPO / "tests" / "data" / "lindahl"


def pytest_report_header(config) -> str:
    """The versions the suite ran with: a fresh install takes the newest releases the
    dependency ranges allow, and a failure that depends on them must say which."""
    from importlib.metadata import PackageNotFoundError, version

    names = ("numpy", "scipy", "numba", "llvmlite", "capytaine", "xarray", "matplotlib",
             "netCDF4", "h5netcdf", "moorpy", "moordyn", "dask", "openturns")
    found = []
    for name in names:
        try:
            found.append(f"{name} {version(name)}")
        except PackageNotFoundError:
            pass
    return "floatmoor dependencies: " + ", ".join(found)


@pytest.fixture(autouse=True)
def _strict_floating_point():
    """Turn floating-point trouble (overflow, invalid, division by zero) into errors."""
    old = np.seterr(all="raise", under="ignore")
    yield
    np.seterr(**old)


@pytest.fixture
def rng() -> np.random.Generator:
    """A seeded random generator, so failures reproduce."""
    return np.random.default_rng(20261122)


@pytest.fixture
def python_sigint():
    """SIGINT with Python's own handler (KeyboardInterrupt) for the test, whatever the test
    process inherited: a shell without job control starts background jobs with SIGINT
    ignored (``pytest ... &``), and the signal tests count on Python's default."""
    import signal

    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)
