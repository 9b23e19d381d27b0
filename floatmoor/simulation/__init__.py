"""Runs: a case assembled once, the forced-motion and coupled runs, checkpoints and the
recorder (docs/guide/running.md).
"""

from floatmoor._exports import lazy_exports

#: Public name -> the module that defines it (docs/development.md#public-api).
_API = {
    "run_case": "floatmoor.simulation.run",
    "run_forced_motion": "floatmoor.simulation.forced",
    "RunResult": "floatmoor.simulation.forced",
    "run_coupled": "floatmoor.simulation.coupled_run",
    "assemble": "floatmoor.simulation.assembly",
    "MooredSystem": "floatmoor.simulation.assembly",
}
__all__, __getattr__, __dir__ = lazy_exports(__name__, _API)
