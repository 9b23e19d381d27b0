"""The WAMIT reader (floatmoor.io.wamit) on OpenFAST's OC4 DeepCwind ``marin_semi.1`` /
``.hst`` (tests/data/wamit_oc4, Apache-2.0, see its README) and on small synthetic files
written here: dimensions and ULEN exponents, WAMIT's (force, motion) index order, the phase
convention, and every malformed-file error naming its file and line."""

from __future__ import annotations

import math
import os
from pathlib import Path

import numpy as np
import pytest

from floatmoor.io.bem_data import BemFileError
from floatmoor.io.wamit import read_wamit, read_wamit_out

OC4 = Path(__file__).parents[1] / "data" / "wamit_oc4"
RHO, G = 1025.0, 9.80665


@pytest.fixture(scope="module")
def oc4():
    return read_wamit([OC4 / "marin_semi.1", OC4 / "marin_semi.hst"], water_density=RHO)


# --- the OC4 file ------------------------------------------------------------------------

def test_oc4_frequencies(oc4):
    # 500 periods in the file: PER = -1, PER = 0 and 498 finite ones, 628.319 to 1.26168 s.
    assert oc4.omega.shape == (498,)
    assert np.all(np.diff(oc4.omega) > 0.0)
    assert oc4.omega[0] == pytest.approx(2 * math.pi / 628.319, rel=1e-6)
    assert oc4.omega[-1] == pytest.approx(2 * math.pi / 1.26168, rel=1e-6)
    assert oc4.added_mass.shape == oc4.radiation_damping.shape == (498, 6, 6)
    assert oc4.format == "wamit" and oc4.files == (str(OC4 / "marin_semi.1"),
                                                   str(OC4 / "marin_semi.hst"))
    assert oc4.excitation_force is None and oc4.directions is None
    np.testing.assert_array_equal(oc4.rotation_center, np.zeros(3))
    assert oc4.water_density == RHO and oc4.gravity == G


def test_oc4_zero_and_infinite_frequency_rows(oc4):
    # File lines "-0.100000E+01 1 1 8.526887E+03" and "0.000000E+00 1 1 6.329164E+03".
    assert oc4.added_mass_zero[0, 0] == pytest.approx(8526.887 * RHO, rel=1e-12)
    assert oc4.added_mass_infinite[0, 0] == pytest.approx(6329.164 * RHO, rel=1e-12)
    # "0.000000E+00 3 3 1.434026E+04" and "-0.100000E+01 5 5 7.440574E+06" (L^5, L = 1).
    assert oc4.added_mass_infinite[2, 2] == pytest.approx(1.434026e4 * RHO, rel=1e-12)
    assert oc4.added_mass_zero[4, 4] == pytest.approx(7.440574e6 * RHO, rel=1e-12)


def test_oc4_damping_by_hand(oc4):
    # Line 1106: "0.104720E+02 3 3 1.481899E+04 4.425681E+02": B = Bbar rho omega.
    w = int(np.argmin(np.abs(oc4.omega - 2 * math.pi / 10.4720)))
    omega = 2 * math.pi / 10.4720
    assert oc4.omega[w] == pytest.approx(omega, rel=1e-12)
    assert oc4.radiation_damping[w, 2, 2] == pytest.approx(442.5681 * RHO * omega, rel=1e-12)
    assert oc4.added_mass[w, 2, 2] == pytest.approx(1.481899e4 * RHO, rel=1e-12)


def test_oc4_index_order(oc4):
    # WAMIT's A_ij is the force in mode i for motion j; floatmoor's [w, radiating, influenced].
    # Lines 1110 "4 6 4.875592E+01 7.750627E+00" and 1115 "6 4 7.783971E+01 -7.741964E-01".
    w = int(np.argmin(np.abs(oc4.omega - 2 * math.pi / 10.4720)))
    assert oc4.added_mass[w, 5, 3] == pytest.approx(48.75592 * RHO, rel=1e-12)   # A_46
    assert oc4.added_mass[w, 3, 5] == pytest.approx(77.83971 * RHO, rel=1e-12)   # A_64
    omega = 2 * math.pi / 10.4720
    assert oc4.radiation_damping[w, 3, 5] == pytest.approx(-0.7741964 * RHO * omega,
                                                            rel=1e-12)


