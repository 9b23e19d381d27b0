"""The ``floatmoor`` command line.

``floatmoor check CASE`` validates a case and prints what follows from it; ``floatmoor run CASE``
runs it; ``floatmoor sweep CASE --grid ...`` runs a campaign; ``floatmoor study
qd-verification -o DIR`` runs the quasi-dynamic verification study (docs/cases/qd_verification.md);
``floatmoor uq STUDY.toml -o DIR`` runs an uncertainty-quantification study (gPC surrogates of
quantities of interest, :mod:`floatmoor.uq.run`; a failed run of a quadrature design exits 1);
``floatmoor hydro build CASE`` builds the floater's BEM database and checks it,
``floatmoor hydro import FILE... -o PATH`` makes one from WAMIT or BEMIO files,
``floatmoor hydro check NAME`` checks one (all three exit 1 when a check fails), ``floatmoor
hydro info NAME`` describes it and where its data came from, and ``floatmoor hydro
fit-state-space NAME`` adds a state-space realisation of its radiation kernel; ``floatmoor rao
CASE -o RAO.nc`` writes the floater's RAOs with its mooring (:mod:`floatmoor.hydro.rao_cli`); ``floatmoor import moordyn DECK -o CASE.toml`` and
``floatmoor export moordyn CASE -o DECK.dat`` convert MoorDyn input files, ``floatmoor
import orcaflex MODEL.yml -o CASE.toml`` reads the mooring of an OrcaFlex text data file; ``floatmoor animate
RUN.nc -o OUT.gif`` and ``floatmoor vtk RUN.nc -o DIR`` draw a run's line shapes
(:mod:`floatmoor.plots.cli`); ``floatmoor scale CASE --length-scale LAMBDA -o NEW.toml``
writes the case at another scale (:mod:`floatmoor.similitude`); a missing, damaged or
stale database, or one failing a
check its case does not accept (``[hydro] accept_failed_checks``), is bad input for a run
(exit 2). Bad input (a malformed case, a bad ``--set`` or output path) prints one message and
exits with status 2, without a traceback and without writing output. A run that fails (no
valid line state) or is interrupted writes its partial results and exits with 1 or 130. A
sweep or study with any failed run writes its results, prints a one-line summary naming the
failed runs (and the first messages) and exits with 1; 0 only when every run completed. An
interrupted floater run also leaves a checkpoint and says the command that resumes it (a
floater run checkpoints every ``--checkpoint-every`` seconds too, so a killed one resumes:
docs/guide/running.md#checkpoints). SIGTERM
is handled as Ctrl-C but exits with 143; a second Ctrl-C (or SIGTERM) lets the partial writes
finish, a third stops at once (:mod:`floatmoor.signals`); the message says what was written.
The first run after an install says that it is compiling the numerical kernels.

Size: the top-level parser and one handler per top-level command (check, run, sweep,
study, uq), each a few dozen lines; the hydro, report and uq subcommands that need more keep
their own ``cli`` modules.
"""

from __future__ import annotations

import argparse
import json
import os
import shlex
import sys
import time
from contextlib import contextmanager, nullcontext
from pathlib import Path
from typing import TYPE_CHECKING, Callable, Iterator, Sequence

from floatmoor._version import __version__
from floatmoor.errors import CaseError, FloatmoorError, SolverError
from floatmoor.signals import exit_status, interrupt_handling, signal_name
from floatmoor.terminal_text import MESSAGE_LIMIT, shown

#: What a Ctrl-C before a command has started says (status 130).
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
STARTUP_INTERRUPTED = "floatmoor: interrupted while starting; nothing was run or written"
try:  # the numerical libraries load here: a Ctrl-C during it gets one line, no traceback
    from floatmoor.case.load import load_case
    from floatmoor.case.schema import Case
except KeyboardInterrupt:
    print(STARTUP_INTERRUPTED, file=sys.stderr)
    raise SystemExit(130) from None

if TYPE_CHECKING:
    from floatmoor.campaign.design import CampaignDesign
    from floatmoor.mooring.static_strength import StaticLineLoad
    from floatmoor.simulation.forced import RunResult
    from floatmoor.uq.study import Study

__all__ = ["main"]

