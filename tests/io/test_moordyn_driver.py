"""MoorDyn driver inputs: ``floatmoor import moordyn DECK --driver md_driver.inp`` on OpenFAST's
r-test MoorDyn cases (tests/data/moordyn/rtest, NOTICE there), the driver and motion-file
readers, the rigid-body fit of fairlead positions, and the imported OC4 semi run against
MoorDyn-C on the same deck driven along the same positions.

Cases: md_5MW_OC4Semi (three fairleads moved along a recorded platform motion; its motion file
is a 185-row subsample), md_case2 (a chain and a rope joined at a free point, no coupled
points), md_float (one line between two fixed points; the deck's floating body and rods are
not modelled: listed), md_syrope (a SYROPE synthetic-rope line type: refused by name).
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

from floatmoor.body_motion import rotation_matrices
from floatmoor.case.load import load_case
from floatmoor.cli import main
from floatmoor.errors import CaseError
from floatmoor.io.moordyn.driver import parse_driver, read_driver, read_motion_file
from floatmoor.io.moordyn.driver_import import RIGID_FIT_TOLERANCE
from floatmoor.io.moordyn.importer import import_deck
from floatmoor.io.moordyn.motion_fit import fit_rigid_motion
from floatmoor.io.moordyn.parser import parse_deck, read_deck
from floatmoor.simulation.forced import run_forced_motion

RTEST = Path(__file__).parents[1] / "data" / "moordyn" / "rtest"
OC4 = RTEST / "md_5MW_OC4Semi"
#: The fairlead tensions at t = 20 s against MoorDyn-C on the same deck, relative [-], per line
#: model. Observed (floatmoor at the imported numerics, MoorDyn at the deck's dtM with the
#: driver's 0.0125 s coupling step): dynamic 0.07-0.22 %, quasi-dynamic 0.25-0.54 %; the
#: quasi-static model has no line drag or inertia, which MoorDyn's tension carries: 0.76-1.11 %
#: (floatmoor's own dynamic and quasi-static tensions differ by 1.1 % at 20 s, the platform
#: surging at ~0.1 m/s), hence 1.5 % for it.
TENSION_RTOL_AT_20S = {"dynamic": 0.01, "quasi-dynamic": 0.01, "quasi-static": 0.015}
#: Largest change of floatmoor's fairlead tension over the first 0.5 s, relative to its value
#: at t = 0 [-]: the platform barely moves then. Observed: quasi-static 0.005 %, dynamic
#: 0.37 % (the discretised line settling from the static catenary; MoorDyn-C's own tension
#: moves 0.2 % from its initial-condition solve). A start-up spike (lines not starting at the
#: motion's first pose, 5 m of surge from rest) would be tens of percents.
START_RTOL = 0.005
#: md_case2 against MoorDyn-C: floatmoor's tension at 20 s against MoorDyn's at the driver's
#: TMax = 60 s, relative [-]. The deck asks MoorDyn for no initial-condition solve (TmaxIC 0):
#: MoorDyn starts from the deck's free-point position 120 m off the equilibrium and settles
#: after ~40 s (then +-0.1 %); floatmoor starts at its statics. Observed 0.3 %.
CASE2_RTOL = 0.01


def _import(tmp_path: Path, case: str, capsys, *extra: str) -> tuple[int, str, str]:
    out = tmp_path / f"{case}.toml"
    code = main(["import", "moordyn", str(RTEST / case / "moordyn.dat"), "--driver",
                 str(RTEST / case / "md_driver.inp"), "-o", str(out), *extra])
    captured = capsys.readouterr()
    return code, captured.out, captured.err


# -- item: the deck's title and OUTPUTS --------------------------------------------------------

def test_title_stops_before_the_echo_flag_and_end_closes_the_outputs():
    deck = read_deck(OC4 / "moordyn.dat")
    assert deck.title == "Mooring system for OC4-DeepCwind Semi"
    assert "END" not in [o.upper() for o in deck.outputs] and deck.outputs[-1] == "Con6Pz"
    unmapped = import_deck(deck, water_depth=200.0).unmapped
    assert not any("END" in item.split(":")[0].split() for item in unmapped)
    assert any(item.startswith("option Echo = FALSE (line 3)") for item in unmapped)


def test_rows_after_end_in_outputs_are_refused():
    text = (OC4 / "moordyn.dat").read_text().replace("END\n", "END\nFairTen9\n")
    with pytest.raises(CaseError, match=r"moordyn.dat:\d+: OUTPUTS: expected nothing after END"):
        parse_deck(text, "moordyn.dat")


def test_syrope_and_viscoelastic_line_types_are_refused_by_name():
    with pytest.raises(CaseError, match=r"moordyn.dat:5: LINE TYPES, column EA: .*SYROPE"):
        read_deck(RTEST / "md_syrope" / "moordyn.dat")
    text = (RTEST / "md_syrope" / "moordyn.dat").read_text().replace(
        "SYROPE:syrope.dat|1.53e8|23.12", "1.53e8")
    with pytest.raises(CaseError, match=r"column BA/-zeta: .*viscoelastic"):
        parse_deck(text, "moordyn.dat")


# -- the driver file ---------------------------------------------------------------------------

def test_oc4_driver_values():
    d = read_driver(OC4 / "md_driver.inp")
    assert (d.gravity, d.water_density, d.water_depth) == (9.80665, 1025.0, 200.0)
    assert (d.duration, d.coupling_interval, d.inputs_mode) == (60.0, 0.0125, 1)
    assert d.inputs_file == "ptfm_motion.dat" and d.deck_file == "moordyn.dat"
    assert d.initial_pose == (5.0, 0.0, 0.0, 0.0, 0.0331612, 0.0)
    assert d.where("TMax").endswith("md_driver.inp:11")


@pytest.mark.parametrize("old, new, where, expected", [
    ("60             TMax", "sixty          TMax", ":11", "TMax: expected a number [s]"),
    ("0.0125              dtC", "0                   dtC", ":12", "dtC: expected a number > 0"),
    ("1                   InputsMode", "2                   InputsMode", ":13",
     "InputsMode: expected 0 (no inputs file) or 1"),
    ("0                   NumTurbines", "2                   NumTurbines", ":15",
     "NumTurbines: expected 0 (OpenFAST mode"),
    ("200.0               WtrDpth", "200.0               Depth", ":7", "expected one of the keys"),
    ("  0        0         5 ", "  0        0 ", ":19", "expected 8 numbers"),
    ("---------------------- MOORDYN", "---------------------- MOORING", ":8",
     "expected a section heading"),
])
def test_malformed_driver_file_names_file_and_line(old, new, where, expected):
    text = (OC4 / "md_driver.inp").read_text()
    assert old in text
    with pytest.raises(CaseError, match=re.escape(expected)) as err:
        parse_driver(text.replace(old, new, 1), "md_driver.inp")
    assert str(err.value).startswith(f"md_driver.inp{where}")


def test_driver_gravity_zero_without_a_deck_value_is_refused(tmp_path, capsys):
    folder = _oc4_copy(tmp_path, lambda s: s.replace("9.80665             Gravity",
                                                     "0                   Gravity"))
    assert _run_import(folder) == 2
    err = capsys.readouterr().err
    assert "md_driver.inp:5: Gravity: expected a number > 0" in err
    assert not (folder / "case.toml").exists()


def test_driver_without_a_key_is_refused():
    text = "\n".join(line for line in (OC4 / "md_driver.inp").read_text().splitlines()
                     if "dtC" not in line)
    with pytest.raises(CaseError, match="md_driver.inp: dtC: expected a dtC row, found none"):
        parse_driver(text, "md_driver.inp")


# -- the motion file and the rigid fit --------------------------------------------------------

def test_rigid_fit_recovers_poses_with_one_two_and_three_points():
    rng = np.random.default_rng(7)
    pose = np.c_[rng.normal(size=(6, 3)), rng.normal(scale=0.3, size=(6, 3))]
    rest = np.array([[20.434, 35.393, -14.0], [-40.868, 0.0, -14.0], [20.434, -35.393, -14.0]])
    x = np.einsum("nij,kj->nki", rotation_matrices(pose[:, 3:]), rest) + pose[:, None, :3]
    fit = fit_rigid_motion(rest, x)
    np.testing.assert_allclose(fit.pose, pose, atol=1e-12)
    assert fit.residual.max() < 1e-12 and fit.rotation_fitted
    for k in (1, 2):  # fewer points: their positions are reproduced, the rotation is not fixed
        fit = fit_rigid_motion(rest[:k], x[:, :k])
        assert fit.residual.max() < 1e-12
    assert not fit_rigid_motion(rest[:1], x[:, :1]).rotation_fitted


def test_oc4_motion_file_is_fitted_to_its_first_row_pose():
    record = read_motion_file(OC4 / "ptfm_motion.dat")
    assert record.values.shape == (185, 9) and record.names[0] == "CON4PX"
    rest = np.array([p.position for p in read_deck(OC4 / "moordyn.dat").points[3:]])
    fit = fit_rigid_motion(rest, record.values.reshape(-1, 3, 3))
    assert fit.residual.max() < 2e-6  # rows rounded to 1e-6 m
    np.testing.assert_allclose(fit.pose[0], [5.0, 0.0, 0.0, 0.0, 0.033149, 0.0], atol=1e-5)


def _moved(row: str, column: int, by: float) -> str:
    """A motion-file row with one position moved by ``by`` [m]."""
    fields = row.split()
    fields[column] = f"{float(fields[column]) + by:.6f}"
    return " ".join(fields)


@pytest.mark.parametrize("edit, where, expected", [
    (lambda rows: rows[:5] + [rows[5] + " 1.0"] + rows[6:], ":6", "expected 10 numbers"),
    (lambda rows: rows[:5] + [rows[3]] + rows[6:], ":6", "times strictly increasing"),
    (lambda rows: rows[:5] + [rows[5].replace("24.", "x4.", 1)] + rows[6:], ":6",
     "expected numbers"),
    (lambda rows: rows[:40] + [_moved(rows[40], 1, 0.01)] + rows[41:], ":41",
     "a point 0.00"),
    (lambda rows: rows[:100], ":100", "rows up to TMax = 60 s"),
])
def test_malformed_motion_file_is_refused_and_nothing_written(tmp_path, capsys, edit, where,
                                                              expected):
    for name in ("moordyn.dat", "md_driver.inp"):
        (tmp_path / name).write_text((OC4 / name).read_text())
    rows = (OC4 / "ptfm_motion.dat").read_text().splitlines()
    (tmp_path / "ptfm_motion.dat").write_text("\n".join(edit(rows)) + "\n")
    out = tmp_path / "case.toml"
    code = main(["import", "moordyn", str(tmp_path / "moordyn.dat"), "--driver",
                 str(tmp_path / "md_driver.inp"), "-o", str(out)])
    err = capsys.readouterr().err
    assert code == 2
    assert err.startswith(f"floatmoor: error: {tmp_path / 'ptfm_motion.dat'}{where}:")
    assert expected in err and len(err.strip().splitlines()) == 1
    assert not out.exists() and not (tmp_path / "case_motion.csv").exists()


def test_rigid_fit_tolerance_is_a_millimetre():
    assert RIGID_FIT_TOLERANCE == 1e-3


# -- one command per r-test case -------------------------------------------------------------

def test_oc4_imports_in_one_command(tmp_path, capsys):
    code, out, _ = _import(tmp_path, "md_5MW_OC4Semi", capsys)
    assert code == 0
    assert "largest residual 6.6e-07 m" in out and "initial pose:" in out
    case = load_case(tmp_path / "md_5MW_OC4Semi.toml")
    assert case.title == "Mooring system for OC4-DeepCwind Semi"
    assert case.environment.water_depth == 200.0 and case.simulation.duration == 60.0
    motion = case.motion
    assert motion.time.size == 185 and motion.ramp_duration == 0.0
    # the table's first row is the driver's initial pose (surge 5 m, pitch 1.9 deg) to 0.02 mrad
    np.testing.assert_allclose(motion.displacement[0], [5.0, 0.0, 0.0, 0.0, 0.0331612, 0.0],
                               atol=2e-5)
    # a second import refuses to overwrite either file; --force replaces both
    code, _, err = _import(tmp_path, "md_5MW_OC4Semi", capsys)
    assert code == 2 and "--force" in err
    assert _import(tmp_path, "md_5MW_OC4Semi", capsys, "--force")[0] == 0


def test_motion_output_replaces_only_a_motion_table(tmp_path, capsys):
    other = tmp_path / "notes.csv"
    other.write_text("a,b\n1,2\n")
    code, _, err = _import(tmp_path, "md_5MW_OC4Semi", capsys, "--motion-output", str(other),
                           "--force")
    assert code == 2 and "another file" in err and other.read_text() == "a,b\n1,2\n"
    assert not (tmp_path / "md_5MW_OC4Semi.toml").exists()


@pytest.mark.parametrize("case, unmapped", [
    ("md_case2", "the driver names MDInputFile 'case2.dat'"),
    ("md_float", "section BODIES (line 11, 1 rows): floatmoor does not model bodies"),
])
def test_other_rtest_cases_import_in_one_command_and_run(tmp_path, capsys, case, unmapped):
    code, out, _ = _import(tmp_path, case, capsys)
    assert code == 0 and unmapped in out and "motion: none" in out
    for model in ("quasi-static", "dynamic"):
        c = load_case(tmp_path / f"{case}.toml", ["simulation.duration=5.0"] + [
            f'lines.{line.name}.model="{model}"' for line in
            load_case(tmp_path / f"{case}.toml").lines])
        tension = run_forced_motion(c).dataset["fairlead_tension"].transpose(
            "time", "line").values
        assert np.all(np.isfinite(tension)) and tension.min() > 0.0
        # nothing moves: no start-up transient in either model
        assert np.ptp(tension, axis=0).max() <= START_RTOL * tension.min()


def test_syrope_case_is_refused_naming_the_feature(tmp_path, capsys):
    code, _, err = _import(tmp_path, "md_syrope", capsys)
    assert code == 2 and "SYROPE synthetic-rope model" in err
    assert not list(tmp_path.iterdir())


# -- against MoorDyn-C on the same deck --------------------------------------------------------

def _oc4_against_moordyn(tmp_path, capsys, model: str, start: bool = True) -> None:
    pytest.importorskip("moordyn")
    from tests.peer.moordyn_deck_runner import run_moordyn_deck

    assert _import(tmp_path, "md_5MW_OC4Semi", capsys)[0] == 0
    case = load_case(tmp_path / "md_5MW_OC4Semi.toml", ["simulation.duration=20.0"] + [
        f'lines.line{i}.model="{model}"' for i in (1, 2, 3)])
    ds = run_forced_motion(case).dataset
    t = ds["time"].values
    theirs = run_moordyn_deck(OC4 / "moordyn.dat", case, t,
                              coupling_interval=read_driver(OC4 / "md_driver.inp")
                              .coupling_interval)
    early = t <= 0.5
    for line, point in (("line1", "point4"), ("line2", "point5"), ("line3", "point6")):
        ours = ds["fairlead_tension"].sel(line=line).values
        error = abs(ours[-1] - theirs[point][-1]) / theirs[point][-1]
        spike = np.abs(ours[early] - ours[0]).max() / ours[0]
        print(f"\n{model} {line}: t = 20 s floatmoor {ours[-1] / 1e3:.1f} kN, MoorDyn-C "
              f"{theirs[point][-1] / 1e3:.1f} kN ({error:.2%}); first 0.5 s {spike:.3%}")
        assert t[-1] == pytest.approx(20.0)
        assert error <= TENSION_RTOL_AT_20S[model]
        assert spike <= START_RTOL or not start


@pytest.mark.parametrize("model", ["quasi-static", "quasi-dynamic"])
def test_oc4_fairlead_tensions_match_moordyn_c_at_20_s(tmp_path, capsys, model):
    _oc4_against_moordyn(tmp_path, capsys, model, start=model != "quasi-dynamic")


@pytest.mark.xfail(strict=True, reason="the quasi-dynamic model's tension steps 1.4 % down "
                   "on the first step of the OC4 motion (k_QD leaves 1 at once), then follows "
                   "MoorDyn within 0.6 %; not the import's (a constant table at the same pose "
                   "has no step)")
def test_oc4_quasi_dynamic_starts_without_a_step(tmp_path, capsys):
    assert _import(tmp_path, "md_5MW_OC4Semi", capsys)[0] == 0
    case = load_case(tmp_path / "md_5MW_OC4Semi.toml", ["simulation.duration=0.5"] + [
        f'lines.line{i}.model="quasi-dynamic"' for i in (1, 2, 3)])
    tension = run_forced_motion(case).dataset["fairlead_tension"].values
    assert (np.abs(tension - tension[:, :1]).max() / tension[:, 0].min()) <= START_RTOL


@pytest.mark.slow  # the dynamic lines (a few seconds once compiled, a minute to compile)
def test_oc4_dynamic_fairlead_tensions_match_moordyn_c_at_20_s(tmp_path, capsys):
    _oc4_against_moordyn(tmp_path, capsys, "dynamic")


def test_case2_tension_matches_settled_moordyn_c(tmp_path, capsys):
    pytest.importorskip("moordyn")
    from tests.peer.moordyn_deck_runner import run_moordyn_deck

    assert _import(tmp_path, "md_case2", capsys)[0] == 0
    ds = run_forced_motion(load_case(tmp_path / "md_case2.toml",
                                     ["simulation.duration=20.0"])).dataset
    case = load_case(tmp_path / "md_case2.toml")  # 60 s: the driver's TMax
    theirs = run_moordyn_deck(RTEST / "md_case2" / "moordyn.dat", case,
                              np.linspace(0.0, 60.0, 601), coupling_interval=0.01,
                              line_tensions=True)
    ours = float(ds["fairlead_tension"].sel(line="line2").values[-1])
    error = abs(ours - theirs["line2"][-1]) / theirs["line2"][-1]
    print(f"\nmd_case2 line2 top: floatmoor {ours / 1e3:.1f} kN at 20 s, MoorDyn-C "
          f"{theirs['line2'][-1] / 1e3:.1f} kN at 60 s ({error:.2%})")
    assert error <= CASE2_RTOL


def _oc4_copy(tmp_path: Path, driver_edit=None, motion: str | None = None) -> Path:
    for name in ("moordyn.dat", "md_driver.inp", "ptfm_motion.dat"):
        (tmp_path / name).write_text((OC4 / name).read_text())
    if driver_edit is not None:
        text = (tmp_path / "md_driver.inp").read_text()
        (tmp_path / "md_driver.inp").write_text(driver_edit(text))
    if motion is not None:
        (tmp_path / "ptfm_motion.dat").write_text(motion)
    return tmp_path


def _run_import(folder: Path, *extra: str) -> int:
    return main(["import", "moordyn", str(folder / "moordyn.dat"), "--driver",
                 str(folder / "md_driver.inp"), "-o", str(folder / "case.toml"), *extra])


def test_six_dof_motion_file_is_taken_as_it_is(tmp_path, capsys):
    t = np.linspace(0.0, 60.0, 61)
    dofs = np.c_[t, 5.0 + 0.01 * t, 0.1 * np.sin(t), 0 * t, 0.01 * np.cos(t), 0.03 + 0 * t,
                 0.002 * t]
    text = "Time PtfmSurge PtfmSway PtfmHeave PtfmRoll PtfmPitch PtfmYaw\n" + "\n".join(
        " ".join(f"{v:.12g}" for v in row) for row in dofs) + "\n"
    folder = _oc4_copy(tmp_path, motion=text)
    assert _run_import(folder) == 0
    assert "six DOFs" in capsys.readouterr().out
    motion = load_case(folder / "case.toml").motion
    np.testing.assert_allclose(motion.time, t)
    np.testing.assert_allclose(motion.displacement, dofs[:, 1:], atol=1e-12)


def test_inputs_mode_0_holds_the_driver_pose(tmp_path, capsys):
    folder = _oc4_copy(tmp_path, lambda s: s.replace("1                   InputsMode",
                                                     "0                   InputsMode"))
    assert _run_import(folder) == 0
    assert "held at the driver's initial pose" in capsys.readouterr().out
    motion = load_case(folder / "case.toml").motion
    np.testing.assert_allclose(motion.time, [0.0, 60.0])
    np.testing.assert_allclose(motion.displacement,
                               [[5.0, 0.0, 0.0, 0.0, 0.0331612, 0.0]] * 2)


def test_motion_output_outside_the_case_folder_is_refused(tmp_path, capsys):
    (tmp_path / "a").mkdir()
    folder = _oc4_copy(tmp_path / "a")
    (tmp_path / "b").mkdir()
    code = _run_import(folder, "--motion-output", str(tmp_path / "b" / "m.csv"))
    err = capsys.readouterr().err
    assert code == 2 and "--motion-output: expected a file in the case file's folder" in err
    assert not (folder / "case.toml").exists() and not (tmp_path / "b" / "m.csv").exists()
    code = main(["import", "moordyn", str(folder / "moordyn.dat"), "--motion-output", "m.csv",
                 "-o", str(folder / "case.toml")])
    assert code == 2 and "expected --driver as well" in capsys.readouterr().err


def test_two_coupled_points_need_a_header_to_tell_positions_from_dofs():
    from floatmoor.io.moordyn.driver import MotionRecord
    from floatmoor.io.moordyn.driver_import import _classify

    values = np.zeros((2, 6))
    record = MotionRecord("m.dat", (), np.array([0.0, 1.0]), values, np.array([2, 3]))
    with pytest.raises(CaseError, match="m.dat:2: .*no header naming them"):
        _classify(record, 2)
    named = MotionRecord("m.dat", ("P4PX", "P4PY", "P4PZ", "P5PX", "P5PY", "P5PZ"),
                         record.time, values, record.line_numbers)
    assert _classify(named, 2) == "points"
    assert _classify(MotionRecord("m.dat", ("surge", "sway", "heave", "roll", "pitch", "yaw"),
                                  record.time, values, record.line_numbers), 2) == "dofs"
