"""Hydrodynamic databases from another program's BEM results (``floatmoor hydro import``).

The readers (:func:`floatmoor.io.wamit.read_wamit`, :func:`floatmoor.io.bemio.read_bemio`)
return an :class:`~floatmoor.io.bem_data.ImportedBem`; :func:`imported_dataset` turns it into
a database in the layout of :func:`floatmoor.hydro.database.to_dataset` (same variables,
dimensions, coordinates, units and long names; no excitation variables when the files give
none) with its provenance: ``source`` (``"wamit"``, ``"bemio"``), ``source_files_json`` (each
file as given, its SHA-256 and size), ``import_options_json``, ``import_command``, the
importer's version and time, and the reader's notes (``import_notes_json``).

What the files lack and the layout needs:

* displaced volume and centre of buoyancy: BEMIO files give them, WAMIT's numeric files do
  not: its run summary (``.out``) does (:func:`floatmoor.io.wamit.read_wamit_out`), else
  ``--displaced-volume``, ``--centre-of-buoyancy``. Whatever a WAMIT import lacks (options
  and the ``.1`` and ``.hst`` files) is refused in one message listing each with the file
  that would state it (:data:`WAMIT_NEEDS`);
* waterplane area = C33 / (rho g) of the file's hydrostatic stiffness;
* rotation centre = the given reference point: the point the file's coefficients are about
  (its origin for WAMIT) is placed there;
* A_inf: the file's where it gives one (WAMIT PER = 0, BEMIO ``Ainf``); otherwise derived
  from the data (:func:`derived_infinite_added_mass`): per DOF the exponent p of the damping's
  decay B ~ omega^-p fitted over the top of the band (:data:`TAIL_FIT_FRACTION`), K(t) with
  that tail (:func:`floatmoor.hydro.radiation.impulse_response`), and A_inf from
  Kramers-Kronig as :func:`floatmoor.hydro.radiation.consistent_infinite_added_mass` does. The
  attribute ``added_mass_infinite_source`` says which.

Second-order data (WAMIT ``.8``/``.9``/``.12d``, :mod:`floatmoor.io.wamit_second_order`; BEMIO
mean drift, :mod:`floatmoor.io.bemio_second_order`) become ``mean_drift_far_field``,
``mean_drift_near_field`` and ``qtf_difference`` with ``drift_source`` = the format
(docs/guide/hydro_databases.md#imported-second-order-data), turned by the yaw as the
excitation is.

``yaw_deg`` turns the file's body frame about z into the case's: a point p of the file is
``reference + R (p - file reference)``, a 6x6 matrix M becomes T M T^T with
T = blockdiag(R, R) (exact), an excitation vector T X and its wave direction beta + yaw
(the set moved by whole turns so that it starts in [-180, 180) degrees: 0-180 deg turned by
180 deg is -180-0 deg; the excitation interpolation takes directions modulo 360 deg).

Size: reading the options against the files, labelling, the yaw and the derived A_inf are one
import's steps sharing its options and notes; split, each would import the others.
"""

from __future__ import annotations

import datetime as _dt
import json
import math
import os
from dataclasses import asdict, dataclass, replace
from pathlib import Path
from typing import Any, Sequence

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from floatmoor._version import __version__
from floatmoor.errors import CaseError
from floatmoor.hydro.database import (
    DOF_DEFINITION, database_coords, file_sha256, inputs_hash, labelled_variable,
)
from floatmoor.io.bem_data import BemFileError, ImportedBem
from floatmoor.input_files import InputFileError, regular_file_size

__all__ = [
    "ImportOptions", "WAMIT_EXTENSIONS", "BEMIO_EXTENSIONS", "file_format", "read_source",
    "imported_dataset", "import_database", "source_file_records", "yaw_transform",
    "decay_tail_exponents", "derived_infinite_added_mass", "TAIL_FIT_FRACTION",
    "TAIL_FIT_MIN_POINTS", "SAME_VALUE_RTOL", "SAME_POINT_ATOL", "RUN_SUMMARY_NOTE",
    "WAMIT_NEEDS", "YAW_NOTE", "yaw_note",
]

#: File extensions of WAMIT's numeric output: added mass and damping, excitation (total,
#: Haskind), hydrostatics, Froude-Krylov and scattering (diffraction) parts; and its run
#: summary (the gravity, ULEN and water depth of the run).
WAMIT_EXTENSIONS = (".1", ".3", ".hst", ".3fk", ".3sc", ".out", ".8", ".9", ".12d")
#: ... of which the second-order ones (mean drift by momentum and by pressure, the
#: difference-frequency QTF), read by :mod:`floatmoor.io.wamit_second_order`.
WAMIT_SECOND_ORDER = (".8", ".9", ".12d")
#: WEC-Sim BEMIO (HDF5).
BEMIO_EXTENSIONS = (".h5",)
#: The damping's tail exponent is fitted over the frequencies above (1 - this) x the top
#: frequency: the top quarter of the band, where the decay of a body's damping is nearest to
#: its asymptote while still holding several points of a usual grid (a choice).
TAIL_FIT_FRACTION = 0.25
#: ... and over at least this many top frequencies (a line through two points says nothing
#: about the scatter).
TAIL_FIT_MIN_POINTS = 3
#: A value given as an option and stated by the file agree when equal within this (the files
#: print 6 to 7 significant digits).
SAME_VALUE_RTOL = 1e-6
#: ... and a point [m] within this (files print positions to mm or finer).
SAME_POINT_ATOL = 1e-4


