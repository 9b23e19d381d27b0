"""Load a TOML case file into a validated :class:`~floatmoor.case.schema.Case`.

Loading is strict. Unknown keys, missing keys, wrong types, non-finite numbers and unphysical
values each raise one :class:`~floatmoor.errors.CaseError` that names the file, the key path,
what was expected and what was found. Values that are valid but implausible by orders of
magnitude (a unit typed wrong) warn (:mod:`floatmoor.case.plausibility`). ``--set``
overrides are applied to the parsed table first and validated like the file's own values.
"""

from __future__ import annotations

import copy
import math
from dataclasses import replace
from pathlib import Path as FilePath
from typing import Any, Sequence

import numpy as np

from floatmoor.case.campaign import read_campaign
from floatmoor.case.coupling import read_initial, read_waves, read_wind
from floatmoor.case.floater import BEM_BUILD_KEYS, check_panel_size, read_floater, read_hydro
from floatmoor.case.limits import (
    MAX_NESTING_DEPTH, check_sizes, nesting_depth, parse_toml,
)
from floatmoor.case.files import read_input_text
from floatmoor.case.motion_body import read_body_motion
from floatmoor.case.motion_table import read_motion_table
from floatmoor.case.overrides import apply_overrides
from floatmoor.case.plausibility import warn_implausible
from floatmoor.case.reader import ReadContext, TableReader
from floatmoor.case.setting import read_settings, settings_of
from floatmoor.case.schema import (
    AVAILABLE_LINE_MODELS, MAX_QD_INTEGRATION_POINTS, MOTION_KIND,
    Case, CircularMotion, DynamicSettings, Environment, HarmonicMotion, Line, LineType, Motion,
    OneSectionKeys, Point, QuasiDynamicSettings, QuasiStaticSettings, Seabed, Section,
    SectionKeys, Simulation, TableMotion, TopLevelKeys,
)
from floatmoor.case.system_checks import (
    MAX_STATIC_STRAIN, SEABED_TOLERANCE, check_lines, check_motion, check_system,
)
from floatmoor.case.title import render_title
from floatmoor.errors import CaseError
from floatmoor.motion.frequency import fairlead_motion_frequency

__all__ = ["load_case", "parse_case", "MAX_STATIC_STRAIN", "SEABED_TOLERANCE"]

#: Order of a DG line whose elements are given but not its order (and of imported decks):
#: MooDy reproduced the Lindahl chain with order 5 (chain-experiment paper; docs/cases/lindahl.md).
#: Without either key, both follow from ``accuracy`` (mooring/dg/resolution.py).
DEFAULT_DG_ORDER = 5


def load_case(path: str | FilePath, overrides: Sequence[str] = ()) -> Case:
    """Read, override and validate a case file.

    Parameters
    ----------
    path
        The TOML case file.
    overrides
        ``path.to.key=VALUE`` assignments, VALUE a TOML value (see
        :mod:`floatmoor.case.overrides`).

    Raises
    ------
    CaseError
        For any problem with the file or the overrides.
    """
    source = str(path)
    text = read_input_text(path, "case")
    raw = parse_toml(text, source)
    return parse_case(raw, source=source, text=text, overrides=tuple(overrides),
                      base_dir=FilePath(path).parent)


