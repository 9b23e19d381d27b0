"""WAMIT numeric output files (``.1``, ``.3``, ``.3fk``, ``.3sc``, ``.hst``) -> ImportedBem;
the run's summary (``.out``) for the gravity, ULEN, water depth, displaced volume and centre
of buoyancy it states.

A small strict reader of WAMIT's non-dimensional numeric files, one rigid body (six modes),
zero forward speed, the first column a wave period (WAMIT's default ``IPEROUT``). The
conventions are those of the WAMIT User Manual ("Definitions of nondimensional quantities",
numeric output files), with ``L = ULEN`` (``length_scale``):

``.1``  ``PER I J Abar Bbar``: A = rho L^k Abar, B = rho omega L^k Bbar, k = 3, 4, 5 for
        translation-translation, mixed and rotation-rotation pairs. ``PER = -1`` is omega = 0
        and ``PER = 0`` omega = infinity; those lines have no Bbar. Pairs WAMIT omits (it
        omits negligible coefficients) are zero.
``.3``  ``PER BETA I Mod Pha Re Im``: the diffraction-method exciting force per unit wave
        amplitude, X = rho g L^m Xbar, m = 2 for forces and 3 for moments; BETA [deg] is the
        direction the waves travel towards. ``.3fk`` and ``.3sc`` (same layout) are its
        Froude-Krylov and scattering parts.
``.hst`` ``I J Cbar``: C = rho g L^k Cbar, k = 2 for (3, 3), 3 with one rotational index,
        4 with two.

WAMIT's A_ij is the force in mode i due to the motion of mode j; floatmoor's (capytaine's)
``added_mass[w, j, i]`` is indexed (radiating j, influenced i), so line ``I J`` goes to
``[w, J-1, I-1]``. WAMIT's complex amplitudes are for e^{+i omega t}; floatmoor's are for
e^{-i omega t}, the complex conjugate. The hydrostatic matrix keeps WAMIT's (force, motion)
order, as floatmoor's does.

``.out`` The run's summary, of which only its header lines ``Gravity: G  Length scale: ULEN``
        and ``Water depth: H`` (or ``infinite``) and its body's ``Volumes (VOLX,VOLY,VOLZ):
        VX VY VZ`` and ``Center of Buoyancy (Xb,Yb,Zb): X Y Z`` are read
        (:func:`read_wamit_out`): the numeric files state none of them, and a depth given to
        the importer that is not the run's (deep-water coefficients taken as finite-depth
        ones) is an error. WAMIT prints the volumes and the centre of buoyancy dimensional (the
        geometry file's length unit, not divided by ULEN) in the body coordinate system, the
        frame its coefficients are about; the displaced volume taken is VOLZ (the integral
        of z n_z, the one WEC-Sim's BEMIO takes; the three differ only by the panelling). A
        summary of more than one body is refused (one rigid body per import).

Anything that is not a well-formed file of its kind raises :class:`BemFileError` naming the
file and line: a wrong number of columns, a non-number, NaN or inf, a mode index outside
1..6 (multi-body files are not supported), a repeated line, a period that is neither > 0 nor
-1 or 0, excitation periods that are not the ``.1``'s finite periods, a period missing a
wave direction that another has, fewer than two finite periods, an empty or missing file.
The files are data from elsewhere (docs/guide/safeguards.md#files-from-elsewhere): only
regular files of at most :data:`MAX_FILE_BYTES` are read (a FIFO or a device is refused before
it is opened), and quoted tokens are shown with :func:`floatmoor.terminal_text.shown`.

Size: one strict reader per WAMIT file kind sharing the line table (:class:`_Table`), the
period matching and the scaling conventions above; split, each part would import the others.
"""

from __future__ import annotations

import io
import math
from array import array
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from floatmoor.io.bem_data import BemFileError, ImportedBem
from floatmoor.input_files import InputFileError, read_bounded
from floatmoor.terminal_text import shown

__all__ = ["read_wamit", "read_wamit_out", "WamitRunSummary", "WAMIT_EXTENSIONS",
           "MAX_FILE_BYTES"]

