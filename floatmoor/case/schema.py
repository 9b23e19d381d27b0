"""The validated contents of a case file: frozen dataclasses, SI units, angles in radians.

A :class:`Case` is built only by :func:`floatmoor.case.load.load_case`, which checks every
value; the objects here can therefore be trusted by the models.

Size: one frozen dataclass per case-file table (three dozen of them), each key declared
once on its field with its type, unit, bounds, default and description
(:mod:`floatmoor.case.setting`); together they are the one schema :mod:`floatmoor.case.load`
fills and the case-file reference describes.
"""

from __future__ import annotations

from dataclasses import InitVar, dataclass, field
from functools import cached_property
from typing import Any

import numpy as np
from numpy.typing import NDArray

from floatmoor.case.drag import DragSettings
from floatmoor.case.sea import WaveCase
from floatmoor.case.setting import Setting, setting
from floatmoor.case.wind import WindSettings

__all__ = [
    "Environment", "Seabed", "LineType", "QuasiStaticSettings", "Line", "CircularMotion",
    "HarmonicMotion", "TableMotion", "Motion", "Simulation", "Case", "LINE_MODELS",
    "AVAILABLE_LINE_MODELS", "CIRCULAR_SENSES", "DynamicSettings", "INTERNAL_DAMPING_METHODS",
    "SEABED_CONTACT_METHODS", "TIME_INTEGRATIONS", "FRICTION_MODELS",
    "QuasiDynamicSettings", "DEFAULT_QUASI_DYNAMIC", "CylinderGeometry", "Column", "Member",
    "SemisubmersibleGeometry", "FloaterGeometry", "Floater", "HydroSettings", "GEOMETRY_KINDS",
    "MeshGeometry", "MESH_FORMATS", "MESH_LENGTH_UNITS", "MESH_SYMMETRY_PLANES",
    "RADIATION_METHODS", "HYDRO_CHECKS", "HYDRO_SOURCES", "POINT_KINDS", "Point", "Section",
    "BODY_DOFS", "BodyHarmonicMotion", "SectionKeys", "OneSectionKeys", "TopLevelKeys",
    "BemGridKeys",
    "MOTION_KINDS", "MOTION_KIND", "GEOMETRY_KIND", "HarmonicTranslation", "HarmonicRotation",
    "BodyTableMotion", "BodyMotion",
]

#: Range of ``environment.gravity`` [m/s^2]. On Earth g is 9.78 to 9.83 m/s^2 (equator to
#: poles; standard 9.80665); 1 to 30 admits the Moon (1.6) and a deliberately altered tank or
#: model gravity. Times scale with sqrt(L / g): a dynamic line settles for 11 sqrt(L / g)
#: (floatmoor.mooring.dg.line), so g = 1e-9 asked a 33 m chain for 2e6 s of relaxation.
MIN_GRAVITY, MAX_GRAVITY = 1.0, 30.0

#: Every line model name a case file may give (``lines[].model``).
LINE_MODELS = ("quasi-static", "quasi-dynamic", "dynamic")
#: The models this version implements.
AVAILABLE_LINE_MODELS = ("quasi-static", "quasi-dynamic", "dynamic")
#: Treatments of the seabed's normal spring-damper in the dynamic model.
SEABED_CONTACT_METHODS = ("implicit", "explicit")
#: Seabed friction laws of the dynamic model (docs/theory/cable.md#seabed-friction): Coulomb
#: regularised by the slip speed, or a stick spring to an anchor per node (return mapping).
FRICTION_MODELS = ("coulomb", "stick_spring")
#: Treatments of the dynamic model's Kelvin-Voigt internal damping.
INTERNAL_DAMPING_METHODS = ("implicit", "explicit")
#: Time integration of a dynamic line: explicit SSP-RK3 at the axial wave's stability limit,
#: the implicit generalised-alpha method at a step bounded by accuracy (mooring/dg/implicit.py),
#: or "auto": implicit while its accuracy-bound steps cost less than the explicit steps they
#: replace, explicit from then on (mooring/dg/resolution.py).
TIME_INTEGRATIONS = ("auto", "explicit", "implicit")
#: Kinds of points (``points[].kind``): fixed in space (anchors), free (joints, clump weights,
#: buoys: in equilibrium of their lines and loads), or carried by the body (fairleads: moved by
#: the prescribed motion or the floater).
POINT_KINDS = ("fixed", "free", "body")
#: Rotation senses of circular motion, defined by where the end moves at the top of the circle.
CIRCULAR_SENSES = ("away-from-anchor-at-top", "toward-anchor-at-top")


@dataclass(frozen=True)
class Environment:
    """Water and gravity. Still water at z = 0, flat seabed at z = -water_depth."""

    water_density: float = setting(  #: [kg/m^3]
        "number", scale="water_density",
        unit="kg/m^3", gt=0.0, doc="Density of the water, for buoyancy, drag, added "
        "mass and the hydrodynamic database.")
    water_depth: float = setting(  #: [m]
        "number", scale="length",
        unit="m", gt=0.0, doc="Depth of the flat seabed below the still water line.")
    gravity: float = setting(  #: [m/s^2]
        "number", scale="same", unit="m/s^2", ge=MIN_GRAVITY, le=MAX_GRAVITY,
        doc="Acceleration of gravity.")
    current_velocity: tuple[float, float, float] = setting(  #: steady, uniform [m/s]
        "vector", scale="velocity",
        size=3, unit="m/s", default=(0.0, 0.0, 0.0), field_default=(0.0, 0.0, 0.0),
        doc="Steady, uniform current [x, y, z], in the drag of the lines and of a floater's "
            "Morison members.")

    @property
    def seabed_z(self) -> float:
        """Elevation of the seabed [m]."""
        return -self.water_depth


@dataclass(frozen=True)
class Seabed:
    """Seabed contact (gpc paper eq. 7): normal spring-damper and friction, smoothed Coulomb
    or a stick spring (docs/theory/cable.md#seabed-friction)."""

    stiffness: float = setting(  #: normal stiffness per unit contact area [Pa/m]
        "number", scale="seabed_stiffness", unit="Pa/m", gt=0.0,
        doc="Normal stiffness of the seabed per unit contact area.")
    damping_ratio: float = setting(  #: of the normal contact [-]
        "number", scale="same",
        unit="-", ge=0.0, doc="Damping ratio of the normal contact spring-damper.")
    friction_coefficient: float = setting(  #: Coulomb, also the quasi-static catenary's C_B [-]
        "number", scale="same",
        unit="-", ge=0.0, doc="Coulomb friction coefficient along the seabed; also "
        "the quasi-static catenary's friction on its resting length.")
    slip_speed: float = setting(  #: speed at which full friction is reached [m/s]
        "number", scale="velocity",
        unit="m/s", gt=0.0, doc="Sliding speed at which the smoothed friction "
        "reaches its full value (the \"coulomb\" friction model).")
    #: dynamic lines' friction law: "coulomb" (regularised by slip_speed) or "stick_spring"
    #: (an anchor per node, return mapping; docs/theory/cable.md#seabed-friction)
    friction_model: str = setting(
        "string", scale="same",
        choices=FRICTION_MODELS, default="coulomb", field_default="coulomb",
        doc="Seabed friction law of dynamic lines: \"coulomb\", the Coulomb force "
            "regularised by the slip speed, or \"stick_spring\", a spring of the seabed's "
            "normal stiffness to a friction anchor per node, capped at the friction "
            "coefficient times the normal contact force, the anchor moved by return mapping "
            "at committed steps (theory/cable.md).")


