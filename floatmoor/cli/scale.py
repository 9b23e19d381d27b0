"""``floatmoor scale CASE --length-scale LAMBDA ... -o NEW.toml``: the scaled case file.

Bad arguments and cases the scaling cannot rewrite are CaseErrors (one message, status 2,
nothing written). ``-o`` replaces only a case file
(:data:`floatmoor.io.output_kinds.CASE_FILE`; docs/guide/safeguards.md#output-files).
"""

from __future__ import annotations

import argparse
import math
import os
import sys

from floatmoor.case.load import load_case
from floatmoor.errors import CaseError
from floatmoor.io.output_files import atomic_target, check_output_file
from floatmoor.io.output_kinds import CASE_FILE
from floatmoor.similitude.case_scaling import scale_case_file
from floatmoor.similitude.laws import SAME_FACTOR, ScaleLaw, froude_volume_coefficient_ratio

__all__ = ["scale_command", "law_from_arguments"]


#: Range of a scale factor (--length-scale, --diameter-scale, --volume-coefficient-ratio):
#: model tests use 1/10 to 1/100, a prototype 10 to 100 times a model. Quantities scale with
#: up to the fifth power of a factor (a moment of inertia: lambda^5), which for 1e308 (or for
#: 1e150 squared by the elastic match) overflowed with a traceback; 1e6^5 = 1e30 stays finite.
MAX_SCALE_FACTOR = 1.0e6


def _positive(text: str | None, option: str, unit: str = "-",
              bound: float | None = MAX_SCALE_FACTOR) -> float | None:
    if text is None:
        return None
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if bound is None:
        if not (math.isfinite(value) and value > 0.0):
            raise CaseError(option, "", f"a finite number > 0 [{unit}]", f"'{text}'")
    elif not 1.0 / bound <= value <= bound:
        raise CaseError(option, "", f"a number from {1.0 / bound:g} to {bound:g} [{unit}] "
                        "(floatmoor.cli.scale.MAX_SCALE_FACTOR)", f"'{text}'")
    return value


def law_from_arguments(args: argparse.Namespace, water_density: float) -> ScaleLaw:
    """The law the options ask for (``water_density``: the case's, for ``--water-density``)."""
    length = _positive(args.length_scale, "--length-scale")
    diameter = _positive(args.diameter_scale, "--diameter-scale")
    phi = _positive(args.volume_coefficient_ratio, "--volume-coefficient-ratio")
    rho = _positive(args.water_density, "--water-density", "kg/m^3", bound=None)
    assert length is not None  # required by the parser
    beta = length if diameter is None else diameter
    ratio = 1.0 if rho is None else rho / water_density
    match = args.match
    if phi is None and match is None:
        if not math.isclose(beta, length, rel_tol=SAME_FACTOR):
            raise CaseError("--diameter-scale", "", "with a diameter scale other than the "
                            "length scale, how the line mass scales: --volume-coefficient-"
                            "ratio PHI or --match froude|elastic", "neither")
        match = "froude"
    if match == "froude":
        return ScaleLaw(length, beta, froude_volume_coefficient_ratio(length, beta, ratio),
                        ratio, "froude")
    if match == "elastic":
        return ScaleLaw(length, beta, 1.0, ratio, "elastic")
    assert phi is not None
    return ScaleLaw(length, beta, phi, ratio, "given")


def scale_command(args: argparse.Namespace) -> int:
    """Run ``floatmoor scale``; CaseError propagates (status 2)."""
    case = load_case(args.case)
    law = law_from_arguments(args, case.environment.water_density)
    output = check_output_file(args.output, "-o/--output", kind=CASE_FILE,
                               protected={"case file": args.case})
    scaled = scale_case_file(args.case, law, output=output.path,
                             keep_coefficients=args.keep_coefficients,
                             hydro_database=args.hydro_database)
    for table in scaled.tables:
        if os.path.lexists(table.path):
            raise CaseError(args.case, "motion.file", f"a free file name for the scaled "
                            f"motion table {table.path} (floatmoor scale does not overwrite "
                            "one: move it away or choose another -o name)", "an existing file")
    if output.replaces:
        print(f"floatmoor: replacing the existing {output.path}", file=sys.stderr)
    for table in scaled.tables:  # first, so that the case never names a missing table
        with atomic_target(table.path) as tmp:
            tmp.write_text(table.text, encoding="utf-8")
    with atomic_target(output.path) as tmp:
        tmp.write_text(scaled.text, encoding="utf-8")
    print(f"wrote {output.path} from {args.case}: lambda = {law.length:.6g}, beta = "
          f"{law.diameter:.6g}, phi = {law.volume_coefficient:.6g} ({law.name})")
    for table in scaled.tables:
        print(f"wrote {table.path} from {table.source} (the motion table, scaled)")
    print("groups kept exactly: " + (", ".join(scaled.kept) or "none"))
    for name, (lo, hi) in scaled.changed.items():
        span = f"{lo:.4g}" if math.isclose(lo, hi) else f"{lo:.4g} to {hi:.4g}"
        print(f"not kept: {name}, new / old = {span}")
    for note in scaled.notes:
        print(note)
    return 0