@dataclass(frozen=True)
class ImportOptions:
    """What ``floatmoor hydro import`` is told besides the files (None: not given).

    Attributes
    ----------
    water_density, gravity
        [kg/m^3], [m/s^2]: needed for WAMIT's non-dimensional values; BEMIO states them (a
        given value must then equal the file's).
    length_scale
        WAMIT's ULEN [m] (default 1).
    water_depth
        The BEM's water depth [m], ``inf`` for deep water (BEMIO states it).
    reference_point
        Where the point the file's coefficients are about lies in the case's coordinates
        (the case's ``floater.reference_point``) [m].
    disp_volume, centre_of_buoyancy
        [m^3], [m] (case coordinates): needed when the files do not give them (WAMIT).
    body
        BEMIO: which body (1-based) of a multi-body file.
    yaw_deg
        Rotation of the file's body frame about z into the case's [deg].
    """

    water_density: float | None = None
    gravity: float | None = None
    length_scale: float | None = None
    water_depth: float | None = None
    reference_point: tuple[float, float, float] = (0.0, 0.0, 0.0)
    disp_volume: float | None = None
    centre_of_buoyancy: tuple[float, float, float] | None = None
    body: int | None = None
    yaw_deg: float = 0.0

    def as_json(self) -> dict[str, Any]:
        """JSON-ready, the infinite depth as ``"infinite"``."""
        out = asdict(self)
        if out["water_depth"] is not None and not math.isfinite(out["water_depth"]):
            out["water_depth"] = "infinite"
        for key in ("reference_point", "centre_of_buoyancy"):
            if out[key] is not None:
                out[key] = [float(v) for v in out[key]]
        return out


def file_format(paths: Sequence[str]) -> str:
    """``"wamit"`` or ``"bemio"`` from the files' extensions.

    Raises
    ------
    CaseError
        No files, an unknown extension, WAMIT and BEMIO files mixed, more than one BEMIO
        file, or one WAMIT file given twice.
    """
    expected = ("WAMIT files (" + ", ".join(WAMIT_EXTENSIONS) + ") or one WEC-Sim BEMIO file "
                "(.h5)")
    if not paths:
        raise CaseError("FILE", "", expected, "no files")
    kinds = set()
    for path in paths:
        ext = Path(path).suffix.lower()
        if ext in WAMIT_EXTENSIONS:
            kinds.add("wamit")
        elif ext in BEMIO_EXTENSIONS:
            kinds.add("bemio")
        else:
            raise CaseError(str(path), "", expected, f"the extension '{ext or 'none'}'")
    if len(kinds) > 1:
        raise CaseError(" ".join(map(str, paths)), "", expected + ", not both", "both")
    kind = kinds.pop()
    if kind == "bemio" and len(paths) > 1:
        raise CaseError(" ".join(map(str, paths)), "", "one BEMIO .h5 file",
                        f"{len(paths)} files")
    seen = set()
    for path in paths:
        ext = Path(path).suffix.lower()
        if ext in seen:
            raise CaseError(str(path), "", f"one WAMIT {ext} file", f"two {ext} files")
        seen.add(ext)
    return kind


def _agree(path: str, what: str, flag: str, given: float | None, stated: float | None) -> None:
    """A value the file states must equal the one given for it (when both are)."""
    if given is None or stated is None:
        return
    same = (math.isinf(given) and math.isinf(stated)) or \
        math.isclose(given, stated, rel_tol=SAME_VALUE_RTOL)
    if not same:
        raise BemFileError(path, what, f"the {flag} given ({_text(given)})",
                           f"{_text(stated)} in the file")


def _point(p: Any) -> str:
    return ", ".join(f"{v:.10g}" for v in p)


def _text(value: float) -> str:
    return "infinite" if math.isinf(value) else f"{value:.10g}"


def read_source(paths: Sequence[str], options: ImportOptions) -> ImportedBem:
    """Read the files with the reader of their format (:func:`file_format`).

    Raises
    ------
    BemFileError
        A file that cannot be read as its format says, or one stating a value other than the
        option given for it.
    CaseError
        Bad or missing options (WAMIT without ``water_density`` or ``gravity``; ``body`` or
        ``length_scale`` given to the other format).
    """
    kind = file_format(paths)
    for path in paths:
        try:
            regular_file_size(path)
        except InputFileError as err:
            raise BemFileError(str(path), "", "a readable regular file", err.found) from None
    # extreme options (--length-scale 1e308) overflow the scaling: refused below, with one
    # line, instead of NumPy's warnings
    with np.errstate(over="ignore", invalid="ignore"):
        bem = _read_source(kind, paths, options)
    _require_finite(bem, options)
    return bem


