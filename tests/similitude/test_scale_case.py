"""``floatmoor scale``: exact similitude of a scaled line, round trips, refusals."""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.cli import main
from floatmoor.similitude.case_scaling import scale_case_file
from floatmoor.similitude.groups import cable_groups
from floatmoor.similitude.laws import ScaleLaw
from floatmoor.simulation.run import run_case

HERE = Path(__file__).parent
ROOT = HERE.parents[1]
AIR_LINE = HERE / "air_line.toml"
LINDAHL = ROOT / "cases" / "lindahl" / "lindahl_r0.20_T1.25.toml"
BUOY = ROOT / "cases" / "cylinder_buoy" / "buoy_regular_T1.00.toml"
#: DeepCwind cases with Morison drag on the floater ([floater.drag]) and a BEM database.
DEEPCWIND = [ROOT / "cases" / "deepcwind" / f"deepcwind_{n}.toml" for n in ("lc34", "free_decay")]
#: A wave-tank scale for them: 1:50, Froude (beta = lambda, phi = 1).
TANK = ScaleLaw(0.02, 0.02, 1.0)

#: Exact similitude: the dimensionless tension histories of a line and its scaled
#: copy agree to 1e-6. Every term of the discretised equations scales exactly (the explicit
#: step is h / c, which scales sqrt(lambda) like the output interval), so what is left is
#: round-off and the 12 significant digits the scaled case is written with (~1e-11 here).
EXACT_SIMILITUDE = 1e-6
#: A law with every factor different: lambda, beta and phi as in no other test.
DISTORTED = ScaleLaw(length=4.0, diameter=2.5, volume_coefficient=1.3)


def _dimensionless_tension(case) -> tuple[np.ndarray, np.ndarray]:
    """t / T and T_fairlead / (w L), w = m g the line's weight per length (in air)."""
    data = run_case(case).dataset
    line = case.lines[0]
    w = line.line_type.mass_per_length * case.environment.gravity
    tension = data.fairlead_tension.sel(line=line.name).values
    return data.time.values / case.motion.period, tension / (w * line.length)


def test_a_line_in_air_and_its_scaled_copy_are_exactly_similar(tmp_path: Path) -> None:
    old = load_case(AIR_LINE)
    new = scale_case_file(AIR_LINE, DISTORTED, output=tmp_path / "scaled.toml").case
    assert new.lines[0].length == pytest.approx(4.0 * old.lines[0].length, rel=1e-12)
    tau_old, f_old = _dimensionless_tension(old)
    tau_new, f_new = _dimensionless_tension(new)
    assert tau_old.shape == tau_new.shape
    np.testing.assert_allclose(tau_new, tau_old, rtol=0.0, atol=EXACT_SIMILITUDE)
    assert f_old.max() > 2.0 * f_old[0]  # a real dynamic response, not a static line
    assert np.max(np.abs(f_new - f_old)) <= EXACT_SIMILITUDE * np.max(np.abs(f_old))


def test_the_distorted_law_changes_only_reynolds_and_kc(tmp_path: Path) -> None:
    scaled = scale_case_file(LINDAHL, DISTORTED, output=tmp_path / "scaled.toml")
    assert scaled.kept == ["alpha_1", "alpha_2", "alpha_3", "alpha_4", "alpha_5"]
    re_lo, re_hi = scaled.changed["reynolds_number"]
    kc_lo, _ = scaled.changed["keulegan_carpenter_number"]
    assert re_lo == pytest.approx(2.5 * math.sqrt(4.0), rel=1e-9)  # eq. 40
    assert re_hi == pytest.approx(re_lo, rel=1e-12)
    assert kc_lo == pytest.approx(4.0 / 2.5, rel=1e-9)  # section 3.1: KC ~ lambda / beta


def test_keeping_the_coefficients_or_changing_the_water_breaks_the_hydrodynamic_groups(
        tmp_path: Path) -> None:
    kept = scale_case_file(LINDAHL, DISTORTED, output=tmp_path / "a.toml",
                           keep_coefficients=True)
    assert "alpha_5" in kept.changed and "alpha_2" in kept.kept
    # alpha_5 ~ C_dn d L / m: beta lambda / (phi beta^2) with C_dn unchanged (eq. 31e)
    assert kept.changed["alpha_5"][0] == pytest.approx(4.0 / (2.5 * 1.3), rel=1e-9)
    sea = ScaleLaw(37.6, 34.5, 1.3, water_density=1.024)
    salty = scale_case_file(LINDAHL, sea, output=tmp_path / "b.toml")
    ratio = sea.alpha_3_ratio(1000.0 / 7800.0)
    assert salty.changed["alpha_3"][0] == pytest.approx(ratio, rel=1e-9)
    assert salty.case.environment.water_density == pytest.approx(1024.0, rel=1e-12)
    assert {"alpha_1", "alpha_4", "alpha_5"} <= set(salty.kept)