#: Largest WAMIT file read [bytes]: a .3 of 1000 periods x 72 wave directions x 6 modes is
#: ~40 MB of ~90-byte lines, OC4's .1 of 498 periods 0.5 MB; the bound keeps the text and the
#: values parsed from it well inside a workstation's memory (measured: 0.5 GB peak for a
#: 64 MiB .3 of the shortest valid lines, 4.8 million of them).
MAX_FILE_BYTES = 64 * 2**20
#: Most distinct wave periods a file may hold (besides PER = -1 and 0): floatmoor's own
#: databases take at most 2000 frequencies (docs/guide/safeguards.md#input-limits), BEM runs
#: hundreds; the bound keeps what is held per line small whatever the file's size.
MAX_PERIODS = 10_000
#: Most distinct wave directions an excitation file may hold: 3600 is a 0.1 deg grid.
MAX_DIRECTIONS = 3_600

#: The file kinds read, by extension (lower case).
WAMIT_EXTENSIONS = (".1", ".3", ".3fk", ".3sc", ".hst", ".out")

#: Modes of one rigid body (WAMIT's I, J = 1..6; multi-body files number them on to 6 N).
_N_MODES = 6

#: Relative tolerance when matching a period of one file to the same period printed in
#: another: WAMIT prints periods with 7 significant digits (E13.6, ~5e-7 relative); 1e-5
#: also accepts a file re-printed with 6 digits and still separates any two periods of a
#: usable frequency set (a spacing of 1e-5 T is far below any BEM resolution).
PERIOD_RTOL = 1e-5

#: Agreement required between a .3 line's Mod/Pha and its Re/Im, relative to Mod: WAMIT
#: prints the phase in degrees with a few decimals (one decimal is +-0.05 deg = 9e-4 rad),
#: the moduli with 7 digits; 5e-3 (0.3 deg) passes any such rounding and catches a line
#: whose columns do not belong together.
MOD_PHASE_RTOL = 5e-3

#: Absolute floor of the Mod/Pha check, relative to the file's largest modulus: an entry
#: printed as 1e-12 with a meaningless phase is round-off, not a broken line.
MOD_PHASE_ATOL_REL = 1e-6

#: Agreement required between .3 and .3fk + .3sc, relative to the largest modulus of the
#: mode over the file: WAMIT's diffraction-method force is the sum of the two parts, each
#: printed with 7 digits; 1e-3 catches parts taken from another run.
PARTS_SUM_RTOL = 1e-3

#: An excitation block before any line filled it: (Re, Im, line number) x 6 modes, all NaN.
_EMPTY_BLOCK = array("d", [math.nan] * (3 * _N_MODES))

_KIND_NAMES = {".1": "added mass and damping (.1)", ".3": "exciting force (.3)",
               ".3fk": "Froude-Krylov force (.3fk)", ".3sc": "scattering force (.3sc)",
               ".hst": "hydrostatic restoring (.hst)", ".out": "run summary (.out)",
               # second-order files, read by floatmoor.io.wamit_second_order
               ".8": "mean drift, momentum conservation (.8)",
               ".9": "mean drift, pressure integration (.9)",
               ".12d": "difference-frequency QTF (.12d)"}

#: The header fields of a ``.out`` read, as WAMIT prints them (``Gravity:     9.80665
#: Length scale:        1.00000``, ``Water depth:        200.000000`` or ``infinite``).
_OUT_FIELDS = {"gravity": "Gravity:", "length_scale": "Length scale:",
               "water_depth": "Water depth:"}
#: The body lines of a ``.out`` read, as WAMIT prints them (``Volumes (VOLX,VOLY,VOLZ):
#: 13917.4  13917.4  13917.4``, ``Center of Buoyancy (Xb,Yb,Zb):  0.000000  0.000000
#: -13.150000``), each three numbers.
_OUT_BODY_FIELDS = {"volumes": "Volumes (VOLX,VOLY,VOLZ):",
                    "center_of_buoyancy": "Center of Buoyancy (Xb,Yb,Zb):"}


@dataclass(frozen=True)
class WamitRunSummary:
    """What a WAMIT ``.out`` states about its run (None: a field it does not print)."""

    path: str
    gravity: float | None  #: [m/s^2]
    length_scale: float | None  #: ULEN [m]
    water_depth: float | None  #: [m], inf for infinite depth
    disp_volume: float | None = None  #: [m^3], VOLZ of ``Volumes (VOLX,VOLY,VOLZ):``
    #: [m] in the body coordinate system (the frame of the coefficients)
    center_of_buoyancy: tuple[float, float, float] | None = None
    #: (VOLX, VOLY, VOLZ) [m^3] as printed
    volumes: tuple[float, float, float] | None = None


