"""``floatmoor hydro build | check | info`` (called from :mod:`floatmoor.cli`).

Exit statuses: 0 success (all checks pass), 1 a check fails, 2 bad input (a malformed case,
a case without [floater]/[hydro], a bad output path, or a missing, damaged or stale database).
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

from floatmoor.case.load import load_case
from floatmoor.errors import CaseError

__all__ = ["hydro_command", "resolve_database"]

EXIT_OK, EXIT_FAILED, EXIT_BAD_INPUT = 0, 1, 2


def hydro_command(args: argparse.Namespace) -> int:
    """Dispatch ``floatmoor hydro ...``; CaseError propagates to the main CLI (exit 2)."""
    from floatmoor.hydro.database import HydroDatabaseError

    try:
        if args.hydro_command == "build":
            return _build(args)
        if args.hydro_command == "check":
            return _check(args)
        return _info(args)
    except HydroDatabaseError as err:
        print(f"floatmoor: error: {err}", file=sys.stderr)
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
    from floatmoor.hydro.build import build_database
    from floatmoor.hydro.database import (
        HydroDatabaseError, database_path, load_for_case, write_database,
    )

    case = load_case(args.case, args.overrides)
    if case.floater is None or case.hydro is None:
        raise CaseError(args.case, "hydro", "a case with [floater] and [hydro] tables",
                        "none" if case.floater is None else "no [hydro] table")
    output = Path(args.output) if args.output else database_path(case)
    if args.output is not None and (output.is_dir() or not output.parent.is_dir()):
        raise CaseError("-o/--output", "", "a file in an existing folder", f"'{output}'")
    if output.exists() and not args.force:
        try:
            load_for_case(case, output)
        except HydroDatabaseError as err:
            print(f"floatmoor: rebuilding: {err}", file=sys.stderr)
        else:
            print(f"{output}: up to date for {args.case}; nothing to do (--force rebuilds)")
            return EXIT_OK

    def progress(done: int, total: int, omega: float, seconds: float) -> None:
        if not args.quiet:
            label = "inf" if math.isinf(omega) else f"{omega:.4g}"
            print(f"floatmoor: hydro {case.hydro.database}: {done} / {total} frequencies "
                  f"(omega = {label} rad/s, {seconds:.2f} s)", file=sys.stderr, flush=True)

    ds = build_database(case, progress=progress)
    write_database(ds, output)
    print(f"{output}: {ds.attrs['hull_panels']} hull + {ds.attrs['lid_panels']} lid panels "
          f"({ds.attrs['mesh_symmetry']}), {ds.sizes['omega']} frequencies + infinity, "
          f"{ds.sizes['wave_direction']} directions, built in {ds.attrs['build_seconds']:.1f} s")
    return EXIT_OK


def _open(text: str):
    """Read a database and, when its recorded case file is present, check it is up to date."""
    from floatmoor.hydro.database import HydroDatabaseError, read_database, stale_keys

    path = resolve_database(text)
    ds = read_database(path)
    note = "recorded case file not found: staleness not checked"
    source = Path(ds.attrs.get("case_file", ""))
    candidates = [source] + [p / source for p in [path.resolve().parent.parent]]
    for candidate in candidates:
        if str(source) and candidate.is_file():
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


def _check(args: argparse.Namespace) -> int:
    from floatmoor.hydro.checks import run_checks

    path, ds, note = _open(args.database)
    results = run_checks(ds)
    ok = all(r.passed for r in results)
    if args.json:
        print(json.dumps({"database": str(path), "passed": ok, "staleness": note,
                          "checks": [r.as_dict() for r in results]}, indent=2))
    else:
        print(f"{path}: {ds.attrs['database']} ({note})")
        print(f"  {'check':<16}{'result':<8}{'worst':>11}{'tolerance':>11}  detail")
        for r in results:
            print(f"  {r.name:<16}{'pass' if r.passed else 'FAIL':<8}{r.worst:>11.3g}"
                  f"{r.tolerance:>11.3g}  {r.detail}")
        print("all checks pass" if ok else "a check FAILED")
    return EXIT_OK if ok else EXIT_FAILED


def _info(args: argparse.Namespace) -> int:
    path, ds, note = _open(args.database)
    omega = ds["omega"].values
    import numpy as np

    a = ds.attrs
    print(f"{path}: {a['database']} ({note})")
    print(f"  floater {a['floater']} ({a['geometry_kind']}), case {a['case_file']}")
    print(f"  mesh: {a['hull_panels']} hull + {a['lid_panels']} lid panels, {a['mesh_symmetry']}, "
          f"panel size {a['panel_size']} m, lid depth {a['lid_depth']}, hash {a['mesh_hash'][:12]}")
    print(f"  {len(omega)} frequencies {omega[0]:.4g}-{omega[-1]:.4g} rad/s + infinity; "
          f"directions {', '.join(f'{d:g}' for d in np.degrees(ds['wave_direction'].values))} deg")
    print(f"  water depth {a['water_depth']} m (BEM: {a['bem_water_depth']}), density "
          f"{a['water_density']} kg/m^3, g {a['gravity']} m/s^2")
    print(f"  displaced volume {float(ds['disp_volume']):.6g} m^3, waterplane "
          f"{float(ds['waterplane_area']):.6g} m^2")
    print(f"  capytaine {a['capytaine_version']}, floatmoor {a['floatmoor_version']}, built "
          f"{a['created']} in {float(a['build_seconds']):.1f} s")
    return EXIT_OK
