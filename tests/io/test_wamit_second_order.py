"""The WAMIT second-order reader (floatmoor.io.wamit_second_order): mean drift ``.8``/``.9``
and difference-frequency QTF ``.12d`` written here from known SI values read back to
round-off (normalisation by rho g ULEN^k, the conjugated phase, the Hermitian fill, the
diagonal against the ``.9``), every refusal naming its file and line, and a real file: the
last 6 periods of the IEA-15-240-RWT VolturnUS-S ``.12d`` (tests/data/wamit_iea15_qtf)."""

from __future__ import annotations

import cmath
import math
from pathlib import Path

import numpy as np
import pytest

from floatmoor.io.bem_data import BemFileError
from floatmoor.io.wamit_second_order import (
    QTF_DIAGONAL_RTOL, read_wamit_second_order,
)
from tests.io.wamit_files import drift_lines, qtf_lines, scale, write

RHO, G, ULEN = 1025.0, 9.80665, 2.0
PERIODS = (10.0, 5.0)                   # the .1's periods (omega increasing: 10 s first)
BETAS = (0.0, 90.0)                     # the .3's directions
QTF_PERIODS = (10.0, 5.0, 2.5)
IEA = Path(__file__).parents[1] / "data" / "wamit_iea15_qtf" / \
    "IEA-15-240-RWT-UMaineSemi_subset.12d"


def drift_si(per, beta, i):
    """A known mean drift [N/m^2, N m/m^2], different per period, direction and mode."""
    return (1000.0 * i + 37.0 * per) * (1.0 if beta == 0.0 else -0.5)


def qtf_si(w1, w2, i):
    """A known Hermitian difference QTF in capytaine's e^{-i omega t} convention [SI]: real
    diagonal, a phase of 30 deg per unit of (w1 - w2) off it."""
    return (500.0 * i + 100.0 * (w1 + w2)) * cmath.exp(1j * math.radians(30.0) * (w1 - w2))


def wamit_qtf(p1, p2, i):
    """qtf_si as WAMIT writes it: conjugated (e^{+i omega t}) and non-dimensional."""
    w1, w2 = 2 * math.pi / p1, 2 * math.pi / p2
    return np.conj(qtf_si(w1, w2, i)) / scale(RHO, G, ULEN, i)


def _read(files: dict[str, Path], directions=BETAS):
    return read_wamit_second_order(
        files, periods=list(PERIODS), reference_name="b.1", directions_deg=directions,
        excitation_name="b.3", water_density=RHO, gravity=G, length_scale=ULEN)


def _drift(tmp_path, kind, value=None, **kwargs):
    modes = (1, 2, 6) if kind == ".8" else (1, 2, 3, 4, 5, 6)
    value = value or (lambda per, beta, i: drift_si(per, beta, i) / scale(RHO, G, ULEN, i))
    return write(tmp_path, f"b{kind}", drift_lines(PERIODS, BETAS, value, modes=modes,
                                                   **kwargs))


def test_mean_drift_read_back_in_si(tmp_path):
    second = _read({".8": _drift(tmp_path, ".8"), ".9": _drift(tmp_path, ".9")})
    for w, per in enumerate(PERIODS):
        for b, beta in enumerate(BETAS):
            for i in range(1, 7):
                expected = drift_si(per, beta, i)
                assert second.near_field[w, b, i - 1] == pytest.approx(expected, rel=1e-6)
                if i in (1, 2, 6):
                    assert second.far_field[w, b, i - 1] == pytest.approx(expected, rel=1e-6)
                else:  # the momentum route gives Surge, Sway and Yaw only
                    assert math.isnan(second.far_field[w, b, i - 1])
    assert "WAMIT .8, momentum" in second.far_field_from
    assert "WAMIT .9, pressure" in second.near_field_from


def test_qtf_phase_convention_and_hermitian_fill(tmp_path):
    """WAMIT writes one triangle (PER1 <= PER2) in e^{+i omega t}: the database holds the
    conjugate on the whole plane, Q(w2, w1) = conj(Q(w1, w2)), with a real diagonal."""
    path = write(tmp_path, "b.12d", qtf_lines(QTF_PERIODS, wamit_qtf))
    second = _read({".12d": path})
    omega = 2 * math.pi / np.array(QTF_PERIODS)
    np.testing.assert_allclose(second.qtf_omega, omega)
    q = second.qtf_difference[0]
    for a in range(3):
        for b in range(3):
            for i in range(1, 7):
                assert q[a, b, i - 1] == pytest.approx(qtf_si(omega[a], omega[b], i),
                                                       rel=2e-6)
    # one entry by hand: PER1 = 2.5 s, PER2 = 10 s, Surge: WAMIT's phase is -30 deg x
    # (w1 - w2); ours +30 deg x (w1 - w2) = +56.5 deg
    w1, w2 = omega[2], omega[0]
    assert math.degrees(cmath.phase(q[2, 0, 0])) == pytest.approx(30.0 * (w1 - w2), abs=1e-4)
    assert np.all(q[np.arange(3), np.arange(3)].imag == 0.0)
    np.testing.assert_allclose(q, np.conj(np.transpose(q, (1, 0, 2))), rtol=0, atol=0)