def test_oc4_absent_pairs_are_zero(oc4):
    # The file has 18 of the 36 pairs per period; (1, 2) is never written.
    assert np.all(oc4.added_mass[:, 1, 0] == 0.0) and np.all(oc4.added_mass_zero[1, 0] == 0)
    assert any("zero" in note and ".1" in note for note in oc4.notes)


def test_oc4_hydrostatics(oc4):
    # "3 3 3.800615E+02", "3 5 -1.533109E-02", "4 4 -3.787550E+04" with rho g L^k.
    c = oc4.hydrostatic_stiffness
    assert c[2, 2] == pytest.approx(380.0615 * RHO * G, rel=1e-12)
    assert c[2, 4] == pytest.approx(-1.533109e-2 * RHO * G, rel=1e-12)
    assert c[3, 3] == pytest.approx(-3.787550e4 * RHO * G, rel=1e-12)
    assert any("buoyancy part" in note for note in oc4.notes)


#: The OC4 WAMIT figures the project's references give (docs/cases/deepcwind.md, notes: A at 0.5 rad/s and
#: at infinity, 3-4 digits); the reader's dimensional values must round to them.
REFERENCE_ADDED_MASS = {0: (9.68e6, 6.49e6), 2: (1.522e7, 1.470e7), 4: (7.99e9, 7.21e9)}
#: Rounding of those figures (the last digit given).
REFERENCE_ROUNDING = 0.003


@pytest.mark.parametrize("k", sorted(REFERENCE_ADDED_MASS))
def test_oc4_against_reference_figures(oc4, k):
    at_half, at_inf = REFERENCE_ADDED_MASS[k]
    assert np.interp(0.5, oc4.omega, oc4.added_mass[:, k, k]) == pytest.approx(
        at_half, rel=REFERENCE_ROUNDING)
    assert oc4.added_mass_infinite[k, k] == pytest.approx(at_inf, rel=REFERENCE_ROUNDING)


# --- synthetic files -----------------------------------------------------------------------

PERIODS = (10.0, 5.0)


def _write(folder: Path, name: str, lines) -> Path:
    path = folder / name
    path.write_text("".join(line + "\n" for line in lines))
    return path


def _one_lines(periods=PERIODS, value=lambda per, i, j: (1.0, 1.0), limits=True):
    lines = []
    if limits:
        lines += [f" -0.100000E+01 {i:5d} {j:5d} {value(-1, i, j)[0]: .6E}"
                  for i in range(1, 7) for j in range(1, 7)]
        lines += [f"  0.000000E+00 {i:5d} {j:5d} {value(0, i, j)[0]: .6E}"
                  for i in range(1, 7) for j in range(1, 7)]
    for per in periods:
        for i in range(1, 7):
            for j in range(1, 7):
                a, b = value(per, i, j)
                lines.append(f"  {per: .6E} {i:5d} {j:5d} {a: .6E} {b: .6E}")
    return lines


def _three_lines(periods=PERIODS, betas=(0.0, 90.0), value=lambda per, beta, i: 1 + 0j):
    lines = []
    for per in periods:
        for beta in betas:
            for i in range(1, 7):
                x = value(per, beta, i)
                lines.append(f"  {per: .6E}  {beta: .6E} {i:5d} {abs(x): .6E} "
                             f"{math.degrees(math.atan2(x.imag, x.real)):10.4f} "
                             f"{x.real: .6E} {x.imag: .6E}")
    return lines


def _hst_lines(value=lambda i, j: 1.0):
    return [f"{i:6d}{j:6d}  {value(i, j): .6E}" for i in range(1, 7) for j in range(1, 7)]


@pytest.fixture
def unit_files(tmp_path):
    return [_write(tmp_path, "b.1", _one_lines()), _write(tmp_path, "b.3", _three_lines()),
            _write(tmp_path, "b.hst", _hst_lines())]


