"""``floatmoor import orcaflex``: OrcaFlex text data files (hand-written fixtures in
tests/data/orcaflex/) -> case files whose statics are those of a hand-built equivalent case
(exactly) and of MoorPy's catenary; exact unit conversions; every class of malformed input a
one-line status-2 error with nothing written (docs/guide/mooring_systems.md#orcaflex-models).
"""

from __future__ import annotations

import math
import os
import tomllib
from pathlib import Path

import pytest

from floatmoor.case.limits import parse_toml
from floatmoor.case.load import parse_case
from floatmoor.cli import main
from floatmoor.errors import CaseError
from floatmoor.io.orcaflex.importer import import_model
from floatmoor.io.orcaflex.reader import MAX_MODEL_FILE_BYTES, parse_model, read_model
from floatmoor.mooring.static_strength import static_line_loads
from tests.cli.test_output_files import tmpfs  # noqa: F401 (a fixture)

MODELS = Path(__file__).parents[1] / "data" / "orcaflex"
#: Agreement asked of an imported case's static tensions with MoorPy: 0.5 %, the margin of an
#: OrcaFlex model's own FE statics against the catenary. Both solve the same elastic
#: catenary, so it is far tighter when the mapping is right (observed 0 on the single chain,
#: 4e-10 on the three lines); the unit conversions are checked exactly on their own.
MOORPY_RTOL = 5e-3


def _case(name: str):
    path = MODELS / name
    result = import_model(read_model(path), str(path))
    return parse_case(parse_toml(result.text, "imported"), source="imported",
                      text=result.text), result


def _tensions(case) -> dict[str, float]:
    return {load.line: load.fairlead_tension for load in static_line_loads(case)}


def test_units_are_converted_exactly():
    case, _ = _case("single_chain.yml")
    chain = case.line_types["Chain"]
    assert chain.mass_per_length == 0.12 * 1000.0  # te/m -> kg/m
    assert chain.axial_stiffness == 6.0e5 * 1000.0  # kN -> N
    assert chain.diameter == 0.15
    assert chain.material_density == 120.0 / (math.pi * 0.15 ** 2 / 4.0)
    assert chain.tangential_drag_coefficient == math.pi * 1.15
    assert case.environment.water_density == 1.025 * 1000.0
    assert case.environment.gravity == 9.81 and case.environment.water_depth == 100.0
    assert case.seabed.stiffness == 100.0 * 1000.0  # kN/m/m^2 -> Pa/m
    assert case.seabed.damping_ratio == 0.5 and case.seabed.friction_coefficient == 0.5
    assert case.simulation.duration == 100.0 and case.simulation.output_interval == 0.5
    anchor = next(p for p in case.points if p.name == "Mooring1_A")
    assert tuple(anchor.position) == (-500.0, 0.0, -100.0)  # Anchored: z above the seabed


SINGLE_CHAIN_BY_HAND = f"""
title = "by hand"
[environment]
water_density = 1025.0
water_depth = 100.0
gravity = 9.81
[seabed]
stiffness = 1.0e5
damping_ratio = 0.5
friction_coefficient = 0.5
slip_speed = 0.01
[line_types.Chain]
mass_per_length = 120.0
axial_stiffness = 6.0e8
diameter = 0.15
material_density = {120.0 / (math.pi * 0.15 ** 2 / 4.0)!r}
normal_drag_coefficient = 2.4
tangential_drag_coefficient = {math.pi * 1.15!r}
added_mass_coefficient = 1.0
[[points]]
name = "anchor"
kind = "fixed"
position = [-500.0, 0.0, -100.0]
[[points]]
name = "fairlead"
kind = "fixed"
position = [0.0, 0.0, -10.0]
[[lines]]
name = "Mooring1"
start = "anchor"
end = "fairlead"
model = "dynamic"
sections = [{{ type = "Chain", length = 550.0 }}]
[lines.quasi_static]
seabed_friction = false
[simulation]
duration = 100.0
output_interval = 0.5
"""


def test_single_chain_statics_equal_a_hand_built_case_and_moorpy():
    case, result = _case("single_chain.yml")
    by_hand = parse_case(parse_toml(SINGLE_CHAIN_BY_HAND, "hand"), source="hand",
                         text=SINGLE_CHAIN_BY_HAND)
    imported, expected = _tensions(case), _tensions(by_hand)
    assert imported == expected  # bit for bit: the same case
    catenary = pytest.importorskip("moorpy.Catenary").catenary
    w = (120.0 - 1025.0 * math.pi * 0.15 ** 2 / 4.0) * 9.81
    fa_h, fa_v, fb_h, fb_v, _ = catenary(500.0, 90.0, 550.0, 6.0e8, w, CB=0.0, Tol=1e-10)
    t_moorpy = math.hypot(fb_h, fb_v)
    assert imported["Mooring1[0]"] == pytest.approx(t_moorpy, rel=MOORPY_RTOL)
    assert result.not_imported  # the slip speed is always listed