def read_wamit_out(path: str | Path) -> WamitRunSummary:
    """Read the gravity, ULEN and water depth from a WAMIT ``.out`` file's header, and the
    displaced volume and centre of buoyancy from its body parameters (when printed).

    Raises
    ------
    BemFileError
        No such file, no ``Water depth:`` line, a field that is not a number > 0 (the depth
        may be ``infinite``), a volumes or centre of buoyancy line without three numbers, a
        volume that is not > 0, or the lines of a second body.
    """
    table = _Table(Path(path), ".out")
    found: dict[str, float] = {}
    body: dict[str, tuple[float, float, float]] = {}
    body_lines: dict[str, int] = {}
    for lineno, parts in table.rows:
        line = " ".join(parts)
        for name, label in _OUT_BODY_FIELDS.items():
            at = line.find(label)
            if at < 0:
                continue
            if name in body:
                raise table.error(lineno, f"one body's '{label}' line (one rigid body per "
                                  "import; multi-body WAMIT runs are not supported)",
                                  f"a second one (first at line {body_lines[name]})")
            rest = line[at + len(label):].split()
            if len(rest) != 3:
                raise table.error(lineno, f"three numbers after '{label}'",
                                  f"'{shown(' '.join(rest) or 'nothing', 80)}'")
            unit = "m^3" if name == "volumes" else "m"
            values = tuple(table.number(lineno, token, f"{label} [{unit}]") for token in rest)
            if name == "volumes" and not values[2] > 0.0:
                raise table.error(lineno, f"a volume VOLZ > 0 after '{label}'",
                                  f"'{rest[2]}'")
            body[name], body_lines[name] = values, lineno  # type: ignore[assignment]
        for name, label in _OUT_FIELDS.items():
            at = line.find(label)
            if name in found or at < 0:
                continue
            rest = line[at + len(label):].split()
            token = rest[0] if rest else ""
            if name == "water_depth" and token.lower() == "infinite":
                found[name] = math.inf
                continue
            unit = "m/s^2" if name == "gravity" else "m"
            value = table.number(lineno, token, f"{label} [{unit}]") if token else math.nan
            if not value > 0.0:
                raise table.error(lineno, f"a number > 0 after '{label}'",
                                  f"'{token or 'nothing'}'")
            found[name] = value
    if "water_depth" not in found:
        raise BemFileError(table.name, "water depth", "a WAMIT run summary with its "
                           "'Water depth:' line", "none")
    volumes = body.get("volumes")
    return WamitRunSummary(table.name, found.get("gravity"), found.get("length_scale"),
                           found["water_depth"],
                           disp_volume=None if volumes is None else volumes[2],
                           center_of_buoyancy=body.get("center_of_buoyancy"),
                           volumes=volumes)


def _exponent_radiation(i: int, j: int) -> int:
    """L exponent of A and B for WAMIT modes i, j (1-based): 3, 4 or 5."""
    return 3 + (i > 3) + (j > 3)


def _exponent_excitation(i: int) -> int:
    """L exponent of X for mode i: 2 forces, 3 moments."""
    return 2 + (i > 3)


def _exponent_hydrostatic(i: int, j: int) -> int:
    """L exponent of C for modes i, j: 2, 3 or 4."""
    return 2 + (i > 3) + (j > 3)


def _format_period(per: float) -> str:
    return f"{per:.6g}"


def _list_periods(periods: Sequence[float], limit: int = 6) -> str:
    shown = ", ".join(_format_period(p) for p in list(periods)[:limit])
    more = len(periods) - limit
    return shown + (f" and {more} more" if more > 0 else "") + " s"