@dataclass(frozen=True)
class LineType:
    """Properties of a line material (docs/theory/cable.md); ``[line_types.NAME]``."""

    name: str
    mass_per_length: float = setting(  #: [kg/m]
        "number", scale="mass_per_length",
        unit="kg/m", gt=0.0, doc="Dry mass per unstretched length.")
    axial_stiffness: float = setting(
        "number", scale="force",
        unit="N", gt=0.0, doc="Axial stiffness EA.")
    diameter: float = setting(
        "number", scale="diameter",
        unit="m", gt=0.0, doc="Diameter the drag and added-mass coefficients refer to "
        "(for chain, usually the volume-equivalent diameter).")
    material_density: float = setting(
        "number", scale="same",
        unit="kg/m^3", gt=0.0, doc="Density of the line's material; with the mass it "
        "gives the displaced volume, hence the submerged weight.")
    normal_drag_coefficient: float = setting(  #: C_dn
        "number", scale="drag_coefficient",
        unit="-", ge=0.0, doc="Morison drag coefficient normal to the line, on its "
        "diameter.")
    tangential_drag_coefficient: float = setting(  #: C_dt
        "number", scale="drag_coefficient",
        unit="-", ge=0.0, doc="Drag coefficient along the line.")
    added_mass_coefficient: float = setting(  #: C_a, on the material area m/rho_c
        "number", scale="added_mass_coefficient",
        unit="-", ge=0.0, doc="Added-mass coefficient normal to the line, on the "
        "material area m / rho_material.")
    tangential_added_mass_coefficient: float = setting(
        "number", scale="added_mass_coefficient",
        unit="-", ge=0.0, default=0.0, doc="Added-mass coefficient along the line.")
    internal_damping_ratio: float = setting(
        "number", scale="same",
        unit="-", ge=0.0, default=0.0, doc="Kelvin-Voigt axial damping, as the "
        "damping ratio of the line's first longitudinal mode (dynamic model).")
    #: minimum breaking load [N], or None when not given
    minimum_breaking_load: float | None = setting(
        "number", scale="force",
        unit="N", gt=0.0, default=None, field_default=None, doc="Minimum breaking "
        "load (MBL), for the safety factors of the run summary; without it `floatmoor check` "
        "warns on large strains.")

    def weight_in_water(self, environment: Environment) -> float:
        """Submerged weight per unstretched length, m g (1 - rho_w / rho_c) [N/m]."""
        return (self.mass_per_length * environment.gravity
                * (1.0 - environment.water_density / self.material_density))

    @property
    def axial_wave_speed(self) -> float:
        """Longitudinal (snap) wave celerity sqrt(EA / m) [m/s]."""
        return float(np.sqrt(self.axial_stiffness / self.mass_per_length))


#: Newton tolerance of the quasi-static catenary, relative to the line length [-]. The
#: equations then hold to ~1e-12 L, far below the 1e-9 L the verification tests demand.
DEFAULT_CATENARY_TOLERANCE = 1e-12
DEFAULT_CATENARY_MAX_ITERATIONS = 100
#: Default Simpson stations of the quasi-dynamic model over the suspended length: the 31
#: integration points of the quasi-dynamic paper's verification study (its Table 3).
DEFAULT_QD_INTEGRATION_POINTS = 31
MAX_QD_INTEGRATION_POINTS = 10_001


@dataclass(frozen=True)
class QuasiStaticSettings:
    """Numerics of the quasi-static catenary (``[lines.quasi_static]``)."""

    tolerance: float = setting(  #: Newton stops when the end-point mismatch is below it * L [-]
        "number", scale="same", unit="-", gt=0.0, le=1e-6, default=DEFAULT_CATENARY_TOLERANCE,
        doc="Newton iterations stop when the end-point mismatch is below this fraction of the "
            "line length.")
    max_iterations: int = setting(
        "integer", scale="same", ge=1, le=10_000, default=DEFAULT_CATENARY_MAX_ITERATIONS,
        doc="Most Newton iterations of one catenary solve.")
    seabed_friction: bool = setting(  #: apply seabed friction on the resting length
        "boolean", scale="same", default=True,
        doc="Apply seabed friction on the resting length.")


#: Default time step as a fraction of the linear SSP-RK3 stability limit of the longitudinal
#: wave (mooring/dg/reference.py): 0.8 leaves a margin for the nonlinear terms (snap loads,
#: drag, contact) and was stable on the whole Lindahl robustness grid.
DEFAULT_DG_CFL = 0.8
#: What ``elements = "auto"`` / ``order = "auto"`` (or leaving them out) means: the DG
#: discretisation follows ``accuracy`` (floatmoor.mooring.dg.resolution).
_FROM_ACCURACY = "chosen from accuracy"
#: Default accepted relative error of the fairlead tension (1 %,
#: docs/theory/dynamic_line.md#accuracy-driven-discretisation).
DEFAULT_DG_ACCURACY = 0.01
#: Largest accuracy a case may ask for: beyond 20 % error a tension is not a result.
MAX_DG_ACCURACY = 0.2


