"""Checks of a whole case across its tables: the mooring system, the lines, the motion.

Each table of a case is read and checked on its own by :mod:`floatmoor.case.load`; these
checks need the assembled :class:`~floatmoor.case.schema.Case`: a system no model can solve
(points no line uses, free points held by nothing, a free point joining lines of different
models), line ends below the seabed or too far apart for any material, and a prescribed
motion that takes a fairlead or body point below the seabed or out of reach. Each failure is
one :class:`~floatmoor.errors.CaseError` naming the key that causes it.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from floatmoor.case.reader import ReadContext
from floatmoor.case.schema import Case, CircularMotion, HarmonicMotion, Point, Section
from floatmoor.disjoint_sets import DisjointSets
from floatmoor.motion.fairlead import horizontal_direction
from floatmoor.motion.rigid_body import (body_points_state, is_body_motion,
                                         prescribed_fairlead_state)

__all__ = ["check_system", "check_lines", "check_motion", "MAX_STATIC_STRAIN",
           "SEABED_TOLERANCE", "COINCIDENT_ENDS"]

#: A line whose anchor-to-fairlead distance needs more than this strain is "too short".
#: Chain breaks near 1 % strain, polyester near 15 %, nylon near 25-30 %: no mooring material
#: survives 30 %, so a larger required strain means the geometry in the case is wrong.
MAX_STATIC_STRAIN = 0.30
#: How far below the seabed an end may be and still count as on it [m]: TOML decimal input
#: such as -3.0 against a depth of 3.0 is exact, so this only absorbs round-off of sums.
SEABED_TOLERANCE = 1e-9
#: Anchor and fairlead closer than this fraction of the line length count as one point [-]:
#: the line has no direction, so no model (nor a circular motion's plane) is defined. 1e-9
#: is round-off of sums of coordinates, far below any real mooring geometry.
COINCIDENT_ENDS = 1e-9
#: Line models whose static catenary needs a line that sinks.
_CATENARY_MODELS = ("quasi-static", "quasi-dynamic")
#: Sampling of the prescribed motion when checking the fairlead stays reachable [-].
_MOTION_CHECK_SAMPLES_PER_PERIOD = 72


def check_system(case: Case, context: ReadContext, paths: dict[str, dict[str, Any]],
                  user_points: list[Point]) -> None:
    """Refuse a mooring system no model can solve: a line or section from a point to itself,
    a point no line uses, a group of free points held by no fixed or body point, a free point
    joining lines of different models, a quasi-dynamic line that is not one section from a
    fixed to a body point, a dynamic line solved in a system (sections, free points) with the
    stick-spring friction (the system kernels have the Coulomb law only)."""
    kinds = {p.name: p.kind for p in case.points}
    user_index = {p.name: i for i, p in enumerate(user_points)}
    used: dict[str, list[Section]] = {p.name: [] for p in case.points}
    for i, line in enumerate(case.lines):
        for section, path in zip(line.sections, paths[line.name]["ends"][1:]):
            if section.start == section.end:
                raise context.error(path, f"a point other than the section's start "
                                    f'"{section.start}"', f'"{section.end}", the same point')
            used[section.start].append(section)
            used[section.end].append(section)
        if line.model == "quasi-dynamic" and (
                len(line.sections) != 1 or kinds[line.start] != "fixed"
                or kinds[line.end] != "body"):
            raise context.error(("lines", i, "model"), "a model for this line: the "
                                "quasi-dynamic model solves one section from a fixed point to a"
                                ' body point; use "dynamic" or "quasi-static" for a line with '
                                "sections or free points",
                                f'"quasi-dynamic" on a line of {len(line.sections)} section(s) '
                                f"from a {kinds[line.start]} point to a {kinds[line.end]} point")
        if (line.model == "dynamic" and case.seabed.friction_model == "stick_spring"
                and (len(line.sections) != 1 or kinds[line.start] != "fixed"
                     or kinds[line.end] != "body")):
            raise context.error(("seabed", "friction_model"), '"coulomb" for a case whose '
                                "dynamic lines have sections or free points (the DG system "
                                'has the Coulomb law only)', f'"stick_spring" with line '
                                f'"{line.name}" of {len(line.sections)} section(s) from a '
                                f"{kinds[line.start]} point to a {kinds[line.end]} point")
    for name, sections in used.items():
        if sections or name not in user_index:
            continue
        raise context.error(("points", user_index[name], "name"), "a point that a line starts "
                            "or ends at (or a section's end)", f'"{name}", which no line uses')
    # free points: one model per point; every group of free points held by a fixed or body one
    line_of = {line.name: line for line in case.lines}
    for name, sections in used.items():
        if kinds[name] != "free":
            continue
        models = {line_of[s.line].model for s in sections}
        if len(models) > 1:
            where = ("points", user_index[name], "name") if name in user_index else \
                ("lines", case.lines.index(line_of[sections[0].line]), "model")
            raise context.error(where, "a free point joining lines of one model (they are "
                                "solved together)", f'"{name}" joining '
                                + ", ".join(sorted(f"{s.line} ({line_of[s.line].model})"
                                                   for s in sections)))
    groups = DisjointSets(kinds)
    root = groups.find
    for section in case.sections:
        if kinds[section.start] == "free" and kinds[section.end] == "free":
            groups.union(section.start, section.end)
    held = {root(s.start) for s in case.sections if kinds[s.end] != "free"} | \
        {root(s.end) for s in case.sections if kinds[s.start] != "free"}
    for name, kind in kinds.items():
        if kind == "free" and root(name) not in held:
            members = sorted(n for n in kinds if kinds[n] == "free" and root(n) == root(name))
            lines = sorted({s.line for s in case.sections
                            if s.start in members or s.end in members})
            raise context.error(("lines", case.lines.index(line_of[lines[0]]), "name"),
                                "lines held by at least one fixed or body point",
                                "free points " + ", ".join(f'"{m}"' for m in members)
                                + " held by nothing (lines " + ", ".join(lines) + ")")


def _end_path(case: Case, i: int, which: str) -> tuple:
    """The key path of a line end's position: the short-form ``anchor`` / ``fairlead``, or
    the named point's ``position``."""
    line = case.lines[i]
    name = line.start if which == "anchor" else line.end
    if name == f"{line.name}.{which}":
        return ("lines", i, which)
    names = [p.name for p in case.points]
    return ("points", names.index(name), "position")


