"""``floatmoor hydro build | import | check | info | fit-state-space`` (called from
:mod:`floatmoor.cli`).

Exit statuses: 0 success (all checks pass), 1 a check fails (or no state-space fit within the
tolerance: nothing written), 2 bad input (a malformed case, a case without [floater]/[hydro],
a bad output path or option, or a missing, damaged or stale database).

``hydro build`` runs the checks on the database it built (or found up to date) and prints the
table ``hydro check`` prints. A database failing a check is still written, with the failed
checks recorded in its attributes (``checks_failed``, ``checks_json``), so that it can be
inspected (``hydro check``, ``hydro info``); the build then exits with 1, and a run refuses
the database unless its case accepts those checks (``[hydro] accept_failed_checks``; a check
the case accepts is shown as such and does not make the build fail).

``hydro import FILE... -o PATH.nc`` makes a database from WAMIT (.1, .3, .hst, .3fk, .3sc,
.out; mean drift .8, .9 and difference-frequency QTF .12d) or WEC-Sim BEMIO (.h5) files
(:mod:`floatmoor.hydro.importing`), checks it and prints the same table (exit 1 when a check fails; the database is written, as by ``build``), the values
taken from a WAMIT .out and the orientation applied (``--yaw-deg``). A file that cannot be
read, a bad option, everything missing (all listed in one line), or an existing output without
``--force`` is exit 2 with one line, and nothing is written. ``hydro info`` says where a
database came from; it and ``hydro fit-state-space`` are in :mod:`floatmoor.cli.hydro_info`.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

from floatmoor.case.load import load_case
from floatmoor.cli.hydro_info import (
    drift_seconds, fit_state_space_command, info_command, open_database, say,
    second_order_lines,
)
from floatmoor.errors import CaseError
from floatmoor.terminal_text import MESSAGE_LIMIT, shown

__all__ = ["hydro_command"]

EXIT_OK, EXIT_FAILED, EXIT_BAD_INPUT = 0, 1, 2


def hydro_command(args: argparse.Namespace) -> int:
    """Dispatch ``floatmoor hydro ...``; CaseError propagates to the main CLI (exit 2)."""
    from floatmoor.hydro.database import HydroDatabaseError
    from floatmoor.io.bem_data import BemFileError

    try:
        if args.hydro_command == "build":
            return _build(args)
        if args.hydro_command == "import":
            return _import(args)
        if args.hydro_command == "check":
            return _check(args)
        if args.hydro_command == "fit-state-space":
            return fit_state_space_command(args)
        return info_command(args)
    except (HydroDatabaseError, BemFileError) as err:
        print(f"floatmoor: error: {shown(err, MESSAGE_LIMIT)}", file=sys.stderr)
        return EXIT_BAD_INPUT


def _build(args: argparse.Namespace) -> int:
    from floatmoor.hydro.database import REIMPORT_ADVICE, HydroDatabaseError, database_path
    from floatmoor.io.output_files import output_lock

    case = load_case(args.case, args.overrides)
    if case.floater is None or case.hydro is None:
        raise CaseError(args.case, "hydro", "a case with [floater] and [hydro] tables",
                        "none" if case.floater is None else "no [hydro] table")
    if case.hydro.source == "imported":
        raise HydroDatabaseError(
            f"{args.case}: [hydro] source = \"imported\": its database "
            f"{database_path(case)} is imported, not built; {REIMPORT_ADVICE}")
    output = _database_output(args, case, database_path(case))
    with output_lock(output):
        _refuse_replacing_import(output, args.force)
        return _build_locked(args, case, output)


def _refuse_replacing_import(output: Path, force: bool) -> None:
    """``hydro build`` replaces an imported database only with ``--force``."""
    from floatmoor.hydro.database import (
        HydroDatabaseError, database_source, is_imported, read_database,
    )

    if force or not output.exists():
        return
    try:
        ds = read_database(output)
    except HydroDatabaseError:
        return  # damaged: rebuilt as any damaged database is
    if is_imported(ds):
        raise HydroDatabaseError(f"{output}: imported from {database_source(ds)} files "
                                 "('floatmoor hydro import'); hydro build replaces it only with "
                                 "--force (or give the case another [hydro] database)")


def _database_output(args: argparse.Namespace, case, default: Path) -> Path:
    """The checked database file of ``hydro build``: ``-o``, else the case's database (its
    folder is created when missing)."""
    from floatmoor.io.output_files import check_output_file
    from floatmoor.io.output_kinds import HYDRO_DATABASE_FILE

    if args.output is None and not default.parent.is_dir():
        try:
            default.parent.mkdir(parents=True)
        except OSError as err:
            raise CaseError(case.source, "hydro.database", "a database folder floatmoor can "
                            "create", f"'{default.parent}': {err.strerror}") from None
    return check_output_file(args.output or default, "-o/--output", kind=HYDRO_DATABASE_FILE,
                             protected={"case file": case.source}).path


def _build_locked(args: argparse.Namespace, case, output: Path) -> int:
    """Build the database of a checked case into its locked output file (with ``--drift``,
    its mean drift coefficients too: added to an up-to-date database without rebuilding)."""
    from floatmoor.hydro.checks import run_checks
    from floatmoor.hydro.drift_checks import check_drift
    from floatmoor.hydro.database import (
        HydroDatabaseError, build_database, load_for_case, write_database,
    )

    def progress(done: int, total: int, omega: float, seconds: float, what: str = "") -> None:
        if not args.quiet:
            label = "inf" if math.isinf(omega) else f"{omega:.4g}"
            print(f"floatmoor: hydro {case.hydro.database}{what}: {done} / {total} frequencies "
                  f"(omega = {label} rad/s, {seconds:.2f} s)", file=sys.stderr, flush=True)

    if output.exists() and not args.force:
        try:
            ds = load_for_case(case, output, checks=False)
        except HydroDatabaseError as err:
            print(f"floatmoor: rebuilding: {err}", file=sys.stderr)
        else:
            if args.drift and not _drift_current(ds, case):
                ds = _with_drift(ds, case, progress)
                results = run_checks(ds) + [check_drift(ds)]
                _record_checks(ds, results)
                write_database(ds, output)
                print(f"{output}: up to date for {args.case}; mean drift added in "
                      f"{drift_seconds(ds)} s")
                return _report_build_checks(output, ds, results, case, "drift added")
            print(f"{output}: up to date for {args.case}; nothing to do (--force rebuilds)")
            _report_mesh(ds, warn=False)
            return _report_build_checks(output, ds, run_checks(ds) + _drift_rows(ds), case,
                                        "up to date")

    ds = build_database(case, progress=progress)
    if args.drift:
        ds = _with_drift(ds, case, progress)
    results = run_checks(ds) + _drift_rows(ds)
    _record_checks(ds, results)
    write_database(ds, output)
    print(f"{output}: {ds.attrs['hull_panels']} hull + {ds.attrs['lid_panels']} lid panels "
          f"({ds.attrs['mesh_symmetry']}), {ds.sizes['omega']} frequencies + infinity, "
          f"{ds.sizes['wave_direction']} directions, built in {ds.attrs['build_seconds']:.1f} s")
    _report_mesh(ds, warn=True)
    return _report_build_checks(output, ds, results, case, "as built")


def _drift_current(ds, case) -> bool:
    from floatmoor.hydro.drift_build import drift_is_current

    return drift_is_current(ds, case)


def _drift_rows(ds) -> list:
    """The drift check row when the database holds drift coefficients."""
    from floatmoor.hydro.drift_checks import check_drift
    from floatmoor.hydro.drift_build import has_drift

    return [check_drift(ds)] if has_drift(ds) else []


def _with_drift(ds, case, progress):
    """The database with the case's mean drift coefficients (``hydro build --drift``)."""
    from floatmoor.hydro.database import HydroDatabaseError, has_excitation
    from floatmoor.hydro.drift_build import add_drift, drift_for_case

    if not has_excitation(ds):
        raise HydroDatabaseError(f"{case.source}: --drift needs wave excitation forces in "
                                 "the database")

    def step(done: int, total: int, omega: float, seconds: float) -> None:
        progress(done, total, omega, seconds, " drift")

    result, x, conditions = drift_for_case(case, ds, progress=step)
    return add_drift(ds, result, x, conditions)