#: The arrays of an ImportedBem that must be finite once dimensional.
_ARRAYS = ("omega", "added_mass", "radiation_damping", "added_mass_infinite", "added_mass_zero",
           "directions", "excitation_force", "froude_krylov_force", "diffraction_force",
           "hydrostatic_stiffness", "disp_volume", "center_of_buoyancy", "center_of_gravity",
           "rotation_center")


def _require_finite(bem: ImportedBem, options: ImportOptions) -> None:
    """Refuse dimensional values that overflowed (finite file values times extreme scales)."""
    second = bem.second_order
    held = [(name, getattr(bem, name)) for name in _ARRAYS]
    if second is not None:
        # the far field's NaN for Heave, Roll and Pitch is the layout's, not an overflow
        far = None if second.far_field is None else second.far_field[..., [0, 1, 5]]
        held += [("mean_drift_far_field", far), ("mean_drift_near_field", second.near_field),
                 ("qtf_difference", second.qtf_difference)]
    for name, value in held:
        if value is not None and not np.all(np.isfinite(value)):
            scales = f"rho = {bem.water_density:g}, g = {bem.gravity:g}" + (
                f", ULEN = {options.length_scale:g}" if options.length_scale is not None else "")
            raise BemFileError(" ".join(map(str, bem.files)), name, "finite dimensional "
                               f"values (the files' values scaled with {scales})",
                               "values that overflow")


def _read_source(kind: str, paths: Sequence[str], options: ImportOptions) -> ImportedBem:
    if kind == "wamit":
        from floatmoor.io.wamit import read_wamit

        if options.body is not None:
            raise CaseError("--body", "", "no --body with WAMIT files (one body per file "
                            "set)", str(options.body))
        options, adopted, summary = _with_run_summary(paths, options)
        _refuse_missing_wamit(paths, options, summary)
        assert options.water_density is not None and options.gravity is not None
        first = [str(p) for p in paths if Path(p).suffix.lower() not in WAMIT_SECOND_ORDER]
        bem = read_wamit(first, water_density=options.water_density,
                         gravity=options.gravity,
                         length_scale=1.0 if options.length_scale is None
                         else options.length_scale, water_depth=options.water_depth)
        bem = _with_wamit_second_order(bem, paths, options)
        if summary is not None:  # the body's volume and centre of buoyancy, as the file's
            bem = replace(bem, disp_volume=summary.disp_volume,
                          center_of_buoyancy=None if summary.center_of_buoyancy is None
                          else np.asarray(summary.center_of_buoyancy, float))
        return replace(bem, notes=bem.notes + tuple(adopted)) if adopted else bem
    from floatmoor.io.bemio import read_bemio

    if options.length_scale is not None:
        raise CaseError("--length-scale", "", "no --length-scale with a BEMIO file (its values "
                        "are dimensional)", _text(options.length_scale))
    # BEMIO stores A / rho, B / (rho omega), X / (rho g), C / (rho g), so a density given
    # re-dimensionalises exactly; it is an override, not a conflict, because BEMIO's readWAMIT
    # records rho = 1000 kg/m^3 whatever the WAMIT run used (the reader's notes say which rho
    # was applied). Gravity and depth shaped the BEM solution itself: those must agree.
    bem = read_bemio(str(paths[0]), body=options.body, water_density=options.water_density)
    _agree(str(paths[0]), "gravity", "--gravity", options.gravity, bem.gravity)
    _agree(str(paths[0]), "water depth", "--water-depth", options.water_depth, bem.water_depth)
    return bem


def _with_wamit_second_order(bem: ImportedBem, paths: Sequence[str],
                             options: ImportOptions) -> ImportedBem:
    """``bem`` with the mean drift and QTF of the ``.8``/``.9``/``.12d`` among ``paths``."""
    files = {Path(p).suffix.lower(): str(p) for p in paths
             if Path(p).suffix.lower() in WAMIT_SECOND_ORDER}
    if not files:
        return bem
    from floatmoor.io.wamit_second_order import read_wamit_second_order

    one = next(str(p) for p in paths if Path(p).suffix.lower() == ".1")
    excitation = next((str(p) for p in paths if Path(p).suffix.lower() in (".3", ".3fk",
                                                                            ".3sc")), ".3")
    directions = None if bem.directions is None else \
        [float(d) for d in np.degrees(bem.directions)]
    second = read_wamit_second_order(
        files, periods=list(2.0 * np.pi / np.asarray(bem.omega)), reference_name=one,
        directions_deg=directions, excitation_name=excitation,
        water_density=bem.water_density, gravity=bem.gravity,
        length_scale=1.0 if options.length_scale is None else options.length_scale)
    return replace(bem, second_order=second)


#: How the notes of the values taken from a WAMIT ``.out`` begin (``hydro import`` prints
#: them).
RUN_SUMMARY_NOTE = "From the WAMIT run summary"


