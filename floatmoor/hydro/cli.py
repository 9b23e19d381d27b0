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
``--force`` is exit 2 with one line, and nothing is written. ``hydro info`` says where a database came from.

Size: the five ``hydro`` subcommands share the option parsing, the output checks and the
checks table; split, each would import the others.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

from floatmoor.case.load import load_case
from floatmoor.errors import CaseError
from floatmoor.terminal_text import MESSAGE_LIMIT, shown

__all__ = ["hydro_command", "resolve_database"]

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
            return _fit_state_space(args)
        return _info(args)
    except (HydroDatabaseError, BemFileError) as err:
        print(f"floatmoor: error: {shown(err, MESSAGE_LIMIT)}", file=sys.stderr)
        return EXIT_BAD_INPUT


def resolve_database(text: str) -> Path:
    """A path as given if it names a file or ends in .nc, else ``hydrodb/NAME.nc`` in the
    current folder or the nearest parent that has a hydrodb folder."""
    path = Path(text)
    if path.suffix == ".nc" or path.is_file() or len(path.parts) > 1:
        return path
    for folder in [Path.cwd(), *Path.cwd().parents]:
        if (folder / "hydrodb").is_dir():
            return folder / "hydrodb" / f"{text}.nc"
    return Path("hydrodb") / f"{text}.nc"


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
                      f"{_drift_seconds(ds)} s")
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


def _drift_seconds(ds) -> str:
    try:
        return f"{float(json.loads(ds.attrs['drift_json'])['drift_seconds']):.1f}"
    except (KeyError, TypeError, ValueError):
        return "?"


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
    second = _second_order_lines(ds)
    if second:
        _say("\n".join(second))
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


def _open(text: str):
    """Read a database and check it is up to date: with its recorded case file when present
    in the database's project (built), with its recorded source files where present there
    (imported); a recorded path out of the project is not looked at."""
    from floatmoor.hydro.database import (
        HydroDatabaseError, inside_project, is_imported, read_database, stale_keys,
    )

    path = resolve_database(text)
    ds = read_database(path)
    if is_imported(ds):
        return path, ds, _imported_note(path, ds)
    note = ("recorded case file not found: staleness not checked (looked for in the "
            "database's project only)")
    candidate = inside_project(ds, ds.attrs.get("case_file"))
    for candidate in [candidate] if candidate is not None else []:
        if candidate.is_file():
            try:
                case = load_case(candidate)
            except CaseError as err:
                raise HydroDatabaseError(f"{path}: its case file no longer loads: {err}") from None
            if case.floater is None or case.hydro is None:
                break
            differ = stale_keys(ds, case)
            if differ:
                raise HydroDatabaseError(f"{path}: stale hydrodynamic database for {candidate}: "
                                         f"recorded inputs differ in {', '.join(differ)}")
            note = f"up to date with {candidate}"
            break
    return path, ds, note


def _imported_note(path: Path, ds) -> str:
    """Whether an imported database's source files are unchanged (HydroDatabaseError when
    one present at its recorded path is not)."""
    from floatmoor.hydro.database import (
        REIMPORT_ADVICE, HydroDatabaseError, changed_source_files, located_source_file,
        source_files,
    )

    changed = changed_source_files(ds)
    if changed:
        raise HydroDatabaseError(f"{path}: stale hydrodynamic database: source file "
                                 f"{', '.join(changed)} changed since the import (size or "
                                 f"SHA-256 differs); {REIMPORT_ADVICE}")
    records = source_files(ds)
    found = sum(located_source_file(ds, r) is not None for r in records)
    if found == len(records):
        return "source files unchanged since the import"
    if found == 0:
        return ("source files not found: staleness not checked (looked for in the "
                "database's project only)")
    return f"{found} of {len(records)} source files found, unchanged since the import"


def _check(args: argparse.Namespace) -> int:
    from floatmoor.hydro.checks import check_values, run_checks

    path, ds, note = _open(args.database)
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


