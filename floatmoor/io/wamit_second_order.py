"""WAMIT second-order numeric output files (``.8``, ``.9``, ``.12d``) -> SecondOrder.

A strict reader of one rigid body's mean drift and difference-frequency QTF, beside the
first-order files of :mod:`floatmoor.io.wamit` (whose line table, period matching and
tolerances it shares). Conventions (WAMIT User Manual, numeric output files; the same as
OpenFAST HydroDyn's WAMIT2 module and WEC-Sim BEMIO read them):

``.8``   ``PER BETA1 BETA2 I Mod Pha Re Im``: mean drift force by momentum conservation
         (Surge, Sway, Yaw: I = 1, 2, 6 only; a file with I = 3, 4 or 5 is a ``.9`` or a
         control-surface ``.7`` and is refused).
``.9``   same columns, pressure integration, all six modes (a file with I = 1, 2, 6 only is
         a momentum ``.8`` given the wrong name, and is refused).
``.12d`` ``PER1 PER2 BETA1 BETA2 I Mod Pha Re Im``: the total difference-frequency QTF of the
         direct (pressure-integration) method, of which WAMIT writes one triangle of the
         (omega_1, omega_2) plane (the IEA-15 VolturnUS-S file: PER1 <= PER2); the other is
         Q(w2, w1) = conj(Q(w1, w2)). Either triangle, or both (then they must agree), is
         read; a pair missing in both is a hole and is refused.

Non-dimensional values: F = rho g A^2 L Fbar for forces, rho g A^2 L^2 Fbar for moments
(L = ULEN), so the stored coefficients are per unit wave amplitude squared (a regular wave
of amplitude a has the mean force a^2 times the coefficient). A first line of text (WAMIT's
``WAMIT Numeric Output -- Filename ...`` header) is skipped. Lines with a negative mode index
(WAMIT's loads in the moving, body-fixed frame) are left out, as HydroDyn does; lines with
BETA1 != BETA2 (bidirectional pairs) are left out (floatmoor's seas are unidirectional per
component), each with a note.

Phases: WAMIT's QTF is defined for e^{+i omega t}, F(t) = Re sum_i sum_j A_i conj(A_j)
Q^W(w_i, w_j) e^{+i (w_i - w_j) t} with A the e^{+i omega t} amplitudes; capytaine's
amplitudes are their conjugates, so Q = conj(Q^W), the rule the ``.3`` reader applies to the
exciting force (docs/conventions.md#phases-and-complex-amplitudes). The mean drift is real (its phase is
0 or 180 deg): its real part is taken after checking the imaginary part is round-off.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from floatmoor.io.bem_data import DOFS, BemFileError, SecondOrder
from floatmoor.io.wamit import (
    MAX_DIRECTIONS, MAX_PERIODS, MOD_PHASE_RTOL, _list_periods,
    _check_polar, _match_periods, _Table,
)
from floatmoor.terminal_text import shown

__all__ = ["read_wamit_second_order", "SECOND_ORDER_EXTENSIONS", "MEAN_DRIFT_IMAG_RTOL",
           "QTF_DIAGONAL_IMAG_RTOL", "QTF_SYMMETRY_RTOL", "QTF_DIAGONAL_RTOL",
           "QTF_PERIOD_RTOL", "DIRECTION_ATOL_DEG"]

#: The second-order file kinds read, by extension (lower case).
SECOND_ORDER_EXTENSIONS = (".8", ".9", ".12d")

#: A mean drift's imaginary part may be at most this fraction of the largest |value| of its
#: mode group (forces, moments) in the file: WAMIT prints the real drift with phase 0 or 180
#: deg and 7 digits; 1e-3 passes the round-off of the phase and catches a complex column.
MEAN_DRIFT_IMAG_RTOL = 1e-3
#: A difference-frequency QTF's diagonal is real (Q(w, w) is the mean drift): its imaginary
#: part may be at most this fraction of the mode group's largest |Q|. WAMIT's own diagonal
#: carries numerical noise (the IEA-15 VolturnUS-S .12d: yaw 1.7e-6 against 1.4e-4, far
#: below its group's peak); 1 % passes it and refuses a sum-frequency .12s, whose diagonal
#: (the double-frequency force) is complex.
QTF_DIAGONAL_IMAG_RTOL = 1e-2
#: Both triangles given: Q(w1, w2) and conj(Q(w2, w1)) agree within this fraction of the mode
#: group's largest |Q| (print rounding is 5e-7 relative; 1e-3 catches a triangle of another
#: run or of the sum-frequency file).
QTF_SYMMETRY_RTOL = 1e-3
#: The .12d's diagonal against the .9's mean drift at their common frequencies and
#: directions, as a fraction of the mode group's largest |drift| (forces, moments). The
#: diagonal is the mean drift of the QTF's own quadratic term, which WAMIT evaluates by the
#: direct method (pressure integration, or its control surfaces): within a run the two differ
#: by discretisation only, a few per cent of the peak at most away from lightly damped
#: resonances (floatmoor's own two routes: 4.3 % on the buoy). Files of different runs (other
#: mass, mooring, damping or model) differ by tens of per cent: the public IEA-15 VolturnUS-S
#: .12d (2023) and .9 (2024) give a non-dimensional surge drift of -1.84 and +12.46 at
#: 2.5 rad/s, about 75 % of the .9's peak.
#: 10 % passes the first and refuses the second: a QTF whose mean is not the stored mean
#: drift would make the time-domain mean force disagree with the drift the checks report.
QTF_DIAGONAL_RTOL = 0.10
#: A .12d period matches a .1 period when within this, relative: WAMIT prints the QTF's
#: periods with 5 significant digits (0.22848E+01: up to 2.2e-5 relative rounding), the .1's
#: with 7; 5e-5 passes that rounding and still separates periods 0.01 % apart.
QTF_PERIOD_RTOL = 5e-5
#: Wave directions [deg] of two files are the same when within this (files print BETA with
#: 4 to 6 decimals).
DIRECTION_ATOL_DEG = 1e-3

_FORCES, _MOMENTS = (0, 1, 2), (3, 4, 5)
_MOMENTUM_MODES = (1, 2, 6)
_ROUTES = {".8": "momentum conservation", ".9": "pressure integration",
           ".12d": "difference-frequency QTF, direct method (pressure integration)"}


def _scale(rho: float, g: float, ulen: float) -> NDArray[np.float64]:
    """rho g L^k per mode: k = 1 for forces, 2 for moments."""
    return rho * g * ulen ** np.array([1, 1, 1, 2, 2, 2], dtype=float)


def _data_rows(table: _Table):
    """The data lines, WAMIT's text header (a first line not starting with a number)
    skipped."""
    first = True
    for lineno, parts in table.rows:
        if first:
            first = False
            if not _is_number(parts[0]):
                continue
        yield lineno, parts


def _is_number(token: str) -> bool:
    try:
        float(token)
    except ValueError:
        return False
    return True


def _mode(table: _Table, lineno: int, token: str) -> int:
    """A mode index 1..6, or -1..-6 (WAMIT's moving-frame loads)."""
    try:
        value = int(token)
    except ValueError:
        raise table.error(lineno, "an integer mode index I in 1..6",
                          f"'{shown(token, 40)}'") from None
    if not 1 <= abs(value) <= 6:
        extra = (" (one rigid body; multi-body WAMIT files are not supported)"
                 if abs(value) > 6 else "")
        raise table.error(lineno, f"a mode index I in 1..6{extra}", f"index {value}")
    return value


def _group_peaks(values: NDArray, axis_modes: int = -1) -> NDArray[np.float64]:
    """Per mode, the largest |value| of its group (forces 1-3, moments 4-6)."""
    peak = np.abs(np.moveaxis(values, axis_modes, -1)).reshape(-1, 6)
    peak = np.where(np.isnan(peak), 0.0, peak).max(axis=0)
    out = np.empty(6)
    out[:3], out[3:] = peak[:3].max(), peak[3:].max()
    return out


def _polar_columns(table: _Table, lineno: int, parts: list[str], first: int
                   ) -> tuple[float, float, complex]:
    """(Mod, Pha, Re + i Im) of columns ``first``..``first + 3``."""
    mod = table.number(lineno, parts[first], "Mod")
    pha = table.number(lineno, parts[first + 1], "Pha [deg]")
    re = table.number(lineno, parts[first + 2], "Re")
    im = table.number(lineno, parts[first + 3], "Im")
    if mod < 0.0:
        raise table.error(lineno, "a modulus Mod >= 0", f"Mod = {shown(parts[first], 40)}")
    return mod, pha, complex(re, im)


def _suspect(mod: float, pha: float, value: complex) -> bool:
    polar = mod * complex(math.cos(math.radians(pha)), math.sin(math.radians(pha)))
    return abs(polar - value) > MOD_PHASE_RTOL * mod


def _skipped_notes(path: str, moving: int, crossed: int, limits: int) -> list[str]:
    notes = []
    if moving:
        notes.append(f"{path}: {moving} lines with a negative mode index (loads in WAMIT's "
                     "moving frame) not used.")
    if crossed:
        notes.append(f"{path}: {crossed} lines of bidirectional pairs (BETA1 != BETA2) not "
                     "used: floatmoor's wave components are unidirectional.")
    if limits:
        notes.append(f"{path}: {limits} lines at PER = -1 or 0 (omega = 0 / infinity) not "
                     "used.")
    return notes


def _same_directions(found: Sequence[float], reference: Sequence[float]) -> bool:
    return len(found) == len(reference) and all(
        abs(a - b) <= DIRECTION_ATOL_DEG for a, b in zip(sorted(found), sorted(reference)))


def _read_mean_drift(table: _Table, kind: str, periods: Sequence[float], reference_name: str,
                     directions_deg: Sequence[float], excitation_name: str
                     ) -> tuple[NDArray[np.float64], list[str]]:
    """Non-dimensional mean drift (omega increasing, direction as ``directions_deg``, mode),
    NaN where the route gives nothing."""
    layout = "PER BETA1 BETA2 I Mod Pha Re Im"
    table.require_rows(layout)
    lines: dict[tuple[float, float], dict[int, tuple[complex, int]]] = {}
    pers: dict[float, dict] = {}
    betas: dict[float, dict] = {}
    suspects: list = []
    largest = 0.0
    moving = crossed = limits = 0
    for lineno, parts in _data_rows(table):
        table.columns(lineno, parts, 8, layout + (" (a .3 has 7 columns, a .12d 9)"))
        per = table.period(lineno, parts[0])
        beta1 = table.number(lineno, parts[1], "wave direction BETA1 [deg]")
        beta2 = table.number(lineno, parts[2], "wave direction BETA2 [deg]")
        i = _mode(table, lineno, parts[3])
        mod, pha, value = _polar_columns(table, lineno, parts, 4)
        if i < 0:
            moving += 1
            continue
        if per in (-1.0, 0.0):
            limits += 1
            continue
        if beta1 != beta2:
            crossed += 1
            continue
        if kind == ".8" and i not in _MOMENTUM_MODES:
            raise table.error(lineno, "mode indices 1, 2 and 6 only (Surge, Sway, Yaw: the "
                              "momentum-conservation drift of a .8; heave, roll and pitch are "
                              "in a pressure-integration .9 or a control-surface .7)",
                              f"I = {i}")
        table.new_key(pers, per, lineno, MAX_PERIODS, "wave periods")
        table.new_key(betas, beta1, lineno, MAX_DIRECTIONS, "wave directions")
        entries = lines.setdefault((per, beta1), {})
        if i in entries:
            raise table.error(lineno, "one line per (PER, BETA1, BETA2, I)", "a second line "
                              f"for PER = {shown(parts[0], 40)}, BETA = {shown(parts[1], 40)}, "
                              f"I = {i} (first at line {entries[i][1]})")
        entries[i] = (value, lineno)
        largest = max(largest, mod)
        if _suspect(mod, pha, value):
            suspects.append((lineno, mod, pha, value))
    _check_polar(table, suspects, largest)
    notes = _skipped_notes(table.name, moving, crossed, limits)
    if not lines:
        raise BemFileError(table.name, "", "mean drift lines at finite periods (PER > 0) with "
                           "BETA1 = BETA2 and I in 1..6", "none")
    modes = sorted({i for entries in lines.values() for i in entries})
    if kind == ".9" and not set(modes) - set(_MOMENTUM_MODES):
        raise BemFileError(table.name, "modes", "the six modes of a pressure-integration .9 "
                           "(a file with Surge, Sway and Yaw only is a momentum .8)",
                           f"I = {', '.join(map(str, modes))} only")
    for (per, beta), entries in lines.items():
        absent = [i for i in modes if i not in entries]
        if absent:
            raise BemFileError(table.name, f"PER = {per:.6g} s, BETA = {beta:g} deg",
                               f"a line for every mode of the file (I = "
                               f"{', '.join(map(str, modes))})",
                               f"none for I = {', '.join(map(str, absent))}")
    index = _match_periods(table, list(pers), periods, reference_name)
    found = sorted(betas)
    if not _same_directions(found, directions_deg):
        raise BemFileError(table.name, "wave directions", f"the directions of "
                           f"{excitation_name} (BETA = "
                           f"{shown(', '.join(f'{b:g}' for b in directions_deg), 200)} deg)",
                           shown(", ".join(f"{b:g}" for b in found), 200) + " deg")
    for per in pers:
        absent = [b for b in found if (per, b) not in lines]
        if absent:
            raise BemFileError(table.name, f"PER = {per:.6g} s", "every wave direction of "
                               "the file", "no lines for BETA = "
                               f"{shown(', '.join(f'{b:g}' for b in absent), 200)} deg")
    out = np.full((len(periods), len(found), 6), np.nan)
    fill = [m for m in range(1, 7) if kind == ".9" or m in _MOMENTUM_MODES]
    for (per, beta), entries in lines.items():
        b = min(range(len(found)), key=lambda k: abs(found[k] - beta))
        for m in fill:
            out[index[per], b, m - 1] = entries[m][0].real if m in entries else 0.0
    imag = np.zeros_like(out)
    for (per, beta), entries in lines.items():
        b = min(range(len(found)), key=lambda k: abs(found[k] - beta))
        for m, (value, _) in entries.items():
            imag[index[per], b, m - 1] = value.imag
    peaks = _group_peaks(out)
    worst = np.abs(imag) - MEAN_DRIFT_IMAG_RTOL * peaks
    if np.any(worst > 0.0):
        w, b, m = np.unravel_index(int(np.argmax(worst)), worst.shape)
        per = periods[w]
        line = lines[(next(p for p in pers if index[p] == w), found[b])][m + 1][1]
        raise table.error(line, f"a real mean drift (Im within {MEAN_DRIFT_IMAG_RTOL:g} of "
                          "the largest value of its forces or moments; phase 0 or 180 deg)",
                          f"Im = {imag[w, b, m]:.6g} at PER = {per:.6g} s")
    omitted = [DOFS[m - 1] for m in fill if m not in modes]
    if omitted:
        notes.append(f"{table.name}: no lines for {', '.join(omitted)}: zero.")
    return out, notes


def _read_qtf(table: _Table) -> tuple[list[float], list[float], NDArray[np.complex128],
                                      list[str]]:
    """(periods decreasing, directions [deg] increasing, non-dimensional Q^W (direction,
    omega_1, omega_2, mode) on omega increasing, Hermitian, in WAMIT's e^{+i omega t}),
    notes."""
    layout = "PER1 PER2 BETA1 BETA2 I Mod Pha Re Im"
    table.require_rows(layout)
    entries: dict[tuple[float, float, float, int], tuple[complex, int]] = {}
    pers: dict[float, dict] = {}
    betas: dict[float, dict] = {}
    suspects: list = []
    largest = 0.0
    moving = crossed = 0
    for lineno, parts in _data_rows(table):
        table.columns(lineno, parts, 9, layout + " (a .8 or .9 has 8 columns)")
        per1 = table.number(lineno, parts[0], "wave period PER1 [s]")
        per2 = table.number(lineno, parts[1], "wave period PER2 [s]")
        if not (per1 > 0.0 and per2 > 0.0):
            raise table.error(lineno, "wave periods PER1, PER2 > 0 (the QTF's frequencies are "
                              "finite)", f"PER1 = {shown(parts[0], 40)}, PER2 = "
                              f"{shown(parts[1], 40)}")
        beta1 = table.number(lineno, parts[2], "wave direction BETA1 [deg]")
        beta2 = table.number(lineno, parts[3], "wave direction BETA2 [deg]")
        i = _mode(table, lineno, parts[4])
        mod, pha, value = _polar_columns(table, lineno, parts, 5)
        if i < 0:
            moving += 1
            continue
        if beta1 != beta2:
            crossed += 1
            continue
        for per in (per1, per2):
            table.new_key(pers, per, lineno, MAX_PERIODS, "wave periods")
        table.new_key(betas, beta1, lineno, MAX_DIRECTIONS, "wave directions")
        key = (per1, per2, beta1, i)
        if key in entries:
            raise table.error(lineno, "one line per (PER1, PER2, BETA1, BETA2, I)", "a second "
                              f"line for PER1 = {shown(parts[0], 40)}, PER2 = "
                              f"{shown(parts[1], 40)}, BETA = {shown(parts[2], 40)}, I = {i} "
                              f"(first at line {entries[key][1]})")
        entries[key] = (value, lineno)
        largest = max(largest, mod)
        if _suspect(mod, pha, value):
            suspects.append((lineno, mod, pha, value))
    _check_polar(table, suspects, largest)
    notes = _skipped_notes(table.name, moving, crossed, 0)
    if not entries:
        raise BemFileError(table.name, "", "QTF lines with BETA1 = BETA2 and I in 1..6",
                           "none")
    periods = sorted(pers, reverse=True)                       # omega increasing
    if len(periods) < 2:
        raise BemFileError(table.name, "", "at least 2 wave periods in the QTF",
                           f"{len(periods)}")
    close = np.diff(np.asarray(periods[::-1])) <= 1e-5 * np.asarray(periods[::-1][1:])
    if np.any(close):
        k = int(np.argmax(close))
        raise BemFileError(table.name, "wave periods", "distinct periods",
                           f"{periods[::-1][k]:.7g} and {periods[::-1][k + 1]:.7g} s")
    directions = sorted(betas)
    modes = sorted({key[3] for key in entries})
    n = len(periods)
    q = np.zeros((len(directions), n, n, 6), dtype=complex)
    both: list[tuple[int, int, int, int, complex, complex, int]] = []
    for d, beta in enumerate(directions):
        for m in modes:
            for a in range(n):
                for b in range(a, n):
                    ab = entries.get((periods[a], periods[b], beta, m))
                    ba = entries.get((periods[b], periods[a], beta, m))
                    if ab is None and ba is None:
                        raise BemFileError(
                            table.name, f"PER1 = {periods[a]:.6g} s, PER2 = {periods[b]:.6g} "
                            f"s, BETA = {beta:g} deg, I = {m}",
                            "a line for every pair of the QTF's periods (in either order: "
                            f"{n} periods, {_list_periods(periods)})",
                            "none (a hole in the QTF)")
                    value = ab[0] if ab is not None else np.conj(ba[0])
                    if ab is not None and ba is not None and a != b:
                        both.append((d, a, b, m, ab[0], np.conj(ba[0]), ba[1]))
                    q[d, a, b, m - 1] = value
                    q[d, b, a, m - 1] = np.conj(value)
    peaks = _group_peaks(q)
    for d, a, b, m, v_ab, v_ba, lineno in both:
        if abs(v_ab - v_ba) > QTF_SYMMETRY_RTOL * peaks[m - 1]:
            raise table.error(lineno, f"Q(PER2, PER1) = conj(Q(PER1, PER2)) (within "
                              f"{QTF_SYMMETRY_RTOL:g} of the largest |Q| of its forces or "
                              "moments: both triangles given must agree)",
                              f"conj = {v_ba:.6g} against {v_ab:.6g}")
    diag = np.einsum("dnnm->dnm", q)
    worst = np.abs(diag.imag) - QTF_DIAGONAL_IMAG_RTOL * peaks
    if np.any(worst > 0.0):
        d, a, m = np.unravel_index(int(np.argmax(worst)), worst.shape)
        line = entries[(periods[a], periods[a], directions[d], m + 1)][1]
        raise table.error(line, "a real diagonal Q(w, w), the mean drift (imaginary part "
                          f"within {QTF_DIAGONAL_IMAG_RTOL:g} of the largest |Q| of its forces "
                          "or moments; a sum-frequency .12s has a complex one)",
                          f"Im = {diag[d, a, m].imag:.6g}")
    for a in range(n):
        q[:, a, a, :] = q[:, a, a, :].real
    omitted = [DOFS[m] for m in range(6) if m + 1 not in modes]
    if omitted:
        notes.append(f"{table.name}: no lines for {', '.join(omitted)}: zero.")
    return periods, directions, q, notes


def _compare_diagonal(qtf_name: str, drift_name: str, qtf_periods: Sequence[float],
                      qtf_dirs: Sequence[float], diag: NDArray[np.float64],
                      periods: Sequence[float], dirs: Sequence[float],
                      near: NDArray[np.float64]) -> str:
    """Refuse a .12d whose diagonal is not the .9's drift (SI arrays); the note saying what
    was compared."""
    ref = np.asarray(periods)
    pairs = []
    for a, per in enumerate(qtf_periods):
        k = int(np.argmin(np.abs(ref - per)))
        if abs(ref[k] - per) <= QTF_PERIOD_RTOL * ref[k]:
            pairs.append((a, k))
    dir_pairs = [(d, min(range(len(dirs)), key=lambda j: abs(dirs[j] - beta)))
                 for d, beta in enumerate(qtf_dirs)
                 if min(abs(np.asarray(dirs) - beta)) <= DIRECTION_ATOL_DEG]
    if not pairs or not dir_pairs:
        return (f"{qtf_name}: diagonal not compared with {drift_name} (no common frequency "
                "and direction).")
    peaks = _group_peaks(near)
    worst = 0.0
    for a, k in pairs:
        for d, j in dir_pairs:
            for m in range(6):
                if peaks[m] > 0.0:
                    worst = max(worst, abs(diag[d, a, m] - near[k, j, m]) / peaks[m])
                if abs(diag[d, a, m] - near[k, j, m]) > QTF_DIAGONAL_RTOL * peaks[m]:
                    raise BemFileError(
                        qtf_name, f"PER1 = PER2 = {qtf_periods[a]:.6g} s, BETA = "
                        f"{qtf_dirs[d]:g} deg, I = {m + 1}",
                        f"the mean drift of {drift_name} on the diagonal (the same pressure "
                        f"route; within {QTF_DIAGONAL_RTOL:.0%} of the largest drift of its "
                        "forces or moments: files of one run)",
                        f"{diag[d, a, m]:.6g} against {near[k, j, m]:.6g} (SI)")
    return (f"{qtf_name}: diagonal agrees with {drift_name} within {QTF_DIAGONAL_RTOL:.0%} "
            f"(worst {worst:.2%} of the peak drift) at {len(pairs)} common frequencies and {len(dir_pairs)} direction"
            f"{'s' if len(dir_pairs) > 1 else ''}.")


def read_wamit_second_order(files: Mapping[str, str | Path], *, periods: Sequence[float],
                            reference_name: str, directions_deg: Sequence[float] | None,
                            excitation_name: str, water_density: float, gravity: float,
                            length_scale: float = 1.0) -> SecondOrder:
    """Read a WAMIT ``.8``, ``.9`` and/or ``.12d`` beside the first-order files.

    Parameters
    ----------
    files
        Extension (``.8``, ``.9``, ``.12d``) -> file; at least one.
    periods
        The ``.1``'s finite periods [s], decreasing (the database's frequencies).
    reference_name
        The ``.1``'s name (for messages).
    directions_deg
        The ``.3``'s wave directions [deg], increasing; None without a ``.3`` (a mean drift
        file then is refused: the database has no wave directions).
    excitation_name
        The ``.3``'s name (for messages).
    water_density, gravity, length_scale
        rho [kg/m^3], g [m/s^2] and ULEN [m] of the run.

    Returns
    -------
    SecondOrder
        SI values per unit wave amplitude squared in the e^{-i omega t} convention, about
        WAMIT's body origin.

    Raises
    ------
    BemFileError
        A file that is not a well-formed file of its kind, other periods than the ``.1``'s or
        other directions than the ``.3``'s, a hole in the QTF, or a QTF diagonal disagreeing
        with the ``.9`` (see the module).
    """
    scale = _scale(water_density, gravity, length_scale)
    drift: dict[str, NDArray[np.float64]] = {}
    names: dict[str, str] = {}
    notes: list[str] = []
    for kind in (".8", ".9"):
        if kind not in files:
            continue
        table = _Table(Path(files[kind]), kind)
        names[kind] = table.name
        if directions_deg is None:
            raise BemFileError(table.name, "", "the .3 file with it (the mean drift is stored "
                               "at the excitation's wave directions)", "no .3")
        values, more = _read_mean_drift(table, kind, periods, reference_name, directions_deg,
                                        excitation_name)
        drift[kind] = values * scale
        notes += more
    qtf = None
    if ".12d" in files:
        table = _Table(Path(files[".12d"]), ".12d")
        names[".12d"] = table.name
        qtf_periods, qtf_dirs, q_wamit, more = _read_qtf(table)
        notes += more
        # WAMIT's e^{+i omega t} QTF -> capytaine's e^{-i omega t}: conjugate (as the .3).
        qtf = np.conj(q_wamit) * scale
        diag = np.einsum("dnnm->dnm", qtf).real
        if ".9" in drift:
            notes.append(_compare_diagonal(table.name, names[".9"], qtf_periods, qtf_dirs, diag,
                                           periods, directions_deg or [], drift[".9"]))
        elif ".8" in drift:
            notes.append(f"{table.name}: diagonal not compared with {names['.8']} (the .12d's "
                         "diagonal is the pressure route's mean drift, the .8 the momentum "
                         "route's).")
        notes.append(f"{table.name}: QTF at {len(qtf_periods)} frequencies "
                     f"({2 * math.pi / qtf_periods[0]:.4g}-{2 * math.pi / qtf_periods[-1]:.4g} "
                     f"rad/s) and {len(qtf_dirs)} direction{'s' if len(qtf_dirs) > 1 else ''}, filled to the whole (omega_1, "
                     "omega_2) plane by Q(w2, w1) = conj(Q(w1, w2)), conjugated from WAMIT's "
                     "e^{+i omega t}.")
    return SecondOrder(
        source="wamit",
        far_field=drift.get(".8"), far_field_from=(
            f"{names['.8']} (WAMIT .8, momentum conservation)" if ".8" in names else ""),
        near_field=drift.get(".9"), near_field_from=(
            f"{names['.9']} (WAMIT .9, pressure integration)" if ".9" in names else ""),
        qtf_omega=None if qtf is None else 2.0 * np.pi / np.asarray(qtf_periods),
        qtf_directions=None if qtf is None else np.radians(np.asarray(qtf_dirs, float)),
        qtf_difference=qtf,
        qtf_from=(f"{names['.12d']} (WAMIT .12d, {_ROUTES['.12d']})"
                  if ".12d" in names else ""),
        notes=tuple(notes))
