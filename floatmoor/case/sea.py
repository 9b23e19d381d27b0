"""The choices of the ``[waves]`` table that the wave models implement: the case's side of
them, so that reading a case imports no model (docs/theory/environment.md,
docs/theory/hydrodynamics.md)."""

from __future__ import annotations

__all__ = ["SPACINGS", "SECOND_ORDER_MODELS", "DRIFT_ROUTES"]

#: Frequency discretisations of irregular seas (floatmoor.waves.realisation).
SPACINGS = ("equal", "random-in-bin")
#: The case's ``[waves] second_order`` choices ("none": first-order forces only;
#: floatmoor.waves.second_order).
SECOND_ORDER_MODELS = ("none", "mean", "newman", "full")
#: The case's ``[waves] drift_coefficients`` choices (docs/theory/hydrodynamics.md).
DRIFT_ROUTES = ("far_field", "near_field")