def test_qtf_force_of_a_bichromatic_sea_is_wamits(tmp_path):
    """The contract's F(t) = Re sum_ij A_i conj(A_j) Q(w_i, w_j) e^{-i (w_i - w_j) t} with
    capytaine's amplitudes equals WAMIT's sum with its own (conjugate) amplitudes and QTF."""
    second = _read({".12d": write(tmp_path, "b.12d", qtf_lines(QTF_PERIODS, wamit_qtf))})
    omega, q = second.qtf_omega, second.qtf_difference[0, :, :, 0]
    amp = np.array([0.7 * cmath.exp(0.3j), 1.1 * cmath.exp(-1.2j), 0.4 * cmath.exp(2.0j)])
    for t in (0.0, 3.7, 11.0):
        ours = sum((amp[i] * np.conj(amp[j]) * q[i, j]
                    * cmath.exp(-1j * (omega[i] - omega[j]) * t)).real
                   for i in range(3) for j in range(3))
        a_w = np.conj(amp)                 # WAMIT's e^{+i omega t} amplitudes
        theirs = 0.0
        for i, p1 in enumerate(QTF_PERIODS):
            for j, p2 in enumerate(QTF_PERIODS):
                q_w = (wamit_qtf(p1, p2, 1) if p1 <= p2 else np.conj(wamit_qtf(p2, p1, 1))) \
                    * scale(RHO, G, ULEN, 1)
                theirs += (a_w[i] * np.conj(a_w[j]) * q_w
                           * cmath.exp(1j * (omega[i] - omega[j]) * t)).real
        assert ours == pytest.approx(theirs, rel=1e-6)


@pytest.mark.parametrize("triangle", ["other", "both"])
def test_qtf_either_triangle_or_both(tmp_path, triangle):
    wamit = _read({".12d": write(tmp_path, "w.12d", qtf_lines(QTF_PERIODS, wamit_qtf))})

    def value(p1, p2, i):
        return wamit_qtf(p1, p2, i) if p1 <= p2 else np.conj(wamit_qtf(p2, p1, i))

    other = _read({".12d": write(tmp_path, "o.12d", qtf_lines(QTF_PERIODS, value,
                                                              triangle=triangle))})
    np.testing.assert_allclose(other.qtf_difference, wamit.qtf_difference, rtol=2e-6)


def test_qtf_diagonal_agrees_with_the_9(tmp_path):
    """A .12d whose diagonal is the .9's drift is accepted with a note; one from another
    run (the .9 scaled by 1.2: 20 % of the peak) is refused naming both files."""
    def diagonal_is_drift(p1, p2, i):
        if p1 == p2 and p1 in PERIODS:
            return drift_si(p1, 0.0, i) / scale(RHO, G, ULEN, i)
        return wamit_qtf(p1, p2, i)

    qtf = write(tmp_path, "b.12d", qtf_lines(QTF_PERIODS, diagonal_is_drift))
    second = _read({".9": _drift(tmp_path, ".9"), ".12d": qtf})
    assert any("diagonal agrees with" in note and "(worst 0.00% of the peak drift) at 2 "
               "common frequencies" in note for note in second.notes)
    other = _drift(tmp_path, ".9", value=lambda per, beta, i: 1.2 * drift_si(per, beta, i)
                   / scale(RHO, G, ULEN, i))
    with pytest.raises(BemFileError) as err:
        _read({".9": other, ".12d": qtf})
    message = str(err.value)
    assert message.startswith(f"{qtf}: PER1 = PER2 = ")
    assert f"the mean drift of {other} on the diagonal" in message
    assert f"within {QTF_DIAGONAL_RTOL:.0%}" in message and "\n" not in message


def _lines(path: Path) -> list[str]:
    return path.read_text().splitlines()


def _edit(path: Path, index: int, text: str | None) -> Path:
    lines = _lines(path)
    if text is None:
        del lines[index]
    else:
        lines[index] = text
    return write(path.parent, path.name, lines)


def _column(path: Path, index: int, column: int, token: str) -> str:
    parts = _lines(path)[index].split()
    parts[column] = token
    return "  ".join(parts)