#: What a WAMIT import needs besides the .1, in the order a missing-options message lists
#: them: (option or file kind, what it is, the field of the .out's WamitRunSummary that
#: states it or None). A WAMIT .3 is optional (without it the database has no excitation).
WAMIT_NEEDS = (
    ("--water-density RHO", "the water density of the WAMIT run [kg/m^3]", None),
    ("--gravity G", "the gravity of the run [m/s^2]", "gravity"),
    ("--water-depth DEPTH", "the run's water depth [m] or 'infinite'", "water_depth"),
    ("--displaced-volume V", "the displaced volume [m^3]", "disp_volume"),
    ("--centre-of-buoyancy X Y Z", "the centre of buoyancy [m] (an option is in the case's "
     "coordinates; the .out's is in the WAMIT body frame, placed by --reference-point and "
     "turned by --yaw-deg)", "center_of_buoyancy"),
)


def _refuse_missing_wamit(paths: Sequence[str], options: ImportOptions,
                          summary: Any) -> None:
    """One CaseError listing everything a WAMIT import lacks (options, and the .1 and .hst
    files), each with the file that would state it, instead of one per attempt."""
    kinds = {Path(p).suffix.lower() for p in paths}
    lacking: list[tuple[str, str]] = []
    for option, what, field in WAMIT_NEEDS:
        if getattr(options, _OPTION_FIELDS[option]) is not None:
            continue
        if field is not None and summary is not None and getattr(summary, field) is not None:
            continue
        if field is None:
            where = "no WAMIT file states it"
        elif summary is None:
            where = "stated by the run's .out: give the .out among the files, or the option"
        else:
            where = f"{summary.path} does not state it: give the option"
        lacking.append((option.split()[0], f"{option} ({what}; {where})"))
    for kind, what in ((".1", "the added mass and damping"),
                       (".hst", "the hydrostatic stiffness")):
        if kind not in kinds:
            lacking.append((kind, f"a {kind} file ({what}; no option gives it)"))
    if lacking:
        raise CaseError(" ".join(map(str, paths)), ", ".join(name for name, _ in lacking),
                        "everything a WAMIT import needs (the .out, when given, states "
                        "gravity, ULEN, water depth, displaced volume and centre of buoyancy; "
                        "the .hst the hydrostatic stiffness; the .1 added mass and damping; "
                        "an optional .3 the wave excitation): "
                        + "; ".join(text for _, text in lacking),
                        f"{len(lacking)} missing")


#: The ImportOptions field of each option of :data:`WAMIT_NEEDS`.
_OPTION_FIELDS = {"--water-density RHO": "water_density", "--gravity G": "gravity",
                  "--water-depth DEPTH": "water_depth",
                  "--displaced-volume V": "disp_volume",
                  "--centre-of-buoyancy X Y Z": "centre_of_buoyancy"}


def _with_run_summary(paths: Sequence[str], options: ImportOptions
                      ) -> tuple[ImportOptions, list[str], Any]:
    """The options with the gravity, ULEN and water depth a WAMIT ``.out`` among ``paths``
    states where they were not given, a note for each so taken, and the run summary (None
    without a ``.out``).

    Raises
    ------
    BemFileError
        A value given that is not the one the ``.out`` states (an infinite depth against a
        finite one included), naming both.
    """
    from floatmoor.io.wamit import read_wamit_out

    out = next((p for p in paths if Path(p).suffix.lower() == ".out"), None)
    if out is None:
        return options, [], None
    summary = read_wamit_out(out)
    adopted, notes = {}, []
    for what, flag, field, unit in (("water depth", "--water-depth", "water_depth", "m"),
                                    ("gravity", "--gravity", "gravity", "m/s^2"),
                                    ("length scale ULEN", "--length-scale", "length_scale",
                                     "m")):
        given, stated = getattr(options, field), getattr(summary, field)
        _agree(str(out), what, flag, given, stated)
        if given is None and stated is not None:
            adopted[field] = stated
            notes.append(f"{RUN_SUMMARY_NOTE} {out}: {what} {_text(stated)}"
                         + ("" if math.isinf(stated) else f" {unit}") + f" (no {flag} given).")
    _agree(str(out), "displaced volume", "--displaced-volume", options.disp_volume,
           summary.disp_volume)
    if summary.disp_volume is not None:
        notes.append(f"{RUN_SUMMARY_NOTE} {out}: displaced volume {_text(summary.disp_volume)} "
                     "m^3 (its VOLZ).")
    if summary.center_of_buoyancy is not None:
        notes.append(f"{RUN_SUMMARY_NOTE} {out}: centre of buoyancy "
                     f"({_point(summary.center_of_buoyancy)}) m in the WAMIT body frame.")
    return (replace(options, **adopted) if adopted else options), notes, summary


def source_file_records(paths: Sequence[str], project: str | os.PathLike[str] | None = None
                        ) -> list[dict[str, Any]]:
    """Each file as given (``path``), with its SHA-256 and size [bytes], and, for a file
    inside the folder ``project`` (:func:`floatmoor.hydro.database.project_folder` of the
    database), its path from there (``project_path``): the staleness check looks for it there,
    and only there, wherever it runs."""
    out = []
    for p in paths:
        record: dict[str, Any] = {"path": str(p), "sha256": file_sha256(p),
                                  "size": os.path.getsize(p)}
        if project is not None:
            try:
                inside = Path(p).resolve().relative_to(Path(project).resolve())
            except ValueError:
                pass
            else:
                record["project_path"] = inside.as_posix()
        out.append(record)
    return out


