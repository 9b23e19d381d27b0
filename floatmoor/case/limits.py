"""Bounds on the sizes a case file controls, checked when the case is loaded.

A case sets how many samples, time steps, frequencies and wave or wind components a run
allocates and loops over. Each bound below is far above what any realistic case needs (the
shipped cases' figures are given with each) and far below what exhausts memory or runs for
days, so a value beyond it is a typing error (``1e6`` for ``1e3``, a missing minus sign in an
exponent), reported at load with exit status 2 instead of a run that swaps, hangs or
overflows. The nesting bound keeps TOML's recursive parser and the loader's copies off
Python's recursion limit.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

from floatmoor.case.schema import MAX_GRAVITY, MIN_GRAVITY
from floatmoor.case.sea import JonswapSettings
from floatmoor.errors import CaseError

if TYPE_CHECKING:
    from floatmoor.case.reader import ReadContext
    from floatmoor.case.schema import Case, DynamicSettings

__all__ = ["MAX_NESTING_DEPTH", "MAX_OUTPUT_SAMPLES", "MAX_TIME_STEPS", "MAX_WAVE_COMPONENTS",
           "MAX_WIND_COMPONENTS", "MAX_AXIAL_WAVE_SPEED", "MAX_MOTION_TABLE_BYTES",
           "MAX_CASE_FILE_BYTES", "MAX_BEM_PANELS", "MAX_SHAPE_POINTS", "MAX_MESH_FILE_BYTES",
           "MIN_GRAVITY", "MAX_GRAVITY",
           "nesting_depth", "parse_toml", "check_sizes"]

#: Deepest nesting of tables and arrays in a case (or a ``--set`` value). Case files nest at
#: most 4 levels (``[lines.dynamic]``, ``frequency_ranges = [[...]]``); 32 leaves room for
#: any future schema, and stays far below Python's recursion limit (1000), which the TOML
#: parser and deep copies would otherwise hit with a traceback.
MAX_NESTING_DEPTH = 32
#: Most output samples per recorded series, duration / output_interval + 1. The shipped
#: cases record at most 21 601 samples (3 h every 0.5 s); 10 million samples of one float are
#: 80 MB per channel, so a run with a few lines stays within a workstation's memory.
MAX_OUTPUT_SAMPLES = 10_000_000
#: Most line-shape values, shape samples x shape nodes summed over the lines (each a position
#: and a tension, 32 bytes): 25 million are 800 MB. No shipped case records shapes; a 3 h
#: record every second of ten 100-node lines is 11 million.
MAX_SHAPE_POINTS = 25_000_000
#: Shape nodes of a quasi-static or quasi-dynamic line (floatmoor.mooring.quasistatic.
#: SHAPE_POINTS, floatmoor.mooring.quasidynamic.SHAPE_NODES); a dynamic line records its
#: elements x (order + 1) nodes.
_OTHER_SHAPE_NODES = 51
#: Nodes of a dynamic section whose numerics follow from its accuracy, at most
#: (floatmoor.mooring.dg.resolution: MAX_AUTO_ELEMENTS x (AUTO_ORDER + 1); a test checks it).
AUTO_MAX_ELEMENTS, AUTO_ORDER = 32, 3
#: Most time steps a run may ask for through a prescribed step (duration / time_step,
#: duration / max_time_step). At a microsecond per step (the cheapest line model) 1e9 steps
#: take a quarter of an hour; the shipped cases prescribe at most 108 000 (3 h at 0.1 s).
#: Smaller steps also stop advancing time in double precision (t + dt == t), which the
#: solvers would misreport (a 1e-300 s step read as "a node moves faster than the wave").
MAX_TIME_STEPS = 1_000_000_000
#: Most components of an irregular sea (JONSWAP: (omega_max - omega_min) / frequency_step,
#: or n_components). The shipped 3 h DeepCwind seas use ~2750 (d omega = 2 pi / duration);
#: every component is evaluated at every body time step, so 1e5 is already a slow run.
MAX_WAVE_COMPONENTS = 100_000
#: Most components of a turbulent wind (cutoff_hz * duration bins of width 1 / duration).
#: The shipped LC43 uses 0.5 Hz over 3 h (5400); same reasoning as the wave bound.
MAX_WIND_COMPONENTS = 100_000
#: Fastest axial wave a dynamic line may carry, sqrt(EA / m) [m/s]. The dynamic model's time
#: step is proportional to 1 / wave speed; no material carries sound faster than ~18 km/s
#: (diamond; steel ~5.9 km/s, the shipped chains ~2 km/s), so 1e5 m/s admits idealised stiff
#: test lines while EA = 1e308 (a zero time step) is refused.
MAX_AXIAL_WAVE_SPEED = 1.0e5
#: Largest motion table file [bytes]. A table sampled at 1 kHz for 3 h is ~10 MB of CSV; 100 MB
#: is far beyond any experiment's record, and keeps /dev/zero-like files from filling memory.
MAX_MOTION_TABLE_BYTES = 100 * 1024 * 1024
#: Most hull panels of a BEM mesh, estimated at load as the wetted area / panel_size^2 (the
#: mesher's count is up to 3 times that: 1633 estimated for DeepCwind's 4380, 2163 for the
#: buoy's 3240). The solver's dense influence matrices take about 32 N^2 bytes, 13 GB at
#: this bound, so a finer panel_size is a typing error rather than a plan.
MAX_BEM_PANELS = 20_000
#: Largest hull mesh file [bytes] (``[floater.geometry] kind = "mesh"``). A text mesh of
#: MAX_BEM_PANELS panels takes about 5 MB (GDF: 4 vertex lines of ~50 bytes a panel; ASCII
#: STL ~250 bytes a triangle); 100 MB leaves room for dry parts and other formats, and keeps
#: a mistaken file from being read into memory. The panel count itself is checked when the
#: file is read, at build time (floatmoor.hydro.mesh_file).
MAX_MESH_FILE_BYTES = 100 * 1024 * 1024
#: Largest case file [bytes]. The longest shipped case is ~12 kB; 10 MB keeps a mistaken
#: argument (a data file, /dev/zero) from being read into memory.
MAX_CASE_FILE_BYTES = 10 * 1024 * 1024


def nesting_depth(value: Any) -> int:
    """Deepest nesting of dicts and lists in ``value`` (a scalar is 0), without recursion."""
    deepest = 0
    stack = [(value, 0)]
    while stack:
        item, depth = stack.pop()
        if isinstance(item, dict):
            children = item.values()
        elif isinstance(item, list):
            children = item
        else:
            deepest = max(deepest, depth)
            continue
        deepest = max(deepest, depth + 1)
        if depth + 1 <= MAX_NESTING_DEPTH:
            stack.extend((child, depth + 1) for child in children)
    return deepest


def parse_toml(text: str, source: str, key: str = "") -> dict[str, Any]:
    """Parse TOML text, bounding its nesting depth.

    Raises
    ------
    CaseError
        For a syntax error, or nesting deeper than :data:`MAX_NESTING_DEPTH` (also when it is
        deep enough to exhaust the parser's recursion).
    """
    import tomllib

    expected = f"valid TOML nested at most {MAX_NESTING_DEPTH} tables or arrays deep"
    try:
        raw = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise CaseError(source, key, "valid TOML", f"a syntax error ({err})") from None
    except RecursionError:
        raise CaseError(source, key, expected, "deeper nesting than the parser can "
                        "follow") from None
    depth = nesting_depth(raw)
    if depth > MAX_NESTING_DEPTH:
        raise CaseError(source, key, expected, f"nesting more than {MAX_NESTING_DEPTH} "
                        "deep") from None
    return raw


def count_text(value: float) -> str:
    """A count for an error message: ``1.2e+12`` or ``inf`` rather than a 300-digit integer."""
    return f"{value:.3g}" if math.isfinite(value) else "an unbounded number"


def check_sizes(case: "Case", context: "ReadContext") -> None:
    """Refuse a case whose samples, time steps, components or axial wave speed exceed the
    bounds above; the error names the key that sets the size.

    Raises
    ------
    CaseError
    """
    sim = case.simulation
    samples = sim.duration / sim.output_interval + 1.0
    if not samples <= MAX_OUTPUT_SAMPLES:
        key = "duration" if context.origin(("simulation", "duration")) != context.source \
            else "output_interval"  # name the value the user changed on the command line
        raise context.error(("simulation", key), "at most "
                            f"{MAX_OUTPUT_SAMPLES:.3g} output samples (duration / output_interval"
                            f" + 1; floatmoor.case.limits.MAX_OUTPUT_SAMPLES) [s]",
                            f"duration {sim.duration!r} with output_interval "
                            f"{sim.output_interval!r} ({count_text(samples)} samples)")
    if sim.shape_output_interval is not None:
        nodes = sum(sum(dynamic_nodes_bound(s.dynamic) for s in line.sections)
                    if line.model == "dynamic" else _OTHER_SHAPE_NODES * len(line.sections)
                    for line in case.lines)
        points = (sim.duration / sim.shape_output_interval + 1.0) * nodes
        if not points <= MAX_SHAPE_POINTS:
            raise context.error(("simulation", "shape_output_interval"), "at most "
                                f"{MAX_SHAPE_POINTS:.3g} shape values (shape samples x nodes of "
                                "every line; floatmoor.case.limits.MAX_SHAPE_POINTS) [s]",
                                f"{sim.shape_output_interval!r} ({count_text(points)} values "
                                f"over {nodes} nodes)")
    steps = [(("simulation", "time_step"), sim.time_step)]
    for i, line in enumerate(case.lines):
        if line.model == "dynamic":
            steps.extend((("lines", i, "dynamic", "max_time_step"), s.dynamic.max_time_step)
                         for s in line.sections)
        elif line.model == "quasi-dynamic":
            steps.append((("lines", i, "quasi_dynamic", "max_time_step"),
                          line.quasi_dynamic.max_time_step))
    for path, step in steps:
        if step is not None and not sim.duration / step <= MAX_TIME_STEPS:
            raise context.error(path, f"a step giving at most {MAX_TIME_STEPS:.3g} steps over "
                                f"simulation.duration ({sim.duration:g} s; floatmoor.case.limits"
                                ".MAX_TIME_STEPS) [s]", f"{step!r} "
                                f"({count_text(sim.duration / step)} steps)")
    for line in case.lines:
        for lt in {s.line_type.name: s.line_type for s in line.sections}.values():
            speed = math.sqrt(lt.axial_stiffness / lt.mass_per_length) \
                if lt.axial_stiffness / lt.mass_per_length < math.inf else math.inf
            if line.model == "dynamic" and not speed <= MAX_AXIAL_WAVE_SPEED:
                key, unit = ("mass_per_length", "kg/m") if context.origin(
                    ("line_types", lt.name, "mass_per_length")) != context.source \
                    else ("axial_stiffness", "N")  # the one set on the command line, if either
                raise context.error(("line_types", lt.name, key),
                                    "an axial wave speed sqrt(EA / mass_per_length) of at most "
                                    f"{MAX_AXIAL_WAVE_SPEED:g} m/s for the dynamic model of line "
                                    f"'{line.name}' (its time step shrinks with the speed) [{unit}]",
                                    f"{getattr(lt, key)!r} ({count_text(speed)} m/s)")
    _check_components(case, context)
    _check_panels(case, context)


def wetted_area_estimate(geometry: Any) -> float:
    """Rough wetted area of a floater geometry [m^2] (sides and bottoms of the columns, the
    pontoons' surfaces), for the panel bound only; 0 for a mesh hull, whose panels are the
    file's (counted against :data:`MAX_BEM_PANELS` when it is read, at build time)."""
    if geometry.kind == "mesh":
        return 0.0
    if geometry.kind == "cylinder":
        d = geometry.diameter
        return math.pi * d * geometry.draft + math.pi * d * d / 4.0
    area = 0.0
    for c in geometry.columns:
        area += math.pi * c.diameter * max(min(c.z_top, 0.0) - c.z_bottom, 0.0)
        plate = max(c.diameter, c.heave_plate_diameter or 0.0)
        area += math.pi * plate * plate / 2.0  # (a product: 1e308^2 is inf, ** raises)
    for m in geometry.members:
        area += math.pi * m.diameter * math.dist(m.start, m.end)
    return area


def _check_panels(case: "Case", context: "ReadContext") -> None:
    if case.floater is None or case.hydro is None or case.hydro.panel_size is None:
        return  # no BEM build (an imported database)
    size = case.hydro.panel_size
    area = wetted_area_estimate(case.floater.geometry)
    if not math.isfinite(area):
        raise context.error(("floater", "geometry"), "dimensions giving a finite wetted area "
                            "[m]", "dimensions whose wetted area overflows double precision "
                            f"({area!r} m^2)")
    panels = area / size / size  # (size * size: 0)
    if not panels <= MAX_BEM_PANELS:
        raise context.error(("hydro", "panel_size"), f"a panel size giving at most "
                            f"{MAX_BEM_PANELS} hull panels (wetted area / panel_size^2; "
                            "floatmoor.case.limits.MAX_BEM_PANELS) [m]",
                            f"{size!r} (~{count_text(panels)} panels)")


def _check_wave_count(context: "ReadContext", key: str, count: float) -> None:
    """Refuse more than :data:`MAX_WAVE_COMPONENTS` wave components (or an infinite count)."""
    if not count <= MAX_WAVE_COMPONENTS:
        raise context.error(("waves", key), f"at most {MAX_WAVE_COMPONENTS:.3g} wave "
                            "components ((omega_max - omega_min) / frequency_step, the step "
                            "2 pi / simulation.duration by default, or n_components; "
                            "floatmoor.case.limits.MAX_WAVE_COMPONENTS)",
                            f"{count_text(count)} components")


def _check_components(case: "Case", context: "ReadContext") -> None:
    duration = case.simulation.duration
    waves = case.waves.settings if case.waves is not None else None
    if isinstance(waves, JonswapSettings):
        if waves.spacing == "random-in-bin":
            count, key = float(waves.n_components or 0), "n_components"
            _check_wave_count(context, key, count)
        else:
            lo, hi = waves.band()
            step = waves.frequency_step or 2.0 * math.pi / duration
            count = (hi - lo) / step
            key = "frequency_step" if waves.frequency_step else "omega_max"
            _check_wave_count(context, key, count)  # first: an infinite count has no floor
            # the components sit at multiples j step of the step inside [lo, hi]
            # (waves.realisation): none there is a sea with no waves
            inside = math.floor(hi / step + 1e-9) - max(math.ceil(lo / step - 1e-9), 1) + 1
            if inside < 1:
                path = ("waves", "frequency_step") if waves.frequency_step else (
                    "simulation", "duration")
                found = (f"{waves.frequency_step!r} rad/s" if waves.frequency_step else
                         f"{duration!r} s (step 2 pi / duration = {step:.4g} rad/s)")
                raise context.error(path, f"a frequency step that puts at least one wave "
                                    f"component in the band [{lo:.4g}, {hi:.4g}] rad/s "
                                    "(components at multiples of the step; by default "
                                    "2 pi / simulation.duration)", found)
    wind = case.wind
    if wind is not None and wind.spectrum != "steady":
        count = wind.cutoff_hz * duration
        if not count <= MAX_WIND_COMPONENTS:
            raise context.error(("wind", "cutoff_hz"), f"at most {MAX_WIND_COMPONENTS:.3g} wind "
                                "components (cutoff_hz * simulation.duration; floatmoor.case."
                                "limits.MAX_WIND_COMPONENTS) [Hz]",
                                f"{wind.cutoff_hz!r} ({count_text(count)} components)")


def dynamic_nodes_bound(st: DynamicSettings) -> int:
    """Nodes of a dynamic section: its own, or at most those the accuracy's choice gives."""
    elements = st.elements if st.elements is not None else AUTO_MAX_ELEMENTS
    order = st.order if st.order is not None else AUTO_ORDER
    return elements * (order + 1)