def check_lines(case: Case, context: ReadContext, paths: dict[str, dict[str, Any]]) -> None:
    seabed_z = case.environment.seabed_z
    kinds = {p.name: p.kind for p in case.points}
    for i, line in enumerate(case.lines):
        for end in ("anchor", "fairlead"):
            z = getattr(line, end)[2]
            if z < seabed_z - SEABED_TOLERANCE:
                raise context.error(_end_path(case, i, end), f"a point on or above the seabed "
                                    f"(z >= {seabed_z:g} m)", f"z = {z!r} m")
        for section in line.sections:
            lt = section.line_type
            if line.model in _CATENARY_MODELS and \
                    lt.material_density <= case.environment.water_density:
                raise context.error(("line_types", lt.name, "material_density"),
                                    f"a density > water_density "
                                    f"({case.environment.water_density:g} kg/m^3): the "
                                    f"{line.model} catenary of line '{line.name}' needs a line "
                                    "that sinks", f"{lt.material_density!r}")
        if "free" in (kinds[line.start], kinds[line.end]):
            continue  # where a free end goes is the statics' answer
        if line.span <= COINCIDENT_ENDS * line.length:  # every model needs a direction
            end, other = ("anchor", "fairlead") \
                if context.origin(_end_path(case, i, "anchor")) != context.source \
                else ("fairlead", "anchor")
            raise context.error(_end_path(case, i, end), f"a point apart from the {other} "
                                f"{list(getattr(line, other))} m",
                                f"{list(getattr(line, end))} m, the same point")
        needed = line.span / line.length - 1.0
        if needed > MAX_STATIC_STRAIN:
            raise context.error(paths[line.name]["length"],
                                f"a length that reaches the fairlead {line.span:.6g} m away "
                                f"without more than {MAX_STATIC_STRAIN:.0%} strain [m]",
                                f"{line.length!r} (needs {needed:.1%} strain)")


# extreme but valid inputs (motion.radius = 1e308) overflow while the path is sampled: the
# checks below refuse the non-finite path with one line, so NumPy's warnings are not printed
@np.errstate(over="ignore", invalid="ignore")
def check_motion(case: Case, context: ReadContext) -> None:
    motion = case.motion
    if motion is None:
        return
    kinds = {p.name: p.kind for p in case.points}
    # the motion moves body points; a line from a fixed to a body point must follow it (lines
    # with free points: the system's statics and dynamics answer where they go)
    moved = [line for line in case.lines
             if kinds[line.start] == "fixed" and kinds[line.end] == "body"]
    for line in moved:
        if isinstance(motion, CircularMotion) and horizontal_direction(line) is None:
            raise context.error(("motion", "kind"), "a motion other than circular: line "
                                f"'{line.name}' is vertical, so it has no vertical plane",
                                '"circular"')
    # The moving fairlead must stay above the seabed and within reach of every line.
    period = motion.cycle_period or case.simulation.output_interval * 10
    n = int(min(200_000, max(1000, case.simulation.duration / period
                             * _MOTION_CHECK_SAMPLES_PER_PERIOD)))
    t = np.linspace(0.0, case.simulation.duration, n)
    # a harmonic body motion: no one key moves the point, so the error names [motion]
    key = ("motion",) + (("radius",) if isinstance(motion, CircularMotion) else
                         ("amplitude",) if isinstance(motion, HarmonicMotion) else
                         ("file",) if hasattr(motion, "file") else ())
    for line in moved:
        path = prescribed_fairlead_state(motion, line, t)[0]
        lowest = float(path[:, 2].min())
        if not lowest >= case.environment.seabed_z - SEABED_TOLERANCE:  # NaN fails too
            raise context.error(key, f"a motion that keeps the fairlead of line '{line.name}' "
                                f"above the seabed (z >= {case.environment.seabed_z:g} m)",
                                f"a fairlead reaching z = {lowest:.6g} m")
        span = float(np.linalg.norm(path - np.asarray(line.anchor), axis=1).max())
        needed = span / line.length - 1.0
        if not needed <= MAX_STATIC_STRAIN:
            raise context.error(key, f"a motion that keeps the fairlead of line '{line.name}' "
                                f"within reach (at most {MAX_STATIC_STRAIN:.0%} strain)",
                                f"a fairlead {span:.6g} m from its anchor ({needed:.1%} strain)")
    if is_body_motion(motion):  # every body point, also those of lines with free points
        body = [p for p in case.points if p.kind == "body"]
        if body:
            positions = body_points_state(motion, np.array([p.position for p in body]), t)[0]
            lowest = positions[:, :, 2].min(axis=0)
            k = int(np.argmin(lowest))
            if not lowest[k] >= case.environment.seabed_z - SEABED_TOLERANCE:
                raise context.error(key, f"a motion that keeps body point '{body[k].name}' "
                                    f"above the seabed (z >= {case.environment.seabed_z:g} m)",
                                    f"the point reaching z = {lowest[k]:.6g} m")
