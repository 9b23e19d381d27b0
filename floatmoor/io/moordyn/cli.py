"""``floatmoor import moordyn DECK -o CASE.toml`` and ``floatmoor export moordyn CASE -o
DECK.dat`` (called from :mod:`floatmoor.cli`).

Both print what they could not map or represent and write it into the file's comments. An
existing output file is refused unless ``--force`` is given; bad input (a malformed deck or
case, a bad output path) is a CaseError: one message, status 2, nothing written.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from floatmoor.errors import CaseError
from floatmoor.io.output_files import atomic_target
from floatmoor.terminal_text import shown

__all__ = ["add_moordyn_parsers", "moordyn_command"]

EXIT_OK = 0


def add_moordyn_parsers(sub: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    """Add ``import moordyn`` and ``export moordyn`` to the top-level subparsers."""
    imp = sub.add_parser("import", help="write a case file from another program's input file")
    isub = imp.add_subparsers(dest="import_format", required=True)
    imd = isub.add_parser("moordyn", help="a MoorDyn v2 input file -> a floatmoor case file")
    imd.add_argument("deck", help="MoorDyn input file")
    imd.add_argument("-o", "--output", metavar="CASE.toml", required=True,
                     help="case file to write")
    imd.add_argument("--water-depth", type=float, metavar="M",
                     help="water depth [m] when the deck has no WtrDpth (MoorDyn-F decks), or "
                     "to replace it")
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


def _check_output(text: str, force: bool, source: str) -> Path:
    path = Path(text)
    if not text or text.endswith("/") or path.is_dir():
        raise CaseError("-o/--output", "", "a file name (not a folder)", f"'{text}'")
    if not path.parent.is_dir():
        raise CaseError("-o/--output", "", "a file in an existing folder", f"'{text}'")
    if path.exists() and path.resolve() == Path(source).resolve():
        raise CaseError("-o/--output", "", "a file other than the input file", f"'{text}'")
    if (path.exists() or path.is_symlink()) and not force:
        raise CaseError("-o/--output", "", "a new file (--force replaces an existing one)",
                        f"'{text}', which exists")
    return path


def _write(path: Path, text: str) -> None:
    with atomic_target(path) as tmp:
        tmp.write_text(text, encoding="utf-8")


def moordyn_command(args: argparse.Namespace) -> int:
    """Run ``import moordyn`` or ``export moordyn``; CaseError propagates (status 2)."""
    if args.command == "import":
        from floatmoor.io.moordyn.importer import import_deck
        from floatmoor.io.moordyn.parser import read_deck

        output = _check_output(args.output, args.force, args.deck)
        if args.water_depth is not None and not args.water_depth > 0.0:
            raise CaseError("--water-depth", "", "a number > 0 [m]", repr(args.water_depth))
        result = import_deck(read_deck(args.deck), water_depth=args.water_depth)
        _write(output, result.text)
        print(f"wrote {output} from {args.deck}")
        _list("not mapped", result.unmapped)
        return EXIT_OK
    from floatmoor.case.load import load_case
    from floatmoor.io.moordyn.exporter import export_case
    from floatmoor.io.moordyn.writer import deck_text

    output = _check_output(args.output, args.force, args.case)
    case = load_case(args.case, args.overrides)
    result = export_case(case)
    _write(output, deck_text(result.deck, result.notes))
    print(f"wrote {output} from {args.case}")
    _list("notes (also in the file's title block)", result.notes)
    return EXIT_OK


def _list(what: str, items: list[str]) -> None:
    if items:
        print(f"{what} ({len(items)}):")
        for item in items:
            print(f"  - {shown(item)}")  # quotes the deck's text: escaped, bounded
    else:
        print(f"{what}: none")
    sys.stdout.flush()