@dataclass(frozen=True)
class DynamicSettings:
    """Numerics of the discontinuous Galerkin cable (``[lines.dynamic]``; a section's
    ``dynamic`` table takes the same keys, its defaults the line's)."""

    #: number of elements; None: chosen from ``accuracy`` (mooring/dg/resolution.py)
    elements: int | None = setting(
        "integer", scale="same", ge=1, le=10_000, default=None, auto=_FROM_ACCURACY,
        default_text='chosen from `accuracy` ("auto")',
        doc="Number of discontinuous-Galerkin elements along the line. Left out (or "
            '"auto"), it is chosen with `order` from `accuracy` and the fairlead motion\'s '
            "frequency; `floatmoor check` prints the choice (theory/dynamic_line.md).")
    #: polynomial order p (1 to 8); None: chosen from ``accuracy``
    order: int | None = setting(
        "integer", scale="same", ge=1, le=8, default=None, auto=_FROM_ACCURACY,
        default_text='chosen from `accuracy` ("auto")',
        doc="Polynomial order of the elements. Left out (or \"auto\"), it is chosen with "
            "`elements` from `accuracy`.")
    #: time step as a fraction of the linear SSP-RK3 stability limit [-]
    cfl: float = setting(
        "number", scale="same", unit="-", gt=0.0, le=1.0, default=DEFAULT_DG_CFL,
        doc="Explicit time step as a fraction of the stability limit of the axial (snap) "
            "wave for the SSP-RK3 scheme; the margin below 1 covers the nonlinear terms "
            "(snap loads, drag, seabed contact).")
    #: user cap on the time step [s]
    max_time_step: float | None = setting(
        "number", scale="time",
        unit="s", gt=0.0, default=None, default_text="none (implicit: 0.5 s)",
        doc="Cap on the line's time step [s]; with implicit integration the step starts from "
            "it (0.5 s when not given) and is halved where the estimated error of the "
            "fairlead force is too large.")
    #: modal filter on elements in compression
    slack_filter: bool = setting(
        "boolean", scale="same", default=True,
        doc="Modal velocity filter on elements in compression, which damps the spurious "
            "high-order modes of a slack chain.")
    #: "implicit" or "explicit" normal spring-damper
    seabed_contact: str = setting(
        "string", scale="same", choices=SEABED_CONTACT_METHODS, default="implicit",
        doc="Treatment of the seabed's normal spring-damper: \"implicit\" (backward-Euler, "
            'so the stiff seabed does not limit the step) or "explicit" (resolved by the '
            "step, much smaller).")
    #: relax the line to the static equilibrium of its discretisation before the run
    settle: bool = setting(
        "boolean", scale="same", default=True, field_default=True,
        doc="Relax the line, fairlead held, to the static equilibrium of its own "
            "discretisation before the run, so that its mismatch with the catenary initial "
            "shape does not ring through the run.")
    #: "implicit" (a backward-Euler step after each SSP-RK3 step, so the axial wave alone sets
    #: the time step) or "explicit" (in the right-hand side) Kelvin-Voigt internal damping
    internal_damping: str = setting(
        "string", scale="same", choices=INTERNAL_DAMPING_METHODS, default="implicit",
        field_default="implicit",
        doc="Treatment of the Kelvin-Voigt internal damping "
            "(`line_types.NAME.internal_damping_ratio`): \"implicit\" keeps the axial wave "
            'alone setting the step; "explicit" puts it in the right-hand side, at a step up '
            "to ten times smaller.")
    #: "explicit" (SSP-RK3, ``cfl`` of the axial wave's stability limit) or "implicit"
    #: (generalised-alpha, steps of at most ``max_time_step``, halved where the estimated error
    #: of the fairlead force exceeds ``accuracy``'s share); a case file's default is "auto"
    time_integration: str = setting(
        "string", scale="same",
        choices=TIME_INTEGRATIONS, default="auto", field_default="explicit",
        doc='"explicit" (SSP-RK3 at `cfl` of the axial wave\'s limit), "implicit" '
            "(generalised-alpha, Chung & Hulbert 1993, steps bounded by accuracy) or \"auto\": "
            "implicit while its steps cost less than the explicit ones they replace, explicit "
            "from then on.")
    #: relative error of the fairlead tension accepted [-]
    accuracy: float = setting(
        "number", scale="same", unit="-", gt=0.0, le=MAX_DG_ACCURACY, default=DEFAULT_DG_ACCURACY,
        field_default=DEFAULT_DG_ACCURACY,
        doc="Accepted relative error of the fairlead tension; the element count, order and "
            "implicit step are chosen for it when not given.")
    #: characteristic angular frequency of the fairlead motion [rad/s] (the case's waves or
    #: prescribed motion; 0 when none is declared): what the choice of numerics resolves
    motion_frequency: float = 0.0

    @property
    def resolved(self) -> bool:
        """Whether the discretisation is fixed (elements and order given or chosen)."""
        return self.elements is not None and self.order is not None


@dataclass(frozen=True)
class QuasiDynamicSettings:
    """Numerics of the quasi-dynamic line (``[lines.quasi_dynamic]``).

    Its static catenary is the quasi-static model's, set by ``[lines.quasi_static]``.
    """

    #: odd number of Simpson stations over the suspended length (odd: floatmoor.case.load)
    integration_points: int = setting(
        "integer", scale="same", ge=3, le=MAX_QD_INTEGRATION_POINTS,
        default=DEFAULT_QD_INTEGRATION_POINTS, field_default=DEFAULT_QD_INTEGRATION_POINTS,
        doc="Odd number of composite-Simpson stations over the suspended length at rest.")
    max_time_step: float | None = setting(  #: cap on the step of the backward differences [s]
        "number", scale="time", unit="s", gt=0.0, default=None, field_default=None,
        default_text="one step per output sample",
        doc="Cap on the step of the backward differences, taken on the fairlead's "
            "interpolated path.")


#: The settings of a line whose case file has no ``[lines.quasi_dynamic]`` table.
DEFAULT_QUASI_DYNAMIC = QuasiDynamicSettings()


#: How the two forms of a line's ends are worded on the reference page.
_ONE_OF_START, _ONE_OF_END = "one of `start`, `anchor`", "one of `end`, `fairlead`"


@dataclass(frozen=True)
class Point:
    """A point of the mooring system (``[[points]]``, or implicit: a line's short-form anchor
    or fairlead, an unnamed joint between sections).

    A free point carries a clump weight (``mass``) or a buoy (``volume``): its weight
    m g acts down and its buoyancy rho_w g V up, its added mass is C_a rho_w V and its drag
    0.5 rho_w (C_d A) |u| u, as MoorDyn's points (Hall, MoorDyn v2 theory).
    """

    name: str = setting(
        "name", scale="same",
        doc="Name of the point, used by `lines[].start`, `end` and `sections[].end`; no `.` "
            "(implicit points are named `LINE.anchor`, ...).")
    kind: str = setting(  #: one of :data:`POINT_KINDS`
        "string", scale="same", choices=POINT_KINDS,
        doc="`fixed` (held in space), `body` (carried by the prescribed motion or the "
            "floater) or `free` (in equilibrium of its lines and loads).")
    #: [m]: fixed points' position, body points' position at rest, free points' initial guess
    position: tuple[float, float, float] = setting(
        "vector", scale="length", size=3, unit="m",
        doc="Position: a fixed point's, a body point's at rest, a free point's initial guess "
            "for the statics.")
    # the loads of a free point (floatmoor.case.load refuses them on the other kinds)
    mass: float = setting(  #: [kg]
        "number", scale="point_mass", unit="kg", ge=0.0, default=0.0, field_default=0.0,
        doc="Mass of a free point (a clump weight); free points only.")
    volume: float = setting(  #: displaced volume [m^3]
        "number", scale="point_volume", unit="m^3", ge=0.0, default=0.0, field_default=0.0,
        doc="Displaced volume of a free point (a buoy); free points only.")
    drag_area: float = setting(  #: C_d A [m^2]
        "number", scale="point_drag_area", unit="m^2", ge=0.0, default=0.0, field_default=0.0,
        doc="Drag coefficient times area C_d A of a free point; free points only.")
    added_mass_coefficient: float = setting(  #: C_a, on the displaced volume [-]
        "number", scale="same", unit="-", ge=0.0, default=0.0, field_default=0.0,
        doc="Added-mass coefficient of a free point, on its displaced volume; free points "
            "only.")


@dataclass(frozen=True)
class TopLevelKeys:
    """The keys of a case file outside any table (its :class:`Case` holds the title with its
    placeholders filled, and the template)."""

    title: str = setting(
        "string", scale="same",
        doc="Title of the run, written into its output. It may name values with placeholders "
            "such as `T = {motion.period:.2f} s` (a key path and an optional format), filled "
            "from the final values, so a run with `--set` shows its own.")
    description: str = setting(
        "string", scale="same", default="",
        doc="Free text about the case for its readers (the output keeps the whole case text "
            "in its attributes).")


@dataclass(frozen=True)
class SectionKeys:
    """The keys of a ``[[lines.sections]]`` entry as a file gives them (its :class:`Section`
    holds the line type they name and its end points, resolved; its ``dynamic`` table is a
    :class:`DynamicSettings`)."""

    type: str = setting(
        "string", scale="same", doc="Line type of the section (a `[line_types.NAME]` name).")
    length: float = setting(  #: unstretched [m]
        "number", scale="length", unit="m", gt=0.0, doc="Unstretched length of the section.")
    #: the free point joining it to the next section (None: an implicit joint)
    end: str | None = setting(
        "string", scale="same", default_text="an implicit joint",
        doc="Name of the free point joining this section to the next; not on the last "
            "section. Without it the joint is an implicit massless point `LINE.jointN`.")