def parse_case(raw: dict[str, Any], *, source: str, text: str = "",
               overrides: tuple[str, ...] = (), base_dir: FilePath | None = None) -> Case:
    """Validate a parsed case table (``raw`` is not modified).

    What :func:`load_case` does once it has read and parsed the file, for a caller that
    holds the table already (a campaign bundle, a scaled or an imported case): apply the overrides to a
    copy, read every key strictly, check the system as a whole, and warn about valid but
    implausible values.

    Parameters
    ----------
    raw
        The case's table as parsed from TOML.
    source
        The case file's path (or a name standing for it), named in errors and recorded as
        :attr:`Case.source`.
    text
        The case file's text, recorded as :attr:`Case.text` (a run's output keeps it).
    overrides
        ``path.to.key=VALUE`` assignments applied before validation
        (:func:`floatmoor.case.overrides.apply_overrides`).
    base_dir
        Folder that relative file paths of the case (a motion table, a hull mesh) are read
        from: the case file's folder; None for the current folder.

    Returns
    -------
    Case
        The validated case, SI units and radians.

    Raises
    ------
    CaseError
        For the first problem found, naming the source (and the ``--set`` that gave the
        value), the key path, what was expected and what was found.

    Warns
    -----
    ImplausibleInputWarning
        Once for each valid but implausible value (:mod:`floatmoor.case.plausibility`).
    """
    original, raw = raw, copy.deepcopy(raw)
    applied = apply_overrides(raw, overrides, source)
    if nesting_depth(raw) > MAX_NESTING_DEPTH:
        raise CaseError(source, "", f"tables and arrays nested at most {MAX_NESTING_DEPTH} "
                        "deep", "deeper nesting (after the --set overrides)")
    context = ReadContext(source, {path: text for text, paths in applied for path in paths})
    root = TableReader(raw, (), context)
    top = settings_of(TopLevelKeys)
    title_template = top["title"].read(root, "title")
    description = top["description"].read(root, "description")

    environment = _environment(root.table("environment"))
    seabed = _seabed(root.table("seabed"))
    has_floater = root.has("floater")
    line_types = {name: _line_type(name, reader) for name, reader in root.named_tables("line_types")} \
        if root.has("line_types") or not has_floater else {}
    user_points = _points(root, environment) \
        if root.has("points") else []
    implicit: list[Point] = []
    # A floater case may have no lines (a free-floating body); other cases need lines.
    parsed = [_line(reader, line_types, implicit) for reader in root.tables("lines")] \
        if root.has("lines") or not has_floater else []
    lines, points = _resolve_points(parsed, user_points, implicit, context)
    simulation = _simulation(root.table("simulation"))
    if simulation.time_step is not None and not has_floater:
        raise root.error(("simulation", "time_step"), "no body time step in a case without a "
                         "[floater] (its lines take their own steps)", simulation.time_step)
    if has_floater and root.has("motion"):
        raise root.error("motion", "no [motion] table in a case with a [floater] (the "
                         "floater's motion follows from its dynamics)", {})
    motion = _motion(root.table("motion"), base_dir or FilePath("."), simulation) \
        if root.has("motion") else None
    campaign = read_campaign(root) if root.has("campaign") else None
    hydro_raw = raw.get("hydro")
    imported = isinstance(hydro_raw, dict) and hydro_raw.get("source") == "imported"
    if has_floater and isinstance(hydro_raw, dict) and "source" not in hydro_raw \
            and not any(key in hydro_raw for key in BEM_BUILD_KEYS):
        read_hydro(root.table("hydro"))  # refuses it: says source = "imported" is missing,
        # before a floater without geometry is refused for want of a hull
    floater = read_floater(root.table("floater"), environment, base_dir,
                           imported=imported) if has_floater else None
    if root.has("hydro") and not has_floater:
        raise root.error("hydro", "a [floater] table for the [hydro] settings to apply to",
                         {})
    hydro = read_hydro(root.table("hydro")) if root.has("hydro") else None
    if hydro is not None and floater is not None:
        def missing(key: str, expected: str, found) -> None:
            raise context.error(("hydro", key), expected, found)

        check_panel_size(floater, hydro, missing)
    for key in ("waves", "initial", "wind"):
        if root.has(key) and not has_floater:
            raise root.error(key, f"a [floater] table for [{key}] to apply to", {})
    waves = read_waves(root.table("waves"), environment, simulation.duration) \
        if root.has("waves") else None
    initial = read_initial(root.table("initial")) if root.has("initial") else (0.0,) * 6
    wind = read_wind(root.table("wind"), simulation.duration) if root.has("wind") else None
    root.finish()
    lines = _with_motion_frequency(lines, fairlead_motion_frequency(motion, waves))
    title = render_title(title_template, original, raw, applied, context.origin(("title",)))

    case = Case(title=title, title_template=title_template, source=source, text=text, overrides=overrides,
                environment=environment, seabed=seabed, line_types=line_types, lines=lines,
                motion=motion, simulation=simulation, description=description,
                campaign=campaign, floater=floater, hydro=hydro, waves=waves,
                initial_offset=initial, wind=wind, points=points)
    check_sizes(case, context)
    check_system(case, context, {line.name: paths for line, paths in parsed}, user_points)
    check_lines(case, context, {line.name: paths for line, paths in parsed})
    check_motion(case, context)
    warn_implausible(case, context)  # after every error: a refused case does not warn
    return case


# -- tables -----------------------------------------------------------------------------------

def _environment(t: TableReader) -> Environment:
    env = Environment(**read_settings(Environment, t))
    t.finish()
    return env


