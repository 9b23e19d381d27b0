"""A floatmoor case -> a MoorDyn v2 deck (:class:`~floatmoor.io.moordyn.deck.Deck`) and the
notes saying what MoorDyn cannot represent.

Every section is a MoorDyn line, its points (section joints included) MoorDyn points: fixed ->
Fixed, body -> Coupled, free -> Free with mass, volume, CdA and Ca. Line types by
:mod:`.line_types`; a section's internal damping ratio becomes MoorDyn's ``-zeta_md`` for its
segment count (one MoorDyn type per floatmoor type and BA, named ``NAME``, ``NAME_2``, ...).
NumSegs = elements x order of the section's DG discretisation (its nodal intervals). The internal
damping coefficient c_int = 2 zeta L sqrt(EA m) / pi of a section takes L = the section's own
length (its ratio zeta is that of the section's first axial mode, as the DG sections are built:
CableProperties.from_section). dtM is the smallest DG time step of the sections
(CableProperties.time_step, the function the DG line steps with: the axial wave, explicit
internal damping and explicit seabed contact, ``max_time_step``) and
:data:`SEABED_STEP_FRACTION` of the RK2 limit of MoorDyn's explicit seabed spring (tScheme
RK2 is written). The deck's title is the case's title; the simulation's output interval is
MoorDyn's dtOut (MoorDyn has no run length: its driver steps it).

Free points are written at the system's static equilibrium (floatmoor's statics,
:func:`floatmoor.mooring.statics_solver.case_statics`, body points at rest): MoorDyn starts its
initial-condition solve from the deck's positions and its catenaries between them, so from the
equilibrium it settles at once to its own discretisation's; the case's positions are only the
statics' initial guesses. A system without a static equilibrium keeps the case's positions,
with a note.

The solvers' answers (the sections' discretisations, their time step, the statics) are not
computed here: file formats sit below the models
(docs/development.md#1-package-layout-and-import-order), so :func:`export_case` takes them as
:class:`DeckNumerics`, which
:func:`floatmoor.mooring.deck_numerics.deck_numerics` computes::

    export_case(case, deck_numerics(case))
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from floatmoor.io.moordyn.deck import (POINT_COUPLED, POINT_FIXED, POINT_FREE, Deck, DeckLine,
                                       DeckLineType, DeckOption, DeckPoint)
from floatmoor.io.moordyn.line_types import (friction_damping, moordyn_line_type,
                                             seabed_to_moordyn)

__all__ = ["DeckNumerics", "ExportResult", "export_case", "SEABED_STEP_FRACTION"]

#: dtM is at most this fraction of the RK2 stability limit 2 / |lambda| of MoorDyn's explicit
#: seabed spring-damper, |lambda| = omega (xi + sqrt(1 + xi^2)), omega^2 = kBot d / m: half the
#: limit, the margin the peer harness's time steps keep (tests/io/moordyn_runner.py users).
SEABED_STEP_FRACTION = 0.5
_KINDS = {"fixed": POINT_FIXED, "body": POINT_COUPLED, "free": POINT_FREE}
_SAME_VALUE_RTOL = 1e-12
#: Characters a MoorDyn line type name cannot hold (it reads whitespace-separated columns).
_TYPE_NAME_CHARACTERS = re.compile(r"[^A-Za-z0-9_.+-]")


@dataclass(frozen=True)
class DeckNumerics:
    """What floatmoor's solvers say about a case, as its deck needs it
    (:func:`floatmoor.mooring.deck_numerics.deck_numerics`)."""

    #: The case's sections, in order, each with the DG discretisation it runs with, stepped
    #: explicitly (MoorDyn's segments follow them).
    sections: tuple[Any, ...]
    #: The smallest DG time step of those sections [s].
    time_step: float
    #: The free points' positions at the static equilibrium (None: no free point, or no
    #: statics to solve).
    free_positions: Mapping[str, tuple[float, float, float]] | None = None
    #: Why the statics found no equilibrium (the solver's message on one line), or None.
    statics_failure: str | None = None


@dataclass
class ExportResult:
    """The deck and the notes on what it does not represent."""

    deck: Deck
    notes: list[str] = field(default_factory=list)


def _segments(section: Any) -> int:
    return int(section.dynamic.elements * section.dynamic.order)


def _free_positions(case: Any, numerics: DeckNumerics, notes: list[str]
                    ) -> Mapping[str, tuple[float, float, float]]:
    """The free points' positions to write: the static equilibrium when there is one (a note
    says so), the case's otherwise (a note says why)."""
    if not any(p.kind == "free" for p in case.points):
        return {}
    if numerics.statics_failure is not None:
        notes.append("free points: at the case's positions (no static equilibrium: "
                     + numerics.statics_failure + ")")
        return {}
    if numerics.free_positions is None:
        return {}
    notes.append("free points: at floatmoor's static equilibrium (the case's positions are "
                 "its initial guesses)")
    return numerics.free_positions


