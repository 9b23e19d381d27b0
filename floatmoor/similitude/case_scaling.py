"""Rewrite a case at another scale (``floatmoor scale``).

Every key a case file may hold has a quantity kind (:data:`KEY_KINDS`), scaled by the law's
factor of that kind (:mod:`floatmoor.similitude.laws`); keys the scaling cannot follow (a
mesh hull, an imported hydrodynamic database, wind, a campaign) are refused with a message
saying what to do. A motion table is rewritten at the new scale beside the new case
(:mod:`floatmoor.similitude.motion_tables`). The original case is validated first, the scaled
one afterwards, through the same loader as any case, and the groups of both are compared to
say which the new case keeps exactly. Scaled values are written exactly, except those within
round-off of a short decimal (:mod:`floatmoor.similitude.decimals`), so that scaling by lambda
and then 1 / lambda gives back the original values exactly.
"""

from __future__ import annotations

import json
import math
import re
import tempfile
import textwrap
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

import numpy as np

from floatmoor.body.morison import DEFAULT_STRIP_LENGTH
from floatmoor.case.files import read_input_text
from floatmoor.case.limits import parse_toml
from floatmoor.case.load import parse_case
from floatmoor.case.reader import format_path
from floatmoor.case.coupling import InitialOffset
from floatmoor.case.schema import (
    BODY_DOFS, GEOMETRY_KIND, MOTION_KIND, BodyHarmonicMotion, BodyTableMotion, Case,
    CircularMotion, Column, CylinderGeometry, DynamicSettings, Environment, Floater,
    HarmonicMotion, HarmonicRotation, HarmonicTranslation, Line, LineType, Member,
    OneSectionKeys, Point, QuasiDynamicSettings, Seabed, SectionKeys, Simulation, TableMotion,
)
from floatmoor.case.setting import settings_of
from floatmoor.errors import CaseError
from floatmoor.similitude.decimals import SIGNIFICANT_DIGITS, rounded, scaled_value
from floatmoor.similitude.groups import cable_groups
from floatmoor.similitude.laws import SAME_FACTOR, ScaleLaw
from floatmoor.similitude.motion_tables import ScaledTable, scale_motion_table, scaled_table_name

__all__ = ["ScaledCase", "KEY_KINDS", "SIGNIFICANT_DIGITS", "scale_case_text",
           "scale_case_file", "GROUP_TOLERANCE"]

#: A group counts as kept when new / old is 1 within this: round-off of the few factors of
#: a group (~1e-15), with a wide margin, far below any physical difference.
GROUP_TOLERANCE = 1e-9

_REFUSE = "refuse"


def _declared(table: str, cls: type) -> dict[str, str]:
    """The quantity kinds the settings of ``cls`` declare (floatmoor.case.setting), under
    ``table``."""
    return {f"{table}.{key}": spec.scale for key, spec in settings_of(cls).items()}