@dataclass(frozen=True)
class OneSectionKeys:
    """The short form of a one-section ``[[lines]]`` entry: its line type and length instead
    of ``[[lines.sections]]``."""

    type: str = setting(
        "string", scale="same", default_text="with `length`, or `sections`",
        doc="Line type of a one-section line (a `[line_types.NAME]` name); instead of "
            "`sections`.")
    length: float = setting(  #: unstretched [m]
        "number", scale="length", unit="m", gt=0.0, default_text="with `type`, or `sections`",
        doc="Unstretched length of a one-section line; instead of `sections`.")


@dataclass(frozen=True)
class Section:
    """One line type over part of a line, from point ``start`` to point ``end``."""

    line: str  #: the line's name
    index: int  #: 0 at the line's start
    line_type: LineType
    length: float  #: unstretched [m]
    start: str  #: point names
    end: str
    dynamic: DynamicSettings  #: the line's ``[lines.dynamic]`` with the section's own keys

    @property
    def label(self) -> str:
        """``line[index]``, as messages and outputs name a section."""
        return f"{self.line}[{self.index}]"


@dataclass(frozen=True)
class Line:
    """One mooring line from point ``start`` (arc length 0) to point ``end``, a series of
    sections. ``anchor`` and ``fairlead`` are the positions of its end points (a body point's
    at rest, a free point's initial guess); ``fairlead`` is the mean position in a
    forced-motion run."""

    name: str = setting(
        "name", scale="same", doc="Name of the line, in outputs and in `--set "
        "lines.NAME.KEY=...`.")
    sections: tuple[Section, ...]
    #: [m]; a file gives it for an implicit fixed start point (floatmoor.case.load)
    anchor: tuple[float, float, float] = setting(
        "vector", scale="length", size=3, unit="m", default_text=_ONE_OF_START,
        doc="Position of the line's start, an implicit fixed point `NAME.anchor`; instead of "
            "`start`.")
    #: [m]; a file gives it for an implicit body end point
    fairlead: tuple[float, float, float] = setting(
        "vector", scale="length", size=3, unit="m", default_text=_ONE_OF_END,
        doc="Position of the line's end, an implicit body point `NAME.fairlead` (its position "
            "at rest); instead of `end`.")
    model: str = setting(  #: one of :data:`AVAILABLE_LINE_MODELS`
        "string", scale="same", choices=LINE_MODELS,
        doc="Line model: `quasi-static` (elastic catenary, theory/quasi_static.md), "
            "`quasi-dynamic` (catenary plus drag and inertia, one section between a fixed and "
            "a body point, theory/quasi_dynamic.md) or `dynamic` (discontinuous Galerkin "
            "cable, theory/dynamic_line.md).")
    quasi_static: QuasiStaticSettings
    dynamic: DynamicSettings  #: the line-level numerics (each section has its merged copy)
    quasi_dynamic: QuasiDynamicSettings = DEFAULT_QUASI_DYNAMIC
    start: str = setting(  #: name of the start point
        "string", scale="same", field_default="", default_text=_ONE_OF_START,
        doc="Name of the `[[points]]` entry the line starts at (arc length 0); instead of "
            "`anchor`.")
    end: str = setting(  #: name of the end point
        "string", scale="same", field_default="", default_text=_ONE_OF_END,
        doc="Name of the `[[points]]` entry the line ends at; instead of `fairlead`.")

    @property
    def line_type(self) -> LineType:
        """The line type of a one-section line.

        Raises
        ------
        ValueError
            For a line of several sections, which has no one line type: code for systems
            uses :attr:`sections`.
        """
        if len(self.sections) != 1:
            raise ValueError(f"line '{self.name}' has {len(self.sections)} sections, not one "
                             "line type")
        return self.sections[0].line_type

    @property
    def end_type(self) -> LineType:
        """The line type at the line's end (its fairlead): what the fairlead tension is
        judged against."""
        return self.sections[-1].line_type

    @property
    def length(self) -> float:
        """Unstretched length, the sum of the sections' [m]."""
        return float(sum(s.length for s in self.sections))

    @property
    def span(self) -> float:
        """Straight distance from anchor to fairlead [m]."""
        return float(np.linalg.norm(np.subtract(self.fairlead, self.anchor)))


#: Kinds of prescribed motion (``motion.kind``).
MOTION_KINDS = ("circular", "harmonic", "table", "body")
#: ``[motion] kind``: which motion, hence which dataclass the table's other keys fill.
MOTION_KIND = Setting(
    "string", scale="same", choices=MOTION_KINDS,
    doc="`circular` (on a circle in each line's vertical plane), `harmonic` (per global "
        "axis), `table` (displacements from a CSV file) or `body` (a six-DOF rigid-body "
        "motion, harmonic or from a CSV file).")
#: The descriptions of the ``[motion]`` keys several kinds of motion share.
_PERIOD_DOC = ("Period of the motion: one number (`circular`), or one number or one per axis "
               "(`harmonic`).")
_PHASE_DOC = ("Phase of the motion: 0 puts a circular motion at the top of its circle at t = "
              "0; for `harmonic`, one or per axis, x = a sin(2 pi t / T + phase).")
_RAMP_DOC = ("Duration of the cosine ramp that brings the motion in from rest; shorter than "
             "the run.")
_RAMP_DEFAULT = "one period (the longest moving one); 0 for a table"
_FILE_DOC = ("CSV file, relative to the case file's folder and inside it: columns `time,x,y,z` "
             "of displacements (`table`) or `time,surge,sway,heave,roll_deg,pitch_deg,yaw_deg` "
             "(or `_rad` for all three rotations; `body`).")
_FILE_DEFAULT = "required (`table`); or the DOF tables (`body`)"
_REFERENCE_POINT_DOC = ("Rotation centre of a body motion at rest (`body`); the origin by "
                        "default, the point MoorDyn, OpenFAST and WEC-Sim motions refer to.")


@dataclass(frozen=True)
class CircularMotion:
    """Fairlead moved on a circle in the vertical plane of each line.

    With phase angle phi = 2 pi t / period + phase (phi = 0 at the top of the circle), the
    displacement is r (s sin(phi) e_h + cos(phi) e_z), where e_h points horizontally away from the
    anchor and s = +1 for ``away-from-anchor-at-top`` (the end moves away from the anchor at the
    top), -1 for ``toward-anchor-at-top``.
    """

    radius: float = setting(  #: [m]
        "number", scale="length", unit="m", gt=0.0, doc="Radius of the circle (`circular`).")
    period: float = setting(  #: [s]
        "number", scale="time", unit="s", gt=0.0, doc=_PERIOD_DOC)
    sense: str = setting(  #: one of :data:`CIRCULAR_SENSES`
        "string", scale="same", choices=CIRCULAR_SENSES,
        doc="Rotation sense of a circular motion, named by where the fairlead moves at the top "
            "of the circle (`circular`).")
    phase: float = setting(  #: [rad], 0 = top of the circle at t = 0
        "number", key="phase_deg", radians=True, scale="same", unit="deg", default=0.0,
        default_text="default 0 (every axis)", doc=_PHASE_DOC)
    ramp_duration: float = setting(  #: [s]; a file's default is one period
        "number", scale="time", unit="s", ge=0.0, default_text=_RAMP_DEFAULT, doc=_RAMP_DOC)
    kind: str = "circular"

    @property
    def cycle_period(self) -> float | None:
        """Period of the motion [s]."""
        return self.period


