"""A MoorDyn deck -> the text of a floatmoor case file, with comments saying where each value
came from, and the list of what could not be mapped.

Choices (stated in the file written):

- every MoorDyn line is a one-section floatmoor line, model "dynamic" (MoorDyn's lumped-mass
  model is dynamic), numbered ``lineN``; points are ``pointN``: Fixed/Anchor -> "fixed",
  Vessel/Coupled -> "body" (they stay where they are unless the case gets a [motion]),
  Free/Connect -> "free" with mass, volume, CdA and Ca; points on a body (BodyN) -> "body"
  at the body's position plus their offset (the body itself is not modelled: listed);
- line types by :mod:`.line_types` (exact); NumSegs N -> DG order min(5, N) and
  ceil(N / order) elements (the export writes elements x order segments back);
- internal damping: floatmoor's ratio is that of the line's (its one section's) first axial mode, MoorDyn's
  negative BA that of a segment: one floatmoor ratio per (type, number of segments), the type
  split into ``NAME``, ``NAME_2``, ... when its lines need different ratios;
- seabed: MoorDyn's kBot, cBot and FricDamp are per contact diameter; floatmoor's stiffness is
  the same number (its contact width is the diameter), its damping ratio and slip speed are
  those of the first line, exact for it (listed when other lines would need other values);
- MoorDyn's defaults (MoorDyn-C 2.7) where the deck gives no option: g = 9.80665 m/s^2,
  rho = 1025 kg/m^3, kBot = 3e6 Pa/m, cBot = 3e5 Pa s/m, no friction, FricDamp = 200 N s/m;
- the deck's TMax (if any) as the duration, else :data:`DEFAULT_DURATION`; dtOut (if any) as
  the output interval, else :data:`DEFAULT_OUTPUT_INTERVAL`.

The case text is then loaded, in memory, by the case loader (:func:`floatmoor.case.load.
parse_case`) before anything is written: a deck the loader would refuse (a point below the
seabed, a line from a point to itself, NumSegs or TMax / dtOut beyond the case's bounds, ...)
is refused here, the loader's message naming the deck line that gave the value (the importer
keeps the deck line of every case key it writes). Text from the deck reaches the case file
only as numbers, names the parser has checked (no control characters) and the deck's file
name, escaped (:func:`floatmoor.terminal_text.shown`) where a comment or string quotes it.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from floatmoor._version import __version__
from floatmoor.case.limits import parse_toml
from floatmoor.case.load import DEFAULT_DG_ORDER, parse_case
from floatmoor.case.naming import toml_text
from floatmoor.case.title import literal_title
from floatmoor.errors import CaseError
from floatmoor.io.moordyn.deck import (POINT_BODY, POINT_COUPLED, POINT_FIXED, Deck,
                                       DeckLine, DeckLineType, DeckOption)
from floatmoor.io.moordyn.line_types import (MoorDynLineType, damping_ratio_from_moordyn,
                                             floatmoor_line_type, seabed_from_moordyn,
                                             slip_speed_from_moordyn)
from floatmoor.terminal_text import shown

__all__ = ["ImportResult", "import_deck", "DEFAULT_DURATION", "DEFAULT_OUTPUT_INTERVAL",
           "MOORDYN_DEFAULTS"]

#: Duration of an imported case whose deck gives no TMax [s]: a deck describes a mooring, not
#: a run; one minute lets a dynamic line settle and shows its first motions.
DEFAULT_DURATION = 60.0
#: Output interval of an imported case whose deck gives no dtOut [s].
DEFAULT_OUTPUT_INTERVAL = 0.1
#: MoorDyn-C 2.7's values of the options a deck may omit (``MoorDyn.cpp``, ``MoorDyn::MoorDyn``).
MOORDYN_DEFAULTS = {"g": 9.80665, "rho": 1025.0, "kBot": 3.0e6, "cBot": 3.0e5,
                    "FrictionCoefficient": 0.0, "FricDamp": 200.0, "StatDynFricScale": 1.0}
#: floatmoor's slip speed when the deck has no friction (then it has no effect) [m/s].
_SLIP_SPEED_WITHOUT_FRICTION = 0.01
#: Relative difference below which two lines' derived seabed values count as one [-]
#: (round-off of the mapping's products and square roots).
_SAME_VALUE_RTOL = 1e-12

#: Option keys (lower case) floatmoor maps, by what they set.
_OPTION_KEYS = {"g": ("g", "gravity"), "rho": ("rho", "wtrdnsty"), "depth": ("wtrdpth",),
                "kBot": ("kbot", "kb"), "cBot": ("cbot", "cb"),
                "FrictionCoefficient": ("frictioncoefficient",), "FricDamp": ("fricdamp",),
                "StatDynFricScale": ("statdynfricscale",), "TMax": ("tmax",),
                "dtOut": ("dtout",)}
#: Options that are MoorDyn's numerics, start-up or output settings: no floatmoor counterpart
#: and no effect on the physics.
_NUMERICS = {"dtm", "cfl", "tscheme", "dtic", "tmaxic", "cdscaleic", "icdfac", "threshic",
             "icgendynamic", "fileic", "writelog", "writeunits", "disableoutput",
             "disableouttime", "outswitch", "echo", "inertialf", "inertialf_rampt"}
#: Options that change the physics when non-zero, which floatmoor does not model.
_PHYSICS = {"wavekin", "currents", "seafloorfile", "mu_kt", "mu_ka", "mc", "cv", "dtwave",
            "unsteady", "ptfmloc", "watervel"}


@dataclass
class ImportResult:
    """The case file text and the items of the deck it could not map."""

    text: str
    unmapped: list[str] = field(default_factory=list)


def _fmt(value: float) -> str:
    return toml_text(float(value))


class _Importer:
    def __init__(self, deck: Deck, water_depth: float | None,
                 driver_values: Mapping[str, tuple[float, str, bool]] | None = None) -> None:
        self.deck = deck
        self.driver_values = dict(driver_values or {})
        self.unmapped: list[str] = []
        self.used_options: set[int] = set()
        self.water_depth_override = water_depth
        #: case key path -> (deck line, the deck item) of the values written (for the loader's
        #: errors); a key of no deck line (a default, an option given on the command line) has
        #: none
        self.origins: dict[str, tuple[int, str]] = {}
        self.source = shown(deck.source)
        #: the deck line and item being mapped (for an arithmetic failure)
        self.current: tuple[int, str] = (0, "OPTIONS")

    def mark(self, key: str, line_number: int, item: str) -> None:
        """Record that the case key ``key`` comes from deck line ``line_number`` (``item``)."""
        if line_number:
            self.origins[key] = (line_number, item)

    def mark_option(self, key: str, opt: DeckOption | None) -> None:
        if opt is not None:
            self.mark(key, opt.line_number, f"OPTIONS, {opt.key}")

    # -- options ---------------------------------------------------------------------------
    def option(self, name: str) -> DeckOption | None:
        opt = self.deck.option(*_OPTION_KEYS[name])
        if opt is not None:
            self.used_options.add(opt.line_number)
        return opt

    def number(self, name: str, *, positive: bool = False,
               default: float | None = None) -> tuple[float | None, str]:
        """The option's value and the comment saying where it came from."""
        opt = self.option(name)
        given = self.driver_values.get(name)  # (value, origin, whether it beats the deck's)
        if given is not None and (opt is None or given[2]):
            return given[0], given[1]
        if opt is None:
            if default is None:
                return None, ""
            return default, f"MoorDyn's default {name} (the deck gives none)"
        try:
            value = float(opt.value)
        except ValueError:
            value = math.nan
        if not math.isfinite(value) or (positive and value <= 0.0) or value < 0.0:
            raise CaseError(f"{self.deck.source}:{opt.line_number}", f"OPTIONS, {opt.key}",
                            "a finite number " + ("> 0" if positive else ">= 0"),
                            repr(opt.value))
        return value, f"{opt.key} (line {opt.line_number})"

    # -- the case ----------------------------------------------------------------------------
    def run(self) -> ImportResult:
        """The case text, or the error naming the deck line whose values it cannot map."""
        try:
            return self._run()
        except CaseError:
            raise
        except (ArithmeticError, ValueError) as err:
            # extreme values (Diam 1e-200 m: pi Diam^2 / 4 underflows to 0) break the mapping's
            # arithmetic: the deck row being mapped is named, as for any bad value
            line, item = self.current
            raise CaseError(f"{self.deck.source}:{line}" if line else self.deck.source, item,
                            "values the mapping to floatmoor's can compute with (finite "
                            "products, quotients and powers)",
                            f"{type(err).__name__}: {err}") from None

    def _run(self) -> ImportResult:
        deck = self.deck
        if not deck.lines:
            raise CaseError(deck.source, "LINES", "at least one line", "none")
        out: list[str] = []
        w = out.append
        w(f"# Imported from the MoorDyn input file {self.source}")
        w(f"# by floatmoor import moordyn (floatmoor {__version__}); comments give each value's "
          "origin.")
        w("# Items of the deck it could not map are listed at the end of this file.")
        w("")
        title = deck.title or f"MoorDyn deck {self.source}"
        w(f"title = {toml_text(literal_title(title))}")
        w(f"description = {toml_text('Imported from the MoorDyn input file ' + self.source)}")
        w("")
        g, g_from = self.number("g", positive=True, default=MOORDYN_DEFAULTS["g"])
        rho, rho_from = self.number("rho", positive=True, default=MOORDYN_DEFAULTS["rho"])
        depth, depth_from = self.number("depth", positive=True)
        for key, name in (("water_density", "rho"), ("water_depth", "depth"), ("gravity", "g")):
            self.mark_option(f"environment.{key}", self.deck.option(*_OPTION_KEYS[name]))
        if self.water_depth_override is not None:
            depth, depth_from = self.water_depth_override, "given on the command line"
            self.origins.pop("environment.water_depth", None)
        if depth is None:
            raise CaseError(deck.source, "OPTIONS, WtrDpth", "a water depth (a WtrDpth option, "
                            "or --water-depth: MoorDyn-F takes it from OpenFAST)",
                            "none")
        w("[environment]")
        w(f"water_density = {_fmt(rho)}  # kg/m^3, {rho_from}")  # type: ignore[arg-type]
        w(f"water_depth = {_fmt(depth)}  # m, {depth_from}")
        w(f"gravity = {_fmt(g)}  # m/s^2, {g_from}")  # type: ignore[arg-type]
        w("")
        self.types = {t.name: t for t in deck.line_types}
        lengths = {}
        for ln in deck.lines:
            self.current = (ln.line_number, f"LINES {ln.number}")
            lengths[ln.number] = self.length(ln)
        w(self.seabed(lengths, rho, g))  # type: ignore[arg-type]
        type_of_line = self.line_types(out, lengths)
        self.points(out)
        self.lines(out, lengths, type_of_line)
        self.simulation(out)
        self.unmappable()
        w("# -- not mapped " + "-" * 76)
        if self.unmapped:
            w("# floatmoor could not map these items of the deck:")
            out.extend(f"# - {item}" for item in self.unmapped)
        else:
            w("# (nothing: every item of the deck was mapped)")
        text = "\n".join(out) + "\n"
        self.load(text)
        return ImportResult(text=text, unmapped=self.unmapped)

    def load(self, text: str) -> None:
        """Load the case text with the case loader, in memory; its error, if any, as one
        naming the deck line that gave the value (module docstring)."""
        where = f"the case imported from {self.source}"
        try:
            # the loader's norms of far-out positions (1e308 m) overflow to inf, which it
            # then refuses: no numpy warning on the way
            with np.errstate(over="ignore", invalid="ignore"):
                parse_case(parse_toml(text, where), source=where, text=text)
        except CaseError as err:
            raise self.deck_error(err) from None

    def deck_error(self, err: CaseError) -> CaseError:
        """The loader's error ``err`` as one naming the deck line of its key."""
        key = err.key
        best = ""
        for path in self.origins:
            if (key == path or key.startswith((path + ".", path + "["))) \
                    and len(path) > len(best):
                best = path
        if not best:
            return CaseError(self.deck.source, f"the imported case's {key}" if key else
                             "the imported case", err.expected, err.found)
        line, item = self.origins[best]
        return CaseError(f"{self.deck.source}:{line}", f"{item} (the case's {key})",
                         err.expected, err.found)

    def length(self, line: DeckLine) -> float:
        if line.length > 0.0:
            return line.length
        pts = {p.number: p for p in self.deck.points}
        a, b = pts[line.start].position, pts[line.end].position
        return -line.length * math.dist(a, b)

    def md_type(self, t: DeckLineType) -> MoorDynLineType:
        return MoorDynLineType(
            diameter=t.diameter, mass_per_length=t.mass_per_length,
            axial_stiffness=t.axial_stiffness, internal_damping=t.internal_damping,
            normal_drag_coefficient=t.normal_drag_coefficient,
            added_mass_coefficient=t.added_mass_coefficient,
            tangential_drag_coefficient=t.tangential_drag_coefficient,
            tangential_added_mass_coefficient=t.tangential_added_mass_coefficient,
            bending_stiffness=t.bending_stiffness)

    def seabed(self, lengths: dict[int, float], rho: float, g: float) -> str:
        k_bot, k_from = self.number("kBot", default=MOORDYN_DEFAULTS["kBot"])
        c_bot, c_from = self.number("cBot", default=MOORDYN_DEFAULTS["cBot"])
        mu, mu_from = self.number("FrictionCoefficient",
                                  default=MOORDYN_DEFAULTS["FrictionCoefficient"])
        fric_damp, fd_from = self.number("FricDamp", positive=True,
                                         default=MOORDYN_DEFAULTS["FricDamp"])
        scale, _ = self.number("StatDynFricScale", default=1.0)
        if scale != 1.0 and mu:
            self.unmapped.append(f"StatDynFricScale = {scale:g}: floatmoor's friction has one "
                                 "(smoothed) coefficient, static = dynamic [physics]")
        for key, name in (("stiffness", "kBot"), ("damping_ratio", "cBot"),
                          ("friction_coefficient", "FrictionCoefficient"),
                          ("slip_speed", "FricDamp")):
            self.mark_option(f"seabed.{key}", self.deck.option(*_OPTION_KEYS[name]))
        if k_bot == 0.0:
            raise CaseError(self.deck.source, "OPTIONS, kBot", "a seabed stiffness > 0 "
                            "(floatmoor's seabed is always a spring)", "0")
        ratios, slips = [], []
        for ln in self.deck.lines:
            t = self.types[ln.line_type]
            self.current = (t.line_number, f"LINE TYPES '{t.name}' (of LINES {ln.number}, "
                            "with the seabed options)")
            fm = floatmoor_line_type(self.md_type(self.types[ln.line_type]))
            desc = _Desc(**fm)
            ratios.append(seabed_from_moordyn(k_bot, c_bot, desc)[1])  # type: ignore[arg-type]
            weight = fm["mass_per_length"] * g * (1.0 - rho / fm["material_density"])
            slips.append(slip_speed_from_moordyn(fric_damp, weight,  # type: ignore[arg-type]
                                                 lengths[ln.number], ln.segments))
        first = self.deck.lines[0]
        ratio = ratios[0]
        lines = ["[seabed]",
                 f"stiffness = {_fmt(k_bot)}  # Pa/m, {k_from}: per m of contact width, the "
                 "width being Diam (= floatmoor's diameter here)"]  # type: ignore[arg-type]
        lines.append(f"damping_ratio = {_fmt(ratio)}  # {c_from} = {c_bot:g} Pa s/m as a "
                     f"ratio of critical for line {first.number}'s own mass")
        if any(abs(r - ratio) > _SAME_VALUE_RTOL * abs(ratio) for r in ratios):
            self.unmapped.append(
                f"cBot = {c_bot:g} Pa s/m: floatmoor's seabed damping is one ratio of critical "
                f"for each line's own mass; {_fmt(ratio)} (line {first.number}'s) reproduces "
                f"cBot on line {first.number} only, the others would need "
                f"{min(ratios):.4g} to {max(ratios):.4g} [physics, approximate]")
        lines.append(f"friction_coefficient = {_fmt(mu)}  # {mu_from}")  # type: ignore[arg-type]
        if mu:
            slip = slips[0]
            lines.append(f"slip_speed = {_fmt(slip)}  # m/s, {fd_from} = {fric_damp:g} N s/m: "
                         f"MoorDyn's friction saturates at this speed on a resting node of "
                         f"line {first.number}")
            if any(s <= 0.0 for s in slips):
                raise CaseError(self.deck.source, "OPTIONS, FrictionCoefficient",
                                "friction only with lines that sink (a slip speed > 0)",
                                f"{mu:g} with a buoyant line")
            if any(abs(s - slip) > _SAME_VALUE_RTOL * slip for s in slips):
                self.unmapped.append(
                    f"FricDamp = {fric_damp:g} N s/m: floatmoor's friction reaches its full "
                    f"value at one slip speed; {slip:.4g} m/s (line {first.number}'s) "
                    f"reproduces FricDamp on line {first.number} only, the others would need "
                    f"{min(slips):.4g} to {max(slips):.4g} m/s [physics, approximate]")
        else:
            lines.append(f"slip_speed = {_fmt(_SLIP_SPEED_WITHOUT_FRICTION)}  # m/s, no effect "
                         "without friction")
        return "\n".join(lines) + "\n"

    def line_types(self, out: list[str], lengths: dict[int, float]) -> dict[int, str]:
        """Write the line types; the floatmoor type name of every line."""
        names: dict[tuple[str, float], str] = {}
        count: dict[str, int] = {}
        type_of_line: dict[int, str] = {}
        origin: dict[str, str] = {}
        for ln in self.deck.lines:
            t = self.types[ln.line_type]
            self.current = (ln.line_number, f"LINES {ln.number}, with its LineType '{t.name}'")
            ratio = damping_ratio_from_moordyn(t.internal_damping, lengths[ln.number],
                                               ln.segments, t.axial_stiffness,
                                               t.mass_per_length)
            key = (t.name, ratio)
            if key not in names:
                count[t.name] = count.get(t.name, 0) + 1
                name = t.name if count[t.name] == 1 else f"{t.name}_{count[t.name]}"
                names[key] = name
                origin[name] = (
                    f"BA/-zeta = {t.internal_damping:g} on line {ln.number} "
                    + (f"({ln.segments} segments): c_int = zeta_md (L/N) sqrt(EA m)"
                       if t.internal_damping < 0.0 else "[N s]")
                    + ", as the ratio of the first axial mode")
            type_of_line[ln.number] = names[key]
        for (type_name, ratio), name in names.items():
            t = self.types[type_name]
            self.current = (t.line_number, f"LINE TYPES '{t.name}'")
            fm = floatmoor_line_type(self.md_type(t))
            src = f"LINE TYPES '{t.name}' (line {t.line_number})"
            self.mark(f"line_types.{name}", t.line_number, f"LINE TYPES '{t.name}'")
            out.append(f"[line_types.{toml_text(name)}]  # {src}")
            out.append(f"mass_per_length = {_fmt(fm['mass_per_length'])}  # kg/m, Mass/m")
            out.append(f"axial_stiffness = {_fmt(fm['axial_stiffness'])}  # N, EA")
            out.append(f"diameter = {_fmt(fm['diameter'])}  # m, Diam: MoorDyn's one diameter, "
                       "for drag and volume alike")
            out.append(f"material_density = {_fmt(fm['material_density'])}  # kg/m^3, Mass/m "
                       "over pi Diam^2/4: floatmoor's volume is then MoorDyn's")
            out.append(f"normal_drag_coefficient = {_fmt(fm['normal_drag_coefficient'])}  # Cd")
            out.append(f"tangential_drag_coefficient = "
                       f"{_fmt(fm['tangential_drag_coefficient'])}  # pi CdAx (MoorDyn's "
                       "refers to the circumference pi Diam)")
            out.append(f"added_mass_coefficient = {_fmt(fm['added_mass_coefficient'])}  # Ca")
            out.append(f"tangential_added_mass_coefficient = "
                       f"{_fmt(fm['tangential_added_mass_coefficient'])}  # CaAx")
            out.append(f"internal_damping_ratio = {_fmt(ratio)}  # {origin[name]}")
            out.append("")
            if t.bending_stiffness != 0.0:
                self.unmapped.append(f"LINE TYPES '{t.name}' (line {t.line_number}): EI = "
                                     f"{t.bending_stiffness:g} N m^2; floatmoor's lines have no "
                                     "bending stiffness [physics]")
        return type_of_line

    def points(self, out: list[str]) -> None:
        bodies_listed: set[int] = set()
        for i, p in enumerate(self.deck.points):
            self.mark(f"points[{i}]", p.line_number, f"POINTS {p.number}")
            self.current = (p.line_number, f"POINTS {p.number}")
            src = f"POINTS {p.number} (line {p.line_number}): {p.attachment_text}"
            position = p.position
            if p.attachment == POINT_FIXED:
                kind = "fixed"
            elif p.attachment == POINT_COUPLED:
                kind = "body"
                src += " (coupled: stays where it is unless the case gets a [motion])"
            elif p.attachment == POINT_BODY:
                kind = "body"
                position = self.on_body(p.body, p.position, p.line_number)
                src += f" (offset from body {p.body}, which is not modelled)"
                if p.body not in bodies_listed:
                    bodies_listed.add(p.body)
                    self.unmapped.append(
                        f"body {p.body}: floatmoor does not model MoorDyn bodies; its points are "
                        "imported as body points at rest [physics]")
            else:
                kind = "free"
            out.append("[[points]]")
            out.append(f"name = \"point{p.number}\"  # {src}")
            out.append(f"kind = \"{kind}\"")
            out.append(f"position = [{', '.join(_fmt(c) for c in position)}]  # m")
            if kind == "free":
                out.append(f"mass = {_fmt(p.mass)}  # kg, M")
                out.append(f"volume = {_fmt(p.volume)}  # m^3, V")
                out.append(f"drag_area = {_fmt(p.drag_area)}  # m^2, CdA")
                out.append(f"added_mass_coefficient = {_fmt(p.added_mass_coefficient)}  # Ca")
            elif any((p.mass, p.volume, p.drag_area, p.added_mass_coefficient)):
                self.unmapped.append(
                    f"POINTS {p.number} (line {p.line_number}): mass, volume, CdA or Ca of a "
                    f"{p.attachment_text} point (floatmoor's {kind} points carry none) [physics]")
            out.append("")

    def on_body(self, body: int, offset: tuple[float, float, float], n: int) -> tuple[float, ...]:
        row = self.deck.bodies.get(body)
        if row is None:
            raise CaseError(f"{self.deck.source}:{n}", "POINTS, column Attachment",
                            "BodyN naming a row of BODIES", f"Body{body}")
        try:
            r0 = [float(v) for v in row[2:8]]
        except ValueError:
            raise CaseError(f"{self.deck.source}", f"BODIES {body}", "numbers X0 Y0 Z0 r0 p0 "
                            "y0", " ".join(row[2:8])) from None
        if any(r0[3:]):
            raise CaseError(f"{self.deck.source}", f"BODIES {body}", "a body without initial "
                            "rotation (r0 = p0 = y0 = 0) for its points to be imported",
                            " ".join(row[5:8]))
        return tuple(a + b for a, b in zip(r0[:3], offset))

    def lines(self, out: list[str], lengths: dict[int, float],
              type_of_line: dict[int, str]) -> None:
        for i, ln in enumerate(self.deck.lines):
            self.mark(f"lines[{i}]", ln.line_number, f"LINES {ln.number}")
            self.current = (ln.line_number, f"LINES {ln.number}")
            order = min(DEFAULT_DG_ORDER, ln.segments)
            elements = math.ceil(ln.segments / order)
            src = f"LINES {ln.number} (line {ln.line_number})"
            out.append("[[lines]]")
            out.append(f"name = \"line{ln.number}\"  # {src}")
            out.append(f"start = \"point{ln.start}\"  # AttachA")
            out.append(f"end = \"point{ln.end}\"  # AttachB")
            out.append(f"type = {toml_text(type_of_line[ln.number])}  # LineType "
                       f"'{ln.line_type}'")
            length_note = ("UnstrLen" if ln.length > 0 else
                           f"UnstrLen = {ln.length:g}: that multiple of the end points' distance")
            out.append(f"length = {_fmt(lengths[ln.number])}  # m, {length_note}")
            out.append("model = \"dynamic\"  # MoorDyn's lumped-mass line is dynamic")
            out.append("")
            out.append("[lines.dynamic]")
            out.append(f"elements = {elements}  # NumSegs = {ln.segments}: elements x order "
                       f">= NumSegs nodal intervals")
            out.append(f"order = {order}")
            out.append("")
            if ln.outputs not in ("-", ""):
                self.unmapped.append(f"LINES {ln.number} (line {ln.line_number}): output flags "
                                     f"'{ln.outputs}' (floatmoor records its own outputs)")

    def simulation(self, out: list[str]) -> None:
        tmax, t_from = self.number("TMax", positive=True)
        dt_out, o_from = self.number("dtOut")
        duration = tmax if tmax is not None else DEFAULT_DURATION
        interval = dt_out if dt_out else DEFAULT_OUTPUT_INTERVAL
        interval = min(interval, duration)
        tmax_opt, dt_opt = self.deck.option(*_OPTION_KEYS["TMax"]), \
            self.deck.option(*_OPTION_KEYS["dtOut"])
        self.mark_option("simulation.duration", tmax_opt)
        # the output interval's bounds involve the duration: name both when both are given
        self.mark_option("simulation.output_interval", dt_opt or tmax_opt)
        if dt_opt is not None and tmax_opt is not None:
            self.mark("simulation.output_interval", dt_opt.line_number,
                      f"OPTIONS, dtOut (with TMax on line {tmax_opt.line_number})")
        out.append("[simulation]")
        out.append(f"duration = {_fmt(duration)}  # s, "
                   + (t_from if tmax is not None else "a deck has no run length: a default"))
        out.append(f"output_interval = {_fmt(interval)}  # s, "
                   + (o_from if dt_out else "a default"))
        out.append("")

    def unmappable(self) -> None:
        deck = self.deck
        for opt in deck.options:
            if opt.line_number in self.used_options:
                continue
            key = opt.key.lower()
            where = f"option {opt.key} = {opt.value} (line {opt.line_number})"
            if key in _NUMERICS:
                self.unmapped.append(f"{where}: MoorDyn's own numerics, start-up or output "
                                     "setting (floatmoor's are in [lines.dynamic])")
            elif key in _PHYSICS:
                zero = opt.value.strip() in ("0", "0.0")
                self.unmapped.append(f"{where}: " + ("off, no effect" if zero else
                                                     "not modelled by floatmoor [physics]"))
            else:
                self.unmapped.append(f"{where}: unknown to floatmoor")
        for section in deck.other_sections:
            self.unmapped.append(f"section {section.name} (line {section.line_number}, "
                                 f"{len(section.rows)} rows): floatmoor does not model "
                                 f"{section.name.lower()} [physics]")
        if deck.outputs:
            self.unmapped.append(f"OUTPUTS {' '.join(deck.outputs)}: MoorDyn's output channels "
                                 "(floatmoor records its own outputs)")