def _seabed(t: TableReader) -> Seabed:
    seabed = Seabed(**read_settings(Seabed, t))
    t.finish()
    return seabed


def _line_type(name: str, t: TableReader) -> LineType:
    line_type = LineType(name=name, **read_settings(LineType, t))
    t.finish()
    return line_type


#: The keys of a free point's loads (clump weight, buoy), which the other kinds refuse.
_POINT_LOADS = ("mass", "volume", "drag_area", "added_mass_coefficient")


def _points(root: TableReader, environment: Environment) -> list[Point]:
    """``[[points]]``: named fixed, free and body points."""
    points: list[Point] = []
    declared = settings_of(Point)
    for t in root.tables("points"):
        name = declared["name"].read(t, "name")
        if "." in name:  # implicit points are "LINE.anchor", ...; --set addresses by name
            raise t.error("name", "a name without '.'", name)
        kind = declared["kind"].read(t, "kind")
        position = declared["position"].read(t, "position")
        for key in _POINT_LOADS:
            if t.has(key) and kind != "free":
                raise t.error(key, f"no {key} on a {kind} point (only free points carry "
                              "clump weights and buoys"
                              + ("; a body's mass is the [floater]'s)" if kind == "body"
                                 else ")"), t.data[key])
        loads = read_settings(Point, t, skip=("name", "kind", "position"))
        t.finish()
        if position[2] < environment.seabed_z - SEABED_TOLERANCE:
            raise t.error("position", f"a point on or above the seabed (z >= "
                          f"{environment.seabed_z:g} m)", f"z = {position[2]!r} m")
        points.append(Point(name=name, kind=kind, position=position, **loads))
    return points


def _dynamic_settings(dg: TableReader, defaults: DynamicSettings | None) -> DynamicSettings:
    """``[lines.dynamic]`` (defaults: the declared ones), or a section's ``dynamic`` table
    (defaults: its line's)."""
    inherited = None if defaults is None else {
        key: getattr(defaults, key) for key in settings_of(DynamicSettings)}
    settings = DynamicSettings(**read_settings(DynamicSettings, dg, inherited))
    dg.finish()
    return settings


def _with_motion_frequency(lines: list[Line], omega: float) -> list[Line]:
    """The lines with the fairlead motion's frequency in their (and their sections') dynamic
    settings: what the choice of their numerics resolves."""
    def tag(st: DynamicSettings) -> DynamicSettings:
        return replace(st, motion_frequency=omega)

    return [replace(ln, dynamic=tag(ln.dynamic), sections=tuple(
        replace(s, dynamic=tag(s.dynamic)) for s in ln.sections)) for ln in lines]


def _line_type_named(t: TableReader, keys: type, line_types: dict[str, LineType]) -> LineType:
    """The line type the ``type`` key of ``t`` names (declared on ``keys``)."""
    key = "type"
    type_name = settings_of(keys)[key].read(t, key)
    if type_name not in line_types:
        raise t.error(key, "the name of a [line_types.NAME] table ("
                      + ", ".join(f'"{n}"' for n in line_types) + ")", type_name)
    return line_types[type_name]


def _end(t: TableReader, point_key: str, short_key: str, kind: str, name: str,
         implicit: list[Point]) -> str:
    """The point a line end names (``start`` / ``end``), or the implicit ``kind`` point of
    its short form (``anchor`` / ``fairlead`` = [x, y, z])."""
    if t.has(point_key) and t.has(short_key):
        raise t.error(short_key, f"either {point_key} (a point's name) or {short_key} "
                      "(a position), not both", t.data[short_key])
    declared = settings_of(Line)
    if t.has(point_key):
        return declared[point_key].read(t, point_key)
    position = declared[short_key].read(t, short_key)
    implicit.append(Point(name=f"{name}.{short_key}", kind=kind, position=position))
    return implicit[-1].name