#: Quantity kind of every key (``*`` = any entry name or index); kinds of
#: :data:`floatmoor.similitude.laws.QUANTITY_KINDS`, ``diameter`` (beta), or a refusal.
KEY_KINDS: dict[str, str] = {
    "title": "same", "description": "same",
    **_declared("environment", Environment), **_declared("seabed", Seabed),
    **_declared("line_types.*", LineType),
    **_declared("points.*", Point),
    **_declared("lines.*", Line), **_declared("lines.*", OneSectionKeys),
    "lines.*.quasi_static.*": "same", **_declared("lines.*.quasi_dynamic", QuasiDynamicSettings),
    **_declared("lines.*.dynamic", DynamicSettings),
    **_declared("lines.*.sections.*", SectionKeys),
    **_declared("lines.*.sections.*.dynamic", DynamicSettings),
    "motion.kind": MOTION_KIND.scale,
    **{key: kind for cls in (CircularMotion, HarmonicMotion, TableMotion, BodyHarmonicMotion,
                             BodyTableMotion) for key, kind in _declared("motion", cls).items()},
    **{key: kind for dof in BODY_DOFS for key, kind in _declared(
        f"motion.{dof}", HarmonicTranslation if dof in BODY_DOFS[:3] else HarmonicRotation
    ).items()},
    **_declared("simulation", Simulation),
    "campaign.*": _REFUSE + ": the swept values are not rewritten; scale the case without "
    "its [campaign] and sweep the scaled values",
    **_declared("floater", Floater), "floater.geometry.kind": GEOMETRY_KIND.scale,
    **_declared("floater.geometry", CylinderGeometry),
    **_declared("floater.geometry.columns.*", Column),
    **_declared("floater.geometry.members.*", Member),
    **{f"floater.geometry.{k}": _REFUSE + ": a mesh hull is not rescaled; write the mesh at "
       "the new scale and name it in the scaled case" for k in (
           "file", "format", "length_unit", "position", "symmetry")},
    # Morison drag: the coefficients are dimensionless and the floater's force scale is
    # Froude's (rho lambda^3, checked), so they are kept; the areas follow the geometry; the
    # strips are lengths (the default strip_length is written, scaled, when not given)
    **{f"floater.drag.{k}": "same" for k in (
        "preset", "column_transverse", "heave_plate_transverse", "heave_plate_axial",
        "member_transverse", "member_axial", "column_axial", "min_strips",
        "heave_plate_area")},
    "floater.drag.strip_length": "length", "floater.drag.kinematics_interval": "time",
    "hydro.database": "database", "hydro.frequency_ranges": "frequency_ranges",
    "hydro.frequencies": "frequency", "hydro.directions_deg": "same",
    "hydro.panel_size": "length", "hydro.lid_depth": "length",
    "hydro.drift_waterline_panel_size": "length",
    "hydro.drift_panel_size": "length",
    **{f"hydro.{k}": "same" for k in ("lid", "infinite_depth", "symmetry", "radial_panels",
                                      "accept_failed_checks")},
    "hydro.source": "hydro_source",
    **{f"waves.{k}": "same" for k in ("kind", "direction_deg", "phase_deg", "seed", "gamma",
                                      "spacing", "n_components", "second_order",
                                      "drift_coefficients")},
    "waves.height": "length", "waves.hs": "length", "waves.period": "time", "waves.tp": "time",
    "waves.ramp_duration": "time", "waves.frequency_step": "frequency",
    "waves.omega_min": "frequency", "waves.omega_max": "frequency",
    **_declared("initial", InitialOffset),
    "wind": _REFUSE + ": the rotor thrust (the NREL 5 MW turbine's curves) has no scaled "
    "version; scale the case without [wind]",
}
#: Keys whose value is a table of names (``[line_types.NAME]``) or an array of tables.
_NAMED = ("line_types",)
_BARE_KEY = re.compile(r"^[A-Za-z0-9_-]+$")
#: Characters a multi-line TOML string cannot hold unescaped (tab and newline it can).
_CONTROL = re.compile(r"[\x00-\x08\x0b-\x1f\x7f]")


@dataclass(frozen=True)
class ScaledCase:
    """A scaled case: its TOML text, the validated case, and the groups' new / old ratios."""

    text: str
    case: Case
    kept: list[str]  #: groups equal in every section (within :data:`GROUP_TOLERANCE`)
    changed: dict[str, tuple[float, float]]  #: group -> (min, max) new / old over sections
    notes: list[str]
    #: motion tables to write beside the case (the case names them)
    tables: tuple[ScaledTable, ...] = ()


def _kind(path: tuple[str | int, ...]) -> tuple[str, str] | None:
    """The kind of a key path and the pattern that gave it (None: unknown key)."""
    parts = [("*" if isinstance(p, int) or (i > 0 and path[i - 1] in _NAMED) else p)
             for i, p in enumerate(path)]
    for n in range(len(parts), 0, -1):  # the longest pattern first, then its parents'
        for pattern in (".".join(parts[:n]), ".".join(parts[:n - 1] + ["*"])):
            if pattern in KEY_KINDS and (n == len(parts) or KEY_KINDS[pattern].startswith(
                    _REFUSE) or pattern.endswith("*")):
                return KEY_KINDS[pattern], pattern
    return None