class _Table:
    """The data lines of one numeric file: (line number, tokens), blank lines skipped."""

    def __init__(self, path: Path, kind: str) -> None:
        self.path = path
        self.name = str(path)
        self.kind = kind
        try:
            self.text = read_bounded(path, MAX_FILE_BYTES).decode("utf-8")
        except InputFileError as err:
            raise BemFileError(self.name, "", f"a WAMIT {_KIND_NAMES[kind]} file",
                               err.found) from None
        except UnicodeDecodeError:
            raise BemFileError(self.name, "", f"a WAMIT {_KIND_NAMES[kind]} text file",
                               "bytes that are not UTF-8 text") from None
        except OSError as err:
            raise BemFileError(self.name, "", "a readable file", shown(err)) from None

    @property
    def rows(self) -> Iterator[tuple[int, list[str]]]:
        """(line number, tokens) of the non-blank lines, one at a time (a list of them all
        would take ten times the text's memory)."""
        for n, line in enumerate(io.StringIO(self.text), 1):
            parts = line.split()
            if parts:
                yield n, parts

    def error(self, lineno: int, expected: str, found: str) -> BemFileError:
        return BemFileError(self.name, f"line {lineno}", expected, found)

    def number(self, lineno: int, token: str, what: str) -> float:
        try:
            value = float(token)
        except ValueError:
            raise self.error(lineno, f"a number ({what})", f"'{shown(token, 40)}'") from None
        if not math.isfinite(value):
            raise self.error(lineno, f"a finite number ({what})", f"'{shown(token, 40)}'")
        return value

    def mode(self, lineno: int, token: str, what: str) -> int:
        try:
            value = int(token)
        except ValueError:
            raise self.error(lineno, f"an integer mode index {what} in 1..6",
                             f"'{shown(token, 40)}'") from None
        if value > _N_MODES:
            raise self.error(lineno, f"a mode index {what} in 1..6 (one rigid body; "
                             "multi-body WAMIT files are not supported)", f"index {value}")
        if value < 1:
            raise self.error(lineno, f"a mode index {what} in 1..6", f"index {value}")
        return value

    def period(self, lineno: int, token: str) -> float:
        per = self.number(lineno, token, "wave period PER [s]")
        if per < 0.0 and per != -1.0:
            raise self.error(lineno, "a wave period PER > 0, or -1 (omega = 0) or 0 (omega "
                             "= infinity); the first column must be the period (WAMIT's "
                             "default IPEROUT)", f"PER = {shown(token, 40)}")
        return per

    def columns(self, lineno: int, parts: list[str], count: int, layout: str) -> None:
        if len(parts) != count:
            raise self.error(lineno, f"{count} columns '{layout}'",
                             f"{len(parts)}: '{shown(' '.join(parts), 120)}'")

    def once(self, seen: dict, key: tuple, lineno: int, fields: str, described: str) -> None:
        """Refuse a second line for ``key`` (``fields`` names its columns, ``described``
        their values); ``seen`` maps keys to the line that gave them first."""
        if key in seen:
            raise self.error(lineno, f"one line per ({fields})",
                             f"a second line for {described} (first at line {seen[key]})")
        seen[key] = lineno

    def new_key(self, held: dict, key: float, lineno: int, limit: int, what: str) -> dict:
        """The entries of ``held[key]``, a new dict when ``key`` is new and fewer than
        ``limit`` keys are held."""
        entries = held.get(key)
        if entries is None:
            if len(held) >= limit:
                raise self.error(lineno, f"at most {limit} distinct {what}",
                                 f"one more, {key:g}")
            entries = held[key] = {}
        return entries

    def once_in(self, entries: dict, key: Any, lineno: int, fields: str, described: str,
                ) -> None:
        """Refuse a second line for ``key`` in ``entries`` (values ``(..., first line)``)."""
        if key in entries:
            raise self.error(lineno, f"one line per ({fields})", f"a second line for "
                             f"{described} (first at line {entries[key][-1]})")

    def require_rows(self, layout: str) -> None:
        if not self.text.strip():
            raise BemFileError(self.name, "", f"lines '{layout}'", "an empty file")


@dataclass
class _Radiation:
    periods: list[float]                      # finite, decreasing (omega increasing)
    added_mass: NDArray[np.float64]          # non-dimensional, (n, 6, 6) [w, J-1, I-1]
    damping: NDArray[np.float64]
    zero: NDArray[np.float64] | None          # PER = -1
    infinite: NDArray[np.float64] | None      # PER = 0
    omitted: int                              # (period, pair) entries absent from the file