def test_length_scale_exponents(unit_files):
    one = read_wamit(unit_files, water_density=RHO, length_scale=1.0)
    two = read_wamit(unit_files, water_density=RHO, length_scale=2.0)
    trans, rot = slice(0, 3), slice(3, 6)
    for name in ("added_mass", "radiation_damping"):
        ratio = getattr(two, name) / getattr(one, name)
        assert np.all(ratio[:, trans, trans] == 8.0)
        assert np.all(ratio[:, trans, rot] == 16.0) and np.all(ratio[:, rot, trans] == 16.0)
        assert np.all(ratio[:, rot, rot] == 32.0)
    for name in ("added_mass_zero", "added_mass_infinite"):
        ratio = getattr(two, name) / getattr(one, name)
        assert ratio[0, 0] == 8.0 and ratio[0, 4] == 16.0 and ratio[5, 3] == 32.0
    x = two.excitation_force / one.excitation_force
    np.testing.assert_array_equal(x[..., :3], 4.0)
    np.testing.assert_array_equal(x[..., 3:], 8.0)
    c = two.hydrostatic_stiffness / one.hydrostatic_stiffness
    assert c[2, 2] == 4.0 and c[0, 1] == 4.0
    assert c[2, 3] == 8.0 and c[4, 2] == 8.0
    assert c[3, 3] == 16.0 and c[4, 5] == 16.0
    # ... and the L = 1 values are the file's times rho (omega) and rho g.
    assert one.added_mass[0, 0, 0] == RHO
    assert one.radiation_damping[1, 0, 0] == pytest.approx(RHO * 2 * math.pi / 5.0)
    assert one.hydrostatic_stiffness[3, 3] == pytest.approx(RHO * G)


def test_index_convention_on_asymmetric_file(tmp_path):
    # A_15 (force in surge per pitch motion) = 2, A_51 = 3: floatmoor's [w, j, i].
    def value(per, i, j):
        return {(1, 5): (2.0, 20.0), (5, 1): (3.0, 30.0)}.get((i, j), (0.0, 0.0))

    bem = read_wamit([_write(tmp_path, "a.1", _one_lines(value=value))], water_density=1.0)
    assert bem.added_mass[0, 4, 0] == 2.0 and bem.added_mass[0, 0, 4] == 3.0
    omega = bem.omega[0]
    assert bem.radiation_damping[0, 4, 0] == pytest.approx(20.0 * omega)
    assert bem.radiation_damping[0, 0, 4] == pytest.approx(30.0 * omega)
    assert bem.added_mass_zero[4, 0] == 2.0 and bem.added_mass_infinite[0, 4] == 3.0
    # The .hst keeps (force i, motion j) as floatmoor's hydrostatic_stiffness[i, j].
    hst = _write(tmp_path, "a.hst", _hst_lines(lambda i, j: 5.0 if (i, j) == (3, 5) else 0.0))
    c = read_wamit([tmp_path / "a.1", hst], water_density=1.0, gravity=1.0)
    assert c.hydrostatic_stiffness[2, 4] == 5.0 and c.hydrostatic_stiffness[4, 2] == 0.0


def test_frequencies_sorted_increasing_with_their_values(tmp_path):
    periods = (5.0, 20.0, 10.0)         # neither increasing nor decreasing

    def value(per, i, j):
        return (per, per / 10)

    def exc(per, beta, i):
        return complex(per, beta)

    bem = read_wamit([_write(tmp_path, "s.1", _one_lines(periods, value, limits=False)),
                      _write(tmp_path, "s.3", _three_lines(periods, (45.0, -30.0), exc))],
                     water_density=1.0, gravity=1.0)
    np.testing.assert_allclose(bem.omega, 2 * math.pi / np.array([20.0, 10.0, 5.0]))
    np.testing.assert_array_equal(bem.added_mass[:, 2, 2], [20.0, 10.0, 5.0])
    np.testing.assert_allclose(bem.directions, np.radians([-30.0, 45.0]))
    np.testing.assert_allclose(bem.excitation_force[:, 1, 0], [20 - 45j, 10 - 45j, 5 - 45j])
    assert bem.added_mass_zero is None and bem.added_mass_infinite is None


def test_excitation_phase_is_conjugated(tmp_path):
    # A line with Re = 3, Im = 4 (phase +53.13 deg in WAMIT's e^{+i omega t}) is 3 - 4i in
    # floatmoor's e^{-i omega t}: the force lags the crest by the same time.
    one = _write(tmp_path, "c.1", _one_lines())
    three = _write(tmp_path, "c.3", [
        f"  {per: .6E}  {90.0: .6E} {i:5d}  5.000000E+00   53.1301  3.000000E+00  4.000000E+00"
        for per in PERIODS for i in range(1, 7)])
    bem = read_wamit([one, three], water_density=1000.0, gravity=10.0)
    assert bem.directions.tolist() == [pytest.approx(math.pi / 2)]
    assert bem.excitation_force.shape == (2, 1, 6)
    assert bem.excitation_force[0, 0, 2] == pytest.approx((3 - 4j) * 1e4)
    assert bem.excitation_force[0, 0, 4] == pytest.approx((3 - 4j) * 1e4)   # L^3, L = 1
    assert bem.froude_krylov_force is None and bem.diffraction_force is None


