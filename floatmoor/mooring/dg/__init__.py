"""The dynamic line: the discontinuous Galerkin (DG) cable model, one line or a system of
sections joined at points (docs/theory/dynamic_line.md).
"""

from floatmoor._exports import lazy_exports

#: Public name -> the module that defines it (docs/development.md#public-api).
_API = {
    "DynamicLine": "floatmoor.mooring.dg.line",
    "DynamicLineState": "floatmoor.mooring.dg.line",
    "DynamicSystem": "floatmoor.mooring.dg.system",
    "DynamicLineBatch": "floatmoor.mooring.dg.batch",
    "CableProperties": "floatmoor.mooring.dg.cable",
    "resolve_settings": "floatmoor.mooring.dg.resolution",
}
__all__, __getattr__, __dir__ = lazy_exports(__name__, _API)