@dataclass(frozen=True)
class HarmonicMotion:
    """Independent harmonic motion per global axis: a_i sin(2 pi t / T_i + phase_i)."""

    amplitude: tuple[float, float, float] = setting(  #: [m], at least one non-zero
        "vector", scale="length", size=3, unit="m", ge=0.0,
        doc="Amplitudes [x, y, z] of a harmonic motion (`harmonic`); at least one non-zero.")
    period: tuple[float, float, float] = setting(  #: [s]
        "number_or_vector", scale="time", size=3, unit="s", gt=0.0, doc=_PERIOD_DOC)
    phase: tuple[float, float, float] = setting(  #: [rad]
        "number_or_vector", key="phase_deg", radians=True, scale="same", size=3, unit="deg",
        default=(0.0, 0.0, 0.0), default_text="default 0 (every axis)", doc=_PHASE_DOC)
    ramp_duration: float = setting(  #: [s]; a file's default is the longest moving period
        "number", scale="time", unit="s", ge=0.0, default_text=_RAMP_DEFAULT, doc=_RAMP_DOC)
    kind: str = "harmonic"

    @property
    def cycle_period(self) -> float | None:
        """Common period of the moving axes [s], or None when they differ."""
        periods = {p for a, p in zip(self.amplitude, self.period) if a != 0.0}
        if len(periods) == 1:
            return periods.pop()
        return None


@dataclass(frozen=True)
class TableMotion:
    """Displacement time history from a CSV file (columns ``time, x, y, z``), interpolated
    by a cubic spline (:func:`floatmoor.motion.fairlead.table_state`)."""

    file: str = setting(  #: resolved path of the CSV file (the file's key: as written)
        "string", scale="motion_table", default_text=_FILE_DEFAULT, doc=_FILE_DOC)
    time: NDArray[np.float64] = field(repr=False)  #: [s]
    displacement: NDArray[np.float64] = field(repr=False)  #: (n, 3) [m]
    ramp_duration: float = setting(  #: [s]
        "number", scale="time", unit="s", ge=0.0, default=0.0, field_default=0.0,
        default_text=_RAMP_DEFAULT, doc=_RAMP_DOC)
    kind: str = "table"

    @property
    def cycle_period(self) -> float | None:
        """A table has no declared period."""
        return None


#: The six DOFs of a prescribed body motion, in the order of its arrays (as capytaine's).
BODY_DOFS = ("surge", "sway", "heave", "roll", "pitch", "yaw")


def _dof_period() -> Any:
    """The ``period`` of one ``[motion.DOF]`` table (a translation's or a rotation's)."""
    return setting("number", scale="time", unit="s", gt=0.0, doc="Period of the {table} [s].")


def _dof_phase() -> Any:
    """The ``phase_deg`` of one ``[motion.DOF]`` table, held in radians."""
    return setting("number", key="phase_deg", radians=True, scale="same", unit="deg",
                   default=0.0, doc="Phase of the {table}, x = a sin(2 pi t / T + phase) [deg].")


@dataclass(frozen=True)
class HarmonicTranslation:
    """A ``[motion.surge]``, ``[motion.sway]`` or ``[motion.heave]`` table: x = a sin(2 pi t /
    T + phase)."""

    amplitude: float = setting(  #: [m]
        "number", scale="length", unit="m", ge=0.0, doc="Amplitude of the {table} [m].")
    period: float = _dof_period()  #: [s]
    phase: float = _dof_phase()  #: [rad]


@dataclass(frozen=True)
class HarmonicRotation:
    """A ``[motion.roll]``, ``[motion.pitch]`` or ``[motion.yaw]`` table, angles in degrees
    as every angle of a case file."""

    amplitude: float = setting(  #: [rad]
        "number", key="amplitude_deg", radians=True, scale="same", unit="deg", ge=0.0,
        doc="Amplitude of the {table} [deg]; rotations are given in degrees as every angle "
            "of a case file.")
    period: float = _dof_period()  #: [s]
    phase: float = _dof_phase()  #: [rad]


@dataclass(frozen=True)
class BodyHarmonicMotion:
    """Rigid-body motion of the body points, harmonic per DOF: x_i = a_i sin(2 pi t / T_i +
    phase_i) for the DOFs of :data:`BODY_DOFS` (see :mod:`floatmoor.motion.rigid_body` for the
    rotation convention). DOFs that do not move have amplitude 0 (and period 1 s)."""

    reference_point: tuple[float, float, float] = setting(  #: rotation centre at rest [m]
        "vector", scale="length", size=3, unit="m", default=(0.0, 0.0, 0.0),
        doc=_REFERENCE_POINT_DOC)
    #: (6,) [m, m, m, rad, rad, rad], from the ``[motion.DOF]`` tables
    #: (:class:`HarmonicTranslation`, :class:`HarmonicRotation`)
    amplitude: tuple[float, ...]
    period: tuple[float, ...]  #: (6,) [s]
    phase: tuple[float, ...]  #: (6,) [rad]
    ramp_duration: float = setting(  #: [s]; a file's default is the longest moving period
        "number", scale="time", unit="s", ge=0.0, default_text=_RAMP_DEFAULT, doc=_RAMP_DOC)
    kind: str = "body"

    @property
    def cycle_period(self) -> float | None:
        """Common period of the moving DOFs [s], or None when they differ."""
        periods = {p for a, p in zip(self.amplitude, self.period) if a != 0.0}
        return periods.pop() if len(periods) == 1 else None


@dataclass(frozen=True)
class BodyTableMotion:
    """Rigid-body motion of the body points from a CSV file (columns time, the six DOFs of
    :data:`BODY_DOFS`), interpolated in each DOF by a cubic spline (rotations in the Euler
    angles; :func:`floatmoor.motion.fairlead.table_state`)."""

    reference_point: tuple[float, float, float] = setting(  #: rotation centre at rest [m]
        "vector", scale="length", size=3, unit="m", default=(0.0, 0.0, 0.0),
        doc=_REFERENCE_POINT_DOC)
    file: str = setting(  #: resolved path of the CSV file (the file's key: as written)
        "string", scale="motion_table", default_text=_FILE_DEFAULT, doc=_FILE_DOC)
    time: NDArray[np.float64] = field(repr=False)  #: [s]
    displacement: NDArray[np.float64] = field(repr=False)  #: (n, 6) [m, m, m, rad, rad, rad]
    ramp_duration: float = setting(  #: [s]
        "number", scale="time", unit="s", ge=0.0, default=0.0, field_default=0.0,
        default_text=_RAMP_DEFAULT, doc=_RAMP_DOC)
    kind: str = "body"

    @property
    def cycle_period(self) -> float | None:
        """A table has no declared period."""
        return None


BodyMotion = BodyHarmonicMotion | BodyTableMotion
Motion = CircularMotion | HarmonicMotion | TableMotion | BodyHarmonicMotion | BodyTableMotion