def test_parts_sum_and_derived_part(tmp_path):
    one = _write(tmp_path, "p.1", _one_lines())
    fk = _write(tmp_path, "p.3fk", _three_lines(value=lambda per, beta, i: 1 + 2j))
    sc = _write(tmp_path, "p.3sc", _three_lines(value=lambda per, beta, i: 0.5 - 1j))
    both = read_wamit([one, fk, sc], water_density=1.0, gravity=1.0)
    np.testing.assert_allclose(both.excitation_force, np.conj(1.5 + 1j))
    np.testing.assert_allclose(both.froude_krylov_force, np.conj(1 + 2j))
    np.testing.assert_allclose(both.diffraction_force, np.conj(0.5 - 1j))
    total = _write(tmp_path, "p.3", _three_lines(value=lambda per, beta, i: 1.5 + 1j))
    derived = read_wamit([one, total, fk], water_density=1.0, gravity=1.0)
    np.testing.assert_allclose(derived.diffraction_force, np.conj(0.5 - 1j), atol=1e-6)
    assert any(".3 - .3fk" in note for note in derived.notes)


# --- malformed files -----------------------------------------------------------------------

def _error(tmp_path, files: dict[str, list[str]], **kwargs) -> BemFileError:
    paths = [_write(tmp_path, name, lines) for name, lines in files.items()]
    with pytest.raises(BemFileError) as info:
        read_wamit(paths, water_density=RHO, **kwargs)
    return info.value


def _replace(lines: list[str], index: int, text: str) -> list[str]:
    out = list(lines)
    out[index] = text
    return out


GOOD_ONE = _one_lines()
GOOD_THREE = _three_lines()
# Line 73 of GOOD_ONE is the first finite-period line: "10.0 1 1 1.0 1.0".
FIRST_FINITE = 72


@pytest.mark.parametrize("text, line, expected, found", [
    ("  1.000000E+01     1     1  1.0  1.0  9.0", 73, "5 columns", "6:"),
    ("  1.000000E+01     1     1  1.0", 73, "5 columns 'PER I J Abar Bbar'", "4:"),
    ("  1.000000E+01     1     1  1.0  abc", 73, "a number (Bbar)", "'abc'"),
    ("  1.000000E+01     1     1  nan  1.0", 73, "a finite number (Abar)", "'nan'"),
    ("  1.000000E+01     1     1  1.0  inf", 73, "a finite number (Bbar)", "'inf'"),
    ("  1.000000E+01     1     0  1.0  1.0", 73, "a mode index J in 1..6", "index 0"),
    ("  1.000000E+01     7     1  1.0  1.0", 73, "multi-body WAMIT files are not supported",
     "index 7"),
    ("  1.000000E+01   1.5     1  1.0  1.0", 73, "an integer mode index I", "'1.5'"),
    ("  1.000000E+01     1     2  1.0  1.0", 74, "one line per (PER, I, J)",
     "PER = 1.000000E+01, I = 1, J = 2 (first at line 73)"),
    (" -2.000000E+00     1     1  1.0  1.0", 73, "a wave period PER > 0, or -1", "PER = -2"),
])
def test_radiation_line_errors(tmp_path, text, line, expected, found):
    err = _error(tmp_path, {"m.1": _replace(GOOD_ONE, FIRST_FINITE, text)})
    message = str(err)
    assert message.startswith(f"{tmp_path / 'm.1'}: line {line}: expected ")
    assert expected in message and found in message


def test_limit_period_line_with_damping_column(tmp_path):
    err = _error(tmp_path, {"m.1": _replace(GOOD_ONE, 0,
                                            " -0.100000E+01 1 1 8.5E+03 1.0E+00")})
    assert str(err).startswith(f"{tmp_path / 'm.1'}: line 1: expected 4 columns 'PER I J "
                               "Abar (no Bbar at PER = -1 or 0)', found 5")


def test_fewer_than_two_finite_periods(tmp_path):
    err = _error(tmp_path, {"m.1": _one_lines(periods=(10.0,))})
    assert str(err) == f"{tmp_path / 'm.1'}: expected at least 2 finite wave periods " \
                       "(PER > 0), found 1"