@dataclass(frozen=True)
class _Desc:
    """A floatmoor line description (line_types.LineDescription) from plain values."""

    mass_per_length: float
    axial_stiffness: float
    diameter: float
    material_density: float
    normal_drag_coefficient: float
    tangential_drag_coefficient: float
    added_mass_coefficient: float
    tangential_added_mass_coefficient: float


def import_deck(deck: Deck, *, water_depth: float | None = None,
                driver_values: Mapping[str, tuple[float, str, bool]] | None = None
                ) -> ImportResult:
    """The case file text for ``deck`` and the list of what it could not map.

    Parameters
    ----------
    deck
        A parsed deck (:func:`floatmoor.io.moordyn.parser.read_deck`).
    water_depth
        The water depth [m] when the deck has none (MoorDyn-F decks take it from OpenFAST), or
        to replace the deck's.
    driver_values
        Values of a MoorDyn driver file (:mod:`.driver_import`) by option name (``g``,
        ``rho``, ``depth``, ``TMax``): (value, origin comment, whether it replaces the
        deck's option rather than filling in a missing one).

    Raises
    ------
    CaseError
        An item of the deck floatmoor cannot represent at all (no water depth, a body point on
        a rotated body, ...), naming the file and line.
    """
    return _Importer(deck, water_depth, driver_values).run()
