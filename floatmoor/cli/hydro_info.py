"""``floatmoor hydro info NAME`` (what a database holds and where its data came from) and
``floatmoor hydro fit-state-space NAME`` (a state-space realisation of its radiation
kernel); the opening of a named database and the descriptions that ``hydro import`` prints
too (:mod:`floatmoor.cli.hydro` dispatches the ``hydro`` subcommands).

Exit statuses as :mod:`floatmoor.cli.hydro`'s: 0 done, 1 no state-space fit within the
tolerance (nothing written), 2 bad input.
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

__all__ = ["info_command", "fit_state_space_command", "resolve_database", "open_database",
           "say", "second_order_lines", "drift_seconds"]

EXIT_OK, EXIT_FAILED = 0, 1


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


def open_database(text: str):
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


def fit_state_space_command(args: argparse.Namespace) -> int:
    """Fit the realisation from the stored BEM data and write it into the same file, or a new
    one with ``-o``: the BEM variables and recorded inputs stay as they are (the database
    stays up to date). A realisation already in the file, or an existing ``-o`` file, is
    replaced only with ``--force``: a committed database is never rewritten unasked (a refit
    on other library versions can choose other orders)."""
    from floatmoor.hydro.database import database_path, load_for_case, write_database
    from floatmoor.hydro.state_space.fit import fit_state_space
    from floatmoor.hydro.state_space.kernel_fit import HANKEL_ROWS, KERNEL_RTOL, MAX_ORDER
    from floatmoor.hydro.state_space.realisation import DOFS
    from floatmoor.hydro.state_space.storage import add_to_dataset
    from floatmoor.io.output_files import output_lock

    rtol = KERNEL_RTOL if args.tolerance is None else args.tolerance
    max_order = MAX_ORDER if args.max_order is None else args.max_order
    if not (math.isfinite(rtol) and 0.0 < rtol < 1.0):
        raise CaseError("--tolerance", "", "a number between 0 and 1", str(args.tolerance))
    if not 1 <= max_order <= HANKEL_ROWS:
        raise CaseError("--max-order", "", f"a whole number from 1 to {HANKEL_ROWS}",
                        str(args.max_order))
    if args.database.endswith(".toml"):
        case = load_case(args.database)
        if case.floater is None or case.hydro is None:
            raise CaseError(args.database, "hydro", "a case with [floater] and [hydro] tables",
                            "none" if case.floater is None else "no [hydro] table")
        path = database_path(case)
        ds = load_for_case(case, path, checks=False)  # fitting does not need them to pass
    else:
        path, ds, _ = open_database(args.database)
    target = _fit_target(args, path, ds)
    realisation = fit_state_space(ds, rtol=rtol, max_order=max_order)
    summary = realisation.summary()
    missed = [p for p in realisation.pairs if not p.within_tolerance]
    if args.json:
        print(json.dumps({"database": str(path), "written": not missed, **summary}, indent=2))
    else:
        print(f"{path}: state-space realisation of K(t), {len(realisation.pairs)} pairs, "
              f"{realisation.n_states} states, fitted in {realisation.fit_seconds:.1f} s")
        print(_pairs_table(realisation, rtol))
    if missed:
        names = ", ".join(f"{DOFS[p.radiating]}-{DOFS[p.influenced]}" for p in missed)
        print(f"floatmoor: no realisation within {rtol:g} up to order {max_order} for {names}; "
              f"nothing written (raise --max-order or --tolerance)", file=sys.stderr)
        return EXIT_FAILED
    with output_lock(target):
        write_database(add_to_dataset(ds, realisation), target)
    if not args.json:
        print(f"written to {target}")
    return EXIT_OK


def _fit_target(args: argparse.Namespace, source: Path, ds) -> Path:
    """Where ``fit-state-space`` may write, checked before the fit: the database itself when
    it holds no realisation (variables are added, nothing is replaced), else only with
    ``--force``; an ``-o`` file in an existing folder, not over an existing file unless
    ``--force``."""
    from floatmoor.hydro.state_space.storage import has_state_space, read_state_space

    if args.output is None:
        held = read_state_space(ds) if has_state_space(ds) else None
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
    from floatmoor.hydro.state_space.realisation import DOFS

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


def say(text: str) -> None:
    """Print a line quoting database attributes (file text): escaped, bounded (shown)."""
    print("\n".join(shown(line, MESSAGE_LIMIT) for line in str(text).split("\n")))


def _seconds(ds) -> str:
    try:
        return f"{float(ds.attrs['build_seconds']):.1f}"
    except (KeyError, TypeError, ValueError):
        return _attr(ds, "build_seconds", 40)


def drift_seconds(ds) -> str:
    """The recorded seconds the mean drift took to compute, as text (``?`` when unknown)."""
    try:
        return f"{float(json.loads(ds.attrs['drift_json'])['drift_seconds']):.1f}"
    except (KeyError, TypeError, ValueError):
        return "?"


def info_command(args: argparse.Namespace) -> int:
    """``floatmoor hydro info``: describe a database and where its data came from."""
    from floatmoor.hydro.database import (
        EXCITATION_VARIABLES, database_source, has_excitation, is_imported,
    )

    path, ds, note = open_database(args.database)
    omega = ds["omega"].values
    import numpy as np

    def a(name: str, limit: int = 200) -> str:
        return _attr(ds, name, limit)

    print(f"{path}: {a('database', 80)} ({note})")
    if is_imported(ds):
        say(_import_info(ds))
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
        say(f"  excitation: {', '.join(held)}; directions "
              f"{', '.join(f'{d:g}' for d in np.degrees(ds['wave_direction'].values))} deg")
    else:
        say(f"  excitation: none (from {database_source(ds)} files without it): a run with "
              "waves refuses this database; still water and wind only run")
    print(f"  water depth {a('water_depth', 40)} m (BEM: {a('bem_water_depth', 40)}), density "
          f"{a('water_density', 40)} kg/m^3, g {a('gravity', 40)} m/s^2")
    print(f"  displaced volume {float(ds['disp_volume']):.6g} m^3, waterplane "
          f"{float(ds['waterplane_area']):.6g} m^2, rotation centre "
          f"{', '.join(f'{v:g}' for v in ds['rotation_center'].values)} m")
    say(_state_space_info(ds))
    from floatmoor.hydro.drift_build import has_drift

    from floatmoor.hydro.drift_build import drift_is_imported

    if drift_is_imported(ds) or "qtf_difference" in ds.variables:
        say("\n".join(second_order_lines(ds)))
    elif has_drift(ds):
        print(f"  mean drift: far and near field with the recorded RAOs ('hydro build --drift', "
              f"{drift_seconds(ds)} s); 'hydro check' compares them")
    else:
        print("  mean drift: none ('floatmoor hydro build CASE --drift' adds it)")
    return EXIT_OK


def second_order_lines(ds) -> list[str]:
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
    from floatmoor.hydro.state_space.fit import stale_reasons
    from floatmoor.hydro.state_space.storage import read_state_space

    realisation = read_state_space(ds)
    if realisation is None:
        return ("  state-space radiation: none (add it with 'floatmoor hydro fit-state-space "
                f"{shown(ds.attrs.get('database', 'NAME'), 80)}')")
    try:
        stale = stale_reasons(ds, realisation)
    except (TypeError, ValueError, AttributeError):  # recorded settings of another shape
        stale = ["its recorded K(t) settings are not readable"]
    status = "up to date with the database's K(t)" if not stale else \
        "STALE (refit with 'floatmoor hydro fit-state-space'): " + shown("; ".join(stale))
    rtol = realisation.settings.get("kernel_rtol")
    head = (f"  state-space radiation: {len(realisation.pairs)} pairs, {realisation.n_states} "
            f"states, worst K error {realisation.worst_kernel_error:.2e}, fitted "
            f"{realisation.created}; {status}")
    return head + "\n" + _pairs_table(realisation, rtol)