def _read_radiation(table: _Table) -> _Radiation:
    layout = "PER I J Abar [Bbar]"
    table.require_rows(layout)
    # per period: (I, J) -> (Abar, Bbar, line number)
    values: dict[float, dict[tuple[int, int], tuple[float, float, int]]] = {}
    for lineno, parts in table.rows:
        if len(parts) not in (4, 5):
            table.columns(lineno, parts, 5, layout)
        per = table.period(lineno, parts[0])
        limit = per in (-1.0, 0.0)
        if limit:
            table.columns(lineno, parts, 4, "PER I J Abar (no Bbar at PER = -1 or 0)")
        else:
            table.columns(lineno, parts, 5, "PER I J Abar Bbar")
        i = table.mode(lineno, parts[1], "I")
        j = table.mode(lineno, parts[2], "J")
        a = table.number(lineno, parts[3], "Abar")
        b = 0.0 if limit else table.number(lineno, parts[4], "Bbar")
        entries = table.new_key(values, per, lineno, MAX_PERIODS + 2,
                                 "wave periods (PER = -1 and 0 included)")
        table.once_in(entries, (i, j), lineno, "PER, I, J",
                      f"PER = {shown(parts[0], 40)}, I = {i}, J = {j}")
        entries[(i, j)] = (a, b, lineno)

    periods = sorted((p for p in values if p > 0.0), reverse=True)
    if len(periods) < 2:
        raise BemFileError(table.name, "", "at least 2 finite wave periods (PER > 0)",
                           f"{len(periods)}")

    def matrix(entries: dict[tuple[int, int], tuple[float, float, int]], column: int
               ) -> NDArray[np.float64]:
        out = np.zeros((_N_MODES, _N_MODES))
        for (i, j), pair in entries.items():
            out[j - 1, i - 1] = pair[column]   # WAMIT (force i, motion j) -> [motion, force]
        return out

    added = np.stack([matrix(values[p], 0) for p in periods])
    damping = np.stack([matrix(values[p], 1) for p in periods])
    zero = matrix(values[-1.0], 0) if -1.0 in values else None
    infinite = matrix(values[0.0], 0) if 0.0 in values else None
    omitted = sum(_N_MODES * _N_MODES - len(entries) for entries in values.values())
    return _Radiation(periods, added, damping, zero, infinite, omitted)


@dataclass
class _Excitation:
    path: str
    directions_deg: list[float]                # increasing
    values: NDArray[np.complex128]             # non-dimensional, WAMIT's e^{+i w t}
    dropped_limits: list[float]                # PER = -1 / 0 lines present and not used
    omitted: int


def _match_periods(table: _Table, found: Sequence[float], reference: Sequence[float],
                   reference_name: str) -> dict[float, int]:
    """Index in ``reference`` of every period in ``found``; both sets must be the same."""
    ref = np.asarray(reference)
    index: dict[float, int] = {}
    extra = []
    for per in found:
        k = int(np.argmin(np.abs(ref - per)))
        if abs(ref[k] - per) <= PERIOD_RTOL * ref[k]:
            index[per] = k
        else:
            extra.append(per)
    missing = [p for k, p in enumerate(reference) if k not in set(index.values())]
    if missing or extra:
        parts = []
        if missing:
            parts.append(f"missing frequencies: no lines for PER = {_list_periods(missing)} "
                         f"(omega = {', '.join(f'{2 * math.pi / p:.4g}' for p in missing[:6])}"
                         f"{' ...' if len(missing) > 6 else ''} rad/s)")
        if extra:
            parts.append(f"periods absent from {reference_name}: "
                         f"PER = {_list_periods(sorted(extra, reverse=True))}")
        raise BemFileError(table.name, "wave periods",
                           f"the finite periods of {reference_name} "
                           f"({len(reference)} periods)", "; ".join(parts))
    return index


def _check_polar(table: _Table, suspects: list, largest: float) -> None:
    """Refuse a line whose Mod/Pha do not give its Re/Im: ``suspects`` (line number, Mod, Pha,
    Re + i Im) failed the relative test alone; a line passes within MOD_PHASE_RTOL of Mod plus
    MOD_PHASE_ATOL_REL of the file's ``largest`` Mod (the print's last digit)."""
    atol = MOD_PHASE_ATOL_REL * largest
    for lineno, mod, pha, value in suspects:
        polar = mod * complex(math.cos(math.radians(pha)), math.sin(math.radians(pha)))
        if abs(polar - value) > MOD_PHASE_RTOL * mod + atol:
            raise table.error(lineno, f"Mod and Pha agreeing with Re and Im (within "
                              f"{MOD_PHASE_RTOL:g} of Mod)",
                              f"Mod e^(i Pha) = {polar.real:.6g}{polar.imag:+.6g}i, "
                              f"Re + i Im = {value.real:.6g}{value.imag:+.6g}i")