def yaw_transform(yaw_deg: float) -> NDArray[np.float64]:
    """T = blockdiag(R, R) (6, 6), R the rotation by ``yaw_deg`` about z: DOF vectors and
    forces turn as T q, 6x6 matrices as T M T^T."""
    c, s = math.cos(math.radians(yaw_deg)), math.sin(math.radians(yaw_deg))
    # exact quarter turns (cos 90 deg is 6e-17 in floating point)
    c, s = (round(c) if abs(c - round(c)) < 1e-15 else c), \
        (round(s) if abs(s - round(s)) < 1e-15 else s)
    r = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    t = np.zeros((6, 6))
    t[:3, :3] = r
    t[3:, 3:] = r
    return t


def _turn_matrices(m: NDArray, t: NDArray) -> NDArray:
    """T M T^T for a (6, 6) or (n, 6, 6) array."""
    return np.einsum("ik,...kl,jl->...ij", t, m, t)


def decay_tail_exponents(omega: NDArray[np.float64], damping: NDArray[np.float64]
                         ) -> NDArray[np.float64]:
    """Tail exponents (6, 6) from the damping's decay over the top of the band.

    Per diagonal DOF, p = -d ln B_ii / d ln omega by least squares over the frequencies of
    the top :data:`TAIL_FIT_FRACTION` of the band (at least :data:`TAIL_FIT_MIN_POINTS`),
    clipped to [TAIL_MIN, TAIL_MAX] of :mod:`floatmoor.hydro.radiation`; a DOF whose damping
    is not positive there keeps :data:`~floatmoor.hydro.radiation.TAIL_EXPONENT`.
    Off-diagonal terms take the mean of their two diagonal exponents (as
    :func:`~floatmoor.hydro.radiation.fit_tail_exponents`).
    """
    from floatmoor.hydro.radiation import TAIL_EXPONENT, TAIL_MAX, TAIL_MIN

    omega = np.asarray(omega, float)
    top = omega >= (1.0 - TAIL_FIT_FRACTION) * omega[-1]
    if top.sum() < TAIL_FIT_MIN_POINTS:
        top = np.arange(len(omega)) >= len(omega) - TAIL_FIT_MIN_POINTS
    diag = np.full(6, TAIL_EXPONENT)
    for i in range(6):
        b = damping[top, i, i]
        if np.all(b > 0.0):
            slope = np.polyfit(np.log(omega[top]), np.log(b), 1)[0]
            diag[i] = float(np.clip(-slope, TAIL_MIN, TAIL_MAX))
    return 0.5 * (diag[:, None] + diag[None, :])


def derived_infinite_added_mass(ds: xr.Dataset) -> tuple[NDArray[np.float64],
                                                          NDArray[np.float64]]:
    """A_inf (6, 6) and the tail exponents (6, 6) it was derived with, for a database whose
    files give no A_inf: K(t) from the damping with :func:`decay_tail_exponents` on the
    default kernel grid, then :func:`floatmoor.hydro.radiation.consistent_infinite_added_mass`."""
    from floatmoor.hydro.radiation import (
        consistent_infinite_added_mass, default_time_step, impulse_response, truncation_time,
    )

    omega = ds["omega"].values
    damping = ds["radiation_damping"].transpose("omega", "radiating_dof",
                                                "influenced_dof").values
    exponents = decay_tail_exponents(omega, damping)
    dt = default_time_step(omega)
    n = int(math.ceil(truncation_time(omega) / dt))
    n += n % 2
    t = np.linspace(0.0, n * dt, n + 1)
    kernel = impulse_response(omega, damping, t, tail_exponent=exponents)
    a_inf = consistent_infinite_added_mass(ds, t, kernel)
    return 0.5 * (a_inf + a_inf.T), exponents


def _resolved(bem: ImportedBem, options: ImportOptions) -> dict[str, Any]:
    """Depth, volume and centre of buoyancy (file coordinates, or None when given as an option
    in case coordinates), from the file or the options; CaseError when neither has them."""
    where = bem.files[0] if bem.files else "FILE"
    _agree(where, "displaced volume", "--displaced-volume", options.disp_volume,
           bem.disp_volume)
    depth = bem.water_depth if bem.water_depth is not None else options.water_depth
    if depth is None:
        raise CaseError("--water-depth", "", f"the water depth of the {bem.format.upper()} run "
                        "[m] or 'infinite' (its files do not state it)", "nothing")
    volume = bem.disp_volume if bem.disp_volume is not None else options.disp_volume
    if volume is None or (options.centre_of_buoyancy is None and bem.center_of_buoyancy is None):
        missing = [flag for flag, value in (
            ("--displaced-volume", volume),
            ("--centre-of-buoyancy", options.centre_of_buoyancy
             if options.centre_of_buoyancy is not None else bem.center_of_buoyancy))
            if value is None]
        raise CaseError(" and ".join(missing), "", f"the displaced volume [m^3] and centre of "
                        f"buoyancy X Y Z [m] of the hull ({bem.format.upper()} files "
                        f"{', '.join(map(str, bem.files))} do not give them)", "nothing")
    if bem.hydrostatic_stiffness is None:
        raise BemFileError(" ".join(map(str, bem.files)), "hydrostatic stiffness",
                           "a hydrostatic stiffness matrix (WAMIT: the .hst file)", "none")
    return {"depth": float(depth), "volume": float(volume)}


