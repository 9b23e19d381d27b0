"""What each case-file key not yet declared as a setting means, for the case-file reference.

Declared keys (:mod:`floatmoor.case.setting`: the migrated case tables, ``[campaign]`` and
every key of a study file) carry their own descriptions.

The type, unit, range and default of a key come from its reader (the accessors of
:class:`~floatmoor.case.reader.TableReader`, recorded while files load); only what a reader
cannot state is written here: what the key is, when it matters and where the model is
explained. Keys are generic paths (``lines[].dynamic.cfl``, ``line_types.<name>.diameter``; a
table's own entry, e.g. ``lines``, describes the table). ``defaults`` words a default that
is computed from other values, ``allowed`` a range or a choice that depends on other values,
``types`` an array whose length does.
The tests fail on a key the readers ask for that has no description here, and on a
description of a key no reader asks for.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Mapping

from floatmoor.case.schema import DynamicSettings
from floatmoor.case.setting import settings_of

__all__ = ["KeyDocs", "CASE"]


@dataclass(frozen=True)
class KeyDocs:
    """The descriptions of one kind of input file, by generic key path."""

    descriptions: Mapping[str, str]
    #: The required / default column of keys whose default is computed from other values.
    defaults: Mapping[str, str] = field(default_factory=dict)
    #: The allowed column of keys whose range or choices depend on other values.
    allowed: Mapping[str, str] = field(default_factory=dict)
    #: The type column of arrays whose length depends on other values.
    types: Mapping[str, str] = field(default_factory=dict)


# -- case files -------------------------------------------------------------------------------

_DOF_UNITS = {"surge": "m", "sway": "m", "heave": "m", "roll": "deg", "pitch": "deg",
              "yaw": "deg"}


def _body_dofs() -> dict[str, str]:
    """The six ``[motion.DOF]`` tables of a harmonic body motion."""
    out = {}
    for dof, unit in _DOF_UNITS.items():
        amplitude = "amplitude" if unit == "m" else "amplitude_deg"
        out[f"motion.{dof}"] = (f"Harmonic {dof} of the body, "
                                f"{'a translation' if unit == 'm' else 'a rotation about the reference point'}"
                                " (`kind = \"body\"`); a DOF without its table does not move.")
        out[f"motion.{dof}.{amplitude}"] = (
            f"Amplitude of the {dof}" + (" [m]." if unit == "m" else
                                         " [deg]; rotations are given in degrees as every "
                                         "angle of a case file."))
        out[f"motion.{dof}.period"] = f"Period of the {dof} [s]."
        out[f"motion.{dof}.phase_deg"] = (f"Phase of the {dof}, x = a sin(2 pi t / T + "
                                          "phase) [deg].")
    return out


_CASE = {
    "": "The keys outside any table.",
    "title": "Title of the run, written into its output. It may name values with "
             "placeholders such as `T = {motion.period:.2f} s` (a key path and an optional "
             "format), filled from the final values, so a run with `--set` shows its own.",
    "description": "Free text about the case for its readers (the output keeps the whole "
                   "case text in its attributes).",
    # environment
    "environment": "Water and gravity: still water at z = 0, a flat seabed at "
                   "z = -water_depth (theory/environment.md).",
    # seabed
    "seabed": "Seabed contact of the lines: a normal spring-damper and friction, smoothed "
              "Coulomb or a stick spring (theory/dynamic_line.md, theory/cable.md).",
    # line types
    "line_types": "The line materials, one table per name (`[line_types.chain]`); lines and "
                  "sections name them with `type`.",
    # points
    "points": "Named points of a mooring system: anchors (`fixed`), fairleads (`body`) and "
              "joints, clump weights and buoys (`free`); lines connect them by name "
              "(theory/mooring_systems.md).",
    "points[].name": "Name of the point, used by `lines[].start`, `end` and "
                     "`sections[].end`; no `.` (implicit points are named `LINE.anchor`, ...).",
    "points[].kind": "`fixed` (held in space), `body` (carried by the prescribed motion or "
                     "the floater) or `free` (in equilibrium of its lines and loads).",
    "points[].position": "Position: a fixed point's, a body point's at rest, a free point's "
                         "initial guess for the statics.",
    "points[].mass": "Mass of a free point (a clump weight); free points only.",
    "points[].volume": "Displaced volume of a free point (a buoy); free points only.",
    "points[].drag_area": "Drag coefficient times area C_d A of a free point; free points "
                          "only.",
    "points[].added_mass_coefficient": "Added-mass coefficient of a free point, on its "
                                       "displaced volume; free points only.",
    # lines
    "lines": "The mooring lines, each from a start point to an end point, one line type or a "
             "series of sections.",
    "lines[].name": "Name of the line, in outputs and in `--set lines.NAME.KEY=...`.",
    "lines[].start": "Name of the `[[points]]` entry the line starts at (arc length 0); "
                     "instead of `anchor`.",
    "lines[].anchor": "Position of the line's start, an implicit fixed point `NAME.anchor`; "
                      "instead of `start`.",
    "lines[].end": "Name of the `[[points]]` entry the line ends at; instead of `fairlead`.",
    "lines[].fairlead": "Position of the line's end, an implicit body point `NAME.fairlead` "
                        "(its position at rest); instead of `end`.",
    "lines[].model": "Line model: `quasi-static` (elastic catenary, theory/quasi_static.md), "
                     "`quasi-dynamic` (catenary plus drag and inertia, one section between a "
                     "fixed and a body point, theory/quasi_dynamic.md) or `dynamic` "
                     "(discontinuous Galerkin cable, theory/dynamic_line.md).",
    "lines[].type": "Line type of a one-section line (a `[line_types.NAME]` name); instead of "
                    "`sections`.",
    "lines[].length": "Unstretched length of a one-section line; instead of `sections`.",
    "lines[].sections": "The line's sections from start to end, each of one line type; "
                        "instead of `type` and `length`.",
    "lines[].sections[].type": "Line type of the section (a `[line_types.NAME]` name).",
    "lines[].sections[].length": "Unstretched length of the section.",
    "lines[].sections[].end": "Name of the free point joining this section to the next; not "
                              "on the last section. Without it the joint is an implicit "
                              "massless point `LINE.jointN`.",
    "lines[].sections[].dynamic": "The section's own dynamic-model numerics; each key "
                                  "overrides the line's `[lines.dynamic]`.",
    "lines[].quasi_static": "Numerics of the quasi-static catenary (also the static "
                            "catenary of the other models).",
    "lines[].quasi_dynamic": "Numerics of the quasi-dynamic model.",
    "lines[].dynamic": "Numerics of the dynamic (discontinuous Galerkin) model; by default "
                       "they are chosen from `accuracy` (theory/dynamic_line.md).",
    # simulation
    "simulation": "Time span and output sampling of the run.",
    # motion
    "motion": "Prescribed motion of the body points (the fairleads); without it, and without "
              "a `[floater]`, they stay at rest. Not with a `[floater]`.",
    "motion.kind": "`circular` (on a circle in each line's vertical plane), `harmonic` "
                   "(per global axis), `table` (displacements from a CSV file) or `body` "
                   "(a six-DOF rigid-body motion, harmonic or from a CSV file).",
    "motion.radius": "Radius of the circle (`circular`).",
    "motion.period": "Period of the motion: one number (`circular`), or one number or one "
                     "per axis (`harmonic`).",
    "motion.sense": "Rotation sense of a circular motion, named by where the fairlead moves "
                    "at the top of the circle (`circular`).",
    "motion.phase_deg": "Phase of the motion: 0 puts a circular motion at the top of its "
                        "circle at t = 0; for `harmonic`, one or per axis, x = a sin(2 pi t / T "
                        "+ phase).",
    "motion.amplitude": "Amplitudes [x, y, z] of a harmonic motion (`harmonic`); at least one "
                        "non-zero.",
    "motion.file": "CSV file, relative to the case file's folder and inside it: columns "
                   "`time,x,y,z` of displacements (`table`) or `time,surge,sway,heave,roll_deg,"
                   "pitch_deg,yaw_deg` (or `_rad` for all three rotations; `body`).",
    "motion.reference_point": "Rotation centre of a body motion at rest (`body`); the origin "
                              "by default, the point MoorDyn, OpenFAST and WEC-Sim motions "
                              "refer to.",
    "motion.ramp_duration": "Duration of the cosine ramp that brings the motion in from "
                            "rest; shorter than the run.",
    **_body_dofs(),
    # floater
    "floater": "A floating body coupled to its lines (theory/floater.md); a case with a "
               "floater has no `[motion]`.",
    "floater.name": "Name of the body, in outputs.",
    "floater.mass": "Mass of the body.",
    "floater.centre_of_mass": "Centre of mass, global coordinates at rest.",
    "floater.inertia": "Inertia about the centre of mass: [Ixx, Iyy, Izz] or [Ixx, Iyy, Izz, "
                       "Ixy, Ixz, Iyz]; positive definite.",
    "floater.reference_point": "Rotation centre of the six DOFs, global coordinates at rest.",
    "floater.radiation": "Radiation memory: `convolution` of the retardation kernel K(t) "
                         "with the velocity history, or `state-space` (the realisation stored "
                         "in the database by `floatmoor hydro fit-state-space`).",
    "floater.geometry": "Hull of the body, meshed for the BEM database; optional with "
                        "`hydro.source = \"imported\"` (the hydrostatics come from the "
                        "database), where it only carries `floater.drag` and the views' hull "
                        "(guide/hydro_databases.md).",
    "floater.geometry.kind": "`cylinder`, `semisubmersible` (columns and members) or `mesh` "
                             "(a hull mesh file).",
    "floater.geometry.diameter": "Diameter of a cylinder (`cylinder`).",
    "floater.geometry.height": "Height of a cylinder, bottom to top (`cylinder`).",
    "floater.geometry.draft": "Draft of a cylinder (`cylinder`); default the draft at which "
                              "it floats freely, mass / (water_density pi R^2).",
    "floater.geometry.file": "Hull mesh file, relative to the case file's folder and inside "
                             "it (`mesh`); checked and hashed on loading, read when the "
                             "database is built.",
    "floater.geometry.format": "Format of the mesh file (`mesh`); default from its "
                               "extension.",
    "floater.geometry.length_unit": "Length unit of the mesh file's coordinates (`mesh`).",
    "floater.geometry.position": "Offset added to the scaled mesh coordinates (`mesh`).",
    "floater.geometry.symmetry": "Symmetry planes the mesh file is the positive half of: "
                                 "`xz` (the file holds y >= 0), `yz` (x >= 0), or both "
                                 "(`mesh`).",
    "floater.geometry.columns": "Vertical columns of a semisubmersible; for a `mesh` hull, "
                                "drag elements only (not meshed).",
    "floater.geometry.columns[].x": "x of the column's axis.",
    "floater.geometry.columns[].y": "y of the column's axis.",
    "floater.geometry.columns[].diameter": "Diameter of the column.",
    "floater.geometry.columns[].z_top": "Elevation of the column's top.",
    "floater.geometry.columns[].z_bottom": "Elevation of the column's bottom.",
    "floater.geometry.columns[].heave_plate_diameter": "Diameter of a heave plate at the "
                                                       "column's bottom; with "
                                                       "`heave_plate_height`.",
    "floater.geometry.columns[].heave_plate_height": "Height of the heave plate above "
                                                     "`z_bottom`; with "
                                                     "`heave_plate_diameter`.",
    "floater.geometry.members": "Pontoons and braces (cylinders between two points); for a "
                                "`mesh` hull, drag elements only.",
    "floater.geometry.members[].start": "Start of the member's axis.",
    "floater.geometry.members[].end": "End of the member's axis, more than one diameter from "
                                      "its start.",
    "floater.geometry.members[].diameter": "Diameter of the member.",
    "floater.drag": "Morison drag on the columns and members (theory/floater.md); needs "
                    "columns or members.",
    # hydro
    "hydro": "The hydrodynamic database of the floater (`hydrodb/NAME.nc`): how `floatmoor "
             "hydro build` computes it with the BEM, or that it was imported "
             "(theory/hydrodynamics.md).",
    "hydro.frequency_ranges": "BEM frequencies as [first, last, count] triples, evenly "
                              "spaced; with or instead of `frequencies`.",
    "hydro.frequencies": "BEM frequencies, listed; with or instead of `frequency_ranges`.",
    "hydro.directions_deg": "Wave directions of the excitation, distinct and increasing.",
    "hydro.accept_failed_checks": "Database checks whose failure a run of this case "
                                  "accepts; a run refuses a database failing any other.",
    # waves
    "waves": "The sea of a coupled case (theory/environment.md).",
    # initial
    "initial": "The floater's displacement from its static equilibrium at t = 0 (a free "
               "decay); body and lines start at rest there.",
    "initial.surge": "Initial surge offset.",
    "initial.sway": "Initial sway offset.",
    "initial.heave": "Initial heave offset.",
    "initial.roll_deg": "Initial roll angle.",
    "initial.pitch_deg": "Initial pitch angle.",
    "initial.yaw_deg": "Initial yaw angle.",
    # wind
    "wind": "Rotor thrust of the NREL 5 MW turbine in a steady or turbulent wind "
            "(theory/environment.md).",
}

_CASE_DEFAULTS = {
    **{f"lines[].sections[].dynamic.{key}": f"the line's `dynamic.{key}`"
       for key in settings_of(DynamicSettings)},
    "motion.ramp_duration": "one period (the longest moving one); 0 for a table",
    "motion.phase_deg": "default 0 (every axis)",
    "floater.geometry": "required unless `hydro.source = \"imported\"`",
    "floater.geometry.draft": "from the mass",
    "floater.geometry.format": "from the file's extension",
    "floater.geometry.symmetry": "none",
    "floater.geometry.columns": "required for `semisubmersible`",
    "floater.geometry.members": "optional",
    "hydro.frequency_ranges": "one of the two (`bem`)",
    "hydro.frequencies": "one of the two (`bem`)",
    "hydro.directions_deg": "required (`bem`)",
    "hydro.accept_failed_checks": "none",
    "lines[].start": "one of `start`, `anchor`",
    "lines[].anchor": "one of `start`, `anchor`",
    "lines[].end": "one of `end`, `fairlead`",
    "lines[].fairlead": "one of `end`, `fairlead`",
    "lines[].type": "with `length`, or `sections`",
    "lines[].length": "with `type`, or `sections`",
    "lines[].sections": "or `type` and `length`",
    "lines[].sections[].end": "an implicit joint",
    "points": "optional",
    "lines": "required (optional with a `[floater]`)",
    "line_types": "required (optional with a `[floater]`)",
    "motion.file": "required (`table`); or the DOF tables (`body`)",
    **{f"motion.{dof}": "optional (`body`)" for dof in _DOF_UNITS},
}

_CASE_ALLOWED = {
    "floater.geometry.columns[].z_bottom": "> -water_depth and < z_top",
    "floater.geometry.columns[].heave_plate_diameter": "> the column's diameter",
    "floater.geometry.columns[].heave_plate_height": "> 0 and < z_top - z_bottom",
    "hydro.frequencies": "> 0; with the ranges, 2 to 2000 distinct",
    "hydro.frequency_ranges": "0 < first < last, count >= 2",
    "hydro.directions_deg": "within [-360, 360], distinct, increasing",
    "floater.geometry.columns": ">= 1 entries (`semisubmersible`)",
}

_CASE_TYPES = {
    "floater.inertia": "array of 3 or 6 numbers",
    "hydro.frequencies": "array of numbers",
    "hydro.directions_deg": "array of numbers",
}

#: The keys of a case file.
CASE = KeyDocs(_CASE, _CASE_DEFAULTS, _CASE_ALLOWED, _CASE_TYPES)
