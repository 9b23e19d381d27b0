"""Scaled values written so that scaling back gives the original decimals exactly.

A scaled value within :data:`SNAP_ULPS` units in the last place of a decimal of at most
:data:`SIGNIFICANT_DIGITS` significant digits is written as that decimal, any other value
exactly: scaling by lambda and then by 1 / lambda lands within a few ulps of the original
value (each factor is a product of a few rounded operations), so the round trip gives back
every input of up to 12 digits exactly, while a generic scaled value is left untouched.
"""

from __future__ import annotations

import math
from typing import Any

__all__ = ["SIGNIFICANT_DIGITS", "SNAP_ULPS", "rounded", "scaled_value"]

#: Most significant digits of a decimal a scaled value snaps to.
SIGNIFICANT_DIGITS = 12
#: Round-off tolerance of that snapping [ulp]: 64 ulp ~ 1.4e-14 relative, above the few ulps
#: of a round trip, far below any physical significance.
SNAP_ULPS = 64


def rounded(value: float) -> float:
    """``value``, or the shortest decimal within round-off of it (:data:`SNAP_ULPS`)."""
    for digits in range(1, SIGNIFICANT_DIGITS + 1):
        short = float(f"{value:.{digits}g}")
        if abs(short - value) <= SNAP_ULPS * math.ulp(value):
            return short
    return value


def scaled_value(value: Any, factor: float) -> Any:
    """A number (or nested list of numbers) times ``factor``, :func:`rounded`; booleans,
    strings and other values as they are."""
    if isinstance(value, list):
        return [scaled_value(v, factor) for v in value]
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return value
    return rounded(value * factor)