def _scale_node(node: Any, path: tuple[str | int, ...], law: ScaleLaw, options: dict[str, Any],
                source: str) -> Any:
    if isinstance(node, dict):
        return {k: _scale_node(v, path + (k,), law, options, source) for k, v in node.items()}
    if isinstance(node, list) and node and all(isinstance(v, dict) for v in node):
        return [_scale_node(v, path + (i,), law, options, source) for i, v in enumerate(node)]
    found = _kind(path)
    key = format_path(path)
    if found is None:
        raise CaseError(source, key, "a key floatmoor scale knows how to scale",
                        "a key with no scaling rule")
    kind, _ = found
    if kind == "motion_table":
        original = Path(options["motion_file"])
        new = Path(options["output"]).parent / scaled_table_name(options["output"], node)
        note = (f"Scaled by floatmoor scale from {original.name}: times x {law.time:.12g}, "
                f"positions x {law.length:.12g}, angles unchanged.")
        options["tables"].append(ScaledTable(new, original, scale_motion_table(
            original.read_text(encoding="utf-8"), law, note)))
        return new.name
    if kind.startswith(_REFUSE):
        raise CaseError(source, key, "a case floatmoor scale can rewrite ("
                        + kind[len(_REFUSE) + 2:] + ")", "this key")
    if kind == "same":
        return node
    if kind == "database":
        if options["database"] is None:
            raise CaseError(source, key, "--hydro-database NAME for the scaled case: its "
                            "BEM database differs (frequencies, lengths, masses) and must be "
                            f"built for it (the case names \"{node}\")", f'"{node}"')
        if options["database"] == node:
            raise CaseError(source, key, "--hydro-database naming a new database: the "
                            f"scaled case's differs from \"{node}\", which would be stale for "
                            "it", f'"{node}" again')
        return options["database"]
    if kind == "hydro_source":
        if node != "bem":
            raise CaseError(source, key, 'source = "bem": an imported database cannot be '
                            "rebuilt at another scale (import the scaled BEM results)",
                            f'"{node}"')
        return node
    if kind == "frequency_ranges":
        return [[rounded(lo * law.frequency), rounded(hi * law.frequency), n]
                for lo, hi, n in node]
    if kind == "diameter":
        return scaled_value(node, law.diameter)
    if kind in ("drag_coefficient", "added_mass_coefficient") and options["keep_coefficients"]:
        return node
    return scaled_value(node, law.factor(kind))


# -- TOML text ---------------------------------------------------------------------------------

def _toml_key(key: str) -> str:
    return key if _BARE_KEY.match(key) else json.dumps(key, ensure_ascii=False)


def _toml_value(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        if "\n" in value and not _CONTROL.search(value):  # a multi-line basic string
            return '"""\n' + value.replace("\\", "\\\\").replace('"""', '""\\"') + '"""'
        return json.dumps(value, ensure_ascii=False)  # a TOML basic string
    if isinstance(value, float):
        return repr(value)
    if isinstance(value, int):
        return str(value)
    if isinstance(value, list):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{_toml_key(k)} = {_toml_value(v)}" for k, v in value.items()) \
            + "}"
    raise TypeError(f"no TOML form for {type(value).__name__}")


def _is_table_array(value: Any) -> bool:
    return isinstance(value, list) and bool(value) and all(isinstance(v, dict) for v in value)


def _toml_table(table: dict[str, Any], path: tuple[str, ...], out: list[str]) -> None:
    for k, v in table.items():
        if not isinstance(v, dict) and not _is_table_array(v):
            out.append(f"{_toml_key(k)} = {_toml_value(v)}")
    for k, v in table.items():
        name = ".".join(_toml_key(p) for p in path + (k,))
        if isinstance(v, dict):
            out.extend(["", f"[{name}]"])
            _toml_table(v, path + (k,), out)
        elif _is_table_array(v):
            for entry in v:
                out.extend(["", f"[[{name}]]"])
                _toml_table(entry, path + (k,), out)