def test_empty_and_missing_files(tmp_path):
    err = _error(tmp_path, {"m.1": ["", "   "]})
    assert str(err) == f"{tmp_path / 'm.1'}: expected lines 'PER I J Abar [Bbar]', found " \
                       "an empty file"
    with pytest.raises(BemFileError, match=r"nowhere\.1: expected a WAMIT added mass and "
                       r"damping \(\.1\) file, found no such file"):
        read_wamit([tmp_path / "nowhere.1"], water_density=RHO)
    err = _error(tmp_path, {"m.1": GOOD_ONE, "m.3": []})
    assert str(err).startswith(f"{tmp_path / 'm.3'}: expected lines 'PER BETA I Mod Pha Re "
                               "Im', found an empty file")


def test_excitation_missing_frequencies(tmp_path):
    err = _error(tmp_path, {"m.1": _one_lines(periods=(10.0, 5.0, 2.5)), "m.3": GOOD_THREE})
    assert str(err) == (
        f"{tmp_path / 'm.3'}: wave periods: expected the finite periods of "
        f"{tmp_path / 'm.1'} (3 periods), found missing frequencies: no lines for PER = 2.5 s "
        "(omega = 2.513 rad/s)")
    err = _error(tmp_path, {"m.1": GOOD_ONE, "m.3": _three_lines(periods=(10.0, 5.0, 4.0))})
    assert "found periods absent from" in str(err) and "PER = 4 s" in str(err)


def test_excitation_period_missing_a_direction(tmp_path):
    lines = GOOD_THREE[:-6]              # period 5 s has no BETA = 90 lines
    err = _error(tmp_path, {"m.1": GOOD_ONE, "m.3": lines})
    assert str(err) == (f"{tmp_path / 'm.3'}: PER = 5 s: expected every wave direction of the "
                        "file (2: BETA = 0, 90 deg), found no lines for BETA = 90 deg")


@pytest.mark.parametrize("text, line, expected, found", [
    ("  1.000000E+01  0.0  1  1.0  0.0  1.0", 1, "7 columns 'PER BETA I Mod Pha Re Im'",
     "6:"),
    ("  1.000000E+01  0.0  9  1.0  0.0  1.0  0.0", 1, "multi-body WAMIT files are not "
     "supported", "index 9"),
    ("  1.000000E+01  0.0  1  1.0  0.0  NaN  0.0", 1, "a finite number (Re)", "'NaN'"),
    ("  1.000000E+01  0.0  2  1.0  0.0  1.0  0.0", 2, "one line per (PER, BETA, I)",
     "I = 2 (first at line 1)"),
    ("  1.000000E+01  0.0  1  1.0  90.0  1.0  0.0", 1, "Mod and Pha agreeing with Re and Im",
     "Mod e^(i Pha) = 6.12323e-17+1i, Re + i Im = 1+0i"),
])
def test_excitation_line_errors(tmp_path, text, line, expected, found):
    err = _error(tmp_path, {"m.1": GOOD_ONE, "m.3": _replace(GOOD_THREE, 0, text)})
    message = str(err)
    assert message.startswith(f"{tmp_path / 'm.3'}: line {line}: expected ")
    assert expected in message and found in message


def test_excitation_parts_inconsistent_or_alone(tmp_path):
    err = _error(tmp_path, {"m.1": GOOD_ONE, "m.3": GOOD_THREE,
                            "m.3fk": _three_lines(value=lambda per, beta, i: 0.5 + 0j),
                            "m.3sc": _three_lines(value=lambda per, beta, i: 0.4 + 0j)})
    assert str(err).startswith(f"{tmp_path / 'm.3'}: PER = 10 s, BETA = 0 deg, I = 1: "
                               f"expected the sum of {tmp_path / 'm.3fk'} and")
    err = _error(tmp_path, {"m.1": GOOD_ONE, "m.3fk": GOOD_THREE})
    assert str(err) == (f"{tmp_path / 'm.3fk'}: expected the .3 file with it, or both .3fk "
                        "and .3sc (the excitation is their sum), found no .3 and no .3sc")