def test_three_lines_on_a_vessel_fairleads_in_the_vessel_frame():
    case, result = _case("vessel_three_lines.yml")
    pos = {p.name: tuple(p.position) for p in case.points}
    kinds = {p.name: p.kind for p in case.points}
    c, s = math.cos(math.radians(30.0)), math.sin(math.radians(30.0))
    assert pos["L1_A"] == pytest.approx((10.0 + 20.0 * c, 5.0 + 20.0 * s, -8.0), abs=1e-12)
    assert pos["L3_A"] == pytest.approx((10.0 - 10.0 * c + 17.32 * s,
                                         5.0 - 10.0 * s - 17.32 * c, -8.0), abs=1e-12)
    assert kinds["L1_A"] == kinds["L3_A"] == "body" and kinds["L2_B"] == "fixed"
    assert pos["L2_B"] == (-475.0, 285.0, -150.0)
    line = case.lines[0]  # End A on the vessel: reversed to run from the anchor
    assert [s.line_type.name for s in line.sections] == ["Wire", "Chain"]
    wire = case.line_types["Wire"]
    assert wire.normal_drag_coefficient == 1.2 * 0.08 / 0.09  # drag diameter referred to OD
    tensions = _tensions(case)
    # the 120-degree pattern about the turned vessel: three equal fairlead tensions
    tops = [t for name, t in tensions.items() if name.endswith("[1]")]
    assert len(tops) == 3 and max(tops) == pytest.approx(min(tops), rel=1e-3)
    text = "\n".join(result.not_imported)
    assert "WaveType" in text and "VesselTypes" in text
    assert "EndAConnection" not in text  # the older end keys are read, not dropped


def test_three_lines_against_moorpy_system():
    system_mod = pytest.importorskip("moorpy")
    case, _ = _case("vessel_three_lines.yml")
    tensions = _tensions(case)
    ms = system_mod.System(depth=150.0, rho=1025.0, g=9.80665)
    for name, d, m, ea in (("chain", 0.15, 120.0, 6.0e8), ("wire", 0.09, 35.0, 7.0e8)):
        ms.lineTypes[name] = {"name": name, "d_vol": d, "m": m, "EA": ea,
                              "w": (m - 1025.0 * math.pi * d * d / 4.0) * 9.80665,
                              "MBL": 0.0, "cost": 0.0, "input_d": d, "input_type": {}}
    points = {p.name: list(p.position) for p in case.points}
    for line in case.lines:
        start, end = points[line.start], points[line.end]
        a = ms.addPoint(1, start)
        j = ms.addPoint(0, [0.5 * (u + v) for u, v in zip(start, end)])
        f = ms.addPoint(1, end)
        for (p, q), sec, lt in (((a, j), line.sections[0], "wire"),
                                ((j, f), line.sections[1], "chain")):
            ms.addLine(sec.length, lt)
            p.attachLine(len(ms.lineList), 0)
            q.attachLine(len(ms.lineList), 1)
    ms.initialize()
    ms.solveEquilibrium(tol=1e-8)
    for k, line in enumerate(case.lines):
        top = ms.lineList[2 * k + 1]
        assert tensions[f"{line.name}[1]"] == pytest.approx(top.TB, rel=MOORPY_RTOL)


def _line_type_by_hand(name: str, od: float, mass: float, ea: float, cd_n: float,
                       cd_a: float, ca_a: float) -> str:
    return (f"[line_types.{name}]\nmass_per_length = {mass!r}\naxial_stiffness = {ea!r}\n"
            f"diameter = {od!r}\nmaterial_density = {mass / (math.pi * od ** 2 / 4.0)!r}\n"
            f"normal_drag_coefficient = {cd_n!r}\n"
            f"tangential_drag_coefficient = {math.pi * cd_a!r}\n"
            f"added_mass_coefficient = 1.0\ntangential_added_mass_coefficient = {ca_a!r}\n")