# -- the scaled case ---------------------------------------------------------------------------

def _group_ratios(old: Case, new: Case
                  ) -> tuple[list[str], dict[str, tuple[float, float]], list[str]]:
    """Groups kept, groups changed (min, max new / old), groups not evaluated (NaN: they
    need a period and the case declares none)."""
    a, b = cable_groups(old), cable_groups(new)
    kept, changed, missing = [], {}, []
    for name in ("alpha_1", "alpha_2", "alpha_3", "alpha_4", "alpha_5", "reynolds_number",
                 "keulegan_carpenter_number"):
        old_v, new_v = a[name].values, b[name].values
        if np.all(np.isnan(old_v)):
            missing.append(name)
            continue
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = np.where(old_v == new_v, 1.0, new_v / old_v)
        if np.all(np.abs(ratio - 1.0) <= GROUP_TOLERANCE):
            kept.append(name)
        else:
            changed[name] = (float(np.nanmin(ratio)), float(np.nanmax(ratio)))
    return kept, changed, missing


def _header(source: str, law: ScaleLaw, keep_coefficients: bool, floater: bool,
            kept: list[str], changed: dict[str, tuple[float, float]],
            notes: list[str]) -> list[str]:
    f = law
    how = f"from --match {f.name}" if f.name != "given" else "given"
    coefficients = ("drag and added-mass coefficients unchanged (--keep-coefficients)"
                    if keep_coefficients else
                    f"drag coefficients {f.drag_coefficient:.6g} (eq. 38), added-mass "
                    f"coefficients {f.added_mass_coefficient:.6g} (eq. 42; C_a on m / rho_c)")
    text = [
        f"Scaled by floatmoor scale from {source}: dynamic similitude of the cable equation "
        "(Bergdahl, Palm, Eskilsson & Lindahl 2016, section 2; docs/guide/similitude.md).",
        f"Law: length lambda = {f.length:.12g} (eq. 32), diameter beta = {f.diameter:.12g} "
        f"(eq. 35), volume coefficient phi = {f.volume_coefficient:.12g} (eq. 36, {how}), "
        f"water density x {f.water_density:.12g}.",
        f"Factors (new / old): lengths, positions, depths {f.length:.6g}; times, periods, "
        f"time steps {f.time:.6g} (eq. 33); velocities {f.velocity:.6g} (eq. 39); mass per "
        f"length {f.mass_per_length:.6g} (eq. 30); EA, forces, MBL {f.force:.6g} (eqs. "
        f"36-37); {coefficients}; seabed stiffness {f.seabed_stiffness:.6g}"
        + (f"; floater mass {f.mass:.6g}, inertia {f.inertia:.6g} (Froude)" if floater else "")
        + "; element counts, orders and CFL numbers unchanged.",
        "Groups kept exactly: " + (", ".join(kept) if kept else "none") + ".",
    ]
    if changed:
        text.append("Groups not kept (new / old): " + "; ".join(
            f"{k} {lo:.4g}" + (f" to {hi:.4g}" if not math.isclose(lo, hi) else "")
            for k, (lo, hi) in changed.items()) + ".")
    text.extend(notes)
    text.append("The description below is the original case's.")
    return [row for paragraph in text
            for row in textwrap.wrap(paragraph, 96, initial_indent="# ",
                                     subsequent_indent="#   ")]