def _line(t: TableReader, line_types: dict[str, LineType],
          implicit: list[Point]) -> tuple[Line, dict[str, Any]]:
    """A ``[[lines]]`` entry; also the key paths of its point names (``ends``, start to end)
    and of its last section's ``length`` (for errors)."""
    name = settings_of(Line)["name"].read(t, "name")
    start = _end(t, "start", "anchor", "fixed", name, implicit)
    model = settings_of(Line)["model"].read(t, "model")
    if model not in AVAILABLE_LINE_MODELS:
        raise t.error("model", "one of " + ", ".join(f'"{m}"' for m in AVAILABLE_LINE_MODELS)
                      + f' (the "{model}" model is not available in this version)', model)
    qs = t.table("quasi_static", required=False)
    settings = QuasiStaticSettings(**read_settings(QuasiStaticSettings, qs))
    qs.finish()
    dynamic = _dynamic_settings(t.table("dynamic", required=False), None)
    qd = t.table("quasi_dynamic", required=False)
    quasi_dynamic = QuasiDynamicSettings(**read_settings(QuasiDynamicSettings, qd))
    if quasi_dynamic.integration_points % 2 == 0:
        raise qd.error("integration_points", f"an odd integer >= 3 and <= "
                       f"{MAX_QD_INTEGRATION_POINTS} (the composite Simpson rule needs an even "
                       "number of intervals)", quasi_dynamic.integration_points)
    qd.finish()
    # sections: the short form (type, length) or the array; (type, length, end, path)
    if t.has("sections"):
        for key in ("type", "length"):
            if t.has(key):
                raise t.error(key, "either sections or type and length, not both",
                              t.data[key])
        raw_sections = []
        entries = list(t.tables("sections"))
        declared = settings_of(SectionKeys)
        for i, st in enumerate(entries):
            line_type = _line_type_named(st, SectionKeys, line_types)
            length = declared["length"].read(st, "length")
            joint = None
            if st.has("end"):
                if i == len(entries) - 1:
                    raise st.error("end", "no end on the last section (the line's end point "
                                   "is its end)", st.data["end"])
                joint = declared["end"].read(st, "end")
            section_dynamic = _dynamic_settings(st.table("dynamic", required=False), dynamic)
            st.finish()
            raw_sections.append((line_type, length, joint, section_dynamic, st.path))
    else:
        raw_sections = [(_line_type_named(t, OneSectionKeys, line_types),
                         settings_of(OneSectionKeys)["length"].read(t, "length"), None,
                         dynamic, t.path)]
    end = _end(t, "end", "fairlead", "body", name, implicit)
    t.finish()
    # unnamed joints between sections: implicit massless free points (placed by
    # _resolve_points on the chord, at their fraction of the line's length)
    joints = []
    for i, (_, _, joint, _, _) in enumerate(raw_sections[:-1]):
        if joint is None:
            joint = f"{name}.joint{i + 1}"
            implicit.append(Point(name=joint, kind="free", position=(math.nan,) * 3))
        joints.append(joint)
    names = [start] + joints + [end]
    sections = tuple(Section(line=name, index=i, line_type=lt, length=length,
                             start=names[i], end=names[i + 1], dynamic=dg)
                     for i, (lt, length, _, dg, _) in enumerate(raw_sections))
    paths = {"ends": [t.path + (("start",) if t.has("start") else ("anchor",))]
             + [s[4] + ("end",) for s in raw_sections[:-1]]
             + [t.path + (("end",) if t.has("end") else ("fairlead",))],
             "length": raw_sections[-1][4] + ("length",)}
    line = Line(name=name, sections=sections, anchor=(math.nan,) * 3,
                fairlead=(math.nan,) * 3, model=model, quasi_static=settings,
                dynamic=dynamic, quasi_dynamic=quasi_dynamic, start=start, end=end)
    return line, paths


#: How far a ratio of intervals may be from a whole number and still be one [-]: interval
#: values typed in decimal (0.05 against 0.2) are not exact binary fractions, and a step or
#: shape interval off by more than this relative part is a typing mistake.
INTERVAL_RATIO_TOLERANCE = 1e-6


def _simulation(t: TableReader) -> Simulation:
    """``[simulation]``: the declared keys, then the checks between them."""
    simulation = Simulation(**read_settings(Simulation, t))
    duration, interval = simulation.duration, simulation.output_interval
    if interval > duration:
        raise t.error("output_interval", f"a number <= simulation.duration ({duration:g} s) [s]",
                      interval)
    time_step = simulation.time_step
    if time_step is not None and not _divides(time_step, interval):
        raise t.error("time_step", "a number dividing simulation.output_interval "
                      f"({interval:g} s) [s]", time_step)
    shape = simulation.shape_output_interval
    if shape is not None and not _divides(interval, shape):
        raise t.error("shape_output_interval", "a multiple of simulation.output_interval "
                      f"({interval:g} s) [s]", shape)
    t.finish()
    return simulation