def test_hydrostatics_errors(tmp_path):
    hst = _hst_lines()
    err = _error(tmp_path, {"m.1": GOOD_ONE, "m.hst": hst + ["     3     3   2.0"]})
    assert str(err) == (f"{tmp_path / 'm.hst'}: line 37: expected one line per (I, J), found "
                        "a second line for I = 3, J = 3 (first at line 15)")
    err = _error(tmp_path, {"m.1": GOOD_ONE, "m.hst": _replace(hst, 3, "  1  4")})
    assert str(err).startswith(f"{tmp_path / 'm.hst'}: line 4: expected 3 columns 'I J Cbar'")
    err = _error(tmp_path, {"m.1": GOOD_ONE, "m.hst": _replace(hst, 3, "  1  12  0.0")})
    assert "line 4: expected a mode index J in 1..6 (one rigid body; multi-body" in str(err)


def test_file_set_errors(tmp_path):
    one = _write(tmp_path, "m.1", GOOD_ONE)
    with pytest.raises(BemFileError, match=r"m\.2: expected a WAMIT file ending in \.1, \.3, "
                       r"\.3fk, \.3sc, \.hst, \.out, found extension '\.2'"):
        read_wamit([one, _write(tmp_path, "m.2", GOOD_THREE)], water_density=RHO)
    with pytest.raises(BemFileError, match=r"n\.1: expected one \.1 file, found a second"):
        read_wamit([one, _write(tmp_path, "n.1", GOOD_ONE)], water_density=RHO)
    with pytest.raises(BemFileError, match=r"expected a WAMIT \.1 file .* found none"):
        read_wamit([_write(tmp_path, "m.hst", _hst_lines())], water_density=RHO)
    for bad in ({"water_density": 0.0}, {"water_density": RHO, "gravity": float("nan")},
                {"water_density": RHO, "length_scale": -1.0},
                {"water_density": RHO, "water_depth": 0.0}):
        with pytest.raises(ValueError):
            read_wamit([one], **bad)
    assert read_wamit([one], water_density=RHO, water_depth=math.inf).water_depth == math.inf


@pytest.mark.parametrize("lines, depth, gravity, ulen", [
    ([" Gravity:     9.80665                Length scale:        1.00000",
      " Water depth:        200.000000"], 200.0, 9.80665, 1.0),
    ([" Water depth:        infinite", " Gravity:     9.81"], math.inf, 9.81, None),
])
def test_run_summary_states_depth_gravity_and_ulen(tmp_path, lines, depth, gravity, ulen):
    out = _write(tmp_path, "m.out", [" WAMIT  Version 7.3", *lines, " ILOG = 1"])
    summary = read_wamit_out(out)
    assert (summary.water_depth, summary.gravity, summary.length_scale) == (depth, gravity, ulen)


@pytest.mark.parametrize("lines, message", [
    ([" Gravity:     9.80665"], "m.out: water depth: expected a WAMIT run summary with its "
     "'Water depth:' line, found none"),
    ([" Water depth:        deep"], "m.out: line 1: expected a number (Water depth: [m]), "
     "found 'deep'"),
    ([" Water depth:        -3.0"], "m.out: line 1: expected a number > 0 after 'Water depth:'"),
])
def test_run_summary_errors_name_file_and_line(tmp_path, lines, message):
    with pytest.raises(BemFileError) as err:
        read_wamit_out(_write(tmp_path, "m.out", lines))
    assert message in str(err.value)


#: A WAMIT run summary's header and body parameters as WAMIT prints them (the lines WEC-Sim's
#: BEMIO and OpenFAST's tools read: "Volumes (VOLX,VOLY,VOLZ):", "Center of Buoyancy
#: (Xb,Yb,Zb):"), for the OC4 semisubmersible; the period tables that follow are not read.
OUT_EXCERPT = """ WAMIT  Version 7.3
 Gravity:     9.80665                Length scale:        1.00000
 Water depth:        200.000000    Water density:      1025.00000
 Logarithmic singularity index:              ILOG =     1

 Body number: N= 1   Total panels:  5400    Waterline panels:   240      Symmetries: none
 Irregular frequency index: IRR = 0

 XBODY =    0.0000 YBODY =    0.0000 ZBODY =    0.0000 PHIBODY =   0.0
 Volumes (VOLX,VOLY,VOLZ):     13917.4     13916.9     13917.0
 Center of Buoyancy (Xb,Yb,Zb):     -0.000000    0.000000  -13.150000
 Hydrostatic and gravitational restoring coefficients:
 C(3,3),C(3,4),C(3,5):   380.06     0.0000     0.0000
"""