def _values(path: Path) -> dict:
    raw = tomllib.loads(path.read_text())
    raw.pop("description", None)
    return raw


@pytest.mark.parametrize("case", [LINDAHL, BUOY, *DEEPCWIND],
                         ids=["lindahl", "buoy", "deepcwind_lc34", "deepcwind_free_decay"])
def test_scaling_there_and_back_gives_the_original_values_exactly(tmp_path: Path,
                                                                    case: Path) -> None:
    there = tmp_path / "there.toml"
    back = tmp_path / "back.toml"
    law = {LINDAHL: ScaleLaw(37.6, 34.5, 1.2971), BUOY: ScaleLaw(37.6, 37.6, 1.0)}.get(case, TANK)
    original = tomllib.loads(case.read_text())
    original.pop("description", None)
    extra = {"hydro_database": "scaled"} if "hydro" in original else {}
    there.write_text(scale_case_file(case, law, output=there, **extra).text)
    undo = {"hydro_database": original["hydro"]["database"]} if "hydro" in original else {}
    back.write_text(scale_case_file(there, law.inverse(), output=back, **undo).text)
    if "floater" in original and "drag" in original["floater"]:
        # the default strip length, a length, is written out (scaled) by the first scaling
        assert "strip_length" not in original["floater"]["drag"]
        assert tomllib.loads(there.read_text())["floater"]["drag"]["strip_length"] == 0.04
        original["floater"]["drag"]["strip_length"] = 2.0
    assert _values(back) == original


@pytest.mark.parametrize("case", DEEPCWIND, ids=["lc34", "free_decay"])
def test_a_floater_with_morison_drag_scales_and_checks(tmp_path: Path, case: Path,
                                                        capsys) -> None:
    out = tmp_path / "tank.toml"
    scaled = scale_case_file(case, TANK, output=out, hydro_database="deepcwind_1to50")
    old = load_case(case)
    drag_old, drag_new = old.floater.drag, scaled.case.floater.drag
    assert drag_new.coefficients == drag_old.coefficients  # dimensionless, Froude force scale
    assert drag_new.strip_length == pytest.approx(0.02 * drag_old.strip_length, rel=1e-12)
    column_old = old.floater.geometry.columns[1]
    column_new = scaled.case.floater.geometry.columns[1]
    assert column_new.diameter == pytest.approx(0.02 * column_old.diameter, rel=1e-12)
    assert any("floatmoor hydro build tank.toml" in n for n in scaled.notes)  # rebuild it
    out.write_text(scaled.text)
    assert main(["check", str(out)]) == 0
    assert "valid case" in capsys.readouterr().out


def test_a_floater_scales_by_froude(tmp_path: Path) -> None:
    old = load_case(BUOY)
    scaled = scale_case_file(BUOY, ScaleLaw(10.0, 10.0, 1.0), output=tmp_path / "big.toml",
                             hydro_database="buoy_x10").case
    assert scaled.floater.mass == pytest.approx(1e3 * old.floater.mass, rel=1e-11)
    assert scaled.floater.inertia[0] == pytest.approx(1e5 * old.floater.inertia[0], rel=1e-11)
    assert scaled.waves.settings.period == pytest.approx(math.sqrt(10.0), rel=1e-11)
    assert scaled.hydro.database == "buoy_x10"
    np.testing.assert_allclose(scaled.hydro.frequencies,
                               np.asarray(old.hydro.frequencies) / math.sqrt(10.0), rtol=1e-11)
    groups_old, groups_new = cable_groups(old), cable_groups(scaled)
    np.testing.assert_allclose(groups_new.alpha_2, groups_old.alpha_2, rtol=1e-9)


def test_the_command_writes_the_case_and_says_what_is_kept(tmp_path: Path, capsys) -> None:
    out = tmp_path / "prototype.toml"
    status = main(["scale", str(LINDAHL), "--length-scale", "37.6", "--diameter-scale",
                   str(76 / 2.2), "--volume-coefficient-ratio", str(3.58 / 2.76), "-o",
                   str(out)])
    said = capsys.readouterr().out
    assert status == 0
    assert "groups kept exactly: alpha_1, alpha_2, alpha_3, alpha_4, alpha_5" in said
    assert "not kept: reynolds_number" in said
    text = out.read_text()
    assert text.startswith("# Scaled by floatmoor scale")
    assert "Groups not kept (new / old): reynolds_number" in text
    case = load_case(out)
    assert case.lines[0].length == pytest.approx(1240.8, rel=1e-11)
    assert case.line_types["chain"].diameter == pytest.approx(0.076, rel=1e-11)