def _read_excitation(table: _Table, radiation: _Radiation, reference_name: str
                     ) -> _Excitation:
    layout = "PER BETA I Mod Pha Re Im"
    table.require_rows(layout)
    # per period, per direction: a block of (Re, Im, line number) x 6 modes, NaN where no
    # line gave the mode (a compact array: ~35 bytes per line held); PER = -1 / 0 lines too
    lines: dict[float, dict[float, array]] = {}
    betas: dict[float, dict] = {}               # the distinct directions (bounded)
    largest = 0.0                               # the largest Mod at finite periods
    # lines whose Mod/Pha miss Re/Im by more than the relative tolerance: checked again with
    # the absolute floor once the largest Mod is known (kept, not every line: memory)
    suspects: list[tuple[int, float, float, complex]] = []
    for lineno, parts in table.rows:
        table.columns(lineno, parts, 7, layout)
        per = table.period(lineno, parts[0])
        beta = table.number(lineno, parts[1], "wave direction BETA [deg]")
        i = table.mode(lineno, parts[2], "I")
        mod = table.number(lineno, parts[3], "Mod")
        pha = table.number(lineno, parts[4], "Pha [deg]")
        re = table.number(lineno, parts[5], "Re")
        im = table.number(lineno, parts[6], "Im")
        if mod < 0.0:
            raise table.error(lineno, "a modulus Mod >= 0", f"Mod = {shown(parts[3], 40)}")
        by_beta = table.new_key(lines, per, lineno, MAX_PERIODS + 2,
                                 "wave periods (PER = -1 and 0 included)")
        table.new_key(betas, beta, lineno, MAX_DIRECTIONS, "wave directions")
        block = by_beta.get(beta)
        if block is None:
            block = by_beta[beta] = array("d", _EMPTY_BLOCK)
        k = 3 * (i - 1)
        if not math.isnan(block[k + 2]):
            raise table.error(lineno, "one line per (PER, BETA, I)", "a second line for "
                              f"PER = {shown(parts[0], 40)}, BETA = {shown(parts[1], 40)}, "
                              f"I = {i} (first at line {int(block[k + 2])})")
        block[k], block[k + 1], block[k + 2] = re, im, lineno
        value = complex(re, im)
        if per in (-1.0, 0.0):
            continue
        largest = max(largest, mod)
        polar = mod * complex(math.cos(math.radians(pha)), math.sin(math.radians(pha)))
        if abs(polar - value) > MOD_PHASE_RTOL * mod:
            suspects.append((lineno, mod, pha, value))

    _check_polar(table, suspects, largest)
    dropped = {p for p in (-1.0, 0.0) if lines.pop(p, None) is not None}
    if not lines:
        raise BemFileError(table.name, "", "lines at finite wave periods (PER > 0)",
                           "only PER = -1 or 0 lines")

    index = _match_periods(table, list(lines), radiation.periods, reference_name)
    directions = sorted({b for by_beta in lines.values() for b in by_beta})
    for per in sorted(lines, reverse=True):
        absent = [b for b in directions if b not in lines[per]]
        if absent:
            raise BemFileError(table.name, f"PER = {_format_period(per)} s",
                               f"every wave direction of the file ({len(directions)}: "
                               f"BETA = {shown(', '.join(f'{b:g}' for b in directions), 200)}"
                               " deg)", "no lines for BETA = "
                               f"{shown(', '.join(f'{b:g}' for b in absent), 200)} deg")
    values = np.zeros((len(radiation.periods), len(directions), _N_MODES), dtype=complex)
    omitted = 0
    for per, by_beta in lines.items():
        for b, beta in enumerate(directions):
            block = by_beta[beta]
            for m in range(_N_MODES):
                if math.isnan(block[3 * m + 2]):
                    omitted += 1
                else:
                    values[index[per], b, m] = complex(block[3 * m], block[3 * m + 1])
    return _Excitation(table.name, directions, values, sorted(dropped), omitted)


def _read_hydrostatics(table: _Table) -> NDArray[np.float64]:
    layout = "I J Cbar"
    table.require_rows(layout)
    out = np.zeros((_N_MODES, _N_MODES))
    first_line: dict[tuple[int, int], int] = {}
    for lineno, parts in table.rows:
        table.columns(lineno, parts, 3, layout)
        i = table.mode(lineno, parts[0], "I")
        j = table.mode(lineno, parts[1], "J")
        c = table.number(lineno, parts[2], "Cbar")
        table.once(first_line, (i, j), lineno, "I, J", f"I = {i}, J = {j}")
        out[i - 1, j - 1] = c
    return out


def _positive(name: str, value: float, allow_inf: bool = False) -> float:
    value = float(value)
    if not (value > 0.0 and (math.isfinite(value) or allow_inf)) or math.isnan(value):
        raise ValueError(f"{name} must be a {'' if allow_inf else 'finite '}number > 0, "
                         f"got {value!r}")
    return value


