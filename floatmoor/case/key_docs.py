"""What the tables of case files mean, for the case-file reference.

Every key of a case or study file is declared with :func:`floatmoor.case.setting.setting`
(``[campaign]`` and study files in a :class:`~floatmoor.case.setting.SettingTable`) and
carries its own description and the wording of anything its reader computes (default,
bounds, an array's size). What is here: each table's own description (a table is read by
:meth:`~floatmoor.case.reader.TableReader.table` / ``tables``, not declared, e.g. ``lines``,
``floater.geometry.columns``) and the wording of when it is required, by generic path
(``lines[].dynamic``, ``line_types.<name>``): ``defaults`` words a default computed from other
values, ``allowed`` a range that depends on other values, ``types`` an array whose length
does. The tests fail on a key the readers ask for that has no description (here or in its
declaration), on one described in both, and on a description of a key no reader asks for.
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
    """The six ``[motion.DOF]`` tables of a harmonic body motion (their keys are declared on
    floatmoor.case.schema.HarmonicTranslation and HarmonicRotation)."""
    return {f"motion.{dof}": (f"Harmonic {dof} of the body, "
                              f"{'a translation' if unit == 'm' else 'a rotation about the reference point'}"
                              " (`kind = \"body\"`); a DOF without its table does not move.")
            for dof, unit in _DOF_UNITS.items()}


_CASE = {
    "": "The keys outside any table.",
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
    # lines
    "lines": "The mooring lines, each from a start point to an end point, one line type or a "
             "series of sections.",
    "lines[].sections": "The line's sections from start to end, each of one line type; "
                        "instead of `type` and `length`.",
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
    **_body_dofs(),
    # floater
    "floater": "A floating body coupled to its lines (theory/floater.md); a case with a "
               "floater has no `[motion]`.",
    "floater.geometry": "Hull of the body, meshed for the BEM database; optional with "
                        "`hydro.source = \"imported\"` (the hydrostatics come from the "
                        "database), where it only carries `floater.drag` and the views' hull "
                        "(guide/hydro_databases.md).",
    "floater.geometry.columns": "Vertical columns of a semisubmersible; for a `mesh` hull, "
                                "drag elements only (not meshed).",
    "floater.geometry.members": "Pontoons and braces (cylinders between two points); for a "
                                "`mesh` hull, drag elements only.",
    "floater.drag": "Morison drag on the columns and members (theory/floater.md); needs "
                    "columns or members.",
    # hydro
    "hydro": "The hydrodynamic database of the floater (`hydrodb/NAME.nc`): how `floatmoor "
             "hydro build` computes it with the BEM, or that it was imported "
             "(theory/hydrodynamics.md).",
    # waves
    "waves": "The sea of a coupled case (theory/environment.md).",
    # initial
    "initial": "The floater's displacement from its static equilibrium at t = 0 (a free "
               "decay); body and lines start at rest there.",
    # wind
    "wind": "Rotor thrust of the NREL 5 MW turbine in a steady or turbulent wind "
            "(theory/environment.md).",
}

#: Defaults computed from other values: a section's dynamic numerics (its line's), and when
#: the tables (not declared as settings) are required.
_CASE_DEFAULTS = {
    **{f"lines[].sections[].dynamic.{key}": f"the line's `dynamic.{key}`"
       for key in settings_of(DynamicSettings)},
    "floater.geometry": "required unless `hydro.source = \"imported\"`",
    "floater.geometry.columns": "required for `semisubmersible`",
    "floater.geometry.members": "optional",
    "lines[].sections": "or `type` and `length`",
    "points": "optional",
    "lines": "required (optional with a `[floater]`)",
    "line_types": "required (optional with a `[floater]`)",
    **{f"motion.{dof}": "optional (`body`)" for dof in _DOF_UNITS},
}

_CASE_ALLOWED = {
    "floater.geometry.columns": ">= 1 entries (`semisubmersible`)",
}

#: The keys of a case file.
CASE = KeyDocs(_CASE, _CASE_DEFAULTS, _CASE_ALLOWED)