def test_run_summary_states_volume_and_centre_of_buoyancy(tmp_path):
    """The body parameters of a .out: VOLZ as the displaced volume, the centre of buoyancy in
    the body frame, as printed (dimensional)."""
    summary = read_wamit_out(_write(tmp_path, "m.out", OUT_EXCERPT.splitlines()))
    assert summary.volumes == (13917.4, 13916.9, 13917.0)
    assert summary.disp_volume == 13917.0
    assert summary.center_of_buoyancy == (-0.0, 0.0, -13.15)
    assert (summary.water_depth, summary.gravity, summary.length_scale) == (200.0, 9.80665, 1.0)
    header = read_wamit_out(_write(tmp_path, "h.out", OUT_EXCERPT.splitlines()[:3]))
    assert header.disp_volume is None and header.center_of_buoyancy is None


@pytest.mark.parametrize("edit, message", [
    (lambda t: t.replace("  -13.150000", ""),
     "m.out: line 11: expected three numbers after 'Center of Buoyancy (Xb,Yb,Zb):', found "
     "'-0.000000 0.000000'"),
    (lambda t: t.replace("13917.0", "0.0"),
     "m.out: line 10: expected a volume VOLZ > 0 after 'Volumes (VOLX,VOLY,VOLZ):'"),
    (lambda t: t.replace("13916.9", "big"), "m.out: line 10: expected a number"),
    (lambda t: t + " Volumes (VOLX,VOLY,VOLZ):  10.0 10.0 10.0\n",
     "m.out: line 14: expected one body's 'Volumes (VOLX,VOLY,VOLZ):' line (one rigid body "
     "per import; multi-body WAMIT runs are not supported), found a second one (first at "
     "line 10)"),
])
def test_run_summary_body_lines_are_strict(tmp_path, edit, message):
    with pytest.raises(BemFileError) as err:
        read_wamit_out(_write(tmp_path, "m.out", edit(OUT_EXCERPT).splitlines()))
    assert message in str(err.value)


# --- files from elsewhere (docs/guide/safeguards.md#files-from-elsewhere) ------------------

def test_oversized_file_is_refused_before_reading(tmp_path, monkeypatch):
    """A sparse 4 GB .1 (a MemoryError before the bound): refused by its size, unread."""
    from floatmoor.io import wamit

    path = tmp_path / "big.1"
    with open(path, "wb") as f:
        f.truncate(4 * 2**30)
    with pytest.raises(BemFileError) as info:
        read_wamit([path], water_density=RHO)
    assert str(info.value) == (f"{path}: expected a WAMIT added mass and damping (.1) file, "
                               f"found a file of {4 * 2**30} bytes, more than the "
                               f"{wamit.MAX_FILE_BYTES} bytes read")


@pytest.mark.parametrize("kind, found", [("fifo", "a FIFO (named pipe)"),
                                         ("device", "a character device")])
def test_fifo_and_device_are_refused_unopened(tmp_path, kind, found):
    path = tmp_path / "m.1"
    if kind == "fifo":
        os.mkfifo(path)
    else:
        path.symlink_to("/dev/zero")
    with pytest.raises(BemFileError) as info:
        read_wamit([path], water_density=RHO)
    assert str(info.value) == (f"{path}: expected a WAMIT added mass and damping (.1) file, "
                               f"found {found}, not a regular file")


def test_quoted_tokens_are_shown_escaped(tmp_path):
    err = _error(tmp_path, {"m.1": ["10.0 1 1 \x1b]0;owned\x07 1.0"]})
    assert "\x1b" not in str(err) and "'\\x1b]0;owned\\x07'" in str(err)


def test_distinct_periods_and_directions_are_bounded(tmp_path, monkeypatch):
    from floatmoor.io import wamit

    monkeypatch.setattr(wamit, "MAX_PERIODS", 2)
    err = _error(tmp_path, {"m.1": _one_lines(periods=(10.0, 5.0, 2.5, 1.25))})
    assert "line 145: expected at most 4 distinct wave periods (PER = -1 and 0 included), " \
        "found one more, 2.5" in str(err)
    monkeypatch.setattr(wamit, "MAX_PERIODS", 10)
    monkeypatch.setattr(wamit, "MAX_DIRECTIONS", 1)
    three = [f"10.0 {beta} 1 1.0 0.0 1.0 0.0" for beta in (0.0, 90.0)]
    err = _error(tmp_path, {"m.1": _one_lines(periods=(10.0, 5.0)), "m.3": three})
    assert "m.3: line 2: expected at most 1 distinct wave directions, found one more, 90" \
        in str(err)