def imported_dataset(bem: ImportedBem, options: ImportOptions, *, name: str,
                     command: str = "", files: list[dict[str, Any]] | None = None
                     ) -> xr.Dataset:
    """Label an :class:`ImportedBem` as a database dataset (see the module docstring).

    Parameters
    ----------
    bem
        What the reader returned.
    options
        The import options (volume and centre of buoyancy where the files lack them).
    name
        The database's name (its file's stem).
    command
        The command line that made it (recorded, for re-imports).
    files
        :func:`source_file_records` of the files (default: computed from ``bem.files``).

    Raises
    ------
    CaseError
        Values the files lack and the options do not give.
    BemFileError
        No hydrostatic stiffness, or a volume the file states other than the one given.
    """
    values = _resolved(bem, options)
    rho, g, depth = float(bem.water_density), float(bem.gravity), values["depth"]
    t = yaw_transform(options.yaw_deg)
    rot = t[:3, :3]
    ref = np.asarray(options.reference_point, float)
    file_rc = np.zeros(3) if bem.rotation_center is None else np.asarray(bem.rotation_center,
                                                                          float)

    def place(point: Any) -> NDArray[np.float64]:
        return ref + rot @ (np.asarray(point, float) - file_rc)

    cob = np.asarray(options.centre_of_buoyancy, float) \
        if options.centre_of_buoyancy is not None else place(bem.center_of_buoyancy)
    if options.centre_of_buoyancy is not None and bem.center_of_buoyancy is not None:
        stated = place(bem.center_of_buoyancy)
        if not np.allclose(stated, cob, rtol=0.0, atol=SAME_POINT_ATOL):
            raise BemFileError(bem.files[0] if bem.files else "FILE", "centre of buoyancy",
                               f"the --centre-of-buoyancy given ({_point(cob)} m)",
                               f"{_point(stated)} m in the file (placed and turned into the "
                               "case's coordinates)")
    c = _turn_matrices(np.asarray(bem.hydrostatic_stiffness, float), t)
    rad = ("omega", "radiating_dof", "influenced_dof")
    pair = ("radiating_dof", "influenced_dof")
    data_vars = {
        "added_mass": labelled_variable("added_mass", _turn_matrices(bem.added_mass, t), rad),
        "radiation_damping": labelled_variable(
            "radiation_damping", _turn_matrices(bem.radiation_damping, t), rad),
        "hydrostatic_stiffness": labelled_variable("hydrostatic_stiffness", c,
                                                   ("influenced_dof", "radiating_dof")),
        "disp_volume": labelled_variable("disp_volume", values["volume"], ()),
        "waterplane_area": labelled_variable("waterplane_area", c[2, 2] / (rho * g), ()),
        "center_of_buoyancy": labelled_variable("center_of_buoyancy", cob, ("component",)),
        "rotation_center": labelled_variable("rotation_center", ref, ("component",)),
    }
    if bem.added_mass_zero is not None:
        data_vars["added_mass_zero"] = labelled_variable(
            "added_mass_zero", _turn_matrices(bem.added_mass_zero, t), pair)
    directions = None
    if bem.excitation_force is not None:
        directions, order = _turned_directions(bem.directions, options.yaw_deg, bem)
        exc = ("omega", "wave_direction", "influenced_dof")
        parts = [("excitation_force", bem.excitation_force)]
        if bem.froude_krylov_force is not None and bem.diffraction_force is not None:
            parts += [("Froude_Krylov_force", bem.froude_krylov_force),
                      ("diffraction_force", bem.diffraction_force)]
        for var, x in parts:
            turned = np.einsum("ik,wbk->wbi", t, np.asarray(x, complex))[:, order, :]
            data_vars[var] = labelled_variable(var, turned, exc)
    coords = database_coords(bem.omega, depth, g, directions)
    second_vars, second_coords = _second_order_variables(bem, options.yaw_deg, t)
    data_vars.update(second_vars)
    coords.update(second_coords)
    if bem.added_mass_infinite is not None:
        a_inf = _turn_matrices(np.asarray(bem.added_mass_infinite, float), t)
        a_inf_source = f"file ({_INFINITY_ENTRY.get(bem.format, 'the file')})"
        exponents = None
    else:
        probe = xr.Dataset(data_vars=data_vars, coords=coords)
        a_inf, exponents = derived_infinite_added_mass(probe)
        a_inf_source = ("derived: Kramers-Kronig (floatmoor.body.model."
                        "consistent_infinite_added_mass) with the damping tail exponents "
                        "fitted to its decay over the top "
                        f"{TAIL_FIT_FRACTION:.0%} of the band (Surge..Yaw: "
                        + ", ".join(f"{p:.3g}" for p in np.diag(exponents)) + ")")
    data_vars["added_mass_infinite"] = labelled_variable("added_mass_infinite", a_inf, pair)
    records = files if files is not None else source_file_records(bem.files)
    notes = list(bem.notes) + _importer_notes(bem, options, ref, float(c[2, 2] / (rho * g)))
    if bem.second_order is not None:
        notes += list(bem.second_order.notes)
    depth_text = "infinite" if not math.isfinite(depth) else f"{depth!r}"
    inputs = {
        "source": bem.format,
        "reference_point": ref.tolist(),
        "water_density": rho,
        "gravity": g,
        "water_depth": depth_text if not math.isfinite(depth) else depth,
        "files": [{"path": r["path"], "sha256": r["sha256"]} for r in records],
        "options": options.as_json(),
    }
    attrs: dict[str, Any] = {
        "title": f"floatmoor hydrodynamic database {name} (imported from {bem.format} files)",
        "database": name,
        "source": bem.format,
        "source_files_json": json.dumps(records),
        "import_options_json": json.dumps(options.as_json(), sort_keys=True),
        "import_command": command,
        "import_notes_json": json.dumps(notes),
        "importer": f"floatmoor {__version__} (floatmoor hydro import)",
        "floatmoor_version": __version__,
        "created": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
        "body_name": bem.body_name or "",
        "added_mass_infinite_source": a_inf_source,
        "water_depth": depth_text,
        "bem_water_depth": depth_text,
        "water_density": rho,
        "gravity": g,
        "excitation": "none in the files" if directions is None else
        ", ".join(v for v in ("excitation_force", "Froude_Krylov_force", "diffraction_force")
                  if v in data_vars),
        "inputs_json": json.dumps(inputs, sort_keys=True),
        "inputs_hash": inputs_hash(inputs),
        "dof_definition": DOF_DEFINITION,
        "time_convention": "e^{-i omega t} (capytaine); WAMIT phases are the conjugate",
        "Conventions": "CF-1.8",
    }
    if any(name in data_vars for name in ("mean_drift_far_field", "mean_drift_near_field",
                                          "qtf_difference")):
        # imported drift: the source program's RAOs, no floatmoor drift_inputs_hash
        attrs["drift_source"] = bem.format
    if exponents is not None:
        attrs["added_mass_infinite_tail_exponents"] = json.dumps(np.diag(exponents).tolist())
    return xr.Dataset(data_vars=data_vars, coords=coords, attrs=attrs)


