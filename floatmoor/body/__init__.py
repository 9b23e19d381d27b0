"""The rigid floating body: kinematics, radiation memory, hydrostatics and its Cummins equation
(docs/theory/floater.md)."""

from floatmoor._exports import lazy_exports

#: Public name -> the module that defines it (docs/development.md#public-api).
_API = {
    "CumminsBody": "floatmoor.body.cummins",
    "BodyState": "floatmoor.body.cummins",
    "build_body": "floatmoor.body.model",
    "MorisonDrag": "floatmoor.body.morison",
    "rotation_matrix": "floatmoor.rotations",
}
__all__, __getattr__, __dir__ = lazy_exports(__name__, _API)