def export_case(case: Any, numerics: DeckNumerics) -> ExportResult:
    """The MoorDyn deck of ``case`` (a :class:`floatmoor.case.schema.Case`) and the notes on
    what MoorDyn cannot represent (also to be written into the deck's comments), with the
    solvers' ``numerics`` of the case (:func:`floatmoor.mooring.deck_numerics.deck_numerics`).

    What ``floatmoor export moordyn`` writes (docs/guide/mooring_systems.md#moordyn-decks):
    the same lines, points, seabed and water in MoorDyn v2's terms, so that MoorDyn can be
    run on the case as a peer (the mapping: :mod:`floatmoor.io.moordyn.exporter`). Nothing
    is written here: the caller writes the result's deck.

    Parameters
    ----------
    case
        A validated case (:class:`floatmoor.case.schema.Case`).
    numerics
        The sections' DG discretisations and time step and the free points' static
        equilibrium for ``case`` (:class:`DeckNumerics`).

    Returns
    -------
    ExportResult
        The deck (its dtM [s] the smaller of the sections' DG step and
        :data:`SEABED_STEP_FRACTION` of MoorDyn's seabed limit; dtOut the case's output
        interval [s]) and the notes, the source case first.
    """
    notes: list[str] = []
    env, bed = case.environment, case.seabed
    line_of = {line.name: line for line in case.lines}
    numbers = {p.name: i for i, p in enumerate(case.points, start=1)}
    at = _free_positions(case, numerics, notes)
    sections = numerics.sections
    points = tuple(DeckPoint(number=numbers[p.name], attachment=_KINDS[p.kind],
                             position=at.get(p.name,  # type: ignore[arg-type]
                                             tuple(float(c) for c in p.position)),
                             mass=p.mass, volume=p.volume, drag_area=p.drag_area,
                             added_mass_coefficient=p.added_mass_coefficient,
                             attachment_text=p.name) for p in case.points)

    types: dict[tuple[str, float], DeckLineType] = {}
    count: dict[str, int] = {}
    deck_lines: list[DeckLine] = []
    used_names: set[str] = set()
    for k, sec in enumerate(sections, start=1):
        lt = sec.line_type
        n = _segments(sec)
        # floatmoor's c_int = 2 zeta L sqrt(EA m) / pi takes L = the section's own length
        # (CableProperties.from_section); MoorDyn's -zeta_md gives c_int = zeta_md (L / N)
        # sqrt(EA m) on the same L and its N segments: zeta_md = 2 zeta N / pi, L cancels (so
        # sections of one type and N share one MoorDyn type, whatever their lengths)
        ba = -2.0 * lt.internal_damping_ratio * n / math.pi
        key = (lt.name, ba)
        if key not in types:
            base = _TYPE_NAME_CHARACTERS.sub("_", lt.name) or "type"
            if base != lt.name and base not in used_names:
                notes.append(f"line type '{lt.name}' is MoorDyn's '{base}' (a MoorDyn name is "
                             "one word)")
            count[base] = count.get(base, 0) + 1
            name = base if count[base] == 1 else f"{base}_{count[base]}"
            while name in used_names:  # a floatmoor type may already be called NAME_2
                count[base] += 1
                name = f"{base}_{count[base]}"
            used_names.add(name)
            md = moordyn_line_type(lt, ba)
            types[key] = DeckLineType(
                name=name, diameter=md.diameter, mass_per_length=md.mass_per_length,
                axial_stiffness=md.axial_stiffness, internal_damping=ba or 0.0,
                bending_stiffness=0.0, normal_drag_coefficient=md.normal_drag_coefficient,
                added_mass_coefficient=md.added_mass_coefficient,
                tangential_drag_coefficient=md.tangential_drag_coefficient,
                tangential_added_mass_coefficient=md.tangential_added_mass_coefficient)
        where = sec.line if len(line_of[sec.line].sections) == 1 else \
            f"{sec.line} section {sec.index + 1}"
        deck_lines.append(DeckLine(number=k, line_type=types[key].name,
                                   start=numbers[sec.start], end=numbers[sec.end],
                                   length=sec.length, segments=n, outputs="-"))
        notes.append(f"MoorDyn line {k}: floatmoor {where}")
    for line in case.lines:
        if line.model != "dynamic":
            notes.append(f"line {line.name} is {line.model} in floatmoor; MoorDyn models every "
                         "line dynamically (lumped masses)")

    first = sections[0].line_type
    k_bot, c_bot = seabed_to_moordyn(bed.stiffness, bed.damping_ratio, first)
    other = {lt.name: seabed_to_moordyn(bed.stiffness, bed.damping_ratio, lt)
             for lt in (s.line_type for s in sections)}
    if any(abs(k - k_bot) > _SAME_VALUE_RTOL * k_bot or abs(c - c_bot) > _SAME_VALUE_RTOL
           * max(c_bot, 1e-300) for k, c in other.values()):
        notes.append(f"seabed: MoorDyn has one kBot and cBot per unit of its diameter; those "
                     f"of line type {first.name} are written (exact for it only)")
    friction: tuple[DeckOption, ...] = ()
    if bed.friction_coefficient > 0.0:
        # FricDamp saturates MoorDyn's friction at the slip speed on a resting node of the
        # first section that sinks (a buoyant one never rests on the seabed)
        resting = [s for s in sections if s.line_type.weight_in_water(env) > 0.0]
        if resting:
            sec = resting[0]
            where = sec.line if len(line_of[sec.line].sections) == 1 else \
                f"{sec.line} section {sec.index + 1}"
            fric = friction_damping(sec.line_type.weight_in_water(env), sec.length,
                                    _segments(sec), bed.slip_speed)
            friction = (DeckOption("FricDamp", repr(fric)),
                        DeckOption("StatDynFricScale", "1.0"))
            notes.append("friction: floatmoor's smoothed Coulomb friction is MoorDyn's "
                         "FrictionCoefficient with FricDamp saturating at the slip speed on a "
                         f"resting node of {where} (MoorDyn: min(mu FricDamp |v|, mu |F_z|), "
                         "linear ramp per node)")
        else:
            notes.append("friction: no section sinks, so none rests on the seabed; FricDamp "
                         "is MoorDyn's default")
    if any(env.current_velocity):
        notes.append("current: not exported (MoorDyn takes currents from its own files)")
    if getattr(case, "floater", None) is not None:
        notes.append("floater: not exported; its points are Coupled points, driven by the "
                     "program coupled to MoorDyn")
    if getattr(case, "motion", None) is not None:
        notes.append(f"motion ({case.motion.kind}): not exported; drive the Coupled points "
                     "with it through MoorDyn's coupling (Step)")

    dt = numerics.time_step
    for sec in sections:
        lt = sec.line_type
        omega = math.sqrt(bed.stiffness * lt.diameter / lt.mass_per_length)
        xi = bed.damping_ratio
        dt = min(dt, SEABED_STEP_FRACTION * 2.0 / (omega * (xi + math.sqrt(1.0 + xi * xi))))
    options = (
        DeckOption("writeLog", "0"),
        DeckOption("dtM", repr(dt)),
        DeckOption("tScheme", "RK2"),
        DeckOption("dtOut", repr(float(case.simulation.output_interval))),
        DeckOption("g", repr(float(env.gravity))),
        DeckOption("WtrDnsty", repr(float(env.water_density))),
        DeckOption("WtrDpth", repr(float(env.water_depth))),
        DeckOption("kBot", repr(k_bot)),
        DeckOption("cBot", repr(c_bot)),
        DeckOption("FrictionCoefficient", repr(float(bed.friction_coefficient))),
        *friction,
    )
    notes.insert(0, f"dtM: the smallest floatmoor DG time step of the sections and "
                 f"{SEABED_STEP_FRACTION:g} x MoorDyn's RK2 limit of the seabed spring")
    notes.insert(1, f"duration {case.simulation.duration:g} s: not exported (MoorDyn has no run "
                 "length; its driver steps it); dtOut is the output interval")
    notes.insert(0, f"written by floatmoor export moordyn from {case.source}")
    deck = Deck(source="", title=case.title.replace("---", "- - -").replace("\n", " "),
                line_types=tuple(types.values()), points=points, lines=tuple(deck_lines),
                options=options)
    return ExportResult(deck=deck, notes=notes)
