"""``python -m floatmoor.cli.case_reference``: write (``-o``), check (``--check``) or print the
case-file reference page (docs/reference/case_file.md), which
:func:`floatmoor.uq.input_reference.reference_page` generates from the readers.

Regenerate the page after a change to a loader or a description::

    python -m floatmoor.cli.case_reference -o docs/reference/case_file.md

(``--check`` exits 1 when the page differs; the test suite runs the same comparison).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Sequence

from floatmoor.uq.input_reference import PAGE, ROOT, reference_page

__all__ = ["main"]


def main(argv: Sequence[str] | None = None) -> int:
    """Write (``-o``) or check (``--check``) the page; print it without either."""
    parser = argparse.ArgumentParser(
        prog="python -m floatmoor.cli.case_reference",
        description="The case-file reference (docs/reference/case_file.md), generated from "
        "the readers.")
    parser.add_argument("-o", "--output", type=Path, help="write the page here")
    parser.add_argument("--check", action="store_true",
                        help=f"exit 1 if {PAGE} differs from the generated page")
    args = parser.parse_args(argv)
    text = reference_page()
    if args.check:
        current = (ROOT / PAGE).read_text(encoding="utf-8")
        if current != text:
            print(f"{PAGE} is out of date: regenerate it with python -m "
                  f"floatmoor.cli.case_reference -o {PAGE}", file=sys.stderr)
            return 1
        return 0
    if args.output:
        args.output.write_text(text, encoding="utf-8")
    else:
        sys.stdout.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