def _sort_files(paths: Sequence[str | Path]) -> dict[str, Path]:
    if isinstance(paths, (str, Path)):
        paths = [paths]
    if not paths:
        raise ValueError("read_wamit needs at least the .1 file")
    by_kind: dict[str, Path] = {}
    for given in paths:
        path = Path(given)
        kind = path.suffix.lower()
        if kind not in WAMIT_EXTENSIONS:
            raise BemFileError(str(given), "", "a WAMIT file ending in "
                               + ", ".join(WAMIT_EXTENSIONS), f"extension '{path.suffix}'"
                               if path.suffix else "no extension")
        if kind in by_kind:
            raise BemFileError(str(given), "", f"one {kind} file",
                               f"a second one besides {by_kind[kind]}")
        by_kind[kind] = path
    if ".1" not in by_kind:
        raise BemFileError(", ".join(str(p) for p in paths), "",
                           "a WAMIT .1 file (added mass and damping) among the files",
                           "none")
    return by_kind



def read_wamit(paths: Sequence[str | Path], *, water_density: float,
               gravity: float = 9.80665, length_scale: float = 1.0,
               water_depth: float | None = None) -> ImportedBem:
    """Read one rigid body's WAMIT ``.1`` (required), ``.3``/``.3fk``/``.3sc`` and ``.hst``.

    Parameters
    ----------
    paths
        The files, recognised by extension (``.1``, ``.3``, ``.3fk``, ``.3sc``, ``.hst``;
        at most one of each; a ``.out`` is left to :func:`read_wamit_out`). Without ``.3``
        but with both ``.3fk`` and ``.3sc`` the excitation is their sum; a lone ``.3fk`` or
        ``.3sc`` needs the ``.3``.
    water_density, gravity
        rho [kg/m^3] and g [m/s^2] of the WAMIT run (the numeric files state neither).
    length_scale
        WAMIT's ULEN [m], the length the files are non-dimensional by.
    water_depth
        The run's water depth [m] (``inf`` for deep water), recorded as given; None when
        not known.

    Returns
    -------
    ImportedBem
        Dimensional SI values in floatmoor's layout and e^{-i omega t} convention, omega
        increasing, about WAMIT's body origin (``rotation_center`` = 0).

    Raises
    ------
    BemFileError
        A file is missing, malformed or inconsistent with the others (see the module).
    ValueError
        A non-positive or non-finite density, gravity, length scale or water depth.
    """
    rho = _positive("water_density", water_density)
    g = _positive("gravity", gravity)
    ulen = _positive("length_scale", length_scale)
    depth = None if water_depth is None else _positive("water_depth", water_depth,
                                                       allow_inf=True)
    files = _sort_files(paths)  # a .out is read by read_wamit_out (its caller's)
    one = _Table(files[".1"], ".1")
    radiation = _read_radiation(one)
    periods = np.asarray(radiation.periods)
    omega = 2.0 * math.pi / periods
    read = [str(files[".1"])]
    notes = [f"Frequencies from the {len(periods)} finite periods of {one.name} "
             f"({periods[0]:.6g} to {periods[-1]:.6g} s), sorted by increasing omega."]

    k_rad = np.array([[_exponent_radiation(i, j) for i in range(1, 7)] for j in range(1, 7)])
    scale_rad = rho * ulen ** k_rad                    # [radiating j, influenced i]
    added_mass = radiation.added_mass * scale_rad
    damping = radiation.damping * scale_rad * omega[:, None, None]
    a_zero = None if radiation.zero is None else radiation.zero * scale_rad
    a_inf = None if radiation.infinite is None else radiation.infinite * scale_rad
    notes.append("A at omega = 0 (PER = -1): " + ("read" if a_zero is not None else
                                                   "not in the file") +
                 "; A at omega = infinity (PER = 0): " +
                 ("read." if a_inf is not None else "not in the file."))
    if radiation.omitted:
        notes.append(f"{radiation.omitted} (period, I, J) entries absent from the .1 are "
                     "zero (WAMIT omits negligible coefficients).")

    excitation = {}
    for kind in (".3", ".3fk", ".3sc"):
        if kind in files:
            excitation[kind] = _read_excitation(_Table(files[kind], kind), radiation,
                                                one.name)
            read.append(str(files[kind]))
    directions = None
    forces: dict[str, NDArray[np.complex128] | None] = {".3": None, ".3fk": None,
                                                         ".3sc": None}
    if excitation:
        base = next(iter(excitation.values()))
        for kind, exc in excitation.items():
            if exc.directions_deg != base.directions_deg:
                raise BemFileError(exc.path, "wave directions",
                                   f"the directions of {base.path} (BETA = "
                                   f"{', '.join(f'{b:g}' for b in base.directions_deg)} deg)",
                                   ", ".join(f"{b:g}" for b in exc.directions_deg))
        directions = np.radians(np.asarray(base.directions_deg, dtype=float))
        k_exc = np.array([_exponent_excitation(i) for i in range(1, 7)])
        scale_exc = rho * g * ulen ** k_exc
        for kind, exc in excitation.items():
            # WAMIT's e^{+i omega t} amplitudes -> floatmoor's e^{-i omega t}: conjugate.
            forces[kind] = np.conj(exc.values) * scale_exc
            if exc.dropped_limits:
                notes.append(f"{exc.path}: lines at PER = "
                             f"{', '.join(f'{p:g}' for p in exc.dropped_limits)} "
                             "(omega = 0 / infinity) not used: the database holds excitation "
                             "at finite frequencies only.")
            if exc.omitted:
                notes.append(f"{exc.omitted} (period, BETA, I) entries absent from "
                             f"{exc.path} are zero.")
        total, fk, sc = forces[".3"], forces[".3fk"], forces[".3sc"]
        if total is None:
            if fk is None or sc is None:
                given = files[".3fk"] if fk is not None else files[".3sc"]
                raise BemFileError(str(given), "", "the .3 file with it, or both .3fk and "
                                   ".3sc (the excitation is their sum)",
                                   f"no .3 and no {'.3sc' if fk is not None else '.3fk'}")
            total = fk + sc
            notes.append("Excitation = .3fk + .3sc (no .3 given).")
        elif fk is not None and sc is not None:
            scale = np.max(np.abs(total), axis=(0, 1))
            worst = np.abs(fk + sc - total) - PARTS_SUM_RTOL * scale
            if np.any(worst > 0.0):
                w, b, i = np.unravel_index(int(np.argmax(worst)), worst.shape)
                raise BemFileError(str(files[".3"]), f"PER = {periods[w]:.6g} s, BETA = "
                                   f"{base.directions_deg[b]:g} deg, I = {i + 1}",
                                   f"the sum of {files['.3fk']} and {files['.3sc']} "
                                   f"(within {PARTS_SUM_RTOL:g} of the mode's largest value)",
                                   f"{total[w, b, i]:.6g} against {fk[w, b, i] + sc[w, b, i]:.6g}")
        elif fk is not None:
            sc = total - fk
            notes.append("Scattering part = .3 - .3fk (no .3sc given).")
        elif sc is not None:
            fk = total - sc
            notes.append("Froude-Krylov part = .3 - .3sc (no .3fk given).")
        forces = {".3": total, ".3fk": fk, ".3sc": sc}
        notes.append(f"Excitation at {len(directions)} wave directions (BETA = direction of "
                     "propagation), complex conjugate of WAMIT's e^{+i omega t} amplitudes.")
    else:
        notes.append("No .3 file: no wave excitation.")

    stiffness = None
    if ".hst" in files:
        hst = _Table(files[".hst"], ".hst")
        k_hst = np.array([[_exponent_hydrostatic(i, j) for j in range(1, 7)]
                          for i in range(1, 7)])
        stiffness = _read_hydrostatics(hst) * rho * g * ulen ** k_hst
        read.append(str(files[".hst"]))
        notes.append("Hydrostatic stiffness: the .hst as given, which is the buoyancy part "
                     "only when the WAMIT run's centre of gravity was at the body origin (as "
                     "in OpenFAST's files; HydroDyn adds the weight itself), floatmoor's "
                     "convention.")
    else:
        notes.append("No .hst file: no hydrostatic stiffness.")
    notes.append("Rotation centre (0, 0, 0): WAMIT's body-frame origin, which must be the "
                 "floater's reference point.")
    notes.append(f"Dimensional with rho = {rho:g} kg/m^3, g = {g:g} m/s^2, ULEN = {ulen:g} m "
                 "(given to the importer; WAMIT's numeric files do not state them).")

    return ImportedBem(
        format="wamit", files=tuple(read), omega=omega, added_mass=added_mass,
        radiation_damping=damping, water_density=rho, gravity=g,
        added_mass_infinite=a_inf, added_mass_zero=a_zero, directions=directions,
        excitation_force=forces[".3"], froude_krylov_force=forces[".3fk"],
        diffraction_force=forces[".3sc"], hydrostatic_stiffness=stiffness,
        rotation_center=np.zeros(3), water_depth=depth, notes=tuple(notes))
