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

from importlib import import_module
from typing import TYPE_CHECKING, Any

from floatmoor._version import __version__
from floatmoor.errors import (
    CaseError, FloatmoorError, FloatmoorWarning, ImplausibleInputWarning, ModelValidityWarning,
    SolverError,
)

if TYPE_CHECKING:
    from floatmoor.case.load import load_case
    from floatmoor.case.schema import Case
    from floatmoor.io.netcdf import read_dataset, write_dataset
    from floatmoor.mooring.catenary import CatenarySolution, catenary_profile, solve_catenary
    from floatmoor.mooring.quasidynamic import QuasiDynamicLine
    from floatmoor.mooring.quasistatic import QuasiStaticLine
    from floatmoor.simulation.coupled_run import run_coupled
    from floatmoor.simulation.forced import RunResult, run_forced_motion
    from floatmoor.simulation.run import run_case

__all__ = [
    "__version__", "load_case", "Case", "CaseError", "FloatmoorError", "SolverError",
    "FloatmoorWarning", "ImplausibleInputWarning", "ModelValidityWarning",
    "read_dataset", "write_dataset", "CatenarySolution", "catenary_profile", "solve_catenary",
    "QuasiStaticLine", "QuasiDynamicLine", "RunResult", "run_forced_motion", "run_coupled",
    "run_case",
]

#: Where each public name lives. They are imported on first use (PEP 562), so that importing
#: the package (as the ``floatmoor`` command does first) loads no numerical library: the
#: command can then catch a Ctrl-C during its imports and exit with one line.
_LAZY = {
    "load_case": "floatmoor.case.load", "Case": "floatmoor.case.schema",
    "read_dataset": "floatmoor.io.netcdf", "write_dataset": "floatmoor.io.netcdf",
    "CatenarySolution": "floatmoor.mooring.catenary",
    "catenary_profile": "floatmoor.mooring.catenary",
    "solve_catenary": "floatmoor.mooring.catenary",
    "QuasiDynamicLine": "floatmoor.mooring.quasidynamic",
    "QuasiStaticLine": "floatmoor.mooring.quasistatic",
    "run_coupled": "floatmoor.simulation.coupled_run", "RunResult": "floatmoor.simulation.forced",
    "run_forced_motion": "floatmoor.simulation.forced", "run_case": "floatmoor.simulation.run",
}


def __getattr__(name: str) -> Any:
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'floatmoor' has no attribute {name!r}")
    value = getattr(import_module(module), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
