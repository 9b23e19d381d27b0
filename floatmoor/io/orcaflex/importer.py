"""The mooring part of an OrcaFlex model -> the text of a floatmoor case file, checked by the
case loader (:func:`floatmoor.case.load.parse_case`) before it is returned, and the list of
what was not imported. The mapping is documented in
docs/guide/mooring_systems.md#orcaflex-models; in short:

- units: OrcaFlex's SI system (m, kN, te, s) only; kN -> 1000 N, te -> 1000 kg exactly;
- line types ("General" category): floatmoor's ``diameter`` is OrcaFlex's OD (its
  volume-equivalent diameter: buoyancy, added mass and seabed contact refer to it), the
  material density makes floatmoor's volume OrcaFlex's pi OD^2/4, and the drag coefficients
  are rescaled from OrcaFlex's drag diameters to OD so that the drag forces are the same;
- lines: each section a floatmoor section (model "dynamic", its segments as DG elements x
  order); Anchored and Fixed ends fixed points, vessel ends body points at the vessel's
  initial position (still: no [motion]), 3D and lumped 6D buoys free points;
- seabed: the normal stiffness per unit area and the damping (% of critical) of Environment,
  the line types' common friction coefficient.

Size: one mapping class whose methods share the model, the value readers and the list of what
was not imported, plus the writer of the case text that follows the same order; split, each
part would pass that state around.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from floatmoor._version import __version__
from floatmoor.case.load import DEFAULT_DG_ORDER
from floatmoor.case.naming import toml_text
from floatmoor.case.title import literal_title
from floatmoor.errors import CaseError
from floatmoor.io.orcaflex.values import Values, plain
from floatmoor.terminal_text import shown

__all__ = ["ImportResult", "import_model", "ORCAFLEX_DEFAULTS", "KN", "TE",
           "DEFAULT_DURATION", "DEFAULT_OUTPUT_INTERVAL", "SLIP_SPEED"]

#: OrcaFlex's SI units in floatmoor's: 1 kN = 1000 N, 1 te = 1000 kg (exact).
KN = 1000.0
TE = 1000.0
#: OrcaFlex's defaults of the values a file may omit (OrcaFlex's data forms): gravity, water
#: density [te/m^3], seabed stiffness [kN/m/m^2], seabed damping [% of critical], line
#: friction coefficient [-].
ORCAFLEX_DEFAULTS = {"g": 9.80665, "Density": 1.025, "SeabedNormalStiffness": 100.0,
                     "SeabedDamping": 0.0, "SeabedLateralFrictionCoefficient": 0.5}
#: Duration of the imported case without General.StageDuration [s] (as ``import moordyn``).
DEFAULT_DURATION = 60.0
#: Output interval without General.TargetLogSampleInterval [s].
DEFAULT_OUTPUT_INTERVAL = 0.1
#: floatmoor's slip speed of the smoothed friction [m/s]: OrcaFlex's friction is elastic up to
#: slip (SeabedShearStiffness), floatmoor's rises to its full value at this speed (the
#: project's usual value, as the shipped cases'); listed in the summary.
SLIP_SPEED = 0.01
#: Relative difference below which two derived values count as one [-] (round-off of the
#: mapping's products).
_SAME_RTOL = 1e-12

_SECTIONS_READ = ("General", "Environment", "LineTypes", "Lines", "3DBuoys", "6DBuoys",
                  "Vessels", "VesselTypes")
_LINE_TYPE_KEYS = {"Name", "Category", "OD", "ID", "MassPerUnitLength", "EA", "EI", "Cd",
                   "Ca", "NormalDragLiftDiameter", "AxialDragLiftDiameter",
                   "OuterContactDiameter", "SeabedLateralFrictionCoefficient",
                   "SeabedAxialFrictionCoefficient", "RayleighDampingCoefficients", "Pen"}
_LINE_KEYS = {"Name", "StaticsSeabedFrictionPolicy", "IncludedInStatics", "Pen"}
_BUOY_KEYS = {"Name", "Connection", "BuoyType", "InitialPosition", "InitialX", "InitialY",
              "InitialZ", "Mass", "Volume", "Height", "Cd", "DragArea", "Ca",
              "IncludedInStatics", "DegreesOfFreedomInStatics", "CentreOfMass",
              "CentreOfVolume", "InitialAttitude", "Pen"}
_VESSEL_KEYS = {"Name", "VesselType", "InitialPosition", "InitialX", "InitialY", "InitialZ",
                "InitialHeading", "InitialHeel", "InitialTrim", "InitialAttitude",
                "IncludedInStatics", "PrimaryMotion", "SuperimposedMotion", "Pen"}
_CONNECTION_COLUMNS = ("Connection", "ConnectionX", "ConnectionY", "ConnectionZ",
                       "ConnectionAzm", "ConnectionAzimuth", "ConnectionDec",
                       "ConnectionDeclination", "ConnectionGamma", "ReleaseStage",
                       "ConnectionReleaseStage", "ConnectionzRelativeTo")
#: The older per-end keys of a line's connections (read by _Importer.ends).
_END_KEYS = {f"End{e}{k}" for e in "AB" for k in ("Connection", "X", "Y", "Z",
                                                   "ConnectionzRelativeTo",
                                                   "HeightAboveSeabed")}
_SECTION_COLUMNS = ("LineType", "Length", "TargetSegmentLength", "NumberOfSegments")


@dataclass
class ImportResult:
    """The case file text and the items of the model it did not import."""

    text: str
    not_imported: list[str] = field(default_factory=list)


@dataclass
class _Point:
    name: str
    kind: str
    position: tuple[float, float, float]
    origin: str
    extra: list[str] = field(default_factory=list)


def _fmt(value: float) -> str:
    return toml_text(float(value))


def _same(values: list[float]) -> bool:
    return all(abs(v - values[0]) <= _SAME_RTOL * max(abs(values[0]), 1e-300)
               for v in values)


class _Importer:
    def __init__(self, model: dict[str, Any], source: str) -> None:
        self.model = model
        self.source = source
        self.v = Values(source)
        self.dropped: list[str] = []

    # -- helpers ----------------------------------------------------------------------------
    def section(self, name: str) -> Any:
        return self.model.get(name)

    def unread(self, obj: dict[str, Any], keys: set[str], path: str) -> None:
        rest = [k for k in obj if k not in keys and not (isinstance(k, str) and (any(
            k.split(",")[0].strip() == c for c in ("Connection", "LineType"))
            or k in _END_KEYS))]
        for key in rest:
            if isinstance(key, str) and key in ("IncludeFile", "BaseFile"):
                raise self.v.error(f"{path}.{key}", "a self-contained model (included files "
                                   "are not read)", obj[key])
        if rest:
            self.dropped.append(f"{path}: " + ", ".join(shown(k, 60) for k in rest)
                                + " (not imported)")

    def optional(self, obj: dict[str, Any], key: str, path: str, unit: str, default: float,
                 **bounds: Any) -> float:
        value = obj.get(key)
        if value is None:
            return default
        return self.v.number(value, f"{path}.{key}", unit, **bounds)

    def choice(self, obj: dict[str, Any], key: str, path: str, allowed: tuple[Any, ...],
               why: str) -> None:
        """Refuse ``key`` unless it is absent or one of ``allowed``."""
        if key in obj and obj[key] not in allowed:
            shown_allowed = " or ".join(repr(a) if a is not None else "~" for a in allowed)
            raise self.v.error(f"{path}.{key}", f"{shown_allowed} ({why})", obj[key])

    # -- general and environment ----------------------------------------------------------
    def general(self) -> tuple[float, float, float]:
        """Gravity, the duration and the output interval."""
        path = "General"
        general = self.v.mapping(self.section(path) or {}, path, "a mapping")
        self.choice(general, "UnitsSystem", path, ("SI",), "OrcaFlex's SI units m, kN, te, s "
                    "are the only ones imported")
        for key, unit in (("LengthUnits", "m"), ("MassUnits", "te"), ("ForceUnits", "kN"),
                          ("TimeUnits", "s")):
            self.choice(general, key, path, (unit,), "OrcaFlex's SI units")
        g = self.optional(general, "g", path, "m/s^2", ORCAFLEX_DEFAULTS["g"], positive=True)
        duration, interval = DEFAULT_DURATION, DEFAULT_OUTPUT_INTERVAL
        stages = general.get("StageDuration")
        if stages is not None:
            if not isinstance(stages, list) or len(stages) < 2:
                raise self.v.error(f"{path}.StageDuration", "a list of the build-up and the "
                                   "stages' durations [s]", stages)
            lengths = [self.v.number(s, f"{path}.StageDuration[{i}]", "s", positive=True)
                       for i, s in enumerate(stages)]
            duration = sum(lengths[1:])
        if general.get("TargetLogSampleInterval") is not None:
            interval = self.v.number(general["TargetLogSampleInterval"],
                                     f"{path}.TargetLogSampleInterval", "s", positive=True)
        return g, duration, min(interval, duration)

    def environment(self) -> dict[str, float]:
        path = "Environment"
        env = self.v.mapping(self.section(path), path, "an Environment mapping with the "
                             "water depth") if path in self.model else None
        if env is None:
            raise self.v.error(path, "an Environment section (the water depth)", None)
        self.choice(env, "VerticalDensityVariation", path, ("Constant",), "floatmoor's water "
                    "has one density")
        if "WaterDepth" not in env:
            raise self.v.error(f"{path}.WaterDepth", "the water depth [m]", None)
        depth = self.v.number(env["WaterDepth"], f"{path}.WaterDepth", "m", positive=True)
        rho = self.optional(env, "Density", path, "te/m^3", ORCAFLEX_DEFAULTS["Density"],
                            positive=True)
        if self.optional(env, "WaterSurfaceZ", path, "m", 0.0) != 0.0:
            raise self.v.error(f"{path}.WaterSurfaceZ", "0 (floatmoor's water surface is at z = "
                               "0)", env["WaterSurfaceZ"])
        self.choice(env, "SeabedType", path, ("Flat",), "floatmoor's seabed is flat")
        if self.optional(env, "SeabedSlope", path, "deg", 0.0) != 0.0:
            raise self.v.error(f"{path}.SeabedSlope", "0 (floatmoor's seabed is horizontal)",
                               env["SeabedSlope"])
        self.choice(env, "SeabedModel", path, ("Elastic",), "floatmoor's seabed is a linear "
                    "spring-damper")
        stiffness = self.optional(env, "SeabedNormalStiffness", path, "kN/m/m^2",
                                  ORCAFLEX_DEFAULTS["SeabedNormalStiffness"], positive=True)
        damping = self.optional(env, "SeabedDamping", path, "% of critical",
                                ORCAFLEX_DEFAULTS["SeabedDamping"], minimum=0.0)
        if env.get("SeabedShearStiffness") is not None:
            self.dropped.append(f"{path}.SeabedShearStiffness = "
                                f"{plain(env['SeabedShearStiffness'], 40)} kN/m/m^2: floatmoor's "
                                f"friction is smoothed by a slip speed ({SLIP_SPEED} m/s) "
                                "instead of a shear spring [physics, approximate]")
        sea = [k for k in env if isinstance(k, str) and k.startswith(("Wave", "Current",
                                                                      "RefCurrent", "Wind"))]
        if sea:
            self.dropped.append(f"{path}: the sea state ({', '.join(shown(k, 40) for k in sea[:6])}"
                                f"{', ...' if len(sea) > 6 else ''}) is a load case, not the "
                                "mooring: not imported (add [motion] or a [floater] with "
                                "[waves] yourself)")
        return {"depth": depth, "rho": rho * TE, "stiffness": stiffness * KN,
                "damping_ratio": damping / 100.0,
                "stiffness_raw": stiffness, "damping_raw": damping}

    # -- line types -------------------------------------------------------------------------
    def line_types(self) -> dict[str, dict[str, Any]]:
        items = self.v.items(self.section("LineTypes"), "LineTypes", "line types") \
            if "LineTypes" in self.model else []
        out: dict[str, dict[str, Any]] = {}
        for i, item in enumerate(items):
            name = self.v.name(item.get("Name"), f"LineTypes[{i}].Name")
            path = f'LineTypes["{name}"]'
            if name in out:
                raise self.v.error(path, "a unique line type name", "a second one")
            out[name] = self.line_type(item, path)
        return out

    def pair(self, value: Any, path: str, unit: str) -> tuple[float, float]:
        """OrcaFlex's [normal, normal y (~: the same), axial] (or one number for all)."""
        if not isinstance(value, list):
            x = self.v.number(value, path, unit, minimum=0.0)
            return x, x
        if len(value) != 3:
            raise self.v.error(path, f"a number or [normal x, normal y (~), axial] [{unit}]",
                               value)
        x = self.v.number(value[0], f"{path}[0]", unit, minimum=0.0)
        if value[1] is not None and self.v.number(value[1], f"{path}[1]", unit) != x:
            raise self.v.error(f"{path}[1]", "~ or the normal x value (floatmoor's lines are "
                               "axisymmetric)", value[1])
        return x, self.v.number(value[2], f"{path}[2]", unit, minimum=0.0)

    def line_type(self, item: dict[str, Any], path: str) -> dict[str, Any]:
        self.choice(item, "Category", path, ("General",), "the General category, whose OD, "
                    "mass and EA are given; a Homogeneous pipe's are derived and not imported")
        for key in ("OD", "MassPerUnitLength", "EA", "Cd", "Ca"):
            if item.get(key) is None:
                raise self.v.error(f"{path}.{key}", "a value", None)
        od = self.v.number(item["OD"], f"{path}.OD", "m", positive=True)
        if self.optional(item, "ID", path, "m", 0.0, minimum=0.0) != 0.0:
            raise self.v.error(f"{path}.ID", "0 (a line without a bore: contents are not "
                               "modelled)", item["ID"])
        mass = self.v.number(item["MassPerUnitLength"], f"{path}.MassPerUnitLength", "te/m",
                             positive=True)
        ea = item["EA"]
        if isinstance(ea, list):
            raise self.v.error(f"{path}.EA", "one number [kN] (nonlinear or tabulated "
                               "stiffness is not imported)", ea)
        ea = self.v.number(ea, f"{path}.EA", "kN (nonlinear or tabulated stiffness is not "
                           "imported)", positive=True)
        ei = item.get("EI")
        eis = ei if isinstance(ei, list) else [ei]
        if any(e is not None and self.v.number(e, f"{path}.EI", "kN m^2", minimum=0.0) != 0.0
               for e in eis):
            self.dropped.append(f"{path}.EI = {plain(ei, 60)} kN m^2: floatmoor's lines have "
                                "no bending stiffness [physics]")
        cd_n, cd_a = self.pair(item["Cd"], f"{path}.Cd", "-")
        ca_n, ca_a = self.pair(item["Ca"], f"{path}.Ca", "-")
        d_n = self.optional(item, "NormalDragLiftDiameter", path, "m", od, positive=True)
        d_a = self.optional(item, "AxialDragLiftDiameter", path, "m", od, positive=True)
        contact = self.optional(item, "OuterContactDiameter", path, "m", od, positive=True)
        if contact != od:
            raise self.v.error(f"{path}.OuterContactDiameter", "~ or OD (floatmoor's seabed "
                               "contact width is the line's diameter, OD)", item[
                                   "OuterContactDiameter"])
        lateral = self.optional(item, "SeabedLateralFrictionCoefficient", path, "-",
                                ORCAFLEX_DEFAULTS["SeabedLateralFrictionCoefficient"],
                                minimum=0.0)
        axial = self.optional(item, "SeabedAxialFrictionCoefficient", path, "-", lateral,
                              minimum=0.0)
        if axial != lateral:
            raise self.v.error(f"{path}.SeabedAxialFrictionCoefficient", f"~ or {lateral:g}, "
                               "the lateral coefficient (floatmoor's friction is isotropic)",
                               item["SeabedAxialFrictionCoefficient"])
        self.choice(item, "RayleighDampingCoefficients", path, ("(no damping)",),
                    "Rayleigh damping is not imported")
        self.unread(item, _LINE_TYPE_KEYS, path)
        area = math.pi * od * od / 4.0
        return {"path": path, "friction": lateral, "values": [
            ("mass_per_length", mass * TE, "kg/m, MassPerUnitLength x 1000"),
            ("axial_stiffness", ea * KN, "N, EA x 1000"),
            ("diameter", od, "m, OD (buoyancy, added mass and seabed contact refer to it)"),
            ("material_density", mass * TE / area, "kg/m^3, mass over pi OD^2/4: floatmoor's "
             "volume is OrcaFlex's"),
            ("normal_drag_coefficient", cd_n * d_n / od, f"Cd normal {cd_n:g} on the normal "
             f"drag diameter {d_n:g} m, referred to OD"),
            ("tangential_drag_coefficient", math.pi * cd_a * d_a / od, f"pi x Cd axial "
             f"{cd_a:g} on the axial drag diameter {d_a:g} m (OrcaFlex's axial drag acts on "
             "the circumference), referred to OD"),
            ("added_mass_coefficient", ca_n, "Ca normal, on pi OD^2/4"),
            ("tangential_added_mass_coefficient", ca_a, "Ca axial"),
        ]}

    # -- vessels and buoys ----------------------------------------------------------------
    def position(self, obj: dict[str, Any], path: str) -> tuple[float, float, float]:
        if "InitialPosition" in obj:
            x, y, z = self.v.vector(obj["InitialPosition"], f"{path}.InitialPosition", "m")
            return x, y, z
        keys = ("InitialX", "InitialY", "InitialZ")
        if not all(k in obj for k in keys):
            raise self.v.error(f"{path}.InitialPosition", "the initial position [x, y, z] [m]",
                               None)
        x, y, z = (self.v.number(obj[k], f"{path}.{k}", "m") for k in keys)
        return x, y, z

    def vessels(self) -> dict[str, tuple[tuple[float, float, float], float]]:
        types = set()
        if "VesselTypes" in self.model:
            for i, vt in enumerate(self.v.items(self.section("VesselTypes"), "VesselTypes",
                                                "vessel types")):
                types.add(self.v.name(vt.get("Name"), f"VesselTypes[{i}].Name"))
            if types:
                self.dropped.append(f"VesselTypes ({len(types)}): the vessels' hydrodynamics "
                                    "are not imported; the fairleads stay at their vessel's "
                                    "initial position (a forced case without [motion])")
        out: dict[str, tuple[tuple[float, float, float], float]] = {}
        items = self.v.items(self.section("Vessels"), "Vessels", "vessels") \
            if "Vessels" in self.model else []
        for i, item in enumerate(items):
            name = self.v.name(item.get("Name"), f"Vessels[{i}].Name")
            path = f'Vessels["{name}"]'
            if types and item.get("VesselType") not in types:
                raise self.v.error(f"{path}.VesselType", "the name of a VesselTypes entry",
                                   item.get("VesselType"))
            heading = self.optional(item, "InitialHeading", path, "deg", 0.0)
            heel = self.optional(item, "InitialHeel", path, "deg", 0.0)
            trim = self.optional(item, "InitialTrim", path, "deg", 0.0)
            if "InitialAttitude" in item:
                heel, trim, heading = self.v.vector(item["InitialAttitude"],
                                                    f"{path}.InitialAttitude", "deg")
            if heel != 0.0 or trim != 0.0:
                raise self.v.error(f"{path}.InitialAttitude", "an upright vessel (heel and trim "
                                   "0; only the heading is imported)", f"heel {heel:g}, "
                                   f"trim {trim:g}")
            self.choice(item, "IncludedInStatics", path, ("None", None), "floatmoor holds the "
                        "vessel at its initial position; OrcaFlex's statics would move it")
            for key in ("PrimaryMotion", "SuperimposedMotion"):
                if item.get(key) not in (None, "None"):
                    self.dropped.append(f"{path}.{key} = {plain(item[key], 60)}: the vessel "
                                        "is held still (no [motion]) [physics]")
            self.unread(item, _VESSEL_KEYS, path)
            out[name] = (self.position(item, path), math.radians(heading))
        return out

    def buoys(self) -> dict[str, _Point]:
        out: dict[str, _Point] = {}
        for section in ("3DBuoys", "6DBuoys"):
            if section not in self.model:
                continue
            for i, item in enumerate(self.v.items(self.section(section), section, "buoys")):
                name = self.v.name(item.get("Name"), f"{section}[{i}].Name")
                path = f'{section}["{name}"]'
                if name in out:
                    raise self.v.error(path, "a unique buoy name", "a second one")
                out[name] = self.buoy(item, path, section == "6DBuoys")
        return out

    def buoy(self, item: dict[str, Any], path: str, six_d: bool) -> _Point:
        self.choice(item, "Connection", path, ("Free", None), "a free buoy (floatmoor's free "
                    "point); a fixed or attached buoy is not imported")
        self.choice(item, "IncludedInStatics", path, (True, None, "Yes"), "a buoy in "
                    "equilibrium in the statics, as floatmoor's free points")
        if six_d:
            self.choice(item, "BuoyType", path, ("Lumped buoy",), "a lumped buoy whose lines "
                        "meet at its origin is a point; spar buoys and towed fish are not")
            self.choice(item, "DegreesOfFreedomInStatics", path, ("All", "X,Y,Z", None),
                        "a buoy free in the statics")
            for key in ("CentreOfMass", "CentreOfVolume"):
                if key in item and any(c != 0.0 for c in self.v.vector(item[key],
                                                                       f"{path}.{key}", "m")):
                    raise self.v.error(f"{path}.{key}", "[0, 0, 0] (a point: mass and volume at "
                                       "the buoy's origin, where its lines meet)", item[key])
            cas = item.get("Ca") if isinstance(item.get("Ca"), list) else [item.get("Ca")]
            if any(c is not None and self.v.number(c, f"{path}.Ca", "-") != 0.0 for c in cas):
                raise self.v.error(f"{path}.Ca", "0 or ~ (a lumped buoy's added mass refers to "
                                   "its hydrodynamic mass, not its volume: not imported; a 3D "
                                   "buoy's Ca is)", item["Ca"])
        mass = self.optional(item, "Mass", path, "te", 0.0, minimum=0.0) * TE
        volume = self.optional(item, "Volume", path, "m^3", 0.0, minimum=0.0)

        def isotropic(key: str, default: float) -> tuple[float, float, float]:
            value = item.get(key)
            if value is None:
                return (default,) * 3  # type: ignore[return-value]
            if not isinstance(value, list):
                x = self.v.number(value, f"{path}.{key}", "-", minimum=0.0)
                return x, x, x
            x, y, z = self.v.vector(value, f"{path}.{key}", "-")
            return x, y, z

        cd = isotropic("Cd", 0.0 if "DragArea" not in item else 1.0)
        area = isotropic("DragArea", 0.0)
        drag = [c * a for c, a in zip(cd, area)]
        if not _same(drag) or any(d < 0.0 for d in drag):
            raise self.v.error(f"{path}.DragArea", "the same Cd x DragArea in x, y and z "
                               "(floatmoor's point drag is isotropic)",
                               ", ".join(f"{d:g}" for d in drag) + " m^2")
        ca = isotropic("Ca", 0.0)
        if not _same(list(ca)) or ca[0] < 0.0:
            raise self.v.error(f"{path}.Ca", "the same added-mass coefficient in x, y and z "
                               "(floatmoor's point is isotropic)", item.get("Ca"))
        position = self.position(item, path)
        if item.get("Height") is not None:
            height = self.v.number(item["Height"], f"{path}.Height", "m", minimum=0.0)
            if position[2] + height / 2.0 > 0.0:
                raise self.v.error(f"{path}.Height", "a buoy below the surface (floatmoor's "
                                   "points do not pierce it)", f"{height:g} m at z = "
                                   f"{position[2]:g} m")
        self.unread(item, _BUOY_KEYS, path)
        return _Point(path.split('"')[1], "free", position, path, [
            f"mass = {_fmt(mass)}  # kg, Mass x 1000",
            f"volume = {_fmt(volume)}  # m^3, Volume",
            f"drag_area = {_fmt(drag[0])}  # m^2, Cd x DragArea",
            f"added_mass_coefficient = {_fmt(ca[0])}  # Ca, on Volume"])

    # -- lines ------------------------------------------------------------------------------
    def ends(self, item: dict[str, Any], path: str) -> list[dict[str, Any]]:
        table = self.v.table(item, path, "Connection", _CONNECTION_COLUMNS,
                             ("Connection", "ConnectionX", "ConnectionY", "ConnectionZ"),
                             optional=True)
        if table is not None:
            key, rows, unknown = table
            if unknown:
                self.dropped.append(f"{path}.{key}: columns {', '.join(unknown)}, ~ on every "
                                    "row (not read)")
            if len(rows) != 2:
                raise self.v.error(f"{path}.{key}", "two rows (End A, End B)",
                                   f"{len(rows)} rows")
            return [dict(row, _path=f"{path}.Connection[End {'AB'[i]}]")
                    for i, row in enumerate(rows)]
        out = []
        for end in "AB":
            row = {"Connection": item.get(f"End{end}Connection")}
            for axis in "XYZ":
                row[f"Connection{axis}"] = item.get(f"End{end}{axis}")
            if row["Connection"] is None:
                raise self.v.error(f"{path}.Connection", "the end connections (a table "
                                   "'Connection, ConnectionX, ConnectionY, ConnectionZ, ...' "
                                   f"or End{end}Connection, End{end}X, ...)", None)
            if item.get(f"End{end}ConnectionzRelativeTo") is not None:
                row["ConnectionzRelativeTo"] = item[f"End{end}ConnectionzRelativeTo"]
            if item.get(f"End{end}HeightAboveSeabed") is not None:
                raise self.v.error(f"{path}.End{end}HeightAboveSeabed", "~ (the end's z "
                                   "gives its height)", item[f"End{end}HeightAboveSeabed"])
            out.append(dict(row, _path=f"{path}.End{end}"))
        return out

    def end_point(self, row: dict[str, Any], line: str, end: str, depth: float,
                  vessels: dict[str, Any], buoys: dict[str, _Point]) -> _Point:
        path = row["_path"]
        conn = row["Connection"]
        if conn is None or isinstance(conn, (bool, list, dict)):
            raise self.v.error(f"{path}.Connection", "Anchored, Fixed, a vessel or a buoy",
                               conn)
        conn = str(conn)
        xyz = [self.v.number(row.get(f"Connection{a}"), f"{path}.Connection{a}", "m")
               for a in "XYZ"]
        for key in ("ReleaseStage", "ConnectionReleaseStage"):
            if row.get(key) is not None:
                raise self.v.error(f"{path}.{key}", "~ (a line end is never released)",
                                   row[key])
        if row.get("ConnectionzRelativeTo") is not None:
            raise self.v.error(f"{path}.ConnectionzRelativeTo", "~ (z in the connected "
                               "object's frame)", row["ConnectionzRelativeTo"])
        name = f"{line}_{end}"
        if conn == "Anchored":
            # OrcaFlex: an anchored end's z is its height above the seabed
            return _Point(name, "fixed", (xyz[0], xyz[1], -depth + xyz[2]),
                          f"{path}: Anchored, z {xyz[2]:g} m above the seabed")
        if conn == "Fixed":
            return _Point(name, "fixed", (xyz[0], xyz[1], xyz[2]), f"{path}: Fixed")
        if conn in vessels:
            (x0, y0, z0), psi = vessels[conn]
            c, s = math.cos(psi), math.sin(psi)
            pos = (x0 + c * xyz[0] - s * xyz[1], y0 + s * xyz[0] + c * xyz[1], z0 + xyz[2])
            return _Point(name, "body", pos, f"{path}: vessel {conn} at rest, offset "
                          f"({xyz[0]:g}, {xyz[1]:g}, {xyz[2]:g}) m in its axes")
        if conn in buoys:
            if any(xyz):
                raise self.v.error(f"{path}.ConnectionX", "[0, 0, 0] at a buoy (lines meet at "
                                   "its origin, floatmoor's point)", f"({xyz[0]:g}, "
                                   f"{xyz[1]:g}, {xyz[2]:g})")
            return buoys[conn]
        raise self.v.error(f"{path}.Connection", "Anchored, Fixed, the name of a vessel, or of "
                           "a free 3D or lumped 6D buoy (floatmoor does not model other "
                           "connections)", conn)

    def sections(self, item: dict[str, Any], path: str,
                 types: dict[str, dict[str, Any]]) -> list[tuple[str, float, int | None]]:
        key, rows, unknown = self.v.table(  # type: ignore[misc]
            item, path, "LineType", _SECTION_COLUMNS, ("LineType", "Length"))
        if unknown:
            self.dropped.append(f"{path}.{key}: columns {', '.join(unknown)}, ~ on every row "
                                "(not read)")
        out = []
        for i, row in enumerate(rows):
            where = f"{path}.{key}[{i}]"
            lt = row["LineType"]
            if not isinstance(lt, str) or lt not in types:
                raise self.v.error(f"{where}.LineType", "the name of a LineTypes entry ("
                                   + (", ".join(sorted(types))[:200] or "none defined") + ")",
                                   lt)
            length = self.v.number(row["Length"], f"{where}.Length", "m", positive=True)
            segments = None
            if row.get("NumberOfSegments") is not None:
                n = self.v.number(row["NumberOfSegments"], f"{where}.NumberOfSegments", "-",
                                  positive=True)
                if n != int(n) or n > 10_000:
                    raise self.v.error(f"{where}.NumberOfSegments", "an integer 1 to 10000",
                                       row["NumberOfSegments"])
                segments = int(n)
            elif row.get("TargetSegmentLength") is not None:
                target = self.v.number(row["TargetSegmentLength"],
                                       f"{where}.TargetSegmentLength", "m", positive=True)
                segments = max(1, math.ceil(length / target - _SAME_RTOL))
                if segments > 10_000:
                    raise self.v.error(f"{where}.TargetSegmentLength", "at most 10000 "
                                       "segments in a section", f"{segments}")
            out.append((lt, length, segments))
        return out

    # -- the case ---------------------------------------------------------------------------
    def run(self) -> ImportResult:
        for key in self.model:
            if key not in _SECTIONS_READ:
                if key in ("BaseFile", "IncludeFile"):
                    raise self.v.error(str(key), "a self-contained model (included files are "
                                       "not read)", self.model[key])
                value = self.model[key]
                count = f" ({len(value)} items)" if isinstance(value, (list, dict)) else ""
                self.dropped.append(f"{shown(key, 60)}{count}: not imported")
        g, duration, interval = self.general()
        env = self.environment()
        types = self.line_types()
        vessels = self.vessels()
        buoys = self.buoys()
        if "Lines" not in self.model:
            raise self.v.error("Lines", "at least one line", None)
        lines = self.v.items(self.section("Lines"), "Lines", "lines")
        if not lines:
            raise self.v.error("Lines", "at least one line", "none")
        points: dict[str, _Point] = {}
        built = []
        used_types: list[str] = []
        names: set[str] = set()
        for i, item in enumerate(lines):
            name = self.v.name(item.get("Name"), f"Lines[{i}].Name")
            path = f'Lines["{name}"]'
            if name in names:
                raise self.v.error(path, "a unique line name", "a second one")
            names.add(name)
            ends = [self.end_point(row, name, "AB"[j], env["depth"], vessels, buoys)
                    for j, row in enumerate(self.ends(item, path))]
            for p in ends:
                if p.name in points and points[p.name] is not p:
                    raise self.v.error(path, "line and buoy names that do not collide "
                                       f"(floatmoor names this line's ends {name}_A, "
                                       f"{name}_B)", p.name)
                points[p.name] = p
            sections = self.sections(item, path, types)
            reverse = ends[0].kind == "body" and ends[1].kind == "fixed"
            if reverse:  # floatmoor's lines run from anchor to fairlead: the same line reversed
                ends, sections = ends[::-1], sections[::-1]
            used_types += [s[0] for s in sections if s[0] not in used_types]
            policy = item.get("StaticsSeabedFrictionPolicy")
            self.choice(item, "StaticsSeabedFrictionPolicy", path, ("None", "Full", None),
                        "no friction or full friction in the statics; floatmoor has no "
                        "as-laid reference")
            self.choice(item, "IncludedInStatics", path, (True, "Yes", None), "a line in the "
                        "statics")
            self.unread(item, _LINE_KEYS, path)
            built.append((name, path, ends, sections, policy == "Full", reverse))
        frictions = [types[t]["friction"] for t in used_types]
        if not _same(frictions):
            raise self.v.error(f"{types[used_types[0]]['path']}.SeabedLateralFrictionCoefficient",
                               "one friction coefficient for every line type used (floatmoor's "
                               "seabed has one)", ", ".join(f"{t}: {types[t]['friction']:g}"
                                                            for t in used_types))
        for b in buoys:
            if b not in points:
                self.dropped.append(f"{buoys[b].origin}: on no line, not imported")
        for t in types:
            if t not in used_types:
                self.dropped.append(f'LineTypes["{t}"]: used by no line, not imported')
        return self.write(g, duration, interval, env, types, used_types, points, built,
                          frictions[0])

    def write(self, g: float, duration: float, interval: float, env: dict[str, float],
              types: dict[str, dict[str, Any]], used_types: list[str],
              points: dict[str, _Point], built: list[Any], friction: float) -> ImportResult:
        out: list[str] = []
        w = out.append
        w(f"# Imported from the OrcaFlex text data file {self.source}")
        w(f"# by floatmoor import orcaflex (floatmoor {__version__}); comments give each "
          "value's origin.")
        w("# What was not imported is listed at the end of this file.")
        w("")
        w(f"title = {toml_text(literal_title('OrcaFlex model ' + self.source))}")
        w(f"description = {toml_text('Imported from the OrcaFlex text data file ' + self.source)}")
        w("")
        w("[environment]")
        w(f"water_density = {_fmt(env['rho'])}  # kg/m^3, Environment.Density x 1000")
        w(f"water_depth = {_fmt(env['depth'])}  # m, Environment.WaterDepth")
        w(f"gravity = {_fmt(g)}  # m/s^2, General.g (OrcaFlex's default 9.80665 if absent)")
        w("")
        w("[seabed]")
        w(f"stiffness = {_fmt(env['stiffness'])}  # Pa/m, SeabedNormalStiffness "
          f"{env['stiffness_raw']:g} kN/m/m^2 x 1000 (per unit contact area, width OD)")
        w(f"damping_ratio = {_fmt(env['damping_ratio'])}  # SeabedDamping "
          f"{env['damping_raw']:g} % of critical")
        w(f"friction_coefficient = {_fmt(friction)}  # the line types' "
          "SeabedLateralFrictionCoefficient")
        w(f"slip_speed = {_fmt(SLIP_SPEED)}  # m/s, floatmoor's (OrcaFlex has a shear "
          "stiffness instead)")
        w("")
        for t in used_types:
            w(f"[line_types.{toml_text(t)}]  # {types[t]['path']}")
            for key, value, why in types[t]["values"]:
                w(f"{key} = {_fmt(value)}  # {why}")
            w("")
        for p in points.values():
            w("[[points]]")
            w(f"name = {toml_text(p.name)}  # {p.origin}")
            w(f"kind = \"{p.kind}\"")
            w(f"position = [{', '.join(_fmt(c) for c in p.position)}]  # m")
            out.extend(p.extra)
            w("")
        for name, path, ends, sections, friction_in_statics, reverse in built:
            w("[[lines]]")
            w(f"name = {toml_text(name)}  # {path}" + (", from End B (the anchor) to End A, "
                                                       "sections reversed" if reverse else ""))
            w(f"start = {toml_text(ends[0].name)}  # End {'B' if reverse else 'A'}")
            w(f"end = {toml_text(ends[1].name)}  # End {'A' if reverse else 'B'}")
            w("model = \"dynamic\"  # OrcaFlex's finite-element line is dynamic")
            w("sections = [")
            for lt, length, segments in sections:
                dg = ""
                if segments is not None:
                    order = min(DEFAULT_DG_ORDER, segments)
                    dg = (f", dynamic = {{ elements = {math.ceil(segments / order)}, "
                          f"order = {order} }}")
                w(f"  {{ type = {toml_text(lt)}, length = {_fmt(length)}{dg} }},"
                  + (f"  # {segments} segments" if segments is not None else ""))
            w("]")
            w("")
            w("[lines.quasi_static]")
            w(f"seabed_friction = {toml_text(friction_in_statics)}  # "
              "StaticsSeabedFrictionPolicy " + ("Full" if friction_in_statics else
                                                "None (also when absent)"))
            w("")
        w("[simulation]")
        w(f"duration = {_fmt(duration)}  # s, General.StageDuration after the build-up "
          f"(default {DEFAULT_DURATION:g} s)")
        w(f"output_interval = {_fmt(interval)}  # s, General.TargetLogSampleInterval "
          f"(default {DEFAULT_OUTPUT_INTERVAL:g} s)")
        w("")
        self.dropped.append(f"seabed slip speed {SLIP_SPEED} m/s: floatmoor's choice, "
                            "OrcaFlex has none")
        w("# -- not imported " + "-" * 74)
        out.extend(f"# - {shown(item)}" for item in self.dropped)
        return ImportResult(text="\n".join(out) + "\n", not_imported=list(self.dropped))


def import_model(model: dict[str, Any], source: str) -> ImportResult:
    """The case file text for an OrcaFlex ``model`` (the data of
    :func:`floatmoor.io.orcaflex.reader.read_model`), checked by the case loader, and what was
    not imported.

    Parameters
    ----------
    model
        The model's data (:func:`floatmoor.io.orcaflex.reader.read_model`).
    source
        The model file's path, for messages and the case's comments.

    Returns
    -------
    ImportResult
        The case file text and what was not imported.

    Raises
    ------
    CaseError
        Input floatmoor cannot represent (naming the file and the key path), or a case the
        loader refuses (naming the imported file).
    """
    from floatmoor.case.limits import parse_toml
    from floatmoor.case.load import parse_case

    result = _Importer(model, source).run()
    label = f"{source} (imported)"
    try:
        parse_case(parse_toml(result.text, label), source=label, text=result.text)
    except CaseError as err:
        raise CaseError(source, "", "a model whose imported case floatmoor accepts",
                        f"the case refused: {err}") from None
    return result