CLUMP_BY_HAND = f"""
title = "by hand"
[environment]
water_density = 1025.0
water_depth = 100.0
gravity = 9.80665
[seabed]
stiffness = 1.0e5
damping_ratio = 0.0
friction_coefficient = 0.5
slip_speed = 0.01
{_line_type_by_hand("Chain", 0.15, 120.0, 6.0e8, 2.4, 1.15, 0.5)}
{_line_type_by_hand("Wire", 0.09, 35.0, 7.0e8, 1.2, 0.008, 0.0)}
[[points]]
name = "anchor"
kind = "fixed"
position = [-440.0, 0.0, -100.0]
[[points]]
name = "clump"
kind = "free"
position = [-220.0, 0.0, -85.0]
mass = 3000.0
volume = 0.64
drag_area = 2.0
added_mass_coefficient = 0.5
[[points]]
name = "fairlead"
kind = "fixed"
position = [0.0, 0.0, -10.0]
[[lines]]
name = "Lower"
start = "anchor"
end = "clump"
model = "dynamic"
sections = [{{ type = "Chain", length = 150.0 }}, {{ type = "Wire", length = 100.0 }}]
[lines.quasi_static]
seabed_friction = false
[[lines]]
name = "Upper"
start = "clump"
end = "fairlead"
model = "dynamic"
sections = [{{ type = "Chain", length = 220.0 }}]
[lines.quasi_static]
seabed_friction = false
[simulation]
duration = 60.0
output_interval = 0.1
"""


def test_two_sections_and_a_clump():
    case, _ = _case("clump_two_sections.yml")
    clump = next(p for p in case.points if p.name == "Clump")
    assert clump.kind == "free" and clump.mass == 3000.0 and clump.volume == 0.64
    assert clump.drag_area == 2.0 and clump.added_mass_coefficient == 0.5
    lower = next(line for line in case.lines if line.name == "Lower")
    assert [s.length for s in lower.sections] == [150.0, 100.0]
    assert lower.end == "Clump"
    loads = _tensions(case)
    assert loads["Upper[0]"] > loads["Lower[1]"] > 0.0
    by_hand = parse_case(parse_toml(CLUMP_BY_HAND, "hand"), source="hand", text=CLUMP_BY_HAND)
    assert loads == _tensions(by_hand)  # bit for bit: the same case


def _run(tmp_path, text: str, capsys, name="model.yml") -> tuple[int, str, Path]:
    model = tmp_path / name
    model.write_text(text)
    out = tmp_path / "case.toml"
    status = main(["import", "orcaflex", str(model), "-o", str(out)])
    return status, capsys.readouterr().err, out


BASE = (MODELS / "single_chain.yml").read_text()