# (file kind, edit of the written file -> (line number, text fragments of the message))
DRIFT_REFUSALS = [
    (".9", lambda p: _edit(p, 1, "  1.0 0.0 0.0 1 1.0 0.0 1.0"), 2,
     ["8 columns 'PER BETA1 BETA2 I Mod Pha Re Im (a .3 has 7 columns", "found 7"]),
    (".9", lambda p: _edit(p, 3, _column(p, 3, 6, "abc")), 4, ["a number (Re)", "'abc'"]),
    (".9", lambda p: _edit(p, 3, _column(p, 3, 6, "nan")), 4, ["a finite number (Re)"]),
    (".9", lambda p: _edit(p, 3, _column(p, 3, 3, "7")), 4,
     ["a mode index I in 1..6 (one rigid body", "index 7"]),
    (".9", lambda p: _edit(p, 3, _column(p, 3, 3, "0")), 4, ["a mode index I in 1..6",
                                                            "index 0"]),
    (".9", lambda p: _edit(p, 3, _lines(p)[2]), 4,
     ["one line per (PER, BETA1, BETA2, I)", "first at line 3"]),
    (".9", lambda p: _edit(p, 3, _column(p, 3, 5, "179.0")), 4, ["Mod and Pha agreeing"]),
    (".9", lambda p: _edit(p, 3, "  1.0E+01  0.0  0.0  3  1.0  45.0  0.70710678  0.70710678"),
     4, ["a real mean drift", "Im = "]),
    (".8", lambda p: _edit(p, 3, _column(p, 3, 3, "3")), 4,
     ["mode indices 1, 2 and 6 only", "I = 3"]),
]


@pytest.mark.parametrize("kind, edit, line, fragments", DRIFT_REFUSALS)
def test_mean_drift_line_refusals_name_file_and_line(tmp_path, kind, edit, line, fragments):
    path = edit(_drift(tmp_path, kind))
    with pytest.raises(BemFileError) as err:
        _read({kind: path})
    message = str(err.value)
    assert message.startswith(f"{path}: line {line}: expected "), message
    for fragment in fragments:
        assert fragment in message, message


def test_mean_drift_set_refusals(tmp_path):
    def refused(files, *fragments, directions=BETAS):
        with pytest.raises(BemFileError) as err:
            _read(files, directions=directions)
        for fragment in fragments:
            assert fragment in str(err.value), str(err.value)
        assert "\n" not in str(err.value)

    empty = write(tmp_path, "e.9", [])
    refused({".9": empty}, f"{empty}: expected lines", "an empty file")
    refused({".9": tmp_path / "none.9"}, "no such file")
    # the .8's content named .9
    eight = _drift(tmp_path, ".8")
    nine = write(tmp_path, "c.9", _lines(eight))
    refused({".9": nine}, "the six modes of a pressure-integration .9", "I = 1, 2, 6 only")
    # an entry missing (Sway at the first period and direction)
    refused({".9": _edit(_drift(tmp_path, ".9"), 2, None)}, "PER = 10 s, BETA = 0 deg",
            "none for I = 2")
    # a period the .1 does not have, and one missing
    other = write(tmp_path, "p.9", drift_lines((10.0, 4.0), BETAS, lambda *a: 1.0))
    refused({".9": other}, f"{other}: wave periods: expected the finite periods of b.1",
            "missing frequencies", "periods absent from b.1")
    # directions not the .3's
    refused({".9": _drift(tmp_path, ".9")}, "expected the directions of b.3",
            "found 0, 90 deg", directions=(0.0, 45.0))
    # a direction missing at one period
    lines = [x for x in _lines(_drift(tmp_path, ".9")) if not (x.split()[0].startswith("5.")
                                                               and x.split()[1] != "0.000000E+00")]
    refused({".9": write(tmp_path, "d.9", lines)}, "PER = 5 s", "no lines for BETA = 90 deg")
    # no .3 given: no wave directions to store the drift at
    refused({".9": _drift(tmp_path, ".9")}, "the .3 file with it", directions=None)


def test_mean_drift_skips_moving_frame_and_bidirectional_lines_with_notes(tmp_path):
    path = _drift(tmp_path, ".9")
    lines = _lines(path)
    moving = lines[1].split()
    moving[3] = "-1"
    crossed = lines[1].split()
    crossed[2] = "45.0"
    write(tmp_path, path.name, lines + ["  ".join(moving), "  ".join(crossed)])
    second = _read({".9": path})
    assert second.near_field[0, 0, 0] == pytest.approx(drift_si(10.0, 0.0, 1), rel=1e-6)
    assert any("1 lines with a negative mode index" in n for n in second.notes)
    assert any("1 lines of bidirectional pairs" in n for n in second.notes)


def _qtf(tmp_path, value=wamit_qtf, **kwargs):
    return write(tmp_path, "b.12d", qtf_lines(QTF_PERIODS, value, **kwargs))


