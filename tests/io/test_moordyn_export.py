"""``export moordyn``: the written deck's numbers against the case's (line types through the
mapping, points, lines, options), and dtM from the DG line's own time step."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.io.moordyn.exporter import SEABED_STEP_FRACTION
from floatmoor.io.moordyn.line_types import (friction_damping, moordyn_line_type,
                                             seabed_to_moordyn, volume_diameter)
from floatmoor.io.moordyn.parser import read_deck
from floatmoor.mooring.dg.line import CableProperties, DynamicLine
from floatmoor.mooring.dg.system import DynamicSystem
from floatmoor.mooring.statics_solver import case_statics
from tests.conftest import ACCURACY_DEFAULT, LINDAHL_CASE
from tests.io.moordyn_decks import REPO, export_file, exported

SYSTEM = REPO / "tests" / "data" / "systems" / "clump_buoy.toml"
LINDAHL = REPO / "cases" / "lindahl" / "lindahl_r0.20_T1.25.toml"
#: The clump-and-buoy system made dynamic, with internal damping, friction and different
#: numerics per section (so that every mapped number is non-trivial).
SYSTEM_OVERRIDES = ('lines.*.model="dynamic"', "line_types.chain.internal_damping_ratio=0.05",
                    "line_types.rope.internal_damping_ratio=0.02",
                    "seabed.friction_coefficient=0.4", "seabed.slip_speed=0.02",
                    "lines.*.sections.1.dynamic.elements=7",
                    "lines.*.sections.1.dynamic.order=3")
#: Relative accuracy of values computed two ways (c_int from MoorDyn's -zeta and from the
#: section; kBot d_v against K d): a few ulps.
TWO_WAYS_RTOL = 1e-14


def _moordyn_seabed_limit(case, line_type) -> float:
    omega = math.sqrt(case.seabed.stiffness * line_type.diameter / line_type.mass_per_length)
    xi = case.seabed.damping_ratio
    return SEABED_STEP_FRACTION * 2.0 / (omega * (xi + math.sqrt(1.0 + xi * xi)))


def test_deck_numbers_are_the_cases(tmp_path):
    case = load_case(SYSTEM, SYSTEM_OVERRIDES)
    deck = read_deck(export_file(case, tmp_path / "system.dat"))
    names = [p.name for p in case.points]
    kinds = {"fixed": "fixed", "body": "coupled", "free": "free"}
    # points: every point of the case, in order, with its loads; the free ones at the statics
    assert [p.number for p in deck.points] == list(range(1, len(names) + 1))
    statics = case_statics(case).solve()
    for dp, p in zip(deck.points, case.points):
        at = tuple(statics.position(p.name)) if p.kind == "free" else p.position
        assert (dp.attachment, dp.position) == (kinds[p.kind], at)
        assert (dp.mass, dp.volume, dp.drag_area, dp.added_mass_coefficient) == (
            p.mass, p.volume, p.drag_area, p.added_mass_coefficient)
    # lines: one per section, between the section's points, N = elements x order of the
    # numerics the run takes (given, or the accuracy's choice)
    run = {(s.line, s.index): s.settings
           for s in DynamicSystem.from_case(case, settle=False).sections}
    types = {t.name: t for t in deck.line_types}
    assert len(deck.lines) == len(case.sections) == 3
    for dl, sec in zip(deck.lines, case.sections):
        assert (names[dl.start - 1], names[dl.end - 1]) == (sec.start, sec.end)
        assert dl.length == sec.length
        st = run[sec.line, sec.index]
        assert dl.segments == st.elements * st.order
        t = types[dl.line_type]
        md = moordyn_line_type(sec.line_type, t.internal_damping)
        assert (t.diameter, t.mass_per_length, t.axial_stiffness, t.normal_drag_coefficient,
                t.added_mass_coefficient, t.tangential_drag_coefficient,
                t.tangential_added_mass_coefficient) == (
            md.diameter, md.mass_per_length, md.axial_stiffness, md.normal_drag_coefficient,
            md.added_mass_coefficient, md.tangential_drag_coefficient,
            md.tangential_added_mass_coefficient)
        assert t.bending_stiffness == 0.0
        # MoorDyn's c_int = zeta_md (L/N) sqrt(EA m) is floatmoor's on the section's length
        lt = sec.line_type
        c_md = -t.internal_damping * sec.length / dl.segments * math.sqrt(
            lt.axial_stiffness * lt.mass_per_length)
        c_fm = CableProperties.from_section(sec, case.environment, case.seabed).internal_damping
        assert c_md == pytest.approx(c_fm, rel=TWO_WAYS_RTOL) and c_fm > 0.0
    # the two chain sections (same type, same N) share a MoorDyn type; the rope has its own
    assert [dl.line_type for dl in deck.lines] == ["chain", "rope", "chain"]
    # options
    opt = {o.key: o.value for o in deck.options}
    env, bed, chain = case.environment, case.seabed, case.sections[0].line_type
    assert (float(opt["g"]), float(opt["WtrDnsty"]), float(opt["WtrDpth"])) == (
        env.gravity, env.water_density, env.water_depth)
    k_bot, c_bot = seabed_to_moordyn(bed.stiffness, bed.damping_ratio, chain)
    assert (float(opt["kBot"]), float(opt["cBot"])) == (k_bot, c_bot)
    assert float(opt["kBot"]) * volume_diameter(chain) == pytest.approx(
        bed.stiffness * chain.diameter, rel=TWO_WAYS_RTOL)  # the same force per length
    assert float(opt["FrictionCoefficient"]) == 0.4
    first = case.sections[0]
    run = {(s.line, s.index): s.settings  # the numerics the run takes (given, or chosen)
           for s in DynamicSystem.from_case(case, settle=False).sections}
    numerics = [run[s.line, s.index] for s in case.sections]
    assert float(opt["FricDamp"]) == friction_damping(
        chain.weight_in_water(env), first.length, numerics[0].elements * numerics[0].order, 0.02)
    assert (opt["tScheme"], float(opt["dtOut"])) == ("RK2", case.simulation.output_interval)
    steps = [CableProperties.from_section(s, env, bed).time_step(  # (the explicit step)
        replace(st, time_integration="explicit")) for s, st in zip(case.sections, numerics)]
    seabed = [_moordyn_seabed_limit(case, s.line_type) for s in case.sections]
    assert float(opt["dtM"]) == min(steps + seabed)
    assert deck.title == case.title


def test_dtm_is_the_dg_lines_own_step_with_explicit_contact_and_a_cap():
    def dtm(*overrides):
        case = load_case(LINDAHL, overrides)
        line = case.lines[0]
        dg = DynamicLine(CableProperties.from_case(line, case.environment, case.seabed),
                         line.dynamic, np.asarray(line.anchor), np.asarray(line.fairlead))
        return float(exported(case).deck.option("dtM").value), dg.time_step, case

    # implicit contact: MoorDyn's own seabed limit is the smaller
    implicit, dg, case = dtm()
    assert implicit == _moordyn_seabed_limit(case, case.lines[0].line_type) < dg
    # explicit contact at a small cfl: the DG step with its contact limit is the smaller
    explicit, dg, _ = dtm('lines.*.dynamic.seabed_contact="explicit"', "lines.*.dynamic.cfl=0.2")
    assert explicit == dg < implicit
    capped, dg, _ = dtm("lines.*.dynamic.max_time_step=1e-6")
    assert capped == dg == 1e-6


def test_no_friction_writes_no_fricdamp_and_notes_what_moordyn_does_not_model():
    case = load_case(SYSTEM)  # quasi-static, no friction
    result = exported(case)
    keys = [o.key for o in result.deck.options]
    assert "FrictionCoefficient" in keys and "FricDamp" not in keys
    notes = "\n".join(result.notes)
    assert "line line1 is quasi-static in floatmoor" in notes
    assert "MoorDyn line 2: floatmoor line1 section 2" in notes
    motion = exported(load_case(LINDAHL)).notes
    assert any(n.startswith("motion (circular): not exported") for n in motion)


def test_a_line_type_name_moordyn_cannot_read_is_made_one_word(tmp_path):
    text = SYSTEM.read_text().replace("[line_types.rope]", '[line_types."poly rope"]') \
        .replace('type = "rope"', 'type = "poly rope"')
    path = tmp_path / "names.toml"
    path.write_text(text)
    result = exported(load_case(path))
    assert [t.name for t in result.deck.line_types] == ["chain", "poly_rope"]
    assert "line type 'poly rope' is MoorDyn's 'poly_rope' (a MoorDyn name is one word)" \
        in result.notes


def test_free_points_are_written_at_the_static_equilibrium_with_a_note():
    """MoorDyn starts its initial-condition solve from the deck's positions: the exporter
    writes the free points where floatmoor's statics put them (here the clump 1.7 m above the
    case's guess), and says so; fixed and body points stay where the case has them."""
    case = load_case(SYSTEM)
    result = exported(case)
    statics = case_statics(case).solve()
    moved = 0.0
    for dp, p in zip(result.deck.points, case.points):
        if p.kind == "free":
            np.testing.assert_array_equal(dp.position, statics.position(p.name))
            moved = max(moved, float(np.linalg.norm(np.subtract(dp.position, p.position))))
        else:
            assert dp.position == p.position
    assert moved > 0.1  # the case's guesses are not the equilibrium: the test can fail
    assert any("free points: at floatmoor's static equilibrium" in n for n in result.notes)


