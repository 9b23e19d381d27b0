"""``floatmoor rao CASE -o RAO.nc [--plot RAO.png]`` (registered by :mod:`floatmoor.cli`).

Computes the floater's response amplitude operators (:mod:`floatmoor.hydro.rao`) from its
up-to-date database, with its lines' linearised stiffness (``--no-mooring``: without) and
an optional linear damping per DOF (``--damping Surge=1.6e5``), prints the largest |RAO| of
each DOF and writes the RAOs (netCDF, units and long names, the conditions in the
attributes) and, on request, a plot. Exit 0; 2 on bad input (a case without [floater] and
[hydro], a database without excitation, a bad option or output path), nothing written.
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

import numpy as np

from floatmoor.case.load import load_case
from floatmoor.errors import CaseError

__all__ = ["add_rao_parser", "rao_command", "parse_damping"]

_DOFS = ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")


def add_rao_parser(sub, add_case) -> None:
    """The ``rao`` subcommand's options."""
    p = sub.add_parser("rao", help="response amplitude operators of a case's floater with its "
                       "mooring's linearised stiffness (from its hydrodynamic database)")
    add_case(p)
    p.add_argument("-o", "--output", metavar="RAO.nc", required=True,
                   help="netCDF file of the RAOs (a new file, or a RAO file to replace)")
    p.add_argument("--plot", metavar="RAO.png", help="plot |RAO| against the period")
    p.add_argument("--no-mooring", action="store_true",
                   help="leave out the mooring's linearised stiffness (free floating)")
    p.add_argument("--damping", action="append", default=[], metavar="DOF=VALUE",
                   help="extra linear damping on the diagonal, SI units (N s/m, N m s/rad), "
                   "e.g. --damping Surge=1.6e5; repeatable")


def parse_damping(items: list[str]) -> np.ndarray:
    """``DOF=VALUE`` items as a diagonal 6 x 6 damping matrix (CaseError naming the option)."""
    out = np.zeros((6, 6))
    for item in items:
        name, _, text = item.partition("=")
        try:
            value = float(text)
        except ValueError:
            value = math.nan
        if name not in _DOFS or not math.isfinite(value) or value < 0.0:
            raise CaseError("--damping", "", "DOF=VALUE with DOF one of "
                            f"{', '.join(_DOFS)} and VALUE >= 0 [SI]", f"'{item}'")
        out[_DOFS.index(name), _DOFS.index(name)] = value
    return out


def rao_command(args: argparse.Namespace) -> int:
    """Run ``floatmoor rao``; CaseError and HydroDatabaseError propagate (exit 2)."""
    from floatmoor.hydro.database import HydroDatabaseError, has_excitation, load_for_case
    from floatmoor.hydro.excitation_transfer import no_excitation_message
    from floatmoor.hydro.rao import RAO_FILE, rao_dataset, rao_for_case
    from floatmoor.io.netcdf import write_dataset
    from floatmoor.io.output_files import IMAGE, check_output_file

    case = load_case(args.case, args.overrides)
    if case.floater is None or case.hydro is None:
        raise CaseError(args.case, "floater", "a case with [floater] and [hydro] tables",
                        "none" if case.floater is None else "no [hydro] table")
    damping = parse_damping(args.damping)
    if not args.output.endswith(".nc"):
        raise CaseError("-o/--output", "", "a netCDF file RAO.nc", f"'{args.output}'")
    output = check_output_file(args.output, "-o/--output", kind=RAO_FILE,
                               protected={"case file": case.source}).path
    plot = None
    if args.plot is not None:
        from floatmoor.plots.style import SUPPORTED_FORMATS

        if Path(args.plot).suffix.lower() not in SUPPORTED_FORMATS:
            raise CaseError("--plot", "", "an image file (" + ", ".join(SUPPORTED_FORMATS)
                            + ")", f"'{args.plot}'")
        plot = check_output_file(args.plot, "--plot", kind=IMAGE,
                                 protected={"case file": case.source, "-o": output}).path
    ds = load_for_case(case)
    if not has_excitation(ds):
        raise HydroDatabaseError(no_excitation_message(ds))
    x, conditions = rao_for_case(case, ds, mooring=not args.no_mooring,
                                 linear_damping=damping if args.damping else None)
    write_dataset(rao_dataset(x, conditions, ds), output)
    if plot is not None:
        from floatmoor.plots.rao import plot_rao

        plot_rao(x, plot, title=f"RAOs of {case.floater.name} ({case.source})")
    amplitude = np.abs(x.values)
    period = 2.0 * np.pi / x["omega"].values
    print(f"{output}: RAOs of {case.floater.name}, {x.sizes['omega']} frequencies x "
          f"{x.sizes['wave_direction']} directions, mooring "
          f"{'left out' if args.no_mooring else f'{len(case.lines)} lines linearised'}")
    for i, dof in enumerate(_DOFS):
        k = np.unravel_index(int(np.argmax(amplitude[..., i])), amplitude[..., i].shape)
        unit = "m/m" if i < 3 else "deg/m"
        scale = 1.0 if i < 3 else 180.0 / math.pi
        print(f"  {dof:<6} max |RAO| {scale * amplitude[..., i][k]:.4g} {unit} at T = "
              f"{period[k[0]]:.4g} s, direction {math.degrees(x['wave_direction'].values[k[1]]):g}"
              " deg")
    if plot is not None:
        print(f"  plot: {plot}")
    sys.stdout.flush()
    return 0