QTF_REFUSALS = [
    (lambda p: _edit(p, 1, " ".join(_lines(p)[1].split()[:8])), 2,
     ["9 columns 'PER1 PER2 BETA1 BETA2 I Mod Pha Re Im (a .8 or .9 has 8", "found 8"]),
    (lambda p: _edit(p, 1, _column(p, 1, 0, "-1.0")), 2, ["wave periods PER1, PER2 > 0"]),
    (lambda p: _edit(p, 2, _lines(p)[1]), 3, ["one line per (PER1, PER2, BETA1, BETA2, I)"]),
    (lambda p: _edit(p, 2, _column(p, 2, 4, "-7")), 3, ["a mode index I in 1..6",
                                                        "index -7"]),
    (lambda p: _edit(p, 2, _column(p, 2, 7, "inf")), 3, ["a finite number (Re)"]),
]


@pytest.mark.parametrize("edit, line, fragments", QTF_REFUSALS)
def test_qtf_line_refusals_name_file_and_line(tmp_path, edit, line, fragments):
    path = edit(_qtf(tmp_path))
    with pytest.raises(BemFileError) as err:
        _read({".12d": path})
    message = str(err.value)
    assert message.startswith(f"{path}: line {line}: expected "), message
    for fragment in fragments:
        assert fragment in message, message


def test_qtf_holes_complex_diagonal_and_disagreeing_triangles_are_refused(tmp_path):
    # a hole: the pair (2.5 s, 10 s) missing in both triangles
    path = _qtf(tmp_path)
    kept = [x for x in _lines(path) if not (x.split()[0] == "2.500000E+00"
                                            and x.split()[1] == "1.000000E+01"
                                            and x.split()[4] == "3")]
    write(tmp_path, path.name, kept)
    with pytest.raises(BemFileError, match=r"PER1 = 10 s, PER2 = 2.5 s, BETA = 0 deg, "
                       r"I = 3: expected a line for every pair .* found none \(a hole"):
        _read({".12d": path})
    # a sum-frequency file (complex diagonal) named .12d
    sum_qtf = _qtf(tmp_path, value=lambda p1, p2, i: cmath.exp(0.5j) * (1 + i))
    with pytest.raises(BemFileError, match=r"b.12d: line [0-9]+: expected a real diagonal Q\(w, w\)"):
        _read({".12d": sum_qtf})
    # both triangles given, not Hermitian
    both = _qtf(tmp_path, value=lambda p1, p2, i: wamit_qtf(min(p1, p2), max(p1, p2), i),
                triangle="both")
    with pytest.raises(BemFileError, match=r"expected Q\(PER2, PER1\) = conj\(Q\(PER1, PER2"):
        _read({".12d": both})
    # one period only
    one = write(tmp_path, "one.12d", qtf_lines((10.0,), wamit_qtf))
    with pytest.raises(BemFileError, match="at least 2 wave periods in the QTF"):
        _read({".12d": one})


def test_real_wamit_12d_values_by_hand():
    """The IEA-15 VolturnUS-S .12d subset: WAMIT's header skipped, CRLF lines, 6 periods
    2.0944-2.2848 s, one direction; entries checked by hand against the file's lines."""
    second = read_wamit_second_order(
        {".12d": IEA}, periods=[1.0, 2.0], reference_name="-", directions_deg=None,
        excitation_name="-", water_density=1025.0, gravity=9.80665)
    rho_g = 1025.0 * 9.80665
    np.testing.assert_allclose(second.qtf_omega, 2 * np.pi / np.array(
        [2.2848, 2.2440, 2.2046, 2.1666, 2.1299, 2.0944]))
    assert second.qtf_directions.tolist() == [0.0]
    q = second.qtf_difference[0]
    # "0.20944E+01 0.22848E+01 0 0 1 1.12187E+01 9.20676E+00 1.10741E+01 1.79496E+00":
    # omega_1 = 3.0 rad/s (index 5), omega_2 = 2.75 rad/s (index 0), Surge, conjugated
    assert q[5, 0, 0] == pytest.approx((1.10741e1 - 1.79496j) * rho_g, rel=1e-6)
    assert q[0, 5, 0] == pytest.approx((1.10741e1 + 1.79496j) * rho_g, rel=1e-6)
    # "0.21299E+01 0.22440E+01 0 0 5 9.71893E+01 7.65581E+01 2.25926E+01 9.45269E+01":
    # pitch moment, ULEN = 1
    assert q[4, 1, 4] == pytest.approx((2.25926e1 - 9.45269e1j) * rho_g, rel=1e-6)
    # the diagonal is the mean drift, real: "0.20944E+01 0.20944E+01 ... 1 2.91441E+00
    # 1.80000E+02 -2.91441E+00 5.82077E-11"
    assert q[5, 5, 0] == -2.91441 * rho_g
    assert np.all(np.isfinite(q)) and q.shape == (6, 6, 6)