@dataclass(frozen=True)
class Simulation:
    """Time span and output sampling (``[simulation]``)."""

    duration: float = setting(  #: [s]
        "number", scale="time", unit="s", gt=0.0, doc="Simulated time span, from t = 0.")
    output_interval: float = setting(  #: [s], <= duration (floatmoor.case.load)
        "number", scale="time",
        unit="s", gt=0.0, doc="Sampling interval of the output time series.")
    #: body step of a coupled run [s] (dividing the output interval); None = the output interval
    time_step: float | None = setting(
        "number", scale="time", unit="s", gt=0.0, default=None, field_default=None,
        doc="Time step of the floater in coupled runs, dividing `output_interval`; default "
            "the output interval. Only with a `[floater]` (lines take their own steps).")
    #: line shape sampling [s], None = no shapes
    shape_output_interval: float | None = setting(
        "number", scale="time", unit="s", gt=0.0, default=None, field_default=None,
        doc="Sampling interval of the line shapes, a multiple of `output_interval`; no shapes "
            "are written without it.")


#: Floater geometry kinds a case file may give (``floater.geometry.kind``).
GEOMETRY_KINDS = ("cylinder", "semisubmersible", "mesh")
#: Hull mesh file formats (``floater.geometry.format``): capytaine's own readers (WAMIT
#: ``gdf``, Nemoh ``mar``/``nemoh``, HAMS ``pnl``, HydroStar ``hst``) and the surface formats
#: it reads through meshio (floatmoor.hydro.mesh_file).
MESH_FORMATS = ("gdf", "mar", "nemoh", "pnl", "hst", "stl", "obj", "ply", "off", "vtk", "vtu",
                "msh")
#: Length units of a mesh file's coordinates (``floater.geometry.length_unit``) [m per unit].
MESH_LENGTH_UNITS = {"m": 1.0, "cm": 0.01, "mm": 0.001, "ft": 0.3048, "in": 0.0254}
#: Symmetry planes a mesh file may be the positive half of: ``xz`` (y = 0, the file holds
#: y >= 0) and ``yz`` (x = 0, the file holds x >= 0).
MESH_SYMMETRY_PLANES = ("xz", "yz")
#: Radiation memory paths of a floater (``floater.radiation``): the convolution of K(t) with
#: the velocity history, or the database's state-space realisation of K(t).
RADIATION_METHODS = ("convolution", "state-space")
#: The checks of a hydrodynamic database (floatmoor.hydro.checks.run_checks, in its order): the
#: names ``[hydro] accept_failed_checks`` may give.
#: Where a floater's database comes from (``[hydro] source``): built by capytaine from the
#: case's geometry, or imported from another program's files.
HYDRO_SOURCES = ("bem", "imported")
HYDRO_CHECKS = ("symmetry", "damping_psd", "kramers_kronig", "kernel_decay", "haskind",
                "hydrostatics")


#: ``[floater.geometry] kind``: which hull, hence which dataclass the table's other keys fill.
GEOMETRY_KIND = Setting(
    "string", scale="same", choices=GEOMETRY_KINDS,
    doc="`cylinder`, `semisubmersible` (columns and members) or `mesh` (a hull mesh file).")


@dataclass(frozen=True)
class CylinderGeometry:
    """A vertical circular cylinder, axis through the floater's reference point (x, y)."""

    diameter: float = setting(  #: [m]
        "number", scale="length", unit="m", gt=0.0, doc="Diameter of a cylinder (`cylinder`).")
    #: depth of the flat bottom below the still water line [m] (< height, floatmoor.case.floater)
    draft: float = setting(
        "number", scale="length", unit="m", gt=0.0, default=None, default_text="from the mass",
        doc="Draft of a cylinder (`cylinder`); default the draft at which it floats freely, "
            "mass / (water_density pi R^2).")
    height: float = setting(  #: bottom to top [m]; the freeboard is height - draft
        "number", scale="length", unit="m", gt=0.0,
        doc="Height of a cylinder, bottom to top (`cylinder`).")
    draft_from_mass: bool  #: the draft was derived from the mass (``draft`` omitted)
    kind: str = "cylinder"

    @property
    def radius(self) -> float:
        """[m]"""
        return 0.5 * self.diameter


@dataclass(frozen=True)
class Column:
    """A vertical column of a semisubmersible, optionally with a wider base (heave plate)
    of ``heave_plate_diameter`` from ``z_bottom`` up to ``z_bottom + heave_plate_height``."""

    x: float = setting(  #: [m]
        "number", scale="length", unit="m", doc="x of the column's axis.")
    y: float = setting(  #: [m]
        "number", scale="length", unit="m", doc="y of the column's axis.")
    diameter: float = setting(  #: of the upper part [m]
        "number", scale="length", unit="m", gt=0.0, doc="Diameter of the column.")
    z_top: float = setting(  #: [m]
        "number", scale="length", unit="m", doc="Elevation of the column's top.")
    # the bounds of the keys below depend on other values (floatmoor.case.floater)
    z_bottom: float = setting(  #: [m], above the seabed and below z_top
        "number", scale="length", unit="m", allowed_text="> -water_depth and < z_top",
        doc="Elevation of the column's bottom.")
    heave_plate_diameter: float | None = setting(  #: [m], wider than the column
        "number", scale="length", unit="m", default=None, field_default=None,
        allowed_text="> the column's diameter",
        doc="Diameter of a heave plate at the column's bottom; with `heave_plate_height`.")
    heave_plate_height: float = setting(  #: [m] (a file without a plate: 0)
        "number", scale="length", unit="m", gt=0.0, default=None, field_default=0.0,
        allowed_text="> 0 and < z_top - z_bottom",
        doc="Height of the heave plate above `z_bottom`; with `heave_plate_diameter`.")


@dataclass(frozen=True)
class Member:
    """A pontoon or brace: a circular tube between two points (each on a column or another
    member) [m]."""

    start: tuple[float, float, float] = setting(
        "vector", scale="length", size=3, unit="m", doc="Start of the member's axis.")
    end: tuple[float, float, float] = setting(
        "vector", scale="length", size=3, unit="m",
        doc="End of the member's axis, more than one diameter from its start.")
    diameter: float = setting(
        "number", scale="length", unit="m", gt=0.0, doc="Diameter of the member.")


@dataclass(frozen=True)
class SemisubmersibleGeometry:
    """Columns and the pontoons and braces that join them."""

    columns: tuple[Column, ...]
    members: tuple[Member, ...] = ()
    kind: str = "semisubmersible"