EXIT_OK, EXIT_FAILED, EXIT_BAD_INPUT, EXIT_INTERRUPTED = 0, 1, 2, 130
#: Status of a command whose standard output was closed early (``floatmoor check ... | head``):
#: 128 + SIGPIPE, what a shell reports for a program the closed pipe stopped.
EXIT_BROKEN_PIPE = 128 + 13


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
    uq.add_argument("study", help="TOML study file (cases/uq/*.toml)")
    uq.add_argument("-o", "--output", metavar="DIR", required=True,
                    help="output folder, new (created if its parent exists), empty or one uq "
                    "wrote: runs.nc, uq.nc, surrogates/, report/; re-running into it resumes "
                    "the runs")
    uq.add_argument("--workers", type=int, default=1, help="local worker processes")
    uq.add_argument("--scheduler", metavar="ADDRESS",
                    help="run on this Dask distributed scheduler (tcp://host:8786)")
    uq.add_argument("--json", action="store_true",
                    help="print the summary as JSON on standard output")
    uq.add_argument("--restart", action="store_true",
                    help="start the runs afresh: an existing DIR/runs.nc is moved aside to "
                    "runs.nc.bak-N (never deleted) instead of resumed")
    uq.add_argument("--quiet", action="store_true", help="no progress reports")
    from floatmoor.hydro.rao_cli import add_rao_parser

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
    from floatmoor.io.moordyn.cli import add_moordyn_parsers
    from floatmoor.report.cli import add_report_parsers

    add_report_parsers(sub)
    from floatmoor.io.orcaflex.cli import add_orcaflex_parser

    add_orcaflex_parser(add_moordyn_parsers(sub))
    from floatmoor.plots.cli import add_view_parsers

    add_view_parsers(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``floatmoor`` command; returns the exit status."""
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
    replaced, so that warnings recorded by a caller stay recorded.)"""
    import warnings

    from floatmoor.errors import FloatmoorWarning

    formatted = warnings.formatwarning

    def format_warning(message, category, filename, lineno, line=None) -> str:
        if issubclass(category, FloatmoorWarning):
            return f"floatmoor: warning: {message}\n"
        return formatted(message, category, filename, lineno, line)

    warnings.formatwarning = format_warning
    try:
        yield
    finally:
        warnings.formatwarning = formatted


def _command(args: argparse.Namespace) -> int:
    try:
        if args.command == "check":
            return _check(args)
        if args.command == "sweep":
            return _sweep(args)
        if args.command == "study":
            return _study(args)
        if args.command == "uq":
            return _uq(args)
        if args.command == "hydro":
            from floatmoor.hydro.cli import hydro_command

            return hydro_command(args)
        if args.command == "rao":
            from floatmoor.hydro.rao_cli import rao_command

            return rao_command(args)
        if args.command in ("report", "compare"):
            return args.report_handler(args)
        if args.command in ("import", "export"):
            return args.moordyn_handler(args)
        if args.command in ("animate", "vtk"):
            return args.view_handler(args)
        if args.command == "scale":
            from floatmoor.similitude.cli import scale_command

            return scale_command(args)
        return _run(args)
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


def error_line(err: BaseException) -> str:
    """``floatmoor: error: MESSAGE`` as one terminal-safe line (the message quotes file text:
    control characters are escaped and the length bounded, :func:`shown`)."""
    return f"floatmoor: error: {shown(err, MESSAGE_LIMIT)}"


def _check(args: argparse.Namespace) -> int:
    from floatmoor.mooring.static_strength import check_static_below_mbl, static_line_loads

    import warnings

    from floatmoor.errors import ImplausibleInputWarning

    with warnings.catch_warnings(record=True) as implausible:  # printed with the case
        warnings.simplefilter("always", ImplausibleInputWarning)
        case = load_case(args.case, args.overrides)
    mesh_rows = _check_mesh(case)
    loads = static_line_loads(case)
    check_static_below_mbl(case, loads)
    description = _describe(case, loads)  # (may still refuse the case: a line's settle)
    print(f"{shown(args.case)}: valid case \"{shown(case.title)}\"")
    for w in implausible:
        if issubclass(w.category, ImplausibleInputWarning):
            print(f"  warning: {shown(str(w.message), MESSAGE_LIMIT)}")
        else:  # not ours: as it would have been shown
            warnings.showwarning(w.message, w.category, w.filename, w.lineno)
    print(description)
    if mesh_rows:
        print("\n".join(mesh_rows))
    return EXIT_OK


def _check_mesh(case: Case) -> list[str]:
    """For a hull read from a mesh file that ``hydro build`` will solve on: read it and run
    the mesh checks as the build does before solving (floatmoor.hydro.build.checked_mesh),
    so that ``check`` refuses what the build would refuse without solving
    (:class:`floatmoor.io.bem_data.BemFileError`); the build's summary of the mesh."""
    if case.floater is None or case.hydro is None or case.hydro.source != "bem" \
            or case.floater.geometry is None or case.floater.geometry.kind != "mesh":
        return []
    from floatmoor.hydro.build import checked_mesh
    from floatmoor.hydro.mesh_checks import summary_lines

    checked = checked_mesh(case.floater, case.hydro, case.environment)
    info = checked.mesh.source.as_dict()
    return [f"  {row}" for row in summary_lines(info, [c.as_dict()
                                                       for c in checked.mesh_checks or ()])]


def _describe_system(case: Case) -> list[str]:
    """The static equilibrium at rest of the lines joined through free points or of several
    sections: point positions and net loads, section end tensions and laid lengths."""
    import numpy as np

    from floatmoor.errors import SolverError
    from floatmoor.mooring.static_strength import system_statics_at_rest

    try:
        sol = system_statics_at_rest(case)
    except SolverError as err:
        return [f"  mooring system: no static solution: {err}"]
    if sol is None:
        return []
    rows = [f"  mooring system at rest ({sol.iterations} Newton iterations, force residual "
            f"{sol.residual:.2g}):",
            f"    {'point':<18}{'kind':<7}{'x [m]':>10}{'y [m]':>10}{'z [m]':>10}"
            f"{'F_lines [kN]':>14}{'seabed [kN]':>13}"]
    kinds = {p.name: p.kind for p in case.points}
    for k, name in enumerate(sol.point_names):
        x, y, z = sol.positions[k]
        seabed = f"{sol.seabed_reaction[k] / 1e3:>13.4g}" if sol.on_seabed[k] else f"{'-':>13}"
        rows.append(f"    {name:<18}{kinds[name]:<7}{x:>10.3f}{y:>10.3f}{z:>10.3f}"
                    f"{np.linalg.norm(sol.point_force[k]) / 1e3:>14.4g}{seabed}")
    rows.append(f"    {'section':<18}{'type':<12}{'profile':<11}{'T_start [kN]':>13}"
                f"{'T_end [kN]':>12}{'on seabed [m]':>15}")
    types = {s.label: s.line_type.name for s in case.sections}
    for j, name in enumerate(sol.section_names):
        rows.append(f"    {name:<18}{types[name]:<12}{sol.profile_types[j]:<11}"
                    f"{sol.start_tension[j] / 1e3:>13.5g}{sol.end_tension[j] / 1e3:>12.5g}"
                    f"{sol.laid_length[j]:>15.4g}")
    return rows


def _describe(case: Case, loads: list[StaticLineLoad]) -> str:
    """Derived quantities: weights, wave speeds, static tensions at the mean position against
    the minimum breaking loads, and the discretisation and time step of dynamic lines."""
    from floatmoor.body_motion import start_line
    from floatmoor.mooring.dg.line import DynamicLine
    from floatmoor.mooring.static_strength import strain_warnings

    rows = [f"  {'line':<14}{'model':<14}{'length':>9}{'span':>9}{'w [N/m]':>10}"
            f"{'c_axial':>10}{'T_fair':>11}{'T_anch':>11}{'on seabed':>11}"]
    notes = []
    by_name = {load.line: load for load in loads}
    for line in case.lines:
        if not case.is_independent(line):
            types = " + ".join(f"{s.line_type.name} {s.length:g} m" for s in line.sections)
            rows.append(f"  {line.name:<14}{line.model:<14}{line.length:>9.4g}"
                        f"{line.span:>9.4g}  system: {types} (statics below)")
            continue
        load = by_name[line.name]
        if load.failure:
            static = f"  static solution failed: {load.failure}"
        else:
            static = (f"{load.fairlead_tension:>11.5g}{load.anchor_tension:>11.5g}"
                      f"{load.laid_length:>11.4g}")
        rows.append(f"  {line.name:<14}{line.model:<14}{line.length:>9.4g}{line.span:>9.4g}"
                    f"{line.line_type.weight_in_water(case.environment):>10.4g}"
                    f"{line.line_type.axial_wave_speed:>10.4g}{static}")
        if line.model == "dynamic":
            # as the run builds it: in the motion's pose at t = 0
            dg = DynamicLine.from_case(start_line(case.motion, line), case.environment,
                                       case.seabed)
            st, given = dg.settings, line.dynamic
            implicit = (f"implicit steps of at most {dg.time_step:.3g} s (accuracy "
                        f"{100 * st.accuracy:g} % of the fairlead tension)")
            if st.time_integration == "explicit":
                steps = f"time step {dg.time_step:.3g} s (cfl {st.cfl:g})"
            elif dg.auto is None:
                steps = implicit
            else:
                steps = (f"{implicit} or explicit steps of {dg.auto.explicit_step:.3g} s "
                         f"(cfl {st.cfl:g}), whichever cost less, period by period")
            chosen = ("" if given.elements is not None and given.order is not None
                      else f", chosen for {100 * st.accuracy:g} % accuracy")
            notes.append(f"  {line.name}: {st.elements} elements of order {st.order} "
                         f"({st.elements * (st.order + 1)} nodes{chosen}), {steps}, seabed "
                         f"contact {st.seabed_contact}")
    notes.extend(_describe_system(case))
    rows.append("  (m, N, m/s; tensions of the static catenary at the mean fairlead position)")
    rows.extend(notes)
    rows.append(f"  {'line':<14}{'T_fair [N]':>12}{'strain T/EA':>13}{'MBL [N]':>12}"
                f"{'T/MBL':>9}{'safety factor':>15}")
    for load in loads:
        if load.failure:
            rows.append(f"  {load.line:<14}  no static solution: tension and strain unknown")
            continue
        mbl = load.minimum_breaking_load
        strain = f"{100.0 * load.strain:.3g} %"
        rows.append(f"  {load.line:<14}{load.fairlead_tension:>12.5g}{strain:>13}"
                    + (f"{mbl:>12.5g}{load.ratio:>9.4g}{load.safety_factor:>15.4g}"
                       if mbl is not None else f"{'no MBL':>12}{'-':>9}{'-':>15}"))
    rows.append("  (static fairlead tension against the minimum breaking load of the line "
                "type; safety factor = MBL / T)")
    rows.extend(f"  {w}" for w in strain_warnings(loads))
    if case.floater is not None:
        fl = case.floater
        geo = fl.geometry
        if geo is None:
            kind = "no hull geometry (hydrostatics from the imported database)"
        else:
            kind = (f"mesh {geo.file} ({geo.format}, {geo.length_unit}, SHA-256 "
                    f"{geo.sha256[:12]}, symmetry {', '.join(geo.symmetry) or 'none'}, "
                    f"{len(geo.columns)} Morison columns, {len(geo.members)} members)") \
                if geo.kind == "mesh" else geo.kind
        rows.append(f"  floater: {fl.name}, {kind}, mass {fl.mass:.6g} kg, centre of "
                    f"mass z = {fl.centre_of_mass[2]:.6g} m"
                    + (f", draft {geo.draft:.6g} m" if geo is not None and geo.kind == "cylinder"
                       else "") + f", radiation {fl.radiation}")
        rows.append("  (line fairleads: body-fixed points at rest)")
    if case.hydro is not None:
        accepted = case.hydro.accept_failed_checks
        built = (f"{len(case.hydro.frequencies)} frequencies, {len(case.hydro.directions)} "
                 "directions" if case.hydro.source == "bem" else "imported (floatmoor hydro "
                 "import)")
        from floatmoor.hydro.database import database_path

        rows.append(f"  hydro: database {case.hydro.database} ({database_path(case)}), {built}"
                    + (f"; accepts failed checks: {', '.join(accepted)}" if accepted else ""))
        if case.hydro.source == "bem" and case.floater is not None:
            from floatmoor.hydro.checks import haskind_requirement

            geo = case.floater.geometry
            need = haskind_requirement(geo.kind, geo.kind != "mesh" or "xz" in geo.symmetry,
                                       case.hydro.directions)
            if need is not None:
                rows.append(f"  hydro: the built database's haskind check will be n/a: {need}")
    if case.motion is not None:
        rows.append(f"  motion: {case.motion.kind}, ramp {case.motion.ramp_duration:g} s; "
                    f"duration {case.simulation.duration:g} s, output every "
                    f"{case.simulation.output_interval:g} s")
        rows.extend(_start_pose_rows(case))
    rows.extend(_describe_groups(case))
    return "\n".join(rows)


def _describe_groups(case: Case) -> list[str]:
    """The dimensionless groups of each line section (floatmoor.similitude.groups)."""
    from floatmoor.similitude.groups import cable_groups

    groups = cable_groups(case)
    names = ("alpha_1", "alpha_2", "alpha_3", "alpha_4", "alpha_5", "reynolds_number",
             "keulegan_carpenter_number")
    heads = ("alpha_1", "alpha_2", "alpha_3", "alpha_4", "alpha_5", "Re", "KC")
    rows = [f"  dimensionless groups (chain-experiment paper eqs. 29-31; "
            f"{groups.attrs['characteristic_motion']}, T = {float(groups.period[0]):.4g} s, "
            f"a = {float(groups.amplitude[0]):.4g} m):" if groups.sizes["section"] else
            "  dimensionless groups: no lines",
            f"    {'section':<16}" + "".join(f"{h:>11}" for h in heads)]
    values = [groups[n].values for n in names]  # numpy once: xarray indexing per cell is slow
    for i, label in enumerate(groups.section.values):
        rows.append(f"    {label:<16}" + "".join(f"{float(v[i]):>11.4g}" for v in values))
    return rows if groups.sizes["section"] else rows[:1]


def _default_stem(case: Case) -> str:
    """The case file's name, and its overrides by the campaign's run-name rule, so that a run
    with overrides does not overwrite the run without them:
    ``lindahl_r0.20_T1.25_motion.period=3.5``."""
    from floatmoor.case.naming import file_stem, override_items

    stem = Path(case.source).stem
    return f"{stem}_{file_stem(override_items(case.overrides))}" if case.overrides else stem


def _output_path(args: argparse.Namespace, case: Case) -> Path:
    """The run's checked output file (and its plot's, when asked for); a file there that the
    run will replace is announced on standard error once every check has passed."""
    from floatmoor.io.output_files import IMAGE, check_output_file
    from floatmoor.io.output_kinds import CHECKPOINT, RUN_RESULT_FILE
    from floatmoor.plots.style import SUPPORTED_FORMATS
    from floatmoor.simulation.recorder import estimated_output_bytes

    protected = {"case file": case.source}
    if case.hydro is not None:
        from floatmoor.hydro.database import database_path

        protected["hydrodynamic database"] = str(database_path(case))
    text = args.output if args.output else _default_stem(case) + ".nc"
    output = check_output_file(text, "-o/--output", protected=protected, kind=RUN_RESULT_FILE,
                               expected_bytes=int(min(estimated_output_bytes(case), 2**62)))
    if case.floater is not None and not args.resume:  # the checkpoint it writes replaces
        # only a checkpoint (a numpy zip); with --resume it is an input, checked when read
        from floatmoor.simulation.coupled_run import checkpoint_path

        check_output_file(checkpoint_path(output.path), "-o/--output", kind=CHECKPOINT,
                          protected=protected)
    plot = []
    shapes = case.simulation.shape_output_interval is not None
    if args.plot is not None:
        from floatmoor.plots.run_figures import figure_paths

        if Path(args.plot).suffix.lower() not in SUPPORTED_FORMATS:
            raise CaseError("--plot", "", "an image file (" + ", ".join(SUPPORTED_FORMATS)
                            + ") in an existing folder", f"'{args.plot}'")
        taken = {"result file (-o)": output.path}
        for view, path in figure_paths(args.plot, floater=case.floater is not None,
                                       shapes=shapes).items():
            plot.append(check_output_file(path, "--plot", kind=IMAGE,
                                          protected={**protected, **taken}))
            taken[f"--plot {view} image"] = path
    args.plot_times_s = _plot_times(args, case, shapes)
    if args.vtk is not None:
        from floatmoor.io.output_folders import check_owned_folder

        if not shapes:
            raise CaseError("--vtk", "", "a case that records line shapes (set "
                            "simulation.shape_output_interval)", "no line shapes")
        check_owned_folder(args.vtk, "--vtk", "vtk")
    for checked in (output, *plot):
        if checked is not None and checked.replaces and not (checked is output and args.resume):
            print(f"floatmoor: replacing the existing {checked.path}", file=sys.stderr)
    return output.path


def _plot_times(args: argparse.Namespace, case: Case, shapes: bool) -> list[float] | None:
    """``--plot-times`` as seconds within the run (None when not given).

    Raises
    ------
    CaseError
        Without --plot or line shapes, or for a time that is not a number in the run.
    """
    if args.plot_times is None:
        return None
    if args.plot is None or not shapes:
        raise CaseError("--plot-times", "", "--plot and a case that records line shapes "
                        "(simulation.shape_output_interval)",
                        "no --plot" if args.plot is None else "no line shapes")
    duration = case.simulation.duration
    times = []
    for text in str(args.plot_times).split(","):
        try:
            value = float(text)
        except ValueError:
            value = float("nan")
        if not 0.0 <= value <= duration:
            raise CaseError("--plot-times", "", f"comma-separated times from 0 to {duration:g} "
                            "s (the run's duration)", f"'{text.strip()}'")
        times.append(value)
    return times


def _start_pose_rows(case: Case) -> list[str]:
    """A note when the motion does not start at rest (a table without a ramp whose first row
    is not the rest pose): the lines start in that pose, and the statistics include it."""
    import numpy as np

    from floatmoor.body_motion import prescribed_fairlead_state

    offsets = [float(np.linalg.norm(prescribed_fairlead_state(case.motion, line, np.zeros(1))[0][0]
                                    - np.asarray(line.fairlead, dtype=float)))
               for line in case.lines if case.point(line.end).kind == "body"]
    if not offsets or max(offsets) == 0.0:
        return []
    return [f"  (the motion starts away from rest: the lines start, settled, at its pose at "
            f"t = 0, fairleads up to {max(offsets):.4g} m from rest; without a ramp the "
            "statistics include the record from t = 0)"]


def _run(args: argparse.Namespace) -> int:
    from floatmoor.io.output_files import output_lock

    case = load_case(args.case, args.overrides)
    output = _output_path(args, case)
    with output_lock(output), (nullcontext() if args.plot is None
                               else output_lock(args.plot, "--plot")), \
            (nullcontext() if args.vtk is None else output_lock(Path(args.vtk).resolve(),
                                                                 "--vtk")):
        return _run_case(args, case, output)


def _run_case(args: argparse.Namespace, case: Case, output: Path) -> int:
    """Run a checked case into its locked output file."""
    from floatmoor.mooring.static_strength import refuse_static_breaking
    from floatmoor._numba import watch_compilation
    from floatmoor.io.output_files import OutputWriteError, file_state
    from floatmoor.simulation.forced import run_forced_motion
    from floatmoor.ui.progress import ProgressReporter

    refuse_static_breaking(case)  # a line that breaks at rest is bad input (exit 2)

    if args.resume and case.floater is None:
        raise CaseError("--resume", "", "a case with a [floater] (forced-motion runs are not "
                        "checkpointed)", "--resume")
    every = _checkpoint_every(args, case)
    progress = None if args.quiet else ProgressReporter(case.simulation.duration)
    compile_time = [0.0]  # [s] of the run's wall time spent compiling kernels

    def compiling() -> None:
        if progress is not None:
            progress.compiling()

    def compiled(seconds: float) -> None:
        compile_time[0] += seconds
        if progress is not None:
            progress.compiled(seconds)

    before = file_state(output)
    started = time.perf_counter()
    try:
        with watch_compilation(compiling, compiled), _validity_in_summary():
            if case.floater is not None:
                from floatmoor.simulation.coupled_run import run_coupled

                result = run_coupled(case, output=output, progress=progress,
                                     resume=args.resume, checkpoint_interval=every)
            else:
                result = run_forced_motion(case, output=output, progress=progress)
    except SolverError as err:
        _close(progress)
        print(f"floatmoor: run failed: {err}\n  {_left_behind(output, before)}",
              file=sys.stderr)
        return EXIT_FAILED
    except OutputWriteError as err:
        _close(progress)
        print(f"floatmoor: run failed: {err}\n  "
              f"{_left_behind(output, before, 'its writes failed')}",
              file=sys.stderr)
        return EXIT_FAILED
    except KeyboardInterrupt as stop:
        _close(progress)
        print(f"floatmoor: {signal_name(stop)}; {_left_behind(output, before)}"
              + _resume_hint(args, case, output), file=sys.stderr)
        return exit_status(stop)
    _close(progress)
    try:
        return _report_run(args, case, result, output, compile_time[0],
                           time.perf_counter() - started)
    except KeyboardInterrupt as stop:
        print(f"floatmoor: {signal_name(stop)} after the run; its complete results are in "
              f"{output}" + (f", the plot {args.plot} may be missing" if args.plot else ""),
              file=sys.stderr)
        return exit_status(stop)


def _checkpoint_every(args: argparse.Namespace, case: Case) -> float | None:
    """``--checkpoint-every`` in seconds (None when not given).

    Raises
    ------
    CaseError
        For a case without a floater (not checkpointed) or a value that is not a finite
        number >= 0.
    """
    text = args.checkpoint_every
    if text is None:
        return None
    if case.floater is None:
        raise CaseError("--checkpoint-every", "", "a case with a [floater] (forced-motion runs "
                        "are not checkpointed)", f"'{text}'")
    try:
        value = float(text)
    except ValueError:
        value = float("nan")
    if not 0.0 <= value < float("inf"):
        raise CaseError("--checkpoint-every", "", "seconds of wall time, a number >= 0",
                        f"'{text}'")
    return value


@contextmanager
def _validity_in_summary() -> Iterator[None]:
    """Keep the run's model-validity warnings for its summary, which prints them (and so does
    the message of a run that stops; both from the output file's ``validity_warnings``):
    not shown as they are raised, once the progress line has moved on."""
    import warnings

    from floatmoor.errors import ModelValidityWarning

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", ModelValidityWarning)
        try:
            yield
        finally:
            for w in caught:
                if not issubclass(w.category, ModelValidityWarning):
                    warnings.showwarning(w.message, w.category, w.filename, w.lineno)


def _report_run(args: argparse.Namespace, case: Case, result: RunResult, output: Path,
                compile_time: float = 0.0, wall_time: float | None = None) -> int:
    """Print the summary of a completed run (and draw its plot). ``wall_time``: the run's
    whole wall time, set-up included [s] (default: the time loop's); ``compile_time``: the
    part of it spent compiling kernels [s]."""
    wall_time = result.wall_time_s if wall_time is None else wall_time
    from floatmoor.io.output_files import OutputWriteError
    from floatmoor.post.summary import format_summary, run_summary

    summary = run_summary(case, result.dataset)
    summary.update(output=str(output), wall_time_s=result.wall_time_s,
                   simulated_time_s=result.simulated_time_s, compile_time_s=compile_time,
                   run_wall_time_s=wall_time)
    if args.plot is not None:
        from floatmoor.plots.run_figures import plot_run
        from floatmoor.plots.series import FigureDataError

        try:
            figures = plot_run(result.dataset, args.plot, args.plot_times_s)
        except (OutputWriteError, FigureDataError) as err:
            print(f"floatmoor: the plot failed: {err}\n  the run completed; results in "
                  f"{output}", file=sys.stderr)
            return EXIT_FAILED
        summary["plot"] = str(args.plot)
        summary["figures"] = [str(p) for p in figures.values()]
    if args.vtk is not None:
        from floatmoor.io.output_folders import OwnedFolder
        from floatmoor.io.shape_samples import window_samples
        from floatmoor.plots.cli import write_vtk

        try:
            with OwnedFolder(args.vtk, "vtk"):
                summary["vtk"] = str(write_vtk(result.dataset, Path(args.vtk),
                                               window_samples(result.dataset),
                                               quiet=args.quiet))
        except OutputWriteError as err:
            print(f"floatmoor: the VTK output failed: {err} (the VTK files it wrote were "
                  f"removed)\n  the run completed; results in {output}", file=sys.stderr)
            return EXIT_FAILED
    if args.json:
        print(json.dumps(summary, indent=2))
    else:
        print(format_summary(summary))
        compiling = (f" ({compile_time:.3g} s of it compiling the numerical kernels, which "
                     "later runs load from their cache)") if compile_time > 0.0 else ""
        print(f"simulated {result.simulated_time_s:.6g} s in {wall_time:.3g} s of wall "
              f"time{compiling}; results in {output}"
              + (f", plots in {', '.join(summary['figures'])}" if args.plot else "")
              + (f", VTK series {summary['vtk']}" if args.vtk else ""))
    return EXIT_OK


def _resume_hint(args: argparse.Namespace, case: Case, output: Path) -> str:
    """Where an interrupted floater run left its checkpoint and the command that resumes it
    ("" when there is none)."""
    if case.floater is None:
        return ""
    from floatmoor.simulation.coupled_run import checkpoint_path

    ckpt = checkpoint_path(output)
    if not ckpt.is_file():
        return ""
    command = ["floatmoor", "run", args.case, "-o", str(output), "--resume"]
    for text in args.overrides:
        command += ["--set", text]
    for option in ("plot", "plot_times", "vtk", "checkpoint_every"):
        if getattr(args, option) is not None:
            command += [f"--{option.replace('_', '-')}", getattr(args, option)]
    return f"\n  checkpoint written to {ckpt}; continue with: {shlex.join(command)}"


def _sweep(args: argparse.Namespace) -> int:
    from floatmoor.campaign.design import design_from_options
    from floatmoor.io.output_files import output_lock

    case = load_case(args.case, args.overrides)
    design = design_from_options(args.grid, args.zipped, getattr(case, "campaign", None))
    output = _campaign_output(args, case, design.size)
    if args.workers < 1:
        raise CaseError("--workers", "", "a whole number >= 1", str(args.workers))
    with output_lock(output):
        return _sweep_locked(args, design, output)


def _campaign_output(args: argparse.Namespace, case: Case, runs: int) -> Path:
    """The sweep's checked campaign file (and runs folder), with room for what they will
    hold."""
    from floatmoor.io.output_files import CAMPAIGN, check_output_file
    from floatmoor.simulation.recorder import estimated_output_bytes

    run_bytes = estimated_output_bytes(case)
    text = args.output if args.output else _default_stem(case) + "_campaign.nc"
    # per run: a few statistics per line (and DOF); with --timeseries the histories, about
    # a tenth of a run file's values (one of its 13 values per line and sample)
    expected = runs * ((run_bytes / 10.0 if args.timeseries else 0.0) + 8192.0)
    output = check_output_file(text, "-o/--output", kind=CAMPAIGN,
                               protected={"case file": case.source},
                               expected_bytes=int(min(expected, 2**62))).path
    if args.runs_dir is not None:
        folder = Path(args.runs_dir)
        probe = folder / ".floatmoor-runs-dir" if folder.is_dir() else folder
        if folder.is_dir() or not folder.exists():
            check_output_file(probe, "--runs-dir", expected_bytes=int(min(
                runs * run_bytes, 2**62)))
    return output


def _sweep_locked(args: argparse.Namespace, design: CampaignDesign, output: Path) -> int:
    """Run a campaign into its checked and locked output file."""
    from floatmoor._numba import watch_compilation
    from floatmoor.campaign.runner import run_campaign
    from floatmoor.campaign.store import failed_runs
    from floatmoor.io.output_files import OutputWriteError, file_state

    progress, compiling = _campaign_reporters(args.quiet)
    before = file_state(output)
    try:
        with watch_compilation(compiling, lambda seconds: None):
            ds = run_campaign(args.case, design, base_overrides=args.overrides, output=output,
                              workers=args.workers, scheduler=args.scheduler,
                              timeseries=args.timeseries, runs_dir=args.runs_dir,
                              progress=progress, restart=args.restart,
                              moved_aside=_say_moved_aside)
    except KeyboardInterrupt as stop:
        print(f"floatmoor: {signal_name(stop)}; {_campaign_left_behind(output, before)}",
              file=sys.stderr)
        return exit_status(stop)
    except OutputWriteError as err:
        print(f"floatmoor: sweep failed: {err}\n  {_campaign_left_behind(output, before)}",
              file=sys.stderr)
        return EXIT_FAILED
    failed = failed_runs(ds, design)
    print(f"{ds.attrs['runs_complete']} of {ds['status'].size} runs complete, {len(failed)} "
          f"failed; results in {output}")
    if failed:
        report_failures("sweep", failed, int(ds["status"].size))
        return EXIT_FAILED
    return EXIT_OK


def _campaign_reporters(quiet: bool) -> tuple[Callable[[int, int, float], None],
                                              Callable[[], None]]:
    """The progress callback of a campaign's runs (runs done, runs in total, seconds left)
    and the compiling notice (said once: kernels compile in this process with one worker)."""
    from floatmoor.ui.progress import COMPILING_MESSAGE

    said = []

    def progress(done: int, total: int, left: float) -> None:
        if not quiet:
            eta = "" if left != left else f", ~{left:.0f} s left"
            print(f"floatmoor: {done} / {total} runs done{eta}", file=sys.stderr, flush=True)

    def compiling() -> None:
        if not quiet and not said:
            said.append(True)
            print(COMPILING_MESSAGE, file=sys.stderr, flush=True)

    return progress, compiling


def _say_moved_aside(path: Path, backup: Path) -> None:
    print(f"floatmoor: --restart: moved the existing {path} aside to {backup}; starting "
          "afresh", file=sys.stderr, flush=True)


#: Failed runs named in the one-line summary, and failure messages printed after it.
_NAMED_FAILURES, _FAILURE_MESSAGES = 10, 3


def report_failures(what: str, failed: Sequence[tuple[str, str]], total: int) -> None:
    """Print on standard error the one-line summary of a campaign's failed runs (how many,
    which) and the first failure messages.

    Parameters
    ----------
    what
        The command (``"sweep"``, ``"study qd-verification"``).
    failed
        (run label, e.g. its swept values; failure message) of every failed run.
    total
        Runs in the campaign.
    """
    labels = [label for label, _ in failed]
    named = "; ".join(labels[:_NAMED_FAILURES]) + (
        f"; and {len(labels) - _NAMED_FAILURES} more" if len(labels) > _NAMED_FAILURES else "")
    print(f"floatmoor: {what} failed: {len(failed)} of {total} runs failed ({named})",
          file=sys.stderr)
    for label, message in failed[:_FAILURE_MESSAGES]:
        print(f"  {label}: {message}", file=sys.stderr)


def _study(args: argparse.Namespace) -> int:
    from floatmoor.studies import qd_verification

    from floatmoor.io.output_files import OutputWriteError, output_lock, write_errors
    from floatmoor.io.output_folders import MANIFEST_NAME, OwnedFolder, check_owned_folder

    output = check_owned_folder(args.output, "-o/--output", "study qd-verification")
    if args.workers < 1:
        raise CaseError("--workers", "", "a whole number >= 1", str(args.workers))
    options = _study_options(args.dynamic_elements, args.amplitudes, args.alphas,
                             quick=args.quick)

    def progress(done: int, total: int) -> None:
        if not args.quiet:
            print(f"floatmoor: {done} / {total} runs done", file=sys.stderr, flush=True)

    runs = qd_verification.qd_runs.RUNS_DIR
    try:
        with output_lock(output.resolve()), OwnedFolder(output, "study qd-verification",
                                                        keep=(runs,)) as folder:
            def kept() -> None:  # a run file stays the study's even if the process is killed
                with write_errors(output / MANIFEST_NAME):
                    folder.record_written()

            ds = qd_verification.run_study(output, workers=args.workers, quick=args.quick,
                                           progress=progress, resume=args.resume, kept=kept,
                                           **options)
    except KeyboardInterrupt as stop:
        n_kept = qd_verification.qd_runs.count_runs(output)
        said = (f"{n_kept} finished runs kept in {output / runs} (--resume continues the "
                "study)" if n_kept else "nothing written")
        print(f"floatmoor: {signal_name(stop)}; {said}; the dataset, summary and figures are "
              "written at the end", file=sys.stderr)
        return exit_status(stop)
    except OutputWriteError as err:
        n_kept = qd_verification.qd_runs.count_runs(output)
        print(f"floatmoor: study failed: {err}; the files it wrote were removed"
              + (f" but its {n_kept} finished runs, kept in {output / runs} for --resume"
                 if n_kept else ""), file=sys.stderr)
        return EXIT_FAILED
    print(qd_verification.summary(ds))
    print(f"results in {output}")
    failed = qd_verification.failed_runs(ds)
    if failed:
        report_failures("study qd-verification", failed, int(ds.attrs["runs"]))
        return EXIT_FAILED
    return EXIT_OK


def _study_options(dynamic_elements: str | None, amplitudes: str | None, alphas: str | None,
                  quick: bool = False) -> dict:
    """The keyword arguments of ``qd_verification.run_study`` from the command line's texts
    (``--dynamic-elements 20``, ``--amplitudes A1,A3,A5``, ``--alphas 0.1,0.2,0.6``).

    Raises
    ------
    CaseError
        Naming the option, what it takes and what it was given.
    """
    from floatmoor.studies.qd_verification import ALPHAS, AMPLITUDE_NAMES

    out: dict = {}
    if dynamic_elements is not None:
        text = dynamic_elements.strip()
        if not (text.isascii() and text.isdigit()) or int(text) < 1:
            raise CaseError("--dynamic-elements", "", "a whole number >= 1",
                            repr(dynamic_elements))
        out["dynamic_elements"] = int(text)
    if quick and (amplitudes is not None or alphas is not None):
        raise CaseError("--quick", "", "no --amplitudes or --alphas beside it (it picks its own)",
                        "--amplitudes" if amplitudes is not None else "--alphas")
    if amplitudes is not None:
        out["amplitudes"] = _study_pick("--amplitudes", amplitudes, AMPLITUDE_NAMES,
                                        "amplitude names among " + ", ".join(AMPLITUDE_NAMES))
    if alphas is not None:
        names = tuple(f"{a:g}" for a in ALPHAS)
        out["alphas"] = _study_pick("--alphas", alphas, names,
                                    "accelerations among " + ", ".join(names))
    return out


def _study_pick(option: str, text: str, names: Sequence[str], expected: str) -> list[int]:
    """Indices into ``names`` of the comma-separated items of ``text`` (each once)."""
    items = [item.strip() for item in text.split(",")]
    picked = []
    for item in items:
        key = item.upper() if option == "--amplitudes" else item
        if option == "--alphas":
            try:
                key = f"{float(item):g}"
            except ValueError:
                key = item
        if key not in names or names.index(key) in picked:
            why = "repeated" if key in names else "unknown"
            raise CaseError(option, "", f"a comma-separated list of distinct {expected}",
                            f"{repr(text)} ({why} item {repr(item)})")
        picked.append(names.index(key))
    return picked


def _uq(args: argparse.Namespace) -> int:
    from floatmoor.io.output_files import output_lock
    from floatmoor.io.output_folders import check_owned_folder
    from floatmoor.uq.study import load_study

    study = load_study(args.study)
    if args.workers < 1:
        raise CaseError("--workers", "", "a whole number >= 1", str(args.workers))
    if args.scheduler is not None:
        from floatmoor.campaign.scheduler import check_address

        check_address(args.scheduler)
    folder = check_owned_folder(args.output, "-o/--output", "uq")
    with output_lock(folder.resolve()):
        return _uq_locked(args, study, folder)


def _uq_locked(args: argparse.Namespace, study: "Study", folder: Path) -> int:
    """Run a checked study into its checked and locked output folder."""
    from floatmoor._numba import watch_compilation
    from floatmoor.io.output_files import OutputWriteError
    from floatmoor.io.output_folders import OwnedFolder
    from floatmoor.uq.output import study_summary
    from floatmoor.uq.run import RUNS_NAME, StudyRunsFailed, run_study

    progress, compiling = _campaign_reporters(args.quiet)
    runs = folder / RUNS_NAME
    try:  # the runs are kept whatever happens: a re-run resumes them
        with watch_compilation(compiling, lambda seconds: None), \
                OwnedFolder(folder, "uq", keep=(RUNS_NAME,), keep_on=(StudyRunsFailed,)):
            result = run_study(study, folder, workers=args.workers, scheduler=args.scheduler,
                               progress=progress, restart=args.restart,
                               moved_aside=_say_moved_aside)
    except KeyboardInterrupt as stop:
        held = f"the finished runs are in {runs} (re-run the same command to resume)" \
            if runs.is_file() else "no run finished"
        print(f"floatmoor: {signal_name(stop)}; {held}", file=sys.stderr)
        return exit_status(stop)
    except StudyRunsFailed as err:
        print(f"{err.total - len(err.failed)} of {err.total} runs complete; the quadrature "
              f"rule needs every node: no surrogate built; the runs are in {runs}")
        report_failures("uq", err.failed, err.total)
        return EXIT_FAILED
    except OutputWriteError as err:
        held = f"; the finished runs are in {runs} (re-run the same command to resume)" \
            if runs.is_file() else ""
        print(f"floatmoor: uq failed: {err}; the other files it wrote were removed{held}",
              file=sys.stderr)
        return EXIT_FAILED
    summary = study_summary(result)
    if args.json:
        print(json.dumps(summary, indent=2))
    else:
        print(_format_uq_summary(summary))
    if summary["dropped_runs"]:  # the surrogate is written, and the study still fails loudly
        print(f"floatmoor: uq: {len(summary['dropped_runs'])} of {summary['runs']} runs "
              "failed or gave non-finite values and were dropped from the regression (the "
              f"results without them are in {folder}): "
              + "; ".join(summary["dropped_runs"][:_NAMED_FAILURES]), file=sys.stderr)
        return EXIT_FAILED
    return EXIT_OK


def _format_uq_summary(summary: dict) -> str:
    """The study summary as plain text: one line per quantity."""
    rows = [f"{shown(summary['title'])}: {summary['method']}, {summary['runs']} runs "
            f"({len(summary['dropped_runs'])} dropped)"]
    for name, q in summary["quantities"].items():
        u = q["units"]
        if "window_s" in q:
            total = ", ".join(f"{k} {v:.3g}" for k, v in q["sobol_total_weighted"].items())
            rows.append(f"  {name} [{u}] over {q['window_s'][0]:g} to {q['window_s'][1]:g} s: "
                        f"mean {q['min_mean']:.5g} to {q['max_mean']:.5g}, band "
                        f"{q['min_lower']:.5g} to {q['max_upper']:.5g}, largest std "
                        f"{q['max_std']:.4g}; variance-weighted S_T: {total}")
        else:
            total = ", ".join(f"{k} {v:.3g}" for k, v in q["sobol_total"].items())
            rows.append(f"  {name} [{u}]: mean {q['mean']:.7g}, variance {q['variance']:.7g}, "
                        f"std {q['std']:.5g}, band {q['lower']:.5g} to {q['upper']:.5g}, "
                        f"validation error {q['validation_error']:.3g}; S_T: {total}")
    rows.append(f"results in {summary['output']}")
    return "\n".join(rows)


def _left_behind(output: Path, before: tuple[int, int, int] | None,
                 why: str = "the run stopped before recording") -> str:
    """What a stopped run left in ``output`` (``before``: its
    :func:`~floatmoor.io.output_files.file_state` when the run began): partial results up to
    some time, or nothing."""
    from floatmoor.io.netcdf import read_attributes
    from floatmoor.io.output_files import written_since

    if not written_since(output, before):
        return ("nothing written" + (f" ({output} is unchanged)" if before is not None else "")
                + f": {why}")
    attrs = read_attributes(output) or {}
    t = attrs.get("simulated_time_s")
    upto = f" up to t = {float(t):.6g} s" if isinstance(t, (int, float)) else ""
    validity = [m for m in str(attrs.get("validity_warnings", "")).split("\n") if m]
    return f"partial results{upto} written to {output}" + "".join(
        f"\n  warning: outside the model's validity: {m}" for m in validity)


def _campaign_left_behind(output: Path, before: tuple[int, int, int] | None) -> str:
    """What a stopped sweep left in ``output``: how many runs it holds, or nothing."""
    from floatmoor.io.netcdf import read_attributes
    from floatmoor.io.output_files import written_since

    if not written_since(output, before):
        return "nothing written" + (f" ({output} is unchanged)" if before is not None else "")
    attrs = read_attributes(output) or {}
    complete = attrs.get("runs_complete")
    held = f"{int(complete)} finished runs are" if complete is not None else "finished runs are"
    return f"{held} in {output} (re-run the same command to resume)"


def _close(progress: object) -> None:
    if progress is not None:
        progress.close()  # type: ignore[attr-defined]


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


if __name__ == "__main__":  # pragma: no cover - ``python -m floatmoor.cli``
    run()