def _fit_state_space(args: argparse.Namespace) -> int:
    """Fit the realisation from the stored BEM data and write it into the same file, or a new
    one with ``-o``: the BEM variables and recorded inputs stay as they are (the database
    stays up to date). A realisation already in the file, or an existing ``-o`` file, is
    replaced only with ``--force``: a committed database is never rewritten unasked (a refit
    on other library versions can choose other orders)."""
    from floatmoor.hydro import state_space as ss
    from floatmoor.hydro.database import database_path, load_for_case, write_database
    from floatmoor.io.output_files import output_lock

    rtol = ss.KERNEL_RTOL if args.tolerance is None else args.tolerance
    max_order = ss.MAX_ORDER if args.max_order is None else args.max_order
    if not (math.isfinite(rtol) and 0.0 < rtol < 1.0):
        raise CaseError("--tolerance", "", "a number between 0 and 1", str(args.tolerance))
    if not 1 <= max_order <= ss.HANKEL_ROWS:
        raise CaseError("--max-order", "", f"a whole number from 1 to {ss.HANKEL_ROWS}",
                        str(args.max_order))
    if args.database.endswith(".toml"):
        case = load_case(args.database)
        if case.floater is None or case.hydro is None:
            raise CaseError(args.database, "hydro", "a case with [floater] and [hydro] tables",
                            "none" if case.floater is None else "no [hydro] table")
        path = database_path(case)
        ds = load_for_case(case, path, checks=False)  # fitting does not need them to pass
    else:
        path, ds, _ = _open(args.database)
    target = _fit_target(args, path, ds)
    realisation = ss.fit_state_space(ds, rtol=rtol, max_order=max_order)
    summary = realisation.summary()
    missed = [p for p in realisation.pairs if not p.within_tolerance]
    if args.json:
        print(json.dumps({"database": str(path), "written": not missed, **summary}, indent=2))
    else:
        print(f"{path}: state-space realisation of K(t), {len(realisation.pairs)} pairs, "
              f"{realisation.n_states} states, fitted in {realisation.fit_seconds:.1f} s")
        print(_pairs_table(realisation, rtol))
    if missed:
        names = ", ".join(f"{ss.DOFS[p.radiating]}-{ss.DOFS[p.influenced]}" for p in missed)
        print(f"floatmoor: no realisation within {rtol:g} up to order {max_order} for {names}; "
              f"nothing written (raise --max-order or --tolerance)", file=sys.stderr)
        return EXIT_FAILED
    with output_lock(target):
        write_database(ss.add_to_dataset(ds, realisation), target)
    if not args.json:
        print(f"written to {target}")
    return EXIT_OK


def _fit_target(args: argparse.Namespace, source: Path, ds) -> Path:
    """Where ``fit-state-space`` may write, checked before the fit: the database itself when
    it holds no realisation (variables are added, nothing is replaced), else only with
    ``--force``; an ``-o`` file in an existing folder, not over an existing file unless
    ``--force``."""
    from floatmoor.hydro import state_space as ss

    if args.output is None:
        held = ss.read_state_space(ds) if ss.has_state_space(ds) else None
        if held is not None and not args.force:
            raise CaseError(str(source), "state_space_*", "a database without a state-space "
                            "realisation (--force replaces it, -o PATH.nc writes a copy)",
                            f"a realisation of {held.n_states} states fitted {held.created}")
        return source
    target = Path(args.output)
    if target.is_dir() or not target.parent.is_dir():
        raise CaseError("-o/--output", "", "a file in an existing folder", f"'{target}'")
    if target.exists() and not args.force:
        raise CaseError("-o/--output", "", "a new file (--force overwrites)",
                        f"the existing file '{target}'")
    from floatmoor.io.output_files import check_output_file
    from floatmoor.io.output_kinds import HYDRO_DATABASE_FILE

    return check_output_file(args.output, "-o/--output", kind=HYDRO_DATABASE_FILE,
                             protected={"database fitted": source}).path