def _report_mesh(ds, *, warn: bool) -> None:
    """For a hull read from a mesh file: what was read and the mesh checks (a few lines);
    with ``warn``, each failed check also as a warning on standard error."""
    from floatmoor.hydro.mesh_checks import summary_lines

    if "mesh_file_json" not in ds.attrs:
        return
    from floatmoor.hydro.database import recorded_json

    info = recorded_json(ds, "mesh_file_json", {})
    checks = recorded_json(ds, "mesh_checks_json", [])
    try:
        lines = summary_lines(info, checks)
    except (KeyError, TypeError, AttributeError, ValueError):  # recorded by another hand
        lines = ["  mesh: the recorded mesh description is not readable"]
    print("\n".join(shown(line) for line in lines))  # recorded text: escaped
    for c in checks:
        if warn and not c["passed"]:
            print(f"floatmoor: warning: mesh {info['file']}: {c['name']}: {c['detail']} "
                  f"({c['fix']})", file=sys.stderr)


def _record_checks(ds, results) -> list[str]:
    """Record the check results in the database's attributes (for the reader only: a run
    recomputes them); the names of the failed ones."""
    failed = [r.name for r in results if not r.passed]
    ds.attrs["checks_failed"] = ", ".join(failed) or "none"
    ds.attrs["checks_json"] = json.dumps([r.as_dict() for r in results])
    return failed