@pytest.mark.parametrize("argv, says", [
    (["--length-scale", "0"], "--length-scale"),
    (["--length-scale", "abc"], "--length-scale"),
    (["--length-scale", "2", "--diameter-scale", "3"], "how the line mass scales"),
    (["--length-scale", "2", "--water-density", "-1"], "--water-density"),
    (["--length-scale", "2", "--diameter-scale", "3", "--volume-coefficient-ratio", "nan"],
     "--volume-coefficient-ratio"),
])
def test_bad_arguments_are_bad_input(tmp_path: Path, capsys, argv, says) -> None:
    out = tmp_path / "x.toml"
    assert main(["scale", str(LINDAHL), *argv, "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert says in err and "Traceback" not in err
    assert not out.exists()


def _case_with(tmp_path: Path, source: Path, old: str, new: str) -> Path:
    path = tmp_path / source.name
    text = source.read_text()
    assert old in text
    path.write_text(text.replace(old, new).replace("{motion.radius:.2f}", "r").replace(
        "{motion.period:.2f}", "T"))
    return path


def test_what_cannot_be_scaled_is_refused(tmp_path: Path, capsys) -> None:
    out = tmp_path / "x.toml"
    # a floater's database would go stale: a new name is required
    assert main(["scale", str(BUOY), "--length-scale", "2", "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert "hydro.database" in err and "--hydro-database" in err
    assert main(["scale", str(BUOY), "--length-scale", "2", "--hydro-database",
                 "cylinder_buoy", "-o", str(out)]) == 2
    assert "stale" in capsys.readouterr().err
    # a floater with line forces not scaled like its own (Froude)
    assert main(["scale", str(BUOY), "--length-scale", "2", "--diameter-scale", "1",
                 "--match", "elastic", "--hydro-database", "b", "-o", str(out)]) == 2
    assert "--match froude" in capsys.readouterr().err
    assert not out.exists()


#: Shipped cases floatmoor scale refuses, and the key it names: an imported (WAMIT) database,
#: which cannot be rebuilt at another scale, and the rotor's thrust curves.
REFUSED = {"deepcwind_free_decay_wamit.toml": "hydro.source", "deepcwind_lc43.toml": "wind"}


def test_every_shipped_case_scales_or_is_refused_by_name(tmp_path: Path) -> None:
    """Every key of the shipped cases has a rule: a case scales (every alpha kept by plain
    Froude scaling) or is refused naming the key it cannot rewrite."""
    from floatmoor.errors import CaseError

    cases = [p for p in sorted((ROOT / "cases").glob("*/*.toml"))
             if p.parent.name != "uq" and not p.name.startswith("published")]
    assert len(cases) >= 15
    for path in cases:
        try:
            scaled = scale_case_file(path, ScaleLaw(0.02, 0.02, 1.0), output=tmp_path / "s.toml",
                                     hydro_database="scaled_db")
        except CaseError as err:
            assert REFUSED.get(path.name, "not refused") in str(err), (path, err)
            assert "no scaling rule" not in str(err)
            continue
        assert path.name not in REFUSED
        if load_case(path).motion is not None or load_case(path).waves is not None:
            assert scaled.kept[:5] == ["alpha_1", "alpha_2", "alpha_3", "alpha_4",
                                       "alpha_5"], path
            assert list(scaled.changed) == ["reynolds_number"], path
        else:  # a free decay: no period, so only the groups without one
            assert scaled.kept == ["alpha_1", "alpha_4", "alpha_5"], path
            assert not scaled.changed
            assert "Groups not evaluated" in scaled.text


def test_the_match_options_set_phi() -> None:
    from argparse import Namespace

    from floatmoor.cli.scale import law_from_arguments

    def law(**given):
        args = dict(length_scale="0.1", diameter_scale="0.05", volume_coefficient_ratio=None,
                    match=None, water_density=None)
        return law_from_arguments(Namespace(**{**args, **given}), 1000.0)

    froude = law(match="froude", water_density="1025")
    # line forces phi lambda beta^2 = rho lambda^3, the floater's (eq. 37 against Froude)
    assert froude.force == pytest.approx(1.025 * 0.1 ** 3, rel=1e-12)
    assert froude.volume_coefficient == pytest.approx(1.025 * 4.0, rel=1e-12)
    assert law(match="elastic").volume_coefficient == 1.0
    assert law(volume_coefficient_ratio="0.772").volume_coefficient == 0.772
    plain = law(diameter_scale=None)  # beta = lambda: plain Froude scaling, phi = 1
    assert (plain.diameter, plain.volume_coefficient, plain.name) == (0.1, 1.0, "froude")
