"""Reading ``[motion] kind = "body"``: a prescribed 6-DOF rigid-body motion of the body points.

Either a table::

    [motion]
    kind = "body"
    reference_point = [0.0, 0.0, 0.0]   # m, the rotation centre at rest (default: the origin)
    file = "motion.csv"                 # time,surge,sway,heave,roll_deg,pitch_deg,yaw_deg
    ramp_duration = 0.0                 # s (default 0, as for kind = "table")

whose header names the rotations' unit, ``_deg`` or ``_rad``, for all three (translations in
m, time in s); or harmonic DOFs, each an optional sub-table, at least one moving::

    [motion.surge]
    amplitude = 2.0      # m
    period = 12.0        # s
    phase_deg = 0.0      # deg, default 0: x = a sin(2 pi t / T + phase)
    [motion.pitch]
    amplitude_deg = 4.0  # deg: rotations in degrees, as every angle of a case file
    period = 12.0

The default ramp of harmonic DOFs is the longest moving period, as for ``kind = "harmonic"``.
The reference point defaults to the origin (still water level above the global origin): the
point whose motion MoorDyn's coupled bodies, OpenFAST's platform and WEC-Sim pass, so a
motion record of those programs applies unchanged.
"""

from __future__ import annotations

import math
from pathlib import Path

from floatmoor.case.motion_table import read_csv_table
from floatmoor.case.reader import MISSING, TableReader, _Found
from floatmoor.case.schema import (
    BODY_DOFS, BodyHarmonicMotion, BodyMotion, BodyTableMotion, HarmonicRotation,
    HarmonicTranslation, Simulation,
)
from floatmoor.case.setting import read_settings, settings_of

__all__ = ["read_body_motion", "BODY_TABLE_HEADERS", "DEFAULT_REFERENCE_POINT"]

#: The header rows a body-motion table may have: rotations all in degrees or all in radians.
BODY_TABLE_HEADERS = (
    ("time", "surge", "sway", "heave", "roll_deg", "pitch_deg", "yaw_deg"),
    ("time", "surge", "sway", "heave", "roll_rad", "pitch_rad", "yaw_rad"),
)
#: Rotation centre at rest when the case gives none [m] (see the module docstring).
DEFAULT_REFERENCE_POINT = (0.0, 0.0, 0.0)
#: Period of a DOF that does not move [s]: any positive value gives a zero motion.
_STILL_PERIOD = 1.0
_TRANSLATIONS = BODY_DOFS[:3]


def read_body_motion(t: TableReader, base_dir: Path, simulation: Simulation) -> BodyMotion:
    """The body motion of the ``[motion]`` table ``t`` (its ``kind`` already read).

    Raises
    ------
    CaseError
        Naming the file, the key path, what was expected and what was found.
    """
    known = ("kind", "reference_point", "ramp_duration", "file") + BODY_DOFS
    for key in t.data:  # first: a misspelt DOF table would read as no motion at all
        if key not in known:
            raise t.error(key, f"one of the known keys ({', '.join(sorted(known))})",
                          _Found(f"the unknown key '{key}'"))
    reference = settings_of(BodyHarmonicMotion)["reference_point"].read(
        t, "reference_point", DEFAULT_REFERENCE_POINT)
    harmonic = [dof for dof in BODY_DOFS if t.has(dof)]
    if t.has("file") and harmonic:
        raise t.error(harmonic[0], "either a table (file) or harmonic DOF tables "
                      "([motion.surge] ... [motion.yaw]), not both", t.data[harmonic[0]])
    if t.has("file"):
        return _table(t, base_dir, simulation, reference)  # type: ignore[arg-type]
    if not harmonic:
        raise t.error("file", 'a motion table file = "NAME.csv" or at least one harmonic DOF '
                      "table ([motion.surge], [motion.sway], [motion.heave], [motion.roll], "
                      "[motion.pitch] or [motion.yaw])", MISSING)
    return _harmonic(t, reference)  # type: ignore[arg-type]


def _harmonic(t: TableReader, reference: tuple[float, float, float]) -> BodyHarmonicMotion:
    amplitude = [0.0] * 6
    period = [_STILL_PERIOD] * 6
    phase = [0.0] * 6
    for i, dof in enumerate(BODY_DOFS):
        if not t.has(dof):
            continue
        d = t.table(dof)
        if dof in _TRANSLATIONS:
            if d.has("amplitude_deg"):
                raise d.error("amplitude_deg", f"amplitude: the {dof} amplitude in metres (a "
                              "translation)", d.data["amplitude_deg"])
            keys: type = HarmonicTranslation
        else:
            if d.has("amplitude"):
                raise d.error("amplitude", f"amplitude_deg: the {dof} amplitude in degrees, as "
                              "every angle of a case file", d.data["amplitude"])
            keys = HarmonicRotation
        amplitude[i], period[i], phase[i] = read_settings(keys, d).values()
        d.finish()
    if not any(amplitude):
        raise t.error(next(dof for dof in BODY_DOFS if t.has(dof)),
                      "at least one DOF with a non-zero amplitude",
                      _Found("every amplitude 0"))
    longest = max(p for a, p in zip(amplitude, period) if a > 0.0)
    return BodyHarmonicMotion(
        reference_point=reference, amplitude=tuple(amplitude), period=tuple(period),
        phase=tuple(phase),
        ramp_duration=settings_of(BodyHarmonicMotion)["ramp_duration"].read(
            t, "ramp_duration", longest))


def _table(t: TableReader, base_dir: Path, simulation: Simulation,
           reference: tuple[float, float, float]) -> BodyTableMotion:
    declared = settings_of(BodyTableMotion)
    file_name = declared["file"].read(t, "file")
    path, header, time, values = read_csv_table(t, base_dir, file_name, BODY_TABLE_HEADERS)
    if header == BODY_TABLE_HEADERS[0]:
        values[:, 3:] = values[:, 3:] * (math.pi / 180.0)
    if time[-1] < simulation.duration:
        raise t.context.error(("simulation", "duration"),
                              f"a duration <= the end of the motion table {file_name} "
                              f"({time[-1]:g} s) [s]", f"{simulation.duration!r}")
    return BodyTableMotion(reference_point=reference, file=str(path), time=time,
                           displacement=values,
                           ramp_duration=declared["ramp_duration"].read(t, "ramp_duration"))
