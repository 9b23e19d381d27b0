"""The ``floatmoor`` command's parser and entry points (:func:`main`, :func:`run`): the
top-level parser with every command's options, and the dispatch of a parsed command to its
module (:mod:`floatmoor.cli`).
"""

from __future__ import annotations

import argparse
import os
import sys
from contextlib import contextmanager
from typing import Iterator, Sequence

from floatmoor._version import __version__
from floatmoor.cli.campaign import sweep_command
from floatmoor.cli.check import check_command
from floatmoor.cli.run_case import run_command
from floatmoor.cli.status import (
    EXIT_BAD_INPUT, EXIT_BROKEN_PIPE, EXIT_FAILED, EXIT_INTERRUPTED, STARTUP_INTERRUPTED,
    error_line,
)
from floatmoor.cli.study import study_command
from floatmoor.cli.uq import uq_command
from floatmoor.errors import CaseError, FloatmoorError
from floatmoor.signals import exit_status, interrupt_handling, signal_name

__all__ = ["main", "run"]

#: ``hydro import --yaw-deg`` (the importer's note says the same of the angle applied,
#: floatmoor.hydro.importing.yaw_note).
YAW_HELP = ("the angle [deg] the WAMIT/BEMIO body frame is turned about z into the case's "
            "frame, positive counter-clockwise seen from above (+x towards +y): the file's "
            "+x axis points along (cos DEG, sin DEG) of the case; every coefficient turns "
            "with it, and a wave the file computed at heading BETA (travelling towards BETA) "
            "is the case's wave travelling towards BETA + DEG (waves.direction_deg). "
            "Example: --yaw-deg 180 for a hull with an offset column on the file's -x that "
            "the case puts on +x; the file's heading 0 is then the case's direction_deg = "
            "180 (waves from +x). Default 0")


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="floatmoor", description=(
        "Time-domain simulation of floating structures and their mooring lines."))
    parser.add_argument("--version", action="version", version=f"floatmoor {__version__}")
    sub = parser.add_subparsers(dest="command", required=True)

    def add_case(p: argparse.ArgumentParser) -> None:
        p.add_argument("case", help="TOML case file")
        p.add_argument("--set", dest="overrides", action="append", default=[],
                       metavar="KEY=VALUE", help="override a key, VALUE written as a TOML value "
                       "(e.g. --set motion.period=3.5, --set 'lines.chain.model=\"quasi-static\"'; "
                       "entries of [[lines]] by name, all of them by *: lines.*.model)")

    check = sub.add_parser("check", help="validate a case and print derived quantities")
    add_case(check)
    run = sub.add_parser("run", help="run a case")
    add_case(run)
    run.add_argument("-o", "--output", metavar="OUT.nc",
                     help="netCDF result file (default, here: the case name, then the --set "
                     "overrides as key=value_key=value, then .nc)")
    run.add_argument("--plot", metavar="OUT.png",
                     help="plot the tension histories in OUT.png and, beside it, the floater "
                     "motions (OUT_motions.png), the line shapes (OUT_shapes.png) and the "
                     "tension along the lines (OUT_line_tension.png) when the run has them")
    run.add_argument("--plot-times", metavar="T1,T2,...", default=None,
                     help="times [s] of the line shapes drawn by --plot (default: 4 spread "
                     "from the end of the ramp to the end of the run)")
    run.add_argument("--vtk", metavar="DIR", default=None,
                     help="also write the line shapes as a VTK time series for ParaView into "
                     "DIR (as floatmoor vtk does)")
    run.add_argument("--json", action="store_true",
                     help="print the summary as JSON on standard output")
    run.add_argument("--quiet", action="store_true", help="no progress reports")
    run.add_argument("--resume", action="store_true",
                     help="floater cases: continue an interrupted run from OUT.nc.checkpoint")
    run.add_argument("--checkpoint-every", metavar="SECONDS", default=None,
                     help="floater cases: seconds of wall time between checkpoints "
                     "(OUT.nc.checkpoint, written at the end of a chunk of steps; default 10, "
                     "0: every chunk); a killed run resumes from the last one")
    sweep = sub.add_parser("sweep", help="run a case over a grid (or zip) of key values")
    add_case(sweep)
    sweep.add_argument("--grid", action="append", default=[], metavar="KEY=V1,V2,...",
                       help="sweep a key over TOML values; several --grid span a product")
    sweep.add_argument("--zip", dest="zipped", action="append", default=[],
                       metavar="KEY=V1,V2,...", help="keys varied together (equal lengths)")
    sweep.add_argument("-o", "--output", metavar="OUT.nc",
                       help="campaign dataset (default: the case name and --set overrides, as "
                       "for run, with _campaign.nc); "
                       "re-running with the same file resumes")
    sweep.add_argument("--workers", type=int, default=1, help="local worker processes")
    sweep.add_argument("--scheduler", metavar="ADDRESS",
                       help="run on this Dask distributed scheduler (tcp://host:8786): "
                       "the case and the files it names are sent to its workers (the same "
                       "floatmoor, nothing else needed) and the results written here")
    sweep.add_argument("--timeseries", action="store_true",
                       help="also keep every run's fairlead tension history (and body "
                       "displacement history of floater cases)")
    sweep.add_argument("--runs-dir", metavar="DIR",
                       help="also write every run's full output file into DIR (created if its "
                       "parent exists), named from its swept values; a re-run redoes a run "
                       "whose file is missing or incomplete")
    sweep.add_argument("--restart", action="store_true",
                       help="start the campaign afresh: an existing output file is moved "
                       "aside to OUT.nc.bak-N (never deleted) instead of resumed")
    sweep.add_argument("--quiet", action="store_true", help="no progress reports")
    study = sub.add_parser("study", help="run a built-in study (results, summary and figures)")
    study.add_argument("name", choices=["qd-verification"],
                       help="qd-verification: quasi-dynamic verification, docs/cases/qd_verification.md")
    study.add_argument("-o", "--output", metavar="DIR", required=True,
                       help="output folder: new (created if its parent exists), empty, or one "
                       "the same study wrote")
    study.add_argument("--workers", type=int, default=1, help="local worker processes")
    study.add_argument("--quick", action="store_true",
                       help="reduced subset (one amplitude, two accelerations per configuration)")
    study.add_argument("--dynamic-elements", metavar="N", default=None,
                       help="elements (order 5) of the dynamic reference (default: the "
                       "study's, docs/cases/qd_verification.md)")
    study.add_argument("--amplitudes", metavar="LIST", default=None,
                       help="subset of the amplitudes, e.g. A1,A3,A5 (default: all five)")
    study.add_argument("--alphas", metavar="LIST", default=None,
                       help="subset of the accelerations, e.g. 0.1,0.2,0.6 (default: all six)")
    study.add_argument("--resume", action="store_true",
                       help="continue an interrupted study in the same folder: the runs it "
                       "finished (kept in DIR/runs) are not computed again")
    study.add_argument("--quiet", action="store_true", help="no progress reports")
    uq = sub.add_parser("uq", help="run an uncertainty-quantification study (gPC surrogates "
                        "of quantities of interest)")
    uq.add_argument("study", nargs="+", metavar="STUDY",
                    help="TOML study file (cases/uq/*.toml); several run together on the same "
                    "workers, each into its own -o folder")
    uq.add_argument("-o", "--output", metavar="DIR", required=True, action="append",
                    help="output folder, new (created if its parent exists), empty or one uq "
                    "wrote: runs.nc, uq.nc, surrogates/, report/; re-running into it resumes "
                    "the runs; one -o per study, in the order of the studies")
    uq.add_argument("--workers", type=int, default=1, help="local worker processes")
    uq.add_argument("--scheduler", metavar="ADDRESS",
                    help="run on this Dask distributed scheduler (tcp://host:8786)")
    uq.add_argument("--json", action="store_true",
                    help="print the summary as JSON on standard output")
    uq.add_argument("--restart", action="store_true",
                    help="start the runs afresh: an existing DIR/runs.nc is moved aside to "
                    "runs.nc.bak-N (never deleted) instead of resumed")
    uq.add_argument("--quiet", action="store_true", help="no progress reports")
    from floatmoor.cli.rao import add_rao_parser

    add_rao_parser(sub, add_case)
    hydro = sub.add_parser("hydro", help="hydrodynamic (BEM) databases of floaters")
    hsub = hydro.add_subparsers(dest="hydro_command", required=True)
    hbuild = hsub.add_parser("build", help="run capytaine for a case's [floater] and [hydro]")
    add_case(hbuild)
    hbuild.add_argument("--force", action="store_true",
                        help="rebuild even if an up-to-date database exists")
    hbuild.add_argument("-o", "--output", metavar="PATH.nc",
                        help="database file (default: hydrodb/NAME.nc of the case)")
    hbuild.add_argument("--quiet", action="store_true", help="no progress reports")
    hbuild.add_argument("--drift", action="store_true",
                        help="also compute the mean wave drift coefficients (far and near "
                        "field, with the RAOs of the case's floater and its linearised "
                        "mooring); added to an up-to-date database without rebuilding it")
    himport = hsub.add_parser(
        "import", help="make a database from WAMIT (.1 .3 .hst .3fk .3sc .out .8 .9 .12d) or "
        "WEC-Sim BEMIO (.h5) files, and check it",
        description="WAMIT needs the .1 (added mass, damping) and .hst (hydrostatic "
        "stiffness); a .3 gives the wave excitation; the run's .out states the gravity, ULEN, "
        "water depth, displaced volume and centre of buoyancy, which otherwise are options; "
        ".8 and .9 give the mean drift (momentum, pressure; with the .3) and .12d the "
        "difference-frequency QTF. Everything missing is listed at once.")
    himport.add_argument("files", nargs="+", metavar="FILE", help="the BEM result files")
    himport.add_argument("-o", "--output", metavar="PATH.nc", required=True,
                         help="database file; a case names it by its path relative to the "
                         "case file ([hydro] database, source = \"imported\")")
    himport.add_argument("--water-density", metavar="RHO", help="[kg/m^3] (WAMIT: required)")
    himport.add_argument("--gravity", metavar="G",
                         help="[m/s^2] (WAMIT: required unless a .out is given)")
    himport.add_argument("--length-scale", metavar="ULEN", help="WAMIT's ULEN [m] (default: "
                         "the .out's, else 1)")
    himport.add_argument("--water-depth", metavar="DEPTH",
                         help="the BEM's water depth [m] or 'infinite' (WAMIT: required "
                         "unless a .out is given)")
    himport.add_argument("--reference-point", nargs=3, metavar=("X", "Y", "Z"),
                         help="where the file's reference point (WAMIT: its origin) lies: the "
                         "case's floater.reference_point [m] (default 0 0 0)")
    himport.add_argument("--displaced-volume", metavar="V",
                         help="[m^3] (WAMIT: required unless a .out is given)")
    himport.add_argument("--centre-of-buoyancy", nargs=3, metavar=("X", "Y", "Z"),
                         help="[m], case coordinates (WAMIT: required unless a .out is given)")
    himport.add_argument("--body", metavar="N", help="BEMIO: the body (1-based) of a "
                         "multi-body file")
    himport.add_argument("--yaw-deg", metavar="DEG", help=YAW_HELP)
    himport.add_argument("--force", action="store_true", help="overwrite an existing file")
    hcheck = hsub.add_parser("check", help="run the database checks")
    hcheck.add_argument("database", metavar="NAME_OR_PATH",
                        help="database name (hydrodb/NAME.nc) or path")
    hcheck.add_argument("--json", action="store_true", help="results as JSON on standard output")
    hinfo = hsub.add_parser("info", help="describe a database")
    hinfo.add_argument("database", metavar="NAME_OR_PATH",
                       help="database name (hydrodb/NAME.nc) or path")
    hfit = hsub.add_parser("fit-state-space", help="add a state-space realisation of the "
                           "radiation kernel K(t) to a database (no BEM rebuild)")
    hfit.add_argument("database", metavar="NAME_OR_CASE",
                      help="database name (hydrodb/NAME.nc), path, or a case file (.toml)")
    hfit.add_argument("--tolerance", type=float, default=None, metavar="RTOL",
                      help="largest relative L2 error of each K_ij over the truncation time "
                      "(default 0.005)")
    hfit.add_argument("--max-order", type=int, default=None, metavar="N",
                      help="largest number of states per pair (default 30)")
    hfit.add_argument("-o", "--output", metavar="PATH.nc",
                      help="write the database with its realisation to this new file "
                      "(default: into the database itself, if it holds no realisation yet)")
    hfit.add_argument("--force", action="store_true",
                      help="replace a realisation the database already holds, or overwrite "
                      "an existing -o file")
    hfit.add_argument("--json", action="store_true", help="the fit's errors as JSON")
    scale = sub.add_parser("scale", help="write a case at another scale (dynamic similitude "
                           "of the cable equation, docs/guide/similitude.md)")
    scale.add_argument("case", help="TOML case file")
    scale.add_argument("--length-scale", required=True, metavar="LAMBDA",
                       help="new / old lengths (eq. 32); times scale sqrt(LAMBDA)")
    scale.add_argument("--diameter-scale", metavar="BETA",
                       help="new / old line diameters (eq. 35; default LAMBDA)")
    law = scale.add_mutually_exclusive_group()
    law.add_argument("--volume-coefficient-ratio", metavar="PHI",
                     help="new / old volume coefficient m / (rho_c pi d^2 / 4) (eq. 36)")
    law.add_argument("--match", choices=["froude", "elastic"],
                     help="froude: PHI such that line forces scale like a Froude-scaled "
                     "floater's (rho LAMBDA^3); elastic: PHI = 1 (default: froude when BETA "
                     "= LAMBDA, required otherwise)")
    scale.add_argument("--water-density", metavar="RHO",
                       help="water density of the scaled case [kg/m^3] (default unchanged)")
    scale.add_argument("--keep-coefficients", action="store_true",
                       help="leave drag and added-mass coefficients as they are (alpha_1, "
                       "alpha_4, alpha_5 then change)")
    scale.add_argument("--hydro-database", metavar="NAME",
                       help="database name of the scaled case (required with [hydro]; build "
                       "it with floatmoor hydro build)")
    scale.add_argument("-o", "--output", required=True, metavar="NEW.toml",
                       help="the scaled case file")
    from floatmoor.cli.moordyn import add_moordyn_parsers
    from floatmoor.cli.report import add_report_parsers

    add_report_parsers(sub)
    from floatmoor.cli.orcaflex import add_orcaflex_parser

    add_orcaflex_parser(add_moordyn_parsers(sub))
    from floatmoor.cli.plots import add_view_parsers

    add_view_parsers(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``floatmoor`` command; returns the exit status.

    Parameters
    ----------
    argv
        The command's arguments (default: ``sys.argv[1:]``), e.g. ``["run", "case.toml"]``.

    Returns
    -------
    int
        0 done, 1 a run or check failed, 2 bad input, 130/143 interrupted
        (:mod:`floatmoor.cli.status`).
    """
    args = _parser().parse_args(argv)
    with interrupt_handling(), _warnings_shown():
        try:
            return _command(args)
        except KeyboardInterrupt as stop:  # before a command's own handling began
            print(f"floatmoor: {signal_name(stop)}; nothing written", file=sys.stderr)
            return exit_status(stop)


@contextmanager
def _warnings_shown() -> Iterator[None]:
    """Show floatmoor's warnings as ``floatmoor: warning: MESSAGE`` on standard error (no
    source line); other warnings as Python shows them. (The format, not the display, is
    replaced, so that warnings recorded by a caller stay recorded.) A database's accepted
    failed checks (:class:`~floatmoor.errors.AcceptedCheckWarning`, which the library raises
    once per database file) are printed as such a line whatever the filters and recorders."""
    import warnings

    from floatmoor.errors import AcceptedCheckWarning, FloatmoorWarning

    formatted = warnings.formatwarning

    def format_warning(message, category, filename, lineno, line=None) -> str:
        if issubclass(category, FloatmoorWarning):
            return f"floatmoor: warning: {message}\n"
        return formatted(message, category, filename, lineno, line)

    with warnings.catch_warnings():
        warnings.simplefilter("always", AcceptedCheckWarning)
        show = warnings.showwarning

        def show_warning(message, category, filename, lineno, file=None, line=None) -> None:
            if issubclass(category, AcceptedCheckWarning):
                print(f"floatmoor: warning: {message}", file=sys.stderr)
            else:
                show(message, category, filename, lineno, file, line)

        warnings.showwarning = show_warning
        warnings.formatwarning = format_warning
        try:
            yield
        finally:
            warnings.formatwarning = formatted


def _command(args: argparse.Namespace) -> int:
    try:
        if args.command == "check":
            return check_command(args)
        if args.command == "sweep":
            return sweep_command(args)
        if args.command == "study":
            return study_command(args)
        if args.command == "uq":
            return uq_command(args)
        if args.command == "hydro":
            from floatmoor.cli.hydro import hydro_command

            return hydro_command(args)
        if args.command == "rao":
            from floatmoor.cli.rao import rao_command

            return rao_command(args)
        if args.command in ("report", "compare"):
            return args.report_handler(args)
        if args.command in ("import", "export"):
            return args.moordyn_handler(args)
        if args.command in ("animate", "vtk"):
            return args.view_handler(args)
        if args.command == "scale":
            from floatmoor.cli.scale import scale_command

            return scale_command(args)
        return run_command(args)
    except CaseError as err:
        if not err.source and getattr(args, "case", None):  # raised by a model: the case file
            err = CaseError(args.case, err.key, err.expected, err.found)
        print(error_line(err), file=sys.stderr)
        return EXIT_BAD_INPUT
    except FloatmoorError as err:
        from floatmoor.hydro.database import HydroDatabaseError
        from floatmoor.io.bem_data import BemFileError

        if not isinstance(err, (HydroDatabaseError, BemFileError)):
            raise
        # a floater case whose database is missing, damaged, stale or fails a check, or whose
        # hull mesh file cannot be read or fails a fatal mesh check (check): bad input
        print(error_line(err), file=sys.stderr)
        return EXIT_BAD_INPUT


def run() -> None:  # pragma: no cover - console-script shim
    """Console-script entry: exit with :func:`main`'s status.

    A closed standard output (``floatmoor check CASE | head``) ends any command quietly with
    :data:`EXIT_BROKEN_PIPE`: standard output is pointed at the null device so that the final
    flush at exit cannot fail again (the Python documentation's recipe for SIGPIPE)."""
    try:
        status = main()
        sys.stdout.flush()  # a pipe closed after the last print fails here
        sys.exit(status)
    except BrokenPipeError:
        _quiet_broken_pipe()
        sys.exit(EXIT_BROKEN_PIPE)
    except FloatmoorError as err:
        print(error_line(err), file=sys.stderr)
        sys.exit(EXIT_FAILED)
    except KeyboardInterrupt:  # one a command did not handle: while loading, importing
        print(STARTUP_INTERRUPTED.replace("while starting", "before running"), file=sys.stderr)
        sys.exit(EXIT_INTERRUPTED)


def _quiet_broken_pipe() -> None:
    """Point standard output at the null device (its reader has gone)."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError):  # no file descriptor (a replaced sys.stdout): nothing to do
        pass

