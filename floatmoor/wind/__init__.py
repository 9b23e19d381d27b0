"""Wind: the rotor thrust of the NREL 5 MW turbine, the NPD spectrum and hub wind
realisations (docs/theory/environment.md).
"""

from floatmoor._exports import lazy_exports

#: Public name -> the module that defines it (docs/development.md#public-api).
_API = {
    "RotorThrust": "floatmoor.wind.force",
    "WindField": "floatmoor.wind.realisation",
    "npd_spectrum": "floatmoor.wind.spectrum",
    "ThrustCurve": "floatmoor.wind.thrust",
}
__all__, __getattr__, __dir__ = lazy_exports(__name__, _API)