def _pairs_table(realisation, rtol: float | None = None) -> str:
    from floatmoor.hydro.state_space import DOFS

    rows = [f"    {'pair':<14}{'order':>6}{'K error':>10}{'B error':>10}{'A error':>10}"
            f"{'min B':>11}  passivity"]
    for p in realisation.pairs:
        passive = "-" if p.radiating != p.influenced else (
            "enforced" if p.passivity_enforced else "as fitted")
        min_b = "-" if p.radiating != p.influenced else f"{p.min_damping:.1e}"
        rows.append(f"    {DOFS[p.radiating] + '-' + DOFS[p.influenced]:<14}{p.order:>6}"
                    f"{p.kernel_error:>10.2e}{p.damping_error:>10.2e}"
                    f"{p.added_mass_error:>10.2e}{min_b:>11}  {passive}")
    tol = f" (tolerance {rtol:g})" if rtol is not None else ""
    rows.append(f"    K error: relative L2 over the truncation time{tol}; B, A error: largest "
                "over the BEM band / peak; min B: smallest B_fit / largest (diagonal pairs)")
    rows.append(f"    coupled 6 x 6 B_fit: smallest scaled eigenvalue "
                f"{realisation.matrix_min_damping:.2e} (>= 0: passive); ERA modes dropped "
                f"{sum(p.dropped for p in realisation.pairs)}, unstable poles reflected "
                f"{sum(p.reflected for p in realisation.pairs)}")
    return "\n".join(rows)


def _attr(ds, name: str, limit: int = 200) -> str:
    """Recorded attribute ``name`` as text for a terminal (:func:`shown`: a database is data
    from elsewhere), or "not recorded"."""
    return shown(ds.attrs[name], limit) if name in ds.attrs else "not recorded"


def _say(text: str) -> None:
    """Print a line quoting database attributes (file text): escaped, bounded (shown)."""
    print("\n".join(shown(line, MESSAGE_LIMIT) for line in str(text).split("\n")))


def _seconds(ds) -> str:
    try:
        return f"{float(ds.attrs['build_seconds']):.1f}"
    except (KeyError, TypeError, ValueError):
        return _attr(ds, "build_seconds", 40)


def _info(args: argparse.Namespace) -> int:
    from floatmoor.hydro.database import (
        EXCITATION_VARIABLES, database_source, has_excitation, is_imported,
    )

    path, ds, note = _open(args.database)
    omega = ds["omega"].values
    import numpy as np

    def a(name: str, limit: int = 200) -> str:
        return _attr(ds, name, limit)

    print(f"{path}: {a('database', 80)} ({note})")
    if is_imported(ds):
        _say(_import_info(ds))
    else:
        print(f"  source: capytaine ('floatmoor hydro build' of {a('case_file')}), "
              f"capytaine {a('capytaine_version', 40)}, floatmoor {a('floatmoor_version', 40)}"
              f", built {a('created', 40)} in {_seconds(ds)} s")
        print(f"  floater {a('floater', 80)} ({a('geometry_kind', 40)}), case {a('case_file')}")
        print(f"  mesh: {a('hull_panels', 40)} hull + {a('lid_panels', 40)} lid panels, "
              f"{a('mesh_symmetry', 40)}, panel size {a('panel_size', 40)} m, lid depth "
              f"{a('lid_depth', 40)}, hash {a('mesh_hash', 80)[:12]}")
        print(f"  build settings: {a('build_settings_json')}")
    a_inf = a("added_mass_infinite_source") if "added_mass_infinite_source" in ds.attrs else \
        "capytaine (omega = infinity solved)"
    print(f"  {len(omega)} frequencies {omega[0]:.4g}-{omega[-1]:.4g} rad/s; A_inf: {a_inf}")
    if has_excitation(ds):
        held = [v for v in EXCITATION_VARIABLES if v in ds.variables]
        _say(f"  excitation: {', '.join(held)}; directions "
              f"{', '.join(f'{d:g}' for d in np.degrees(ds['wave_direction'].values))} deg")
    else:
        _say(f"  excitation: none (from {database_source(ds)} files without it): a run with "
              "waves refuses this database; still water and wind only run")
    print(f"  water depth {a('water_depth', 40)} m (BEM: {a('bem_water_depth', 40)}), density "
          f"{a('water_density', 40)} kg/m^3, g {a('gravity', 40)} m/s^2")
    print(f"  displaced volume {float(ds['disp_volume']):.6g} m^3, waterplane "
          f"{float(ds['waterplane_area']):.6g} m^2, rotation centre "
          f"{', '.join(f'{v:g}' for v in ds['rotation_center'].values)} m")
    _say(_state_space_info(ds))
    from floatmoor.hydro.drift_build import has_drift

    from floatmoor.hydro.drift_build import drift_is_imported

    if drift_is_imported(ds) or "qtf_difference" in ds.variables:
        _say("\n".join(_second_order_lines(ds)))
    elif has_drift(ds):
        print(f"  mean drift: far and near field with the recorded RAOs ('hydro build --drift', "
              f"{_drift_seconds(ds)} s); 'hydro check' compares them")
    else:
        print("  mean drift: none ('floatmoor hydro build CASE --drift' adds it)")
    return EXIT_OK


