"""Mooring line models (the elastic catenary, the quasi-static, quasi-dynamic and dynamic
lines) and the statics of a mooring system (docs/theory/cable.md,
docs/theory/mooring_systems.md).
"""

from floatmoor._exports import lazy_exports

#: Public name -> the module that defines it (docs/development.md#public-api).
_API = {
    "solve_catenary": "floatmoor.mooring.catenary",
    "catenary_profile": "floatmoor.mooring.catenary",
    "CatenarySolution": "floatmoor.mooring.catenary",
    "QuasiStaticLine": "floatmoor.mooring.quasistatic",
    "QuasiDynamicLine": "floatmoor.mooring.quasidynamic",
    "DynamicLine": "floatmoor.mooring.dg.line",
    "PathStepper": "floatmoor.mooring.stepping",
    "SystemStatics": "floatmoor.mooring.statics_solver",
    "solve_statics": "floatmoor.mooring.statics_solver",
    "body_point_stiffness": "floatmoor.mooring.statics_solver",
    "static_line_loads": "floatmoor.mooring.static_strength",
}
__all__, __getattr__, __dir__ = lazy_exports(__name__, _API)
