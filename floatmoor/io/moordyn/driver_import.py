"""A MoorDyn deck with its driver file and motion file -> a case file text with
``[motion] kind = "body"`` and the body-motion table (CSV) it points at.

What is taken from the driver (docs/guide/mooring_systems.md#importing-with-moordyns-driver):

- ``Gravity``, ``rhoW``, ``WtrDpth`` where the deck gives no ``g``, ``rho``, ``WtrDpth`` option
  (MoorDyn-F reads the deck's options after the driver's values, so the deck's win; a
  difference is listed); ``TMax`` as the run's duration;
- the motion: ``InputsMode 1``: the motion file, positions of the coupled points fitted to a
  rigid-body motion (:mod:`.motion_fit`; refused when a row's largest residual exceeds
  :data:`RIGID_FIT_TOLERANCE`), or six DOFs taken as they are; ``InputsMode 0``: the coupled
  points stay at the driver's initial pose (a two-row table when that pose is not zero);
- the initial pose: the lines start at the table's first row (floatmoor starts them at the
  motion's pose at t = 0); its distance from the driver's initial pose, at the coupled points,
  is reported.

MoorDyn's driver smooths the motion rows (a first-order filter run forward and backward) and
applies each row one coupling step (``dtC``) late; the case follows the rows themselves, and
the import says so.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from floatmoor.errors import CaseError
from floatmoor.io.moordyn.deck import POINT_BODY, POINT_COUPLED, Deck
from floatmoor.io.moordyn.driver import DriverInput, MotionRecord, read_motion_file
from floatmoor.io.moordyn.importer import import_deck
from floatmoor.io.moordyn.motion_fit import fit_rigid_motion
from floatmoor.rotations import rotation_matrices

__all__ = ["DriverImport", "import_with_driver", "RIGID_FIT_TOLERANCE", "MOTION_TABLE_HEADER"]

#: Largest distance [m] of a coupled point from the fitted rigid-body pose of its row: points
#: given to 1e-6 m fit to 6.6e-7 m (OpenFAST r-test md_5MW_OC4Semi, three fairleads 70 m
#: apart); a point a millimetre off is not on one rigid body with the others.
RIGID_FIT_TOLERANCE = 1e-3
#: Header of the written table (``[motion] kind = "body"``, rotations in radians as MoorDyn's).
MOTION_TABLE_HEADER = "time,surge,sway,heave,roll_rad,pitch_rad,yaw_rad"
#: The marker line of the importer's "not mapped" block; the [motion] table goes before it.
_NOT_MAPPED = "# -- not mapped "
#: Suffixes of header names of position columns (MoorDyn's ``P4PX``, ``CON4PX``, ...).
_POSITION_SUFFIXES = ("PX", "PY", "PZ")


@dataclass
class DriverImport:
    """The case text, the table (None when the case gets no motion) and what to report."""

    text: str
    table: str | None
    unmapped: list[str] = field(default_factory=list)
    summary: list[str] = field(default_factory=list)


def _driver_values(deck: Deck, driver: DriverInput, notes: list[str]
                   ) -> dict[str, tuple[float, str, bool]]:
    values: dict[str, tuple[float, str, bool]] = {}
    for name, keys, key, value in (("g", ("g", "gravity"), "Gravity", driver.gravity),
                                   ("rho", ("rho", "wtrdnsty"), "rhoW", driver.water_density),
                                   ("depth", ("wtrdpth",), "WtrDpth", driver.water_depth)):
        values[name] = (value, f"{key} of the driver ({driver.where(key)})", False)
        opt = deck.option(*keys)
        if opt is None and not value > 0.0:
            raise CaseError(driver.where(key), key, "a number > 0 (floatmoor's gravity, water "
                            "density and depth are positive)", repr(value))
        if opt is not None:
            try:
                differs = float(opt.value) != value
            except ValueError:
                differs = False  # the importer reports the malformed value
            if differs:
                notes.append(f"{key} = {value:g} in the driver, {opt.key} = {opt.value} in the "
                             f"deck (line {opt.line_number}): the deck's, as MoorDyn-F")
    values["TMax"] = (driver.duration, f"TMax of the driver ({driver.where('TMax')})", True)
    return values


def _classify(record: MotionRecord, coupled: int) -> str:
    """"points" or "dofs" from the column count and the header names."""
    columns = record.values.shape[1]
    by_points = coupled > 0 and columns == 3 * coupled
    by_dofs = columns == 6
    if by_points and by_dofs and record.names:
        by_dofs = not all(n.upper().endswith(_POSITION_SUFFIXES) for n in record.names)
        by_points = not by_dofs
    if by_points and not by_dofs:
        return "points"
    if by_dofs and not by_points:
        return "dofs"
    expected = (f"1 + 3 x {coupled} columns (time and the positions of the deck's {coupled} "
                "coupled points) or 7 (time and the platform's six DOFs)")
    found = (f"{columns + 1} columns" if not (by_points and by_dofs) else
             f"{columns + 1} columns and no header naming them (positions P..PX or DOFs)")
    raise CaseError(f"{record.source}:{record.line_numbers[0]}", "", expected, found)


def _pose_points(pose: NDArray[np.float64], rest: NDArray[np.float64]) -> NDArray[np.float64]:
    """The points (k, 3) at the poses (n, 6), about the origin: (n, k, 3)."""
    R = rotation_matrices(pose[:, 3:])
    return np.einsum("nij,kj->nki", R, rest) + pose[:, None, :3]


def _table_text(time: NDArray[np.float64], pose: NDArray[np.float64], source: str) -> str:
    out = [f"# Body motion imported from {source} by floatmoor import moordyn",
           MOTION_TABLE_HEADER]
    out.extend(",".join(f"{v:.15g}" for v in (t, *row)) for t, row in zip(time, pose))
    return "\n".join(out) + "\n"


def import_with_driver(deck: Deck, driver: DriverInput, *, motion_file_name: str,
                       water_depth: float | None = None) -> DriverImport:
    """The case text for ``deck`` run as ``driver`` says, and its motion table.

    Parameters
    ----------
    deck, driver
        The parsed deck and driver file.
    motion_file_name
        The table's file name as the case refers to it (beside the case file).
    water_depth
        Replaces the deck's and the driver's water depth [m] (``--water-depth``).

    Raises
    ------
    CaseError
        A malformed motion file, points that are not rigid, a motion file shorter than TMax,
        or a deck whose points cannot follow the motion; naming the file and line.
    """
    notes: list[str] = []
    summary: list[str] = []
    result = import_deck(deck, water_depth=water_depth,
                         driver_values=_driver_values(deck, driver, notes))
    if Path(driver.deck_file).name != Path(deck.source).name:
        notes.append(f"the driver names MDInputFile '{driver.deck_file}' "
                     f"({driver.where('MDInputFile')}); the deck given, {deck.source}, is used")
    if driver.reference != (0.0, 0.0):
        notes.append(f"ref_X, ref_Y = {driver.reference} ({driver.where('Initial Positions')}):"
                     " FAST.Farm's turbine position, unused in OpenFAST mode")
    coupled = [p for p in deck.points if p.attachment == POINT_COUPLED]
    rest = np.array([p.position for p in coupled], dtype=float).reshape(-1, 3)
    initial = np.asarray(driver.initial_pose, dtype=float)[None, :]
    time: NDArray[np.float64] | None = None
    pose: NDArray[np.float64] | None = None
    origin = ""
    if driver.inputs_mode == 1:
        where = driver.where("InputsFile")
        if not coupled:
            raise CaseError(where, "InputsFile", "a deck with coupled (Vessel) points for the "
                            "motion to drive", "none in the deck")
        path = Path(driver.source).parent / driver.inputs_file
        record = read_motion_file(path)
        kind = _classify(record, len(coupled))
        if record.time[-1] < driver.duration:
            raise CaseError(f"{record.source}:{record.line_numbers[-1]}", "time",
                            f"rows up to TMax = {driver.duration:g} s "
                            f"({driver.where('TMax')})", f"the last at {record.time[-1]:g} s")
        time = record.time
        if kind == "points":
            positions = record.values.reshape(-1, len(coupled), 3)
            try:
                fit = fit_rigid_motion(rest, positions)
            except ValueError as err:
                row, _, what = str(err).partition(": ")
                n = record.line_numbers[int(row.split()[1])]
                raise CaseError(f"{record.source}:{n}", "", "positions of points on one "
                                "rigid body", what) from None
            worst = int(np.argmax(fit.residual))
            bad = np.flatnonzero(fit.residual > RIGID_FIT_TOLERANCE)
            if bad.size:
                raise CaseError(f"{record.source}:{record.line_numbers[bad[0]]}", "",
                                f"positions of the {len(coupled)} coupled points on one rigid "
                                f"body (fit residual <= {RIGID_FIT_TOLERANCE:g} m)",
                                f"a point {fit.residual[bad[0]]:.3g} m off the best rigid fit")
            pose = fit.pose
            what = ("rigid-body fit (rotation and translation)" if fit.rotation_fitted else
                    "translation (one coupled point: no rotation)")
            summary.append(f"motion: {time.size} rows of {len(coupled)} coupled points' "
                           f"positions from {record.source}, {what}: largest residual "
                           f"{fit.residual[worst]:.2g} m (line {record.line_numbers[worst]}; "
                           f"tolerance {RIGID_FIT_TOLERANCE:g} m)")
            origin = (f"fitted to the coupled points' positions in {record.source} (largest "
                      f"residual {fit.residual[worst]:.2g} m)")
        else:
            pose = record.values.copy()
            summary.append(f"motion: {time.size} rows of the platform's six DOFs from "
                           f"{record.source} (m, rad)")
            origin = f"the six DOFs of {record.source}"
        notes.append(f"MoorDyn's driver smooths the motion rows and applies each one dtC = "
                     f"{driver.coupling_interval:g} s late ({driver.where('dtC')}); the case "
                     "follows the rows (a not-a-knot spline through them)")
    elif coupled and np.any(initial != 0.0):
        time = np.array([0.0, driver.duration])
        pose = np.repeat(initial, 2, axis=0)
        origin = "InputsMode 0: the coupled points held at the driver's initial pose"
        summary.append("motion: InputsMode 0, the coupled points held at the driver's initial "
                       f"pose ({driver.where('Initial Positions')})")
    else:
        summary.append("motion: none (InputsMode 0, initial pose zero or no coupled points)")
    if pose is None or time is None:
        return DriverImport(text=result.text, table=None, unmapped=result.unmapped + notes,
                            summary=summary)
    if any(p.attachment == POINT_BODY for p in deck.points):
        raise CaseError(driver.where("InputsMode"), "InputsMode", "a deck without points on "
                        "MoorDyn bodies (BodyN) when the driver moves the platform: floatmoor "
                        "would move them with it", "BodyN points")
    if coupled:
        gap = float(np.linalg.norm(_pose_points(pose[:1], rest) - _pose_points(initial, rest),
                                   axis=2).max())
        first = ", ".join(f"{v:.6g}" for v in pose[0])
        summary.append(f"initial pose: the lines start at the table's first row ({first}; m, "
                       f"rad); the driver's initial pose ({driver.where('Initial Positions')}) "
                       f"puts the coupled points up to {gap:.2g} m from it")
    block = [f"[motion]  # from the MoorDyn driver {driver.source}",
             "kind = \"body\"",
             "reference_point = [0.0, 0.0, 0.0]  # m: MoorDyn's platform reference, the "
             "origin (the coupled points' deck positions are the platform's frame)",
             f"file = \"{motion_file_name}\"  # {origin}",
             "ramp_duration = 0.0  # s: the motion as recorded, from its first row",
             ""]
    block.extend(f"# {item}" for item in summary + notes)
    block.append("")
    lines = result.text.split("\n")
    at = next(i for i, line in enumerate(lines) if line.startswith(_NOT_MAPPED))
    text = "\n".join(lines[:at] + block + lines[at:])
    return DriverImport(text=text, table=_table_text(time, pose, driver.source),
                        unmapped=result.unmapped + notes, summary=summary)