def _second_order_lines(ds) -> list[str]:
    """What imported second-order data a database holds and where it came from (recorded
    text: the caller prints it escaped and bounded)."""
    import numpy as np

    rows = []
    routes = [(v, label) for v, label in (("mean_drift_far_field", "far field (momentum)"),
                                          ("mean_drift_near_field", "near field (pressure)"))
              if v in ds.variables]
    if routes:
        rows.append(f"  mean drift imported from {ds.attrs.get('drift_source', '?')} files (the "
                    "source program's RAOs; current while its files are unchanged): "
                    + "; ".join(f"{label} from {ds[v].attrs.get('drift_source', '?')}"
                                for v, label in routes)
                    + ("; 'hydro check' compares them" if len(routes) == 2 else ""))
    if "qtf_difference" in ds.variables:
        source = ds["qtf_difference"].attrs.get("qtf_source", "?")
        try:
            omega = np.asarray(ds["qtf_omega_1"].values, dtype=float)
            n_dir = int(ds.sizes["qtf_direction"])
            rows.append(f"  difference-frequency QTF: {len(omega)} x {len(omega)} frequencies "
                        f"{omega[0]:.4g}-{omega[-1]:.4g} rad/s, {n_dir} "
                        f"direction{'s' if n_dir > 1 else ''}, from {source}")
        except (KeyError, IndexError, TypeError, ValueError):  # written by another hand
            rows.append(f"  difference-frequency QTF from {source} (its frequencies or "
                        "directions are not readable)")
    return rows


def _import_info(ds) -> str:
    """Where an imported database came from: format, files with sizes and SHA-256, options,
    the reader's notes, and the recorded import command, shown as recorded text (escaped,
    bounded) and never as a command to run."""
    from floatmoor.hydro.database import recorded_json, source_files

    body = _attr(ds, "body_name", 80) if ds.attrs.get("body_name") else ""
    rows = [f"  source: {_attr(ds, 'source', 40)} files, imported by "
            f"{_attr(ds, 'importer', 80)} at {_attr(ds, 'created', 40)}"
            + (f", body {body}" if body else "")]
    for record in source_files(ds):
        rows.append(f"    {shown(record.get('path'), 200)}  {shown(record.get('size'), 40)} "
                    f"bytes  SHA-256 {shown(record.get('sha256'), 64)}")
    options = recorded_json(ds, "import_options_json", {})
    given = ", ".join(f"{k} {v}" for k, v in sorted(options.items()) if v is not None) \
        if isinstance(options, dict) else str(options)
    rows.append(f"  import options: {shown(given or 'none')}")
    if ds.attrs.get("import_command"):
        rows.append(f"  recorded import command (text from the file, not checked): "
                    f"{_attr(ds, 'import_command', 400)}")
    notes = recorded_json(ds, "import_notes_json", [])
    for note in notes if isinstance(notes, list) else [notes]:
        rows.append(f"  note: {shown(note)}")
    return "\n".join(rows)


def _state_space_info(ds) -> str:
    from floatmoor.hydro import state_space as ss

    realisation = ss.read_state_space(ds)
    if realisation is None:
        return ("  state-space radiation: none (add it with 'floatmoor hydro fit-state-space "
                f"{shown(ds.attrs.get('database', 'NAME'), 80)}')")
    try:
        stale = ss.stale_reasons(ds, realisation)
    except (TypeError, ValueError, AttributeError):  # recorded settings of another shape
        stale = ["its recorded K(t) settings are not readable"]
    status = "up to date with the database's K(t)" if not stale else \
        "STALE (refit with 'floatmoor hydro fit-state-space'): " + shown("; ".join(stale))
    rtol = realisation.settings.get("kernel_rtol")
    head = (f"  state-space radiation: {len(realisation.pairs)} pairs, {realisation.n_states} "
            f"states, worst K error {realisation.worst_kernel_error:.2e}, fitted "
            f"{realisation.created}; {status}")
    return head + "\n" + _pairs_table(realisation, rtol)
