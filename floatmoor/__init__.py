"""floatmoor: time-domain simulation of floating structures and their mooring lines.

The public API::

    import floatmoor as fm
    case = fm.load_case("cases/lindahl/lindahl_r0.20_T1.25.toml", ["motion.period=3.5"])
    result = fm.run_forced_motion(case)   # fairleads moved by [motion]
    result.dataset["fairlead_tension"]

    decay = fm.run_coupled(fm.load_case("cases/deepcwind/deepcwind_free_decay.toml"))
    result = fm.run_case(case)            # either, as the case needs (as `floatmoor run`)

    sol = fm.solve_catenary(anchor, fairlead, length, EA, w, friction_coefficient=0.3,
                            seabed_z=-3.0)

A runner refuses a case it cannot run as asked (``run_forced_motion`` a case with a
``[floater]``, ``run_coupled`` one without) with a :class:`CaseError`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from floatmoor._exports import lazy_exports
from floatmoor._version import __version__
from floatmoor.errors import (
    CaseError, FloatmoorError, FloatmoorWarning, ImplausibleInputWarning, ModelValidityWarning,
    SolverError,
)

if TYPE_CHECKING:  # for type checkers and editors; tests/test_public_api.py checks it is _LAZY
    from floatmoor.case.load import load_case
    from floatmoor.case.schema import Case
    from floatmoor.hydro.database import build_database, load_for_case, read_database
    from floatmoor.hydro.drift_build import drift_for_case
    from floatmoor.hydro.rao import rao_for_case
    from floatmoor.io.netcdf import read_dataset, write_dataset
    from floatmoor.mooring.catenary import CatenarySolution, catenary_profile, solve_catenary
    from floatmoor.mooring.dg.line import DynamicLine
    from floatmoor.mooring.quasidynamic import QuasiDynamicLine
    from floatmoor.mooring.quasistatic import QuasiStaticLine
    from floatmoor.simulation.coupled_run import run_coupled
    from floatmoor.simulation.forced import RunResult, run_forced_motion
    from floatmoor.simulation.run import run_case

#: Each public name of the top level and the public subpackage it comes from (whose own table,
#: its ``_API``, names the module that defines it: docs/development.md#public-api). They are
#: imported on first use (PEP 562), so that importing the package (as the ``floatmoor`` command
#: does first) loads no numerical library: the command can then catch a Ctrl-C during its
#: imports and exit with one line.
_LAZY = {
    "load_case": "floatmoor.case", "Case": "floatmoor.case",
    "run_case": "floatmoor.simulation", "run_forced_motion": "floatmoor.simulation",
    "run_coupled": "floatmoor.simulation", "RunResult": "floatmoor.simulation",
    "read_dataset": "floatmoor.io", "write_dataset": "floatmoor.io",
    "solve_catenary": "floatmoor.mooring", "catenary_profile": "floatmoor.mooring",
    "CatenarySolution": "floatmoor.mooring", "QuasiStaticLine": "floatmoor.mooring",
    "QuasiDynamicLine": "floatmoor.mooring", "DynamicLine": "floatmoor.mooring",
    "read_database": "floatmoor.hydro", "load_for_case": "floatmoor.hydro",
    "build_database": "floatmoor.hydro", "rao_for_case": "floatmoor.hydro",
    "drift_for_case": "floatmoor.hydro",
}
#: The errors and warnings, imported with the package (they are light).
_EAGER = ("FloatmoorError", "CaseError", "SolverError", "FloatmoorWarning",
          "ImplausibleInputWarning", "ModelValidityWarning")

_lazy_names, __getattr__, __dir__ = lazy_exports(__name__, _LAZY)
__all__ = ["__version__", *_lazy_names, *_EAGER]