def _report_build_checks(path: Path, ds, results, case, note: str) -> int:
    """Print the checks of a built (or up-to-date) database; 1 when one fails that the case
    does not accept."""
    from floatmoor.hydro.checks import describe_failures

    accepted = case.hydro.accept_failed_checks
    print(_checks_table(path, ds, note, results, accepted))
    drift = [r for r in results if r.name == "drift" and not r.passed]
    if drift:  # a run uses the route its case chooses: a disagreement is reported only
        print(f"floatmoor: warning: {path}: mean drift far and near field differ by "
              f"{drift[0].worst:.1%} of the peak (tolerance {drift[0].tolerance:.0%}): finer "
              "panels near the waterline bring them together (docs/guide/hydro_databases.md"
              "#mean-drift)", file=sys.stderr)
    refused = [r for r in results if not r.passed and r.name not in accepted
               and r.name != "drift"]
    if refused:
        names = ", ".join(f'"{r.name}"' for r in results if not r.passed and r.name != "drift")
        print(f"floatmoor: hydro build: {path} is written but fails its checks: "
              f"{describe_failures(refused)}; a run refuses it unless the case accepts them "
              f"([hydro] accept_failed_checks = [{names}])", file=sys.stderr)
        return EXIT_FAILED
    return EXIT_OK


def _import(args: argparse.Namespace) -> int:
    """``hydro import``: read, label, check and write atomically; nothing written on an
    error."""
    from floatmoor.hydro.checks import check_values, run_checks
    from floatmoor.hydro.database import project_folder, write_database
    from floatmoor.hydro.importing import file_format, import_database
    from floatmoor.io.output_files import check_output_file, output_lock
    from floatmoor.io.output_kinds import HYDRO_DATABASE_FILE

    options = _import_options(args)
    file_format(args.files)
    if not args.output.endswith(".nc"):
        raise CaseError("-o/--output", "", "a database file PATH.nc", f"'{args.output}'")
    output = check_output_file(args.output, "-o/--output", kind=HYDRO_DATABASE_FILE,
                               protected={f"source file {f}": f for f in args.files}).path
    with output_lock(output):
        if output.exists() and not args.force:
            raise CaseError("-o/--output", "", "a new file (--force overwrites)",
                            f"the existing file '{output}'")
        ds = import_database(args.files, options, name=output.stem,
                             command=_import_command(args),
                             project=project_folder(output))
        results = [check_values(ds), *run_checks(ds), *_drift_rows(ds)]
        failed = [name for name in _record_checks(ds, results) if name != "drift"]
        write_database(ds, output)
    omega = ds["omega"].values
    print(f"{output}: imported from {ds.attrs['source']} files, {len(omega)} frequencies "
          f"{omega[0]:.4g}-{omega[-1]:.4g} rad/s; A_inf {ds.attrs['added_mass_infinite_source']}"
          f"; excitation: {ds.attrs['excitation']}")
    from floatmoor.hydro.importing import RUN_SUMMARY_NOTE, YAW_NOTE

    for note in json.loads(ds.attrs["import_notes_json"]):
        # values the options did not give, and the orientation
        if note.startswith((RUN_SUMMARY_NOTE, YAW_NOTE)):
            print(f"  {note}")
    second = second_order_lines(ds)
    if second:
        say("\n".join(second))
    print(_checks_table(output, ds, "as imported", results))
    drift = [r for r in results if r.name == "drift" and not r.passed]
    if drift:  # runs do not enforce the drift row: reported, as by hydro build
        print(f"floatmoor: warning: {output}: imported mean drift far and near field differ "
              f"by {drift[0].worst:.1%} of the peak (tolerance {drift[0].tolerance:.0%})",
              file=sys.stderr)
    if failed:
        print(f"floatmoor: hydro import: {output} is written but fails its checks: "
              f"{', '.join(failed)}; a run refuses it unless the case accepts them "
              "([hydro] accept_failed_checks)", file=sys.stderr)
        return EXIT_FAILED
    return EXIT_OK


