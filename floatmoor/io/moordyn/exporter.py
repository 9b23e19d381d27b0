"""A floatmoor case -> a MoorDyn v2 deck (:class:`~floatmoor.io.moordyn.deck.Deck`) and the
notes saying what MoorDyn cannot represent.

Every section is a MoorDyn line, its points (section joints included) MoorDyn points: fixed ->
Fixed, body -> Coupled, free -> Free with mass, volume, CdA and Ca. Line types by
:mod:`.line_types`; a section's internal damping ratio becomes MoorDyn's ``-zeta_md`` for its
segment count (one MoorDyn type per floatmoor type and BA, named ``NAME``, ``NAME_2``, ...).
NumSegs = elements x order of the section's DG discretisation (its nodal intervals). dtM is the
smallest DG time step of the sections (cfl x the SSP-RK3 limit of the axial wave, as
floatmoor.mooring.dg.line computes it with implicit internal damping) and of MoorDyn's explicit
seabed spring (:data:`SEABED_STEP_FRACTION`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from floatmoor.io.moordyn.deck import (POINT_COUPLED, POINT_FIXED, POINT_FREE, Deck, DeckLine,
                                       DeckLineType, DeckOption, DeckPoint)
from floatmoor.io.moordyn.line_types import (friction_damping, internal_damping_coefficient,
                                             moordyn_line_type, seabed_to_moordyn)
from floatmoor.mooring.dg.reference import STABLE_STEP_FACTOR

__all__ = ["ExportResult", "export_case", "SEABED_STEP_FRACTION"]

#: dtM is at most this fraction of the RK2 stability limit 2 / |lambda| of MoorDyn's explicit
#: seabed spring-damper, |lambda| = omega (xi + sqrt(1 + xi^2)), omega^2 = kBot d / m: half the
#: limit, the margin the peer harness's time steps keep (tests/peer/moordyn_runner.py users).
SEABED_STEP_FRACTION = 0.5
_KINDS = {"fixed": POINT_FIXED, "body": POINT_COUPLED, "free": POINT_FREE}
_SAME_VALUE_RTOL = 1e-12


@dataclass
class ExportResult:
    """The deck and the notes on what it does not represent."""

    deck: Deck
    notes: list[str] = field(default_factory=list)


def _segments(section: Any) -> int:
    return int(section.dynamic.elements * section.dynamic.order)


def _dg_step(section: Any) -> float:
    st, lt = section.dynamic, section.line_type
    h = section.length / st.elements
    return st.cfl * STABLE_STEP_FACTOR[st.order] * h / lt.axial_wave_speed


def export_case(case: Any) -> ExportResult:
    """The MoorDyn deck of ``case`` (a :class:`floatmoor.case.schema.Case`) and the notes on
    what MoorDyn cannot represent (also to be written into the deck's comments)."""
    notes: list[str] = []
    env, bed = case.environment, case.seabed
    sections = tuple(case.sections)
    line_of = {line.name: line for line in case.lines}

    numbers = {p.name: i for i, p in enumerate(case.points, start=1)}
    points = tuple(DeckPoint(number=numbers[p.name], attachment=_KINDS[p.kind],
                             position=tuple(float(c) for c in p.position),  # type: ignore
                             mass=p.mass, volume=p.volume, drag_area=p.drag_area,
                             added_mass_coefficient=p.added_mass_coefficient,
                             attachment_text=p.name) for p in case.points)

    types: dict[tuple[str, float], DeckLineType] = {}
    count: dict[str, int] = {}
    deck_lines: list[DeckLine] = []
    for k, sec in enumerate(sections, start=1):
        lt = sec.line_type
        n = _segments(sec)
        c_int = internal_damping_coefficient(lt.internal_damping_ratio, sec.length,
                                             lt.axial_stiffness, lt.mass_per_length)
        ba = -c_int * n / (sec.length * math.sqrt(lt.axial_stiffness * lt.mass_per_length))
        key = (lt.name, ba)
        if key not in types:
            count[lt.name] = count.get(lt.name, 0) + 1
            name = lt.name if count[lt.name] == 1 else f"{lt.name}_{count[lt.name]}"
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
    fric = friction_damping(first.weight_in_water(env), sections[0].length,
                            _segments(sections[0]), bed.slip_speed)
    if bed.friction_coefficient > 0.0:
        notes.append("friction: floatmoor's smoothed Coulomb friction is MoorDyn's "
                     "FrictionCoefficient with FricDamp saturating at the slip speed on a "
                     f"resting node of {sections[0].line} (MoorDyn: min(mu FricDamp |v|, "
                     "mu |F_z|), linear ramp per node)")
    if any(env.current_velocity):
        notes.append("current: not exported (MoorDyn takes currents from its own files)")
    if getattr(case, "floater", None) is not None:
        notes.append("floater: not exported; its points are Coupled points, driven by the "
                     "program coupled to MoorDyn")
    if getattr(case, "motion", None) is not None:
        notes.append(f"motion ({case.motion.kind}): not exported; drive the Coupled points "
                     "with it through MoorDyn's coupling (Step)")

    dt = min(_dg_step(s) for s in sections)
    for sec in sections:
        lt = sec.line_type
        omega = math.sqrt(bed.stiffness * lt.diameter / lt.mass_per_length)
        xi = bed.damping_ratio
        dt = min(dt, SEABED_STEP_FRACTION * 2.0 / (omega * (xi + math.sqrt(1.0 + xi * xi))))
    options = (
        DeckOption("writeLog", "0"),
        DeckOption("dtM", repr(dt)),
        DeckOption("g", repr(float(env.gravity))),
        DeckOption("WtrDnsty", repr(float(env.water_density))),
        DeckOption("WtrDpth", repr(float(env.water_depth))),
        DeckOption("kBot", repr(k_bot)),
        DeckOption("cBot", repr(c_bot)),
        DeckOption("FrictionCoefficient", repr(float(bed.friction_coefficient))),
        DeckOption("FricDamp", repr(fric)),
        DeckOption("StatDynFricScale", "1.0"),
    )
    notes.insert(0, f"dtM: the smallest floatmoor DG time step of the sections and "
                 f"{SEABED_STEP_FRACTION:g} x MoorDyn's RK2 limit of the seabed spring")
    deck = Deck(source="", title=f"floatmoor case: {case.title}".replace("---", "- - -"),
                line_types=tuple(types.values()), points=points, lines=tuple(deck_lines),
                options=options)
    return ExportResult(deck=deck, notes=notes)
