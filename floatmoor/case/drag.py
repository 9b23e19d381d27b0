"""The ``[floater.drag]`` table: Morison drag coefficients and strip discretisation of a
floater's members.

The drag force these settings parametrise is :class:`floatmoor.body.morison.MorisonDrag`
(its module docstring says where each coefficient applies, docs/theory/floater.md); the
settings live here, beside the case schema, so that reading a case needs no model.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, fields, replace
from typing import Any

from floatmoor.case.setting import Setting, setting

__all__ = ["MorisonCoefficients", "DragSettings", "DRAG_PRESET", "DEEPCWIND_OC4", "NO_DRAG",
           "PRESETS",
           "HEAVE_PLATE_AREAS", "DEFAULT_STRIP_LENGTH", "MIN_STRIPS"]

#: Longest strip [m] by default. The wave velocity varies with depth like e^{kz}; the midpoint
#: rule's relative error on e^{kz} over a strip ds is (k ds)^2 / 24: 2.8 % at the top of a
#: full-scale JONSWAP band (2.0 rad/s, k = 0.41 rad/m) where there is little energy, 6e-5 at
#: the LC34 peak (0.44 rad/s). The body-motion part is linear along a strip (the midpoint
#: rule integrates |u_n| u_n of it to O(ds^2) as well). Measured on the DeepCwind preset, 2 m
#: against 0.25 m strips: 6.2e-4 of the largest force or moment (still water, random motion;
#: tests/body/test_morison.py::test_strip_length_convergence).
DEFAULT_STRIP_LENGTH = 2.0
#: Fewest strips per submerged part, so that small (model-scale) bodies are still resolved.
MIN_STRIPS = 4
#: Heave-plate axial drag areas (floatmoor.body.morison docstring, "Heave-plate area").
HEAVE_PLATE_AREAS = ("disc", "annulus")


#: How a coefficient's default is worded on the reference page.
_PRESETS = "the preset's"


def _check_coefficient(name: str, value: float) -> None:
    if not isinstance(value, (int, float)) or isinstance(value, bool):
        raise ValueError(f"drag: {name} must be a number, got {value!r}")
    if not math.isfinite(value) or value < 0.0:
        raise ValueError(f"drag: {name} must be finite and >= 0, got {value!r}")


@dataclass(frozen=True)
class MorisonCoefficients:
    """Drag coefficients per member kind [-] (module docstring for where each applies)."""

    column_transverse: float = setting(  #: Cd_t of vertical columns (above any heave plate)
        "number", scale="same", unit="-", ge=0.0, field_default=0.0, default_text=_PRESETS,
        doc="Transverse drag coefficient of the vertical columns (above any heave plate), "
            "overriding the preset's.")
    heave_plate_transverse: float = setting(  #: Cd_t of a heave plate's side (plate diameter)
        "number", scale="same", unit="-", ge=0.0, field_default=0.0, default_text=_PRESETS,
        doc="Transverse drag coefficient of a heave plate's side, on the plate's diameter.")
    heave_plate_axial: float = setting(  #: Cd of a heave plate's axial drag (A_plate)
        "number", scale="same", unit="-", ge=0.0, field_default=0.0, default_text=_PRESETS,
        doc="Axial drag coefficient of a heave plate, on the area of `heave_plate_area`.")
    member_transverse: float = setting(  #: Cd_t of pontoons and braces
        "number", scale="same", unit="-", ge=0.0, field_default=0.0, default_text=_PRESETS,
        doc="Transverse drag coefficient of the pontoons and braces.")
    member_axial: float = setting(  #: axial (skin-friction) Cd of pontoons and braces, on pi D ds
        "number", scale="same", unit="-", ge=0.0, field_default=0.0, default_text=_PRESETS,
        doc="Axial (skin-friction) drag coefficient of the pontoons and braces, on their "
            "wetted area.")
    column_axial: float = setting(  #: Cd of a plate-less column's bottom disc, pi/4 D^2
        "number", scale="same", unit="-", ge=0.0, field_default=0.0, default_text=_PRESETS,
        doc="Axial drag coefficient of the bottom disc of a column without a heave plate.")

    def validate(self) -> None:
        """Raise ValueError unless every coefficient is a finite number >= 0."""
        for f in fields(self):
            _check_coefficient(f.name, getattr(self, f.name))


#: OC4 DeepCwind, quasi-dynamic paper Table 6 (docs/cases/deepcwind.md): upper columns Cd_t 0.600;
#: lower columns (the heave-plate bases) Cd_t 0.600 and Cd long 1.60 (the heave plates' axial
#: drag); cross braces (pontoons and braces here) Cd_t 0.564. The tower column (dry) and the
#: mooring elements (own model) are not the floater's. No axial drag on the central column's
#: bottom (Table 6 gives none; OpenFAST's OC4 model has AxCd = 0 there).
#: For comparison, OpenFAST's r-test OC4 HydroDyn file uses Cd_t 0.56 (central column), 0.61
#: (upper columns), 0.68 (bases), 0.63 (pontoons, braces) and an effective heave-plate axial
#: Cd of 4.8 on the full 24 m disc (AxCd = 9.6 with HydroDyn's 1/4 factor).
DEEPCWIND_OC4 = MorisonCoefficients(
    column_transverse=0.600, heave_plate_transverse=0.600, heave_plate_axial=1.60,
    member_transverse=0.564)
#: No drag: the default of the cylinder buoy (the gpc paper gives the buoy no Morison coefficients,
#: docs/cases/cylinder_buoy.md; its buoy model is potential flow plus the lines), and of any case that does
#: not ask for drag.
NO_DRAG = MorisonCoefficients()
#: Named presets, the values of ``[floater.drag] preset``.
PRESETS: dict[str, MorisonCoefficients] = {"deepcwind_oc4": DEEPCWIND_OC4, "none": NO_DRAG}
#: ``[floater.drag] preset``: the coefficients the table's own keys override.
DRAG_PRESET = Setting("string", choices=tuple(PRESETS), default="none", scale="same",
                      doc="Set of drag coefficients to start from: `none` or `deepcwind_oc4` "
                          "(the OC4 DeepCwind semisubmersible's).")


@dataclass(frozen=True)
class DragSettings:
    """Morison drag of a floater: coefficients and discretisation (``[floater.drag]``)."""

    coefficients: MorisonCoefficients = NO_DRAG
    strip_length: float = setting(  #: longest strip [m]
        "number", scale="length", unit="m", gt=0.0, default=DEFAULT_STRIP_LENGTH,
        field_default=DEFAULT_STRIP_LENGTH,
        doc="Longest strip the members are cut into for the drag integral.")
    min_strips: int = setting(  #: fewest strips per submerged part
        "integer", scale="same", ge=1, default=MIN_STRIPS, field_default=MIN_STRIPS,
        doc="Fewest strips per submerged part, so that small bodies are resolved.")
    heave_plate_area: str = setting(  #: "disc" (HydroDyn) or "annulus"
        "string", scale="same", choices=HEAVE_PLATE_AREAS, default="disc", field_default="disc",
        doc="Area of a heave plate's axial drag: the full `disc` (as OpenFAST HydroDyn) or "
            "the `annulus` outside the column.")
    #: coarse sampling interval of the fluid velocity [s]: None picks it from the highest
    #: wave frequency (floatmoor.body.morison.KINEMATICS_PHASE_STEP); 0 evaluates every half
    #: step exactly
    kinematics_interval: float | None = setting(
        "number", scale="time", unit="s", ge=0.0, auto="from the highest wave frequency",
        default=None, field_default=None, default_text='default "auto"',
        doc="Sampling interval of the wave velocity at the strips, interpolated in between; "
            '"auto" picks it from the highest wave frequency, 0 evaluates every half step.')

    @classmethod
    def from_settings(cls, table: Mapping[str, Any]) -> DragSettings:
        """Settings from a ``[floater.drag]``-style table: an optional ``preset`` (a key of
        :data:`PRESETS`, default ``"none"``), then coefficient overrides by field name of
        :class:`MorisonCoefficients`, and the discretisation fields of this class
        (``kinematics_interval = "auto"`` is None). Validated.

        Raises
        ------
        ValueError
            Unknown keys or preset, or invalid values.
        """
        data = dict(table)
        preset = data.pop("preset", "none")
        if not isinstance(preset, str) or preset.lower() not in PRESETS:
            raise ValueError(f"drag: unknown preset {preset!r}; known: {sorted(PRESETS)}")
        coef_names = {f.name for f in fields(MorisonCoefficients)}
        own_names = {f.name for f in fields(cls)} - {"coefficients"}
        unknown = sorted(set(data) - coef_names - own_names)
        if unknown:
            raise ValueError(f"drag: unknown key(s) {unknown}; known: "
                             f"{sorted(coef_names | own_names | {'preset'})}")
        overrides = {k: data.pop(k) for k in list(data) if k in coef_names}
        coefficients = replace(PRESETS[preset.lower()], **overrides)
        if data.get("kinematics_interval") == "auto":
            data["kinematics_interval"] = None
        out = cls(coefficients=coefficients, **data)
        out.validate()
        return out

    def validate(self) -> None:
        """Raise ValueError with a clear message for any invalid field."""
        if not isinstance(self.coefficients, MorisonCoefficients):
            raise ValueError("drag: coefficients must be MorisonCoefficients")
        self.coefficients.validate()
        s = self.strip_length
        if (not isinstance(s, (int, float)) or isinstance(s, bool) or not math.isfinite(s)
                or s <= 0.0):
            raise ValueError(f"drag: strip_length must be a finite length > 0 m, got {s!r}")
        n = self.min_strips
        if not isinstance(n, int) or isinstance(n, bool) or n < 1:
            raise ValueError(f"drag: min_strips must be an integer >= 1, got {n!r}")
        if self.heave_plate_area not in HEAVE_PLATE_AREAS:
            raise ValueError(f"drag: heave_plate_area must be one of {HEAVE_PLATE_AREAS}, "
                             f"got {self.heave_plate_area!r}")
        k = self.kinematics_interval
        if k is not None and (not isinstance(k, (int, float)) or isinstance(k, bool)
                              or not math.isfinite(k) or k < 0.0):
            raise ValueError(f"drag: kinematics_interval must be 'auto' (None) or a time "
                             f">= 0 s, got {k!r}")