def _import_options(args: argparse.Namespace):
    """The options of ``hydro import``, checked (CaseError naming the option)."""
    from floatmoor.case.plausibility import WATER_DENSITY_RANGE
    from floatmoor.hydro.importing import ImportOptions

    depth = None
    if args.water_depth is not None:
        depth = math.inf if args.water_depth.strip().lower() in ("infinite", "inf") else \
            _option_number("--water-depth", args.water_depth, "a water depth > 0 [m] or "
                           "'infinite'", positive=True)
    body = None
    if args.body is not None:
        try:
            body = int(args.body)
        except ValueError:
            body = 0
        if body < 1:
            raise CaseError("--body", "", "a body number >= 1 (BEMIO body1, body2, ...)",
                            f"'{args.body}'")
    density = _optional("--water-density", args.water_density, "kg/m^3")
    low, high = WATER_DENSITY_RANGE
    if density is not None and not low <= density <= high:
        raise CaseError("--water-density", "", f"a water density of {low:g} to {high:g} kg/m^3 "
                        "(fresh to sea water; floatmoor.case.plausibility.WATER_DENSITY_RANGE)",
                        f"'{args.water_density}'"
                        + (" (t/m^3 or g/cm^3 rather than kg/m^3?)" if density < low else ""))
    return ImportOptions(
        water_density=density,
        gravity=_optional("--gravity", args.gravity, "m/s^2"),
        length_scale=_optional("--length-scale", args.length_scale, "m"),
        water_depth=depth,
        reference_point=_option_point("--reference-point", args.reference_point)
        if args.reference_point is not None else (0.0, 0.0, 0.0),
        disp_volume=_optional("--displaced-volume", args.displaced_volume, "m^3"),
        centre_of_buoyancy=_option_point("--centre-of-buoyancy", args.centre_of_buoyancy)
        if args.centre_of_buoyancy is not None else None,
        body=body,
        yaw_deg=_option_number("--yaw-deg", args.yaw_deg, "an angle [deg]")
        if args.yaw_deg is not None else 0.0,
    )


def _option_number(flag: str, text: str, expected: str, positive: bool = False) -> float:
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not math.isfinite(value) or (positive and value <= 0.0):
        raise CaseError(flag, "", expected, f"'{text}'")
    return value


def _optional(flag: str, text: str | None, unit: str) -> float | None:
    return None if text is None else _option_number(flag, text, f"a number > 0 [{unit}]",
                                                    positive=True)


def _option_point(flag: str, texts: list[str]) -> tuple[float, float, float]:
    x, y, z = (_option_number(flag, t, "three coordinates X Y Z [m]") for t in texts)
    return (x, y, z)


def _import_command(args: argparse.Namespace) -> str:
    """The import's command line (options as given), recorded for re-imports."""
    import shlex

    parts = ["floatmoor", "hydro", "import", *args.files, "-o", args.output]
    for flag, value in (("--water-density", args.water_density), ("--gravity", args.gravity),
                        ("--length-scale", args.length_scale),
                        ("--water-depth", args.water_depth),
                        ("--reference-point", args.reference_point),
                        ("--displaced-volume", args.displaced_volume),
                        ("--centre-of-buoyancy", args.centre_of_buoyancy),
                        ("--body", args.body), ("--yaw-deg", args.yaw_deg)):
        if value is not None:
            parts += [flag, *(value if isinstance(value, list) else [value])]
    return shlex.join(parts)


def _check(args: argparse.Namespace) -> int:
    from floatmoor.hydro.checks import check_values, run_checks

    path, ds, note = open_database(args.database)
    results = [check_values(ds), *run_checks(ds), *_drift_rows(ds)]
    ok = all(r.passed for r in results)
    if args.json:
        print(json.dumps({"database": str(path), "passed": ok, "staleness": note,
                          "checks": [r.as_dict() for r in results]}, indent=2))
    else:
        print(_checks_table(path, ds, note, results))
    return EXIT_OK if ok else EXIT_FAILED


def _checks_table(path: Path, ds, note: str, results, accepted: tuple[str, ...] = ()) -> str:
    """The table of ``hydro check`` (and ``hydro build``): one row per check; a failed check
    in ``accepted`` is marked as accepted."""
    rows = [f"{path}: {shown(ds.attrs.get('database', path.stem), 80)} ({note})",
            f"  {'check':<16}{'result':<8}{'worst':>11}{'tolerance':>11}  detail"]
    for r in results:
        if not r.applicable:
            rows.append(f"  {r.name:<16}{'n/a':<8}{'-':>11}{r.tolerance:>11.3g}  {r.detail}")
            continue
        result = "pass" if r.passed else "FAIL*" if r.name in accepted else "FAIL"
        rows.append(f"  {r.name:<16}{result:<8}{r.worst:>11.3g}{r.tolerance:>11.3g}  "
                    f"{r.detail}")
    skipped = sum(not r.applicable for r in results)
    if all(r.passed for r in results):
        rows.append("all checks pass" + (f" ({skipped} not applicable)" if skipped else ""))
    elif all(r.passed or r.name in accepted for r in results):
        rows.append("a check FAILED (* accepted by the case: [hydro] accept_failed_checks)")
    else:
        rows.append("a check FAILED")
    return "\n".join(rows)