@dataclass(frozen=True)
class MeshGeometry:
    """A hull given as a panel mesh file (floatmoor.hydro.mesh_file reads it at build time).

    The dataclass fields are the BEM inputs a database records (``dataclasses.asdict``, see
    floatmoor.hydro.database.database_inputs): the path as the case file writes it and the
    file's SHA-256, so a changed mesh file makes the database stale while moving the project
    does not. Two things are attributes outside the fields, not BEM inputs: the resolved
    path (:attr:`path`) and the Morison elements used by ``[floater.drag]`` only
    (:attr:`columns`, :attr:`members`; not meshed), so editing drag elements leaves the
    database up to date. (``dataclasses.replace`` drops them unless passed again.)
    """

    # the mesh keys declare no scale: floatmoor scale refuses a mesh hull
    file: str = setting(  #: the path as written in the case file, relative to its folder
        "string",
        doc="Hull mesh file, relative to the case file's folder and inside it (`mesh`); "
            "checked and hashed on loading, read when the database is built.")
    sha256: str  #: SHA-256 of the file's bytes
    format: str = setting(  #: one of :data:`MESH_FORMATS`
        "string", choices=MESH_FORMATS,
        default_text="from the file's extension",
        doc="Format of the mesh file (`mesh`); default from its extension.")
    length_unit: str = setting(  #: a key of :data:`MESH_LENGTH_UNITS`
        "string", choices=tuple(MESH_LENGTH_UNITS), default="m",
        doc="Length unit of the mesh file's coordinates (`mesh`).")
    position: tuple[float, float, float] = setting(  #: added to the scaled file coordinates [m]
        "vector", size=3, unit="m", default=(0.0, 0.0, 0.0),
        doc="Offset added to the scaled mesh coordinates (`mesh`).")
    #: planes (of :data:`MESH_SYMMETRY_PLANES`, sorted) the file is the positive half of
    symmetry: tuple[str, ...] = setting(
        "strings", choices=MESH_SYMMETRY_PLANES, default=(),
        field_default=(), default_text="none",
        doc="Symmetry planes the mesh file is the positive half of: `xz` (the file holds "
            "y >= 0), `yz` (x >= 0), or both (`mesh`).")
    kind: str = "mesh"
    resolved_path: InitVar[str | None] = None
    morison_columns: InitVar[tuple[Column, ...]] = ()
    morison_members: InitVar[tuple[Member, ...]] = ()

    def __post_init__(self, resolved_path: str | None, morison_columns: tuple[Column, ...],
                      morison_members: tuple[Member, ...]) -> None:
        object.__setattr__(self, "_path", resolved_path)
        object.__setattr__(self, "_columns", tuple(morison_columns))
        object.__setattr__(self, "_members", tuple(morison_members))

    @property
    def path(self) -> str | None:
        """The resolved path of the mesh file (None for a geometry read from a database)."""
        return self._path  # type: ignore[attr-defined]

    @property
    def columns(self) -> tuple[Column, ...]:
        """Morison columns of ``[floater.drag]`` (not meshed)."""
        return self._columns  # type: ignore[attr-defined]

    @property
    def members(self) -> tuple[Member, ...]:
        """Morison pontoons and braces of ``[floater.drag]`` (not meshed)."""
        return self._members  # type: ignore[attr-defined]

    @property
    def scale(self) -> float:
        """Metres per file length unit."""
        return MESH_LENGTH_UNITS[self.length_unit]


FloaterGeometry = CylinderGeometry | SemisubmersibleGeometry | MeshGeometry


@dataclass(frozen=True)
class Floater:
    """A rigid floating body (``[floater]``); positions are global, at rest."""

    name: str = setting("name", scale="same", doc="Name of the body, in outputs.")
    mass: float = setting(  #: [kg]
        "number", scale="mass", unit="kg", gt=0.0, doc="Mass of the body.")
    centre_of_mass: tuple[float, float, float] = setting(  #: [m]
        "vector", scale="length", size=3, unit="m",
        doc="Centre of mass, global coordinates at rest.")
    #: inertia tensor about the centre of mass, (Ixx, Iyy, Izz, Ixy, Ixz, Iyz) [kg m^2]; a
    #: file gives 3 or 6 numbers (its size is the reader's, floatmoor.case.floater)
    inertia: tuple[float, float, float, float, float, float] = setting(
        "vector", scale="inertia", unit="kg m^2", type_text="array of 3 or 6 numbers",
        doc="Inertia about the centre of mass: [Ixx, Iyy, Izz] or [Ixx, Iyy, Izz, Ixy, Ixz, "
            "Iyz]; positive definite.")
    reference_point: tuple[float, float, float] = setting(  #: rotation centre of the DOFs [m]
        "vector", scale="length", size=3, unit="m",
        doc="Rotation centre of the six DOFs, global coordinates at rest.")
    #: the hull (``[floater.geometry]``); None for a floater whose database is imported and
    #: that gives none (its hydrostatics come from the database; no drag members)
    geometry: FloaterGeometry | None
    #: Morison drag on the members (``[floater.drag]``), or None
    drag: DragSettings | None = None
    #: radiation memory path (one of :data:`RADIATION_METHODS`)
    radiation: str = setting(
        "string", scale="same", choices=RADIATION_METHODS, default="convolution",
        field_default="convolution",
        doc="Radiation memory: `convolution` of the retardation kernel K(t) with the velocity "
            "history, or `state-space` (the realisation stored in the database by `floatmoor "
            "hydro fit-state-space`).")

    def mass_matrix(self) -> NDArray[np.float64]:
        """6x6 rigid-body mass matrix about :attr:`reference_point` (Surge .. Yaw)."""
        m = self.mass
        ixx, iyy, izz, ixy, ixz, iyz = self.inertia
        r = np.subtract(self.centre_of_mass, self.reference_point)
        inertia_cm = np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]], dtype=float)
        # parallel axis theorem: I_ref = I_cm + m (|r|^2 1 - r r^T)
        inertia_ref = inertia_cm + m * (float(r @ r) * np.eye(3) - np.outer(r, r))
        skew = np.array([[0.0, -r[2], r[1]], [r[2], 0.0, -r[0]], [-r[1], r[0], 0.0]])
        out = np.zeros((6, 6))
        out[:3, :3] = m * np.eye(3)
        out[:3, 3:] = -m * skew
        out[3:, :3] = m * skew
        out[3:, 3:] = inertia_ref
        return out


@dataclass(frozen=True)
class BemGridKeys:
    """The frequency and direction keys of a BEM ``[hydro]`` as a file gives them (its
    :class:`HydroSettings` holds the distinct frequencies, sorted, and the directions in
    radians)."""

    frequency_ranges: tuple[tuple[float, float, int], ...] | None = setting(
        "triples", unit="rad/s", default=None, default_text="one of the two (`bem`)",
        allowed_text="0 < first < last, count >= 2",
        doc="BEM frequencies as [first, last, count] triples, evenly spaced; with or instead "
            "of `frequencies`.")
    frequencies: tuple[float, ...] | None = setting(
        "vector", unit="rad/s", gt=0.0, default=None, default_text="one of the two (`bem`)",
        allowed_text="> 0; with the ranges, 2 to 2000 distinct", type_text="array of numbers",
        doc="BEM frequencies, listed; with or instead of `frequency_ranges`.")
    directions_deg: tuple[float, ...] = setting(
        "vector", unit="deg", default_text="required (`bem`)",
        allowed_text="within [-360, 360], distinct, increasing", type_text="array of numbers",
        doc="Wave directions of the excitation, distinct and increasing.")