def _divides(step: float, interval: float) -> bool:
    """Whether ``interval`` is a whole multiple of ``step`` (within
    :data:`INTERVAL_RATIO_TOLERANCE`); False for a ratio beyond a float (1e308 / 0.05)."""
    ratio = interval / step
    return step <= interval and math.isfinite(ratio) and \
        abs(ratio - round(ratio)) <= INTERVAL_RATIO_TOLERANCE * ratio


def _motion(t: TableReader, base_dir: FilePath, simulation: Simulation) -> Motion:
    kind = MOTION_KIND.read(t, "kind")
    motion: Motion
    if kind == "body":
        motion = read_body_motion(t, base_dir, simulation)
    elif kind == "circular":
        declared = settings_of(CircularMotion)
        period = declared["period"].read(t, "period")
        motion = CircularMotion(period=period, **read_settings(
            CircularMotion, t, {"ramp_duration": period}, skip=("period",)))
    elif kind == "harmonic":
        declared = settings_of(HarmonicMotion)
        amplitude = declared["amplitude"].read(t, "amplitude")
        if not any(amplitude):
            raise t.error("amplitude", "at least one non-zero amplitude [m]", list(amplitude))
        period = declared["period"].read(t, "period")
        phase = declared["phase_deg"].read(t, "phase_deg")
        longest = max(p for a, p in zip(amplitude, period) if a > 0.0)
        motion = HarmonicMotion(amplitude=amplitude, period=period, phase=phase,
                                ramp_duration=declared["ramp_duration"].read(
                                    t, "ramp_duration", longest))
    else:
        declared = settings_of(TableMotion)
        file_name = declared["file"].read(t, "file")
        path, time, disp = read_motion_table(t, base_dir, file_name)
        motion = TableMotion(file=str(path), time=time, displacement=disp,
                             ramp_duration=declared["ramp_duration"].read(t, "ramp_duration"))
        if time[-1] < simulation.duration:
            raise t.context.error(("simulation", "duration"),
                                  f"a duration <= the end of the motion table {file_name} "
                                  f"({time[-1]:g} s) [s]", f"{simulation.duration!r}")
    if motion.ramp_duration >= simulation.duration:
        raise t.error("ramp_duration", "a ramp shorter than simulation.duration "
                      f"({simulation.duration:g} s) [s]", motion.ramp_duration)
    t.finish()
    return motion


def _resolve_points(parsed: list[tuple[Line, dict[str, Any]]], user_points: list[Point],
                    implicit: list[Point], context: ReadContext
                    ) -> tuple[tuple[Line, ...], tuple[Point, ...]]:
    """Check the point names the lines give, place the implicit joints (on the chord between
    their line's end points, at their fraction of its length) and give each line its end
    positions. Returns the lines and every point (the ``[[points]]``, then the implicit ones)."""
    known: dict[str, Point] = {}
    for i, p in enumerate(user_points):
        if p.name in known:
            raise context.error(("points", i, "name"), "a name no other point has",
                                f'"{p.name}" again')
        known[p.name] = p
    seen: set[str] = set()
    for i, (line, _) in enumerate(parsed):
        if line.name in seen:  # implicit point names would clash too
            raise context.error(("lines", i, "name"), "a name no other line has",
                                f'"{line.name}" again')
        seen.add(line.name)
    known.update((p.name, p) for p in implicit)
    names = ", ".join(f'"{p.name}"' for p in user_points) or "none: no [[points]] table"
    for line, paths in parsed:
        chain = [line.start] + [s.end for s in line.sections]
        for name, path in zip(chain, paths["ends"]):
            if name not in known:
                raise context.error(path, f"the name of a [[points]] entry ({names})",
                                    f'"{name}"')
    placed: dict[str, Point] = {}
    lines = []
    for line, _ in parsed:
        a = np.asarray(known[line.start].position)
        b = np.asarray(known[line.end].position)
        along = 0.0
        for section in line.sections[:-1]:
            along += section.length
            joint = known[section.end]
            if math.isnan(joint.position[0]):
                xyz = a + (b - a) * (along / line.length)
                placed[joint.name] = replace(joint, position=tuple(float(c) for c in xyz))
        lines.append(replace(line, anchor=known[line.start].position,
                             fairlead=known[line.end].position))
    points = tuple(user_points) + tuple(placed.get(p.name, p) for p in implicit)
    return tuple(lines), points