#: Units of the mean drift and QTF variables (per unit wave amplitude squared).
SECOND_ORDER_UNITS = "N/m^2 (Surge, Sway, Heave), N m/m^2 (Roll, Pitch, Yaw)"
_DRIFT_WHAT = ("mean wave drift force and moment about the rotation centre per unit wave "
               "amplitude squared")


def _second_order_variables(bem: ImportedBem, yaw_deg: float, t: NDArray[np.float64]
                            ) -> tuple[dict[str, xr.DataArray], dict[str, tuple]]:
    """The imported mean drift and QTF variables, turned by the yaw like the excitation, and
    the QTF's coordinates (docs/guide/hydro_databases.md#imported-second-order-data)."""
    second = bem.second_order
    out: dict[str, xr.DataArray] = {}
    coords: dict[str, tuple] = {}
    if second is None:
        return out, coords
    drift_dims = ("omega", "wave_direction", "influenced_dof")
    for name, values, route, source in (
            ("mean_drift_far_field", second.far_field, "far field (momentum conservation); "
             "Surge, Sway and Yaw only (NaN for Heave, Roll, Pitch)", second.far_field_from),
            ("mean_drift_near_field", second.near_field, "near field (pressure integration)",
             second.near_field_from)):
        if values is None:
            continue
        _, order = _turned_directions(bem.directions, yaw_deg, bem)
        turned = np.einsum("ik,wbk->wbi", t, np.nan_to_num(values))[:, order, :]
        if name == "mean_drift_far_field":
            turned[..., 2:5] = np.nan
        out[name] = xr.DataArray(turned, dims=drift_dims, attrs={
            "long_name": f"{_DRIFT_WHAT}, {route}, imported from {bem.format} files",
            "units": SECOND_ORDER_UNITS, "drift_source": source})
    if second.qtf_difference is not None:
        beta, order = _turned_directions(second.qtf_directions, yaw_deg, bem)
        q = np.einsum("ik,dabk->dabi", t, second.qtf_difference)[order]
        out["qtf_difference"] = xr.DataArray(
            np.stack([q.real, q.imag]),
            dims=("complex", "qtf_direction", "qtf_omega_1", "qtf_omega_2", "influenced_dof"),
            attrs={"long_name": "difference-frequency quadratic transfer function per unit "
                   "wave amplitude squared: F(t) = Re sum_i sum_j A_i conj(A_j) Q(w_i, w_j) "
                   "e^{-i (w_i - w_j) t} over all ordered pairs of the sea's complex "
                   "amplitudes; Hermitian, Q(w, w) the mean drift",
                   "units": SECOND_ORDER_UNITS, "qtf_source": second.qtf_from})
        omega = np.asarray(second.qtf_omega, float)
        for axis in ("qtf_omega_1", "qtf_omega_2"):
            coords[axis] = (axis, omega, {"long_name": f"wave frequency "
                                          f"{axis[-1]} of the QTF", "units": "rad/s"})
        coords["qtf_direction"] = ("qtf_direction", beta, {
            "long_name": "wave propagation direction of both components (unidirectional "
                         "pairs), from +x counter-clockwise", "units": "rad"})
        coords.setdefault("complex", ("complex", np.array(["re", "im"]),
                                      {"long_name": "real and imaginary parts"}))
    return out, coords