@dataclass(frozen=True)
class HydroSettings:
    """Settings of the BEM database of the floater (``[hydro]``).

    With ``source = "imported"`` (a database made by ``floatmoor hydro import``) the BEM build
    fields are empty: ``frequencies`` and ``directions`` (), ``panel_size`` and ``lid_depth``
    None, the flags False.
    """

    database: str = setting(  #: database name: ``hydrodb/NAME.nc``
        "string", doc="Name of the database file in `hydrodb/` (`NAME` for `hydrodb/NAME.nc`); "
        "with `source = \"imported\"` also the path of the `.nc` that `floatmoor hydro "
        "import` made (a `/` in it or ending in `.nc`), relative to the case file's folder.")
    frequencies: tuple[float, ...]  #: finite wave frequencies, increasing [rad/s]
    directions: tuple[float, ...]  #: wave propagation directions, increasing [rad]
    #: target panel edge length [m] (None: imported; required by the loader except for a mesh
    #: hull without a lid, floatmoor.case.floater.check_panel_size)
    panel_size: float | None = setting(
        "number", unit="m", gt=0.0, default=None, doc="Target panel edge of a parametric hull, "
        "or of a mesh hull's lid; not needed for a mesh hull without a lid.")
    #: lid on the interior waterplane against irregular frequencies
    lid: bool = setting(
        "boolean", default=True, doc="Close the hull's water plane with a lid of panels just "
        "below the water line, against the BEM's irregular frequencies.")
    #: [m] below the still water line, None = from the top frequency
    lid_depth: float | None = setting(
        "number", unit="m", gt=0.0, default=None, doc="Depth of the lid below the water line; "
        "default where wavenumber times depth is 0.15 at the highest frequency.")
    #: solve in deep water (allows omega = 0) instead of water_depth
    infinite_depth: bool = setting(
        "boolean", default=False, doc="Solve the BEM in infinite depth instead of "
        "environment.water_depth.")
    symmetry: bool = setting(  #: use the mesh symmetries capytaine supports
        "boolean", default=True, doc="Use the hull's symmetries in the BEM.")
    radial_panels: int | None = setting(  #: cylinder only: panels across the bottom radius
        "integer", ge=1, le=1000, default=None, field_default=None,
        doc="Panels across the bottom of a cylinder, centre to rim.")
    #: panel height at the still water line of the mean drift's mesh (walls graded from it to
    #: ``panel_size``) [m]; None: the default rule of floatmoor.hydro.drift_build. Not a
    #: first-order input: the database's own mesh is uniform
    drift_waterline_panel_size: float | None = setting(
        "number", unit="m", gt=0.0, default=None, field_default=None,
        doc="Panel height at the water line of the mesh the mean drift is solved on (`hydro "
            "build --drift`), graded to panel_size below; default from the highest frequency "
            "(guide/hydro_databases.md#mean-drift).")
    #: panel size of the mean drift's mesh away from the water line [m]; None: ``panel_size``.
    #: Not a first-order input either (docs/guide/hydro_databases.md#mean-drift)
    drift_panel_size: float | None = setting(
        "number", unit="m", gt=0.0, default=None, field_default=None,
        doc="Panel size of the mean drift's mesh away from the water line; default "
            "panel_size. Finer panels resolve the near field's body-motion terms at a large "
            "resonant response (guide/hydro_databases.md#mean-drift).")
    #: database checks (of :data:`HYDRO_CHECKS`) whose failure a run accepts (not a BEM input)
    accept_failed_checks: tuple[str, ...] = setting(
        "strings", choices=HYDRO_CHECKS, default=(), field_default=(), default_text="none",
        doc="Database checks whose failure a run of this case accepts; a run refuses a "
            "database failing any other.")
    #: ``"bem"`` (built by ``floatmoor hydro build``) or ``"imported"`` (``hydro import``)
    source: str = setting(
        "string", choices=HYDRO_SOURCES, default="bem", field_default="bem",
        doc="`bem` (built from the keys below) or `imported` (made by `floatmoor hydro "
            "import` from WAMIT or BEMIO files; then no build keys).")


@dataclass(frozen=True)
class Case:
    """A validated case: everything a run, a check or an export reads of a case file.

    Made by :func:`floatmoor.case.load_case` (or :func:`floatmoor.case.parse_case` from a
    parsed table) after every check has passed, so that the models trust its values; SI
    units and radians throughout (docs/conventions.md).

    Attributes
    ----------
    title
        The title with its placeholders filled and the overrides it does not show appended
        (:mod:`floatmoor.case.title`).
    source
        Path of the case file, named in errors and recorded in results.
    text
        The case file's text, as read ("" when the case was parsed from a table).
    overrides
        The ``--set`` assignments applied, in order.
    environment
        Water density, gravity, depth and current (``[environment]``).
    seabed
        The seabed's contact stiffness, damping and friction (``[seabed]``).
    line_types
        Line materials by name (``[line_types.NAME]``); empty for a floater case that
        gives none.
    lines
        The mooring lines, in file order, each with its sections and numerics.
    motion
        The prescribed fairlead motion, or None for fixed fairleads.
    simulation
        Duration, output interval and time steps (``[simulation]``).
    description
        Free text of the case file ("" when it gives none).
    campaign
        ``{"grid": {key: [values]}, "zip": {key: [values]}}`` from ``[campaign]``, or None.
    floater
        The floating body; its lines' fairleads are body-fixed points given at rest. A case
        has a floater or a motion, not both.
    hydro
        The BEM database settings of the floater (``[hydro]``), or None.
    waves
        The sea of a coupled run (``[waves]``), or None.
    initial_offset
        The floater's offset from its static equilibrium at t = 0 (``[initial]``):
        surge, sway, heave [m], roll, pitch, yaw [rad].
    wind
        The rotor's wind (``[wind]``), or None.
    title_template
        The title as the case file gives it, placeholders unfilled ("" = same as
        ``title``).
    points
        Every point of the mooring system: the ``[[points]]``, then the lines' implicit
        ones (a short-form line's anchor and fairlead, an unnamed joint between sections).
    """

    title: str
    source: str
    text: str
    overrides: tuple[str, ...]
    environment: Environment
    seabed: Seabed
    line_types: dict[str, LineType]
    lines: tuple[Line, ...]
    motion: Motion | None
    simulation: Simulation
    description: str = ""
    #: ``{"grid": {key: [values]}, "zip": {key: [values]}}`` from ``[campaign]``, or None
    campaign: dict[str, dict[str, list[Any]]] | None = None
    #: the floating body, or None (fairleads fixed or moved by ``motion``)
    floater: Floater | None = None
    #: the BEM database settings of the floater, or None
    hydro: HydroSettings | None = None
    #: the sea of a coupled run (``[waves]``), or None
    waves: WaveCase | None = None
    #: the floater's offset from its static equilibrium at t = 0 (``[initial]``) [m, rad]
    initial_offset: tuple[float, float, float, float, float, float] = (0.0,) * 6
    #: the rotor's wind (``[wind]``), or None
    wind: WindSettings | None = None
    #: the title as the case file gives it, placeholders unfilled ("" = same as ``title``)
    title_template: str = ""
    #: every point of the mooring system, the ``[[points]]`` then the lines' implicit ones
    points: tuple[Point, ...] = ()

    @property
    def line_names(self) -> list[str]:
        """Names of the lines, in file order."""
        return [line.name for line in self.lines]

    def point(self, name: str) -> Point:
        """The point called ``name`` (KeyError if none is)."""
        return self._points_by_name[name]

    @cached_property
    def _points_by_name(self) -> dict[str, Point]:
        # one dict for every lookup: a scan per lookup made loading a case of thousands of
        # lines quadratic in its size (the first point of a name wins, as the scan did)
        by_name: dict[str, Point] = {}
        for p in self.points:
            by_name.setdefault(p.name, p)
        return by_name

    @property
    def sections(self) -> tuple[Section, ...]:
        """Every line's sections, line by line from start to end."""
        return tuple(s for line in self.lines for s in line.sections)

    def is_independent(self, line: Line) -> bool:
        """Whether ``line`` is one section from a fixed to a body point, solved on its own
        (every other line belongs to a system of lines solved together)."""
        return (len(line.sections) == 1 and self.point(line.start).kind == "fixed"
                and self.point(line.end).kind == "body")

    @property
    def is_system(self) -> bool:
        """Whether the mooring is more than independent lines (:meth:`is_independent`)."""
        return not all(self.is_independent(line) for line in self.lines)
