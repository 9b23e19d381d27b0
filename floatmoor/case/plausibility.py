"""Plausibility warnings: case values that are valid but implausible by orders of magnitude.

A value can pass every check of the loader (a number > 0 in the right place) and still be a
unit typed wrong: a line diameter of 108 (mm given as m), a water density of 1.025 (t/m^3
given as kg/m^3), a gravity of 981 (cm/s^2). Such a case runs and gives results wrong by
orders of magnitude, so :func:`warn_implausible` warns, once per key, with an
:class:`~floatmoor.errors.ImplausibleInputWarning` that names the file, the key path, what
was expected and what was found (``floatmoor check`` prints them). The bounds are far outside
every real value (each is given with its sources and the shipped cases' values), so a case
that warns is almost certainly wrong; it is still run, since the loader cannot know.
The guide lists them: docs/guide/case_files.md#plausibility-warnings.
"""

from __future__ import annotations

import math
import warnings

from floatmoor.case.reader import Path, ReadContext, format_path
from floatmoor.case.schema import Case
from floatmoor.errors import ImplausibleInputWarning

__all__ = ["WATER_DENSITY_RANGE", "GRAVITY_RANGE", "LINE_DENSITY_RANGE",
           "MATERIAL_DENSITY_RANGE", "implausible_values", "warn_implausible"]

#: Water density [kg/m^3]: fresh water is 958-1000 (100 to 4 deg C), sea water 1020-1030;
#: 1.025 (t/m^3) or 1025000 (g/m^3) are unit errors. Also the range ``floatmoor hydro import``
#: accepts for ``--water-density``.
WATER_DENSITY_RANGE = (900.0, 1100.0)
#: Gravity [m/s^2]: 9.78-9.83 at the Earth's surface, 10 as a round value; 981 (cm/s^2) and
#: 32.2 (ft/s^2) are unit errors.
GRAVITY_RANGE = (9.0, 10.5)
#: Implied density of a line type, mass_per_length / (pi d^2 / 4) [kg/m^3]. For chain the
#: diameter is the nominal (bar) one and the mass per length about 19.9 d^2 t/m (studless)
#: to 21.9 d^2 t/m (studlink) with d in m (DNV-OS-E302; docs/theory/cable.md), an implied
#: density of 25 000-28 000; wire rope gives ~5 000-6 500, polyester ~800, HMPE and
#: polypropylene ~500-600 (they float), buoyancy elements modelled as line segments less (the
#: MoorDyn tripod deck's float, 252). The shipped cases span 398 (a rope) to 27 770 (a
#: chain). 50-60 000 leaves a factor of 2 beyond the extremes, while a diameter in mm given
#: as m (1e-6 of the density), in cm (1e-4) or a mass in t/m (1e-3) falls far outside.
LINE_DENSITY_RANGE = (50.0, 60_000.0)
#: Density of a line's material [kg/m^3] (it sets the line's buoyancy): from buoyancy foam
#: (~250: the MoorDyn tripod deck's float; syntactic foams 350-700), polypropylene (~900) and
#: HMPE (~975) to steel (7850) and tungsten (19 300); the shipped cases use 800 to 8953.
#: Below 50 or above 30 000 it is a unit error (7.85 for t/m^3).
MATERIAL_DENSITY_RANGE = (50.0, 30_000.0)


def _outside(value: float, bounds: tuple[float, float]) -> bool:
    return not bounds[0] <= value <= bounds[1]


def implausible_values(case: Case, context: ReadContext | None = None
                       ) -> list[tuple[Path, str, str]]:
    """The implausible values of ``case``: (key path, what was expected, what was found).
    A line type's implied density names its ``diameter``, or its ``mass_per_length`` when
    only that was set on the command line (``context``)."""
    env = case.environment
    out: list[tuple[Path, str, str]] = []
    low, high = WATER_DENSITY_RANGE
    if _outside(env.water_density, WATER_DENSITY_RANGE):
        out.append((("environment", "water_density"), f"a water density of {low:g} to "
                    f"{high:g} kg/m^3 (fresh to sea water)",
                    f"{env.water_density!r}" + (" (t/m^3 rather than kg/m^3?)"
                                                if 0.9 <= env.water_density <= 1.1 else "")))
    low, high = GRAVITY_RANGE
    if _outside(env.gravity, GRAVITY_RANGE):
        out.append((("environment", "gravity"), f"the Earth's gravity, {low:g} to {high:g} "
                    "m/s^2", f"{env.gravity!r}" + (" (cm/s^2 rather than m/s^2?)"
                                                   if 900 <= env.gravity <= 1050 else "")))
    for name, lt in case.line_types.items():
        area = math.pi * lt.diameter * lt.diameter / 4.0
        implied = lt.mass_per_length / area if area > 0.0 else math.inf
        low, high = LINE_DENSITY_RANGE
        if _outside(implied, LINE_DENSITY_RANGE):
            unit = (" (mm rather than m?)" if not _outside(implied * 1e6, LINE_DENSITY_RANGE)
                    else " (cm rather than m?)"
                    if not _outside(implied * 1e4, LINE_DENSITY_RANGE) else "")
            path = ("line_types", name, "diameter")
            if context is not None and context.origin(path) == context.source and \
                    context.origin(path[:2] + ("mass_per_length",)) != context.source:
                path = path[:2] + ("mass_per_length",)  # the one set on the command line
            out.append((path, "a diameter d and mass_per_length that give the line type an "
                        f"implied density mass_per_length / (pi d^2 / 4) of {low:g} to "
                        f"{high:g} kg/m^3 (fibre rope ~500-800, wire ~6000, chain with its "
                        "nominal diameter ~25000)",
                        f"diameter {lt.diameter!r} m with mass_per_length "
                        f"{lt.mass_per_length!r} kg/m (implied density {implied:.3g} "
                        f"kg/m^3){unit}"))
        low, high = MATERIAL_DENSITY_RANGE
        if _outside(lt.material_density, MATERIAL_DENSITY_RANGE):
            out.append((("line_types", name, "material_density"), "the density of a mooring "
                        f"material, {low:g} to {high:g} kg/m^3 (fibre ~1000-1400, steel 7850)",
                        f"{lt.material_density!r}" + (" (t/m^3 rather than kg/m^3?)"
                                                      if lt.material_density < 30 else "")))
    return out


def warn_implausible(case: Case, context: ReadContext) -> None:
    """Warn (:class:`~floatmoor.errors.ImplausibleInputWarning`) once for each implausible
    value of a loaded case, naming the file (and the ``--set`` that gave it), the key path,
    what was expected and what was found."""
    for path, expected, found in implausible_values(case, context):
        warnings.warn(ImplausibleInputWarning(
            f"{context.origin(path)}: {format_path(path)}: expected {expected}, found {found} "
            "(valid, but implausible: a unit error?)"))