def _importer_notes(bem: ImportedBem, options: ImportOptions, ref: NDArray[np.float64],
                   waterplane: float) -> list[str]:
    """What the importer did, one sentence each (after the reader's notes)."""
    notes = [f"Rotation centre: the file's reference point placed at "
             f"({', '.join(f'{v:g}' for v in ref)}) m, the case's floater.reference_point."]
    notes.append(yaw_note(options.yaw_deg))
    given = [what for what, option, stated in (
        ("displaced volume", options.disp_volume, bem.disp_volume),
        ("centre of buoyancy", options.centre_of_buoyancy, bem.center_of_buoyancy))
        if option is not None and stated is None]
    if given:
        notes.append(f"{' and '.join(given).capitalize()} as given to the importer (the files "
                     "do not give them).")
    notes.append(f"Waterplane area = C33 / (rho g) = {waterplane:.6g} m^2.")
    return notes


#: How the note on the orientation begins (``hydro import`` prints it).
YAW_NOTE = "Orientation"


def yaw_note(yaw_deg: float) -> str:
    """What ``--yaw-deg`` did, in the case's terms (the CLI's help says the same)."""
    if not yaw_deg:
        return (f"{YAW_NOTE}: the file's body axes are the case's (--yaw-deg 0); its wave "
                "heading BETA is the case's waves.direction_deg = BETA.")
    c, s = yaw_transform(yaw_deg)[:2, 0]
    return (f"{YAW_NOTE}: the file's body frame turned by {yaw_deg:g} deg about z "
            "(counter-clockwise seen from above) into the case's: the file's +x axis is the "
            f"case's ({c + 0.0:.4g}, {s + 0.0:.4g}, 0); 6x6 matrices T M T^T, forces T X; its "
            f"wave heading BETA (travelling towards BETA) is the case's waves.direction_deg = "
            f"BETA + {yaw_deg:g} (its heading 0 travels towards {_wrap_deg(yaw_deg):g} deg).")


def _wrap_deg(angle: float) -> float:
    """``angle`` [deg] in [-180, 180)."""
    return (angle + 180.0) % 360.0 - 180.0


#: Where each format gives A_inf.
_INFINITY_ENTRY = {"wamit": "WAMIT .1, PER = 0", "bemio": "BEMIO hydro_coeffs/added_mass/inf_freq"}


def _turned_directions(directions: Any, yaw_deg: float, bem: ImportedBem
                       ) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """The file's directions turned by the yaw (unchanged without one), the whole set moved
    by whole turns so that its first lies in [-pi, pi): a contiguous range stays contiguous
    (0 to 180 deg turned by 180 deg is -180 to 0 deg); and the order (sorted)."""
    beta = np.asarray(directions, float)
    if yaw_deg:
        beta = beta + math.radians(yaw_deg)
        beta = beta - 2.0 * math.pi * math.floor((beta.min() + math.pi) / (2.0 * math.pi))
        beta = np.where(np.abs(beta) < 1e-12, 0.0, beta)
    order = np.argsort(beta, kind="stable")
    turned = beta[order]
    if np.any(np.diff(turned) < 1e-9):
        raise BemFileError(" ".join(map(str, bem.files)), "wave directions",
                           "distinct directions", ", ".join(
                               f"{d:g}" for d in np.degrees(directions)) + " deg")
    return turned, order


def import_database(paths: Sequence[str], options: ImportOptions, *, name: str,
                    command: str = "", project: str | os.PathLike[str] | None = None
                    ) -> xr.Dataset:
    """Read ``paths`` (:func:`read_source`) and label them (:func:`imported_dataset`).

    Parameters
    ----------
    paths
        The other program's BEM result files.
    options
        What the command was told besides the files.
    name
        The database's name.
    command
        The command line, recorded in the database.
    project
        The folder the source files' paths are recorded from (:func:`source_file_records`).

    Returns
    -------
    xarray.Dataset
        The database, ready for :func:`floatmoor.hydro.database.write_database`."""
    bem = read_source(paths, options)
    with np.errstate(over="ignore", invalid="ignore"):
        ds = imported_dataset(bem, options, name=name, command=command,
                              files=source_file_records(paths, project))
    for var in ds.data_vars:
        values = ds[var].values
        if var == "mean_drift_far_field":  # NaN for Heave, Roll, Pitch by its layout
            values = ds[var].sel(influenced_dof=["Surge", "Sway", "Yaw"]).values
        if not np.all(np.isfinite(values)):
            raise BemFileError(" ".join(map(str, bem.files)), var, "finite values once placed "
                               "and turned into the case's frame", "values that overflow")
    return ds