MALFORMED = {
    "missing key": (BASE.replace("  WaterDepth: 100\n", ""), "Environment.WaterDepth"),
    "unknown unit system": (BASE.replace("UnitsSystem: SI", "UnitsSystem: US"),
                            "General.UnitsSystem"),
    "unsupported connection": (BASE.replace("[Fixed, 0, 0, -10", "[Winch1, 0, 0, -10"),
                               'Lines["Mooring1"].Connection[End B].Connection'),
    "non-numeric": (BASE.replace("EA: 6.0e5", "EA: lots"), 'LineTypes["Chain"].EA'),
    "negative length": (BASE.replace("[Chain, 550, 10]", "[Chain, -550, 10]"),
                        "LineType, Length, TargetSegmentLength[0].Length"),
    "huge number": (BASE.replace("OD: 0.15", "OD: 1e300"), 'LineTypes["Chain"].OD'),
    "infinite": (BASE.replace("OD: 0.15", "OD: .inf"), 'LineTypes["Chain"].OD'),
    "sexagesimal": (BASE.replace("OD: 0.15", "OD: 1:30"), 'LineTypes["Chain"].OD'),
    "alias": (BASE.replace("Cd: [2.4, ~, 1.15]", "Cd: &c [2.4, ~, 1.15]\n    Ca: *c"),
              "anchors and aliases"),
    "merge key": (BASE.replace("    Category: General\n", "    <<: {OD: 0.2}\n"),
                  "merge keys"),
    "repeated key": (BASE.replace("    ID: 0\n", "    ID: 0\n    ID: 0\n"), "each key once"),
    "not yaml": ("General: [1, 2\n", "an OrcaFlex text data file (YAML)"),
    "unknown line type": (BASE.replace("[Chain, 550, 10]", "[Rope, 550, 10]"),
                          "LineType"),
    "nonlinear EA": (BASE.replace("EA: 6.0e5", "EA: Stiffness curve"),
                     'LineTypes["Chain"].EA'),
    "released end": (BASE.replace("[Fixed, 0, 0, -10, 0, 170, 0, ~, ~]",
                                  "[Fixed, 0, 0, -10, 0, 170, 0, 2, ~]"),
                     "ConnectionReleaseStage"),
    "sloping seabed": (BASE.replace("SeabedSlope: 0", "SeabedSlope: 5"),
                       "Environment.SeabedSlope"),
    "spar buoy": (BASE + "6DBuoys:\n  - Name: B\n    BuoyType: Spar buoy\n"
                  "    InitialPosition: [0, 0, -5]\n", '6DBuoys["B"].BuoyType'),
    "control characters": (BASE.replace("Name: Mooring1", "Name: \"M\\e[2J\""),
                           "Lines[0].Name"),
    "missing section": (BASE.replace("LineTypes:", "Unused:"), 'Lines["Mooring1"]'),
    "missing drag": (BASE.replace("    Cd: [2.4, ~, 1.15]\n", ""), 'LineTypes["Chain"].Cd'),
    "a bore": (BASE.replace("ID: 0", "ID: 0.05"), 'LineTypes["Chain"].ID'),
    "anisotropic drag": (BASE.replace("Cd: [2.4, ~, 1.15]", "Cd: [2.4, 2.0, 1.15]"),
                         'LineTypes["Chain"].Cd[1]'),
    "contact diameter": (BASE.replace("    ID: 0\n", "    ID: 0\n    OuterContactDiameter: 0.3\n"),
                         'LineTypes["Chain"].OuterContactDiameter'),
    "axial friction": (BASE.replace("SeabedAxialFrictionCoefficient: ~",
                                    "SeabedAxialFrictionCoefficient: 0.3"),
                       'LineTypes["Chain"].SeabedAxialFrictionCoefficient'),
    "as-laid friction": (BASE.replace("StaticsSeabedFrictionPolicy: None",
                                      "StaticsSeabedFrictionPolicy: As laid"),
                         'Lines["Mooring1"].StaticsSeabedFrictionPolicy'),
    "unknown column with a value": (
        BASE.replace("LineType, Length, TargetSegmentLength:\n      - [Chain, 550, 10]",
                     "LineType, Length, TargetSegmentLength, ExpansionFactor:\n"
                     "      - [Chain, 550, 10, 1.01]"),
        "ExpansionFactor"),
    "included file": (BASE.replace("General:\n", "BaseFile: other.yml\nGeneral:\n"),
                      "BaseFile"),
    "heeled vessel": ((MODELS / "vessel_three_lines.yml").read_text().replace(
        "InitialHeading: 30", "InitialHeading: 30\n    InitialHeel: 2"),
        'Vessels["Barge"].InitialAttitude'),
    "vessel in statics": ((MODELS / "vessel_three_lines.yml").read_text().replace(
        "PrimaryMotion: None", "IncludedInStatics: 6 DOF"),
        'Vessels["Barge"].IncludedInStatics'),
    "offset at a buoy": ((MODELS / "clump_two_sections.yml").read_text().replace(
        "[Clump, 0, 0, 0]\n      - [Fixed", "[Clump, 0, 0, 1]\n      - [Fixed"),
        'Lines["Upper"].Connection[End A].ConnectionX'),
    "one line type's friction": ((MODELS / "clump_two_sections.yml").read_text().replace(
        "    Ca: [1, ~, 0]\n    SeabedLateralFrictionCoefficient: 0.5",
        "    Ca: [1, ~, 0]\n    SeabedLateralFrictionCoefficient: 0.8"),
        "SeabedLateralFrictionCoefficient"),
    "6D buoy added mass": ((MODELS / "clump_two_sections.yml").read_text().replace(
        "3DBuoys:", "6DBuoys:").replace("    Height: 1\n", "    BuoyType: Lumped buoy\n"),
        '6DBuoys["Clump"].Ca'),
    "a surface-piercing buoy": ((MODELS / "clump_two_sections.yml").read_text().replace(
        "InitialPosition: [-220, 0, -85]", "InitialPosition: [-220, 0, -0.2]"),
        '3DBuoys["Clump"].Height'),
}


@pytest.mark.parametrize("kind", sorted(MALFORMED))
def test_malformed_input_is_a_one_line_error_and_nothing_is_written(tmp_path, capsys, kind):
    text, key = MALFORMED[kind]
    status, err, out = _run(tmp_path, text, capsys)
    assert status == 2, err
    assert err.count("\n") == 1 and err.startswith("floatmoor: error: ")
    assert "model.yml" in err and key in err and "expected" in err
    assert "\x1b" not in err
    assert not out.exists()