def test_without_a_static_equilibrium_free_points_keep_the_cases_positions(monkeypatch):
    """When the statics fail (no equilibrium), the deck keeps the case's positions and the
    note says why, instead of refusing to export."""
    from floatmoor.errors import SolverError
    from floatmoor.mooring import deck_numerics

    def no_equilibrium(case):
        raise SolverError("point 'buoy': no equilibrium (residual 1e3 N)")

    monkeypatch.setattr(deck_numerics, "case_statics", no_equilibrium)
    case = load_case(SYSTEM)
    result = exported(case)
    assert [dp.position for dp in result.deck.points] == [p.position for p in case.points]
    assert any("case's positions (no static equilibrium: point 'buoy'" in n
               for n in result.notes)


def test_independent_line_exports_the_numerics_it_runs_with(tmp_path):
    """A line left to the accuracy: NumSegs = elements x order of the line's own choice
    (DynamicLine.from_case), not a line system's sections'."""
    case = load_case(LINDAHL_CASE, ACCURACY_DEFAULT)
    ln = case.lines[0]
    st = DynamicLine.from_case(ln, case.environment, case.seabed).settings
    deck = read_deck(export_file(case, tmp_path / "lindahl.dat"))
    assert deck.lines[0].segments == st.elements * st.order == 36
