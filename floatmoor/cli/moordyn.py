"""``floatmoor import moordyn DECK -o CASE.toml`` and ``floatmoor export moordyn CASE -o
DECK.dat`` (called from :mod:`floatmoor.cli`).

Both print what they could not map or represent and write it into the file's comments. An
existing output file is refused unless ``--force`` is given, and even then only a file of
the kind written is replaced (a case file, a MoorDyn input file); the output goes through the
checks of every command (docs/guide/safeguards.md#output-files). Bad input (a malformed deck
or case, a bad output path, a read-only folder) is a CaseError: one message, status 2,
nothing written; a write that fails (disk full) is status 1.
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

from floatmoor.errors import CaseError
from floatmoor.io.output_files import atomic_target, check_output_file, output_lock
from floatmoor.io.output_kinds import CASE_FILE, MOORDYN_DECK
from floatmoor.terminal_text import shown

__all__ = ["add_moordyn_parsers", "moordyn_command"]

EXIT_OK, EXIT_FAILED = 0, 1
#: Longest item of the printed lists kept whole [characters] (the file holds them whole).
_ITEM_LIMIT = 2000


def add_moordyn_parsers(
        sub: argparse._SubParsersAction) -> argparse._SubParsersAction:  # type: ignore[type-arg]
    """Add ``import moordyn`` and ``export moordyn`` to the top-level subparsers; the
    ``import`` subparsers, for the other importers."""
    imp = sub.add_parser("import", help="write a case file from another program's input file")
    isub = imp.add_subparsers(dest="import_format", required=True)
    imd = isub.add_parser("moordyn", help="a MoorDyn v2 input file -> a floatmoor case file")
    imd.add_argument("deck", help="MoorDyn input file")
    imd.add_argument("-o", "--output", metavar="CASE.toml", required=True,
                     help="case file to write")
    imd.add_argument("--water-depth", type=float, metavar="M",
                     help="water depth [m] when the deck has no WtrDpth (MoorDyn-F decks), or "
                     "to replace it")
    imd.add_argument("--driver", metavar="md_driver.inp",
                     help="MoorDyn driver file: its environment, TMax and motion (InputsFile, "
                     "initial pose) go into the case, the motion as a body-motion table")
    imd.add_argument("--motion-output", metavar="MOTION.csv",
                     help="body-motion table to write with --driver (default: CASE_motion.csv "
                     "beside the case)")
    imd.add_argument("--force", action="store_true", help="replace an existing output file")
    exp = sub.add_parser("export", help="write another program's input file from a case")
    esub = exp.add_subparsers(dest="export_format", required=True)
    emd = esub.add_parser("moordyn", help="a floatmoor case -> a MoorDyn v2 input file")
    emd.add_argument("case", help="TOML case file")
    emd.add_argument("--set", dest="overrides", action="append", default=[],
                     metavar="KEY=VALUE", help="override a case key (as for run)")
    emd.add_argument("-o", "--output", metavar="DECK.dat", required=True,
                     help="MoorDyn input file to write")
    emd.add_argument("--force", action="store_true", help="replace an existing output file")
    for p in (imd, emd):
        p.set_defaults(moordyn_handler=moordyn_command)
    return isub


def _check_output(text: str, force: bool, source: str, kind: tuple,
                  option: str = "-o/--output") -> Path:
    """The checked output: the checks of every command's output (writable folder with room,
    not the input file, not a link or device, only a file of its own kind replaced:
    :func:`floatmoor.io.output_files.check_output_file`), and a new file unless ``--force``."""
    path = Path(text)
    if os.path.lexists(path) and not path.is_dir() and not force:
        raise CaseError(option, "", "a new file (--force replaces an existing one)",
                        f"'{text}', which exists")
    return check_output_file(text, option, kind=kind,
                             protected={"input file": source}).path


def _write(path: Path, text: str) -> None:
    with output_lock(path), atomic_target(path) as tmp:
        tmp.write_text(text, encoding="utf-8")


def moordyn_command(args: argparse.Namespace) -> int:
    """Run ``import moordyn`` or ``export moordyn``; CaseError propagates (status 2)."""
    from floatmoor.io.output_files import OutputWriteError

    try:
        return _convert(args)
    except OutputWriteError as err:
        print(f"floatmoor: {args.command} moordyn failed: {err}; nothing written",
              file=sys.stderr)
        return EXIT_FAILED


def _convert(args: argparse.Namespace) -> int:
    if args.command == "import":
        from floatmoor.io.moordyn.importer import import_deck
        from floatmoor.io.moordyn.parser import read_deck

        output = _check_output(args.output, args.force, args.deck, CASE_FILE)
        if args.water_depth is not None and not args.water_depth > 0.0:
            raise CaseError("--water-depth", "", "a number > 0 [m]", repr(args.water_depth))
        if args.driver is not None or args.motion_output is not None:
            return _import_with_driver(args, output)
        result = import_deck(read_deck(args.deck), water_depth=args.water_depth)
        _write(output, result.text)
        print(f"wrote {shown(output)} from {shown(args.deck)}")
        _list("not mapped", result.unmapped)
        return EXIT_OK
    from floatmoor.case.load import load_case
    from floatmoor.io.moordyn.exporter import export_case
    from floatmoor.io.moordyn.writer import deck_text
    from floatmoor.mooring.deck_numerics import deck_numerics

    output = _check_output(args.output, args.force, args.case, MOORDYN_DECK)
    case = load_case(args.case, args.overrides)
    result = export_case(case, deck_numerics(case))
    _write(output, deck_text(result.deck, result.notes))
    print(f"wrote {output} from {args.case}")
    _list("notes (also in the file's title block)", result.notes)
    return EXIT_OK


def _import_with_driver(args: argparse.Namespace, output: Path) -> int:
    """``import moordyn DECK --driver DRIVER``: the case and its body-motion table."""
    from floatmoor.io.moordyn.driver import read_driver
    from floatmoor.io.moordyn.driver_import import MOTION_TABLE_HEADER, import_with_driver
    from floatmoor.io.moordyn.parser import read_deck

    if args.driver is None:
        raise CaseError("--motion-output", "", "--driver as well (the motion comes from the "
                        "driver's InputsFile)", "no --driver")
    table_name = (args.motion_output if args.motion_output is not None
                  else str(output.with_name(output.stem + "_motion.csv")))
    motion_table = ("body-motion table", (b"",), lambda path: None if _is_motion_table(
        Path(path), MOTION_TABLE_HEADER) else f"not a body-motion table (header "
        f"{MOTION_TABLE_HEADER})")
    table = _check_output(table_name, args.force, args.deck, motion_table, "--motion-output")
    for other in (args.driver, str(output)):
        if table.exists() and table.resolve() == Path(other).resolve() or \
                Path(table_name).absolute() == Path(other).absolute():
            raise CaseError("--motion-output", "", "a file other than the case and the "
                            "inputs", f"'{table_name}'")
    try:  # a case reads its tables from its own folder only (docs/guide/safeguards.md)
        relative = table.resolve().relative_to(output.resolve().parent).as_posix()
    except ValueError:
        raise CaseError("--motion-output", "", "a file in the case file's folder (a case "
                        "reads its tables from there)", f"'{table_name}'") from None
    result = import_with_driver(read_deck(args.deck), read_driver(args.driver),
                                motion_file_name=relative, water_depth=args.water_depth)
    if result.table is not None:
        _write(table, result.table)
    _write(output, result.text)
    print(f"wrote {output} from {args.deck} and {args.driver}"
          + (f", and its motion table {table}" if result.table is not None else ""))
    for line in result.summary:
        print(line)
    _list("not mapped", result.unmapped)
    return EXIT_OK


def _is_motion_table(path: Path, header: str) -> bool:
    """Whether ``path`` is a body-motion table (its first line that is not a comment)."""
    try:
        with path.open("r", encoding="utf-8") as stream:
            for _ in range(100):
                line = stream.readline()
                if not line:
                    return False
                if line.strip() and not line.lstrip().startswith("#"):
                    return line.strip().replace(" ", "") in (
                        header, header.replace("_rad", "_deg"))
    except (OSError, UnicodeDecodeError):
        return False
    return False


def _list(what: str, items: list[str]) -> None:
    if items:
        print(f"{what} ({len(items)}):")
        for item in items:
            print(f"  - {shown(item, _ITEM_LIMIT)}")  # deck text: bidi controls escaped
    else:
        print(f"{what}: none")
    sys.stdout.flush()