def scale_case_text(text: str, source: str, law: ScaleLaw, *, output: str | Path,
                    keep_coefficients: bool = False,
                    hydro_database: str | None = None) -> ScaledCase:
    """Scale a case file's text.

    Parameters
    ----------
    text, source
        The case file's text and path (named in errors).
    law
        The scale factors.
    output
        Where the scaled case will be written (its folder resolves relative paths).
    keep_coefficients
        Leave the drag and added-mass coefficients as they are (their Reynolds dependence
        decided by the user) instead of keeping alpha_1, alpha_4 and alpha_5.
    hydro_database
        Database name of the scaled case (required for a case with ``[hydro]``).

    Raises
    ------
    CaseError
        The case is invalid, holds what the scaling cannot rewrite, or its scaled version is
        not a valid case.
    """
    raw = parse_toml(text, source)
    original = parse_case(raw, source=source, text=text, base_dir=Path(source).parent)
    if original.floater is not None and \
            not math.isclose(law.force, law.mass, rel_tol=SAME_FACTOR):
        raise CaseError(source, "floater", "line forces scaling like the floater's (rho "
                        f"lambda^3 = {law.mass:.6g}): --match froude, or beta = lambda and phi "
                        "= 1", f"phi lambda beta^2 = {law.force:.6g}")
    tables: list[ScaledTable] = []
    motion_file = getattr(original.motion, "file", None)
    scaled = _scale_node(raw, (), law, {"database": hydro_database, "output": output,
                                        "keep_coefficients": keep_coefficients,
                                        "motion_file": motion_file, "tables": tables}, source)
    drag = scaled.get("floater", {}).get("drag")
    if drag is not None and "strip_length" not in drag:  # the default is a length: write it
        drag["strip_length"] = rounded(DEFAULT_STRIP_LENGTH * law.length)
    scaled["description"] = (f"Scaled from {source} by floatmoor scale (see the header).\n"
                             + raw.get("description", "").strip()).strip() + "\n"
    body: list[str] = []
    _toml_table(scaled, (), body)
    notes = []
    if original.hydro is not None:
        notes.append(f"The BEM database \"{hydro_database}\" must be built for this case: "
                     f"floatmoor hydro build {Path(output).name} (the frequencies, panel size "
                     "and lengths are scaled; linear potential flow is Froude-exact, but the "
                     "database is not rescaled here).")
    for table in tables:
        notes.append(f"Motion table {table.path.name}, written beside this case, is "
                     f"{table.source.name} scaled: times x {law.time:.12g}, positions x "
                     f"{law.length:.12g}, angles unchanged.")
    draft = "\n".join(body) + "\n"
    try:
        case = _parse_scaled(draft, Path(output), tables)
    except CaseError as err:
        raise CaseError(source, "", "a case whose scaled version is valid",
                        f"a scaled case that is not: {err}") from None
    kept, changed, missing = _group_ratios(original, case)
    if missing:
        notes.append("Groups not evaluated (they need a period, and the motion and waves "
                     "declare none): " + ", ".join(missing) + ".")
    header = _header(source, law, keep_coefficients, original.floater is not None, kept,
                     changed, notes)
    full = "\n".join(header) + "\n\n" + draft
    case = _parse_scaled(full, Path(output), tables)
    return ScaledCase(full, case, kept, changed, notes, tuple(tables))


def _parse_scaled(text: str, output: Path, tables: list[ScaledTable]) -> Case:
    """The scaled case through the loader. Its motion table, not written yet, is read from
    a temporary folder; the case then names the table's final path."""
    if not tables:
        return parse_case(parse_toml(text, str(output)), source=str(output), text=text,
                          base_dir=output.parent)
    with tempfile.TemporaryDirectory() as folder:
        for table in tables:
            (Path(folder) / table.path.name).write_text(table.text, encoding="utf-8")
        case = parse_case(parse_toml(text, str(output)), source=str(output), text=text,
                          base_dir=Path(folder))
    return replace(case, motion=replace(case.motion, file=str(tables[0].path)))


def scale_case_file(path: str | Path, law: ScaleLaw, *, output: str | Path,
                    keep_coefficients: bool = False,
                    hydro_database: str | None = None) -> ScaledCase:
    """Read a case file and scale it (:func:`scale_case_text`); nothing is written."""
    text = read_input_text(path, "case")
    return scale_case_text(text, str(path), law, output=output,
                           keep_coefficients=keep_coefficients, hydro_database=hydro_database)