def test_harmless_extras_are_listed_not_refused():
    text = BASE.replace("LineType, Length, TargetSegmentLength:\n      - [Chain, 550, 10]",
                        "LineType, Length, TargetSegmentLength, ExpansionFactor:\n"
                        "      - [Chain, 550, 10, ~]").replace(
        "EI: [0, ~]", "EI: [12, ~]\n    PoissonRatio: 0.5") + "Groups:\n  - Name: G\n"
    result = import_model(parse_model(text, "m.yml"), "m.yml")
    listed = "\n".join(result.not_imported)
    assert "ExpansionFactor" in listed and "PoissonRatio" in listed
    assert "EI = [12, ~] kN m^2" in listed and "Groups (1 items)" in listed
    assert "# - " + result.not_imported[0] in result.text


@pytest.mark.parametrize("written", ["WaterSurfaceZ: 0.0", "WaterSurfaceZ: -0", "WaterSurfaceZ: ~"])
def test_a_water_surface_at_zero_however_written(written):
    text = BASE.replace("WaterSurfaceZ: 0", written)
    assert import_model(parse_model(text, "m.yml"), "m.yml").text


def test_a_lumped_6d_buoy_is_the_same_point_as_a_3d_buoy():
    text = (MODELS / "clump_two_sections.yml").read_text()
    six = text.replace("3DBuoys:", "6DBuoys:").replace(
        "    Height: 1\n", "    BuoyType: Lumped buoy\n    CentreOfMass: [0, 0, 0]\n").replace(
        "    Ca: [0.5, 0.5, 0.5]\n", "")
    three = text.replace("    Ca: [0.5, 0.5, 0.5]\n", "")
    cases = []
    for t in (three, six):
        r = import_model(parse_model(t, "m.yml"), "m.yml")
        cases.append(parse_case(parse_toml(r.text, "m"), source="m", text=r.text))
    assert _tensions(cases[0]) == _tensions(cases[1])


def test_a_file_name_with_braces_is_not_a_title_placeholder(tmp_path, capsys):
    model = tmp_path / "run {environment.water_depth}.yml"
    model.write_text(BASE)
    out = tmp_path / "case.toml"
    assert main(["import", "orcaflex", str(model), "-o", str(out)]) == 0
    capsys.readouterr()
    case = parse_case(parse_toml(out.read_text(), "c"), source="c", text=out.read_text())
    assert case.title.endswith("run {environment.water_depth}.yml")


def test_deep_nesting_is_an_error_not_a_crash():
    with pytest.raises(CaseError, match="YAML"):
        parse_model("a: " + "[" * 50_000, "deep.yml")


def test_a_file_over_the_size_bound_is_refused_before_parsing(tmp_path, capsys):
    model = tmp_path / "big.yml"
    with open(model, "wb") as fh:
        fh.truncate(MAX_MODEL_FILE_BYTES + 1)
    with pytest.raises(CaseError, match="at most"):
        read_model(model)


def test_an_alias_bomb_is_refused_without_expanding():
    bomb = "a: &a [x, x, x, x, x, x, x, x, x]\n" + "".join(
        f"{chr(98 + i)}: &{chr(98 + i)} [*{chr(97 + i)}, *{chr(97 + i)}, *{chr(97 + i)}]\n"
        for i in range(20))
    with pytest.raises(CaseError, match="anchors and aliases"):
        parse_model(bomb, "bomb.yml")


def test_cli_writes_the_case_lists_what_was_not_imported_and_honours_force(tmp_path, capsys):
    out = tmp_path / "case.toml"
    model = str(MODELS / "vessel_three_lines.yml")
    assert main(["import", "orcaflex", model, "-o", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "not imported (3):" in printed and "WaveType" in printed
    assert len(tomllib.loads(out.read_text())["lines"]) == 3
    assert main(["import", "orcaflex", model, "-o", str(out)]) == 2  # exists
    assert "--force" in capsys.readouterr().err
    assert main(["import", "orcaflex", model, "-o", str(out), "--force"]) == 0
    other = tmp_path / "notes.txt"
    other.write_text("keep me\n")
    assert main(["import", "orcaflex", model, "-o", str(other), "--force"]) == 2
    assert other.read_text() == "keep me\n"


def test_the_output_gets_the_common_checks(tmp_path, tmpfs, capsys):  # noqa: F811
    model = tmp_path / "m.yml"
    model.write_text(BASE)
    assert main(["import", "orcaflex", str(model), "-o", str(model), "--force"]) == 2
    assert "input file" in capsys.readouterr().err and model.read_text() == BASE
    read_only = tmpfs("ro", "ro,size=1m")
    small = tmpfs("small", "size=4k")
    for folder, found in ((read_only, "Read-only file system"), (small, "free in")):
        assert main(["import", "orcaflex", str(model), "-o", str(folder / "c.toml")]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and "-o/--output: expected" in err and found in err
        assert os.listdir(folder) == []
