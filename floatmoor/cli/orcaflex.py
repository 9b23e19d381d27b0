"""``floatmoor import orcaflex MODEL.yml -o CASE.toml [--force]`` (added to the ``import`` subparsers
that :func:`floatmoor.cli.moordyn.add_moordyn_parsers` makes).

The output rules are those of ``import moordyn``: an existing file is refused unless
``--force``, and then only a case file is replaced; the output passes the checks of every
command (docs/guide/safeguards.md#output-files). The case is built and loaded in memory before
anything is written. Bad input is a CaseError (one message, status 2, nothing written); a
write that fails (disk full) is status 1.
"""

from __future__ import annotations

import argparse
import sys

__all__ = ["add_orcaflex_parser", "orcaflex_command"]

EXIT_OK, EXIT_FAILED = 0, 1


def add_orcaflex_parser(isub: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    """Add ``import orcaflex`` to the ``import`` subparsers."""
    p = isub.add_parser("orcaflex", help="an OrcaFlex text data file (.yml) -> a floatmoor "
                        "case file (the mooring)")
    p.add_argument("model", help="OrcaFlex text data file (.yml)")
    p.add_argument("-o", "--output", metavar="CASE.toml", required=True,
                   help="case file to write")
    p.add_argument("--force", action="store_true", help="replace an existing case file")
    p.set_defaults(moordyn_handler=orcaflex_command)


def orcaflex_command(args: argparse.Namespace) -> int:
    """Run ``import orcaflex``; CaseError propagates (status 2)."""
    from floatmoor.cli.moordyn import _check_output, _list, _write
    from floatmoor.io.orcaflex.importer import import_model
    from floatmoor.io.orcaflex.reader import read_model
    from floatmoor.io.output_files import OutputWriteError
    from floatmoor.io.output_kinds import CASE_FILE
    from floatmoor.terminal_text import shown

    output = _check_output(args.output, args.force, args.model, CASE_FILE)
    result = import_model(read_model(args.model), shown(args.model))
    try:
        _write(output, result.text)
    except OutputWriteError as err:
        print(f"floatmoor: import orcaflex failed: {err}; nothing written", file=sys.stderr)
        return EXIT_FAILED
    print(f"wrote {shown(output)} from {shown(args.model)}")
    _list("not imported", [shown(item) for item in result.not_imported])
    return EXIT_OK
