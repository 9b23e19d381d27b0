"""The ``floatmoor`` command line.

``floatmoor check CASE`` validates a case and prints what follows from it; ``floatmoor run
CASE`` runs it; ``floatmoor sweep CASE --grid ...`` runs a campaign; ``floatmoor study
qd-verification -o DIR`` runs the quasi-dynamic verification study
(docs/cases/qd_verification.md);
``floatmoor uq STUDY.toml -o DIR`` runs an uncertainty-quantification study (gPC surrogates of
quantities of interest, :mod:`floatmoor.uq.run`; a failed run of a quadrature design exits 1);
``floatmoor hydro build CASE`` builds the floater's BEM database and checks it,
``floatmoor hydro import FILE... -o PATH`` makes one from WAMIT or BEMIO files,
``floatmoor hydro check NAME`` checks one (all three exit 1 when a check fails), ``floatmoor
hydro info NAME`` describes it and where its data came from, and ``floatmoor hydro
fit-state-space NAME`` adds a state-space realisation of its radiation kernel; ``floatmoor rao
CASE -o RAO.nc`` writes the floater's RAOs with its mooring (:mod:`floatmoor.cli.rao`);
``floatmoor import moordyn DECK -o CASE.toml`` and ``floatmoor export moordyn CASE -o
DECK.dat`` convert MoorDyn input files, ``floatmoor import orcaflex MODEL.yml -o CASE.toml``
reads the mooring of an OrcaFlex text data file; ``floatmoor animate RUN.nc -o OUT.gif`` and
``floatmoor vtk RUN.nc -o DIR`` draw a run's line shapes (:mod:`floatmoor.cli.plots`);
``floatmoor scale CASE --length-scale LAMBDA -o NEW.toml`` writes the case at another scale
(:mod:`floatmoor.similitude`); a missing, damaged or stale database, or one failing a
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

Every command, its progress display and its printing live here, and only here: library
code never prints (it returns, takes a ``progress`` callback or warns), and nothing outside
this package imports it (docs/development.md#1-package-layout-and-import-order). The
modules, one per command family:

* :mod:`~floatmoor.cli.app`: the parser, :func:`main` and :func:`run` (the console script,
  ``python -m floatmoor`` and ``python -m floatmoor.cli``), the dispatch to the commands;
* :mod:`~floatmoor.cli.status`: the exit statuses 0 done, 1 failed, 2 bad input, 130/143
  interrupted, 141 closed output, and the ``floatmoor: error:`` line;
* :mod:`~floatmoor.cli.check`, :mod:`~floatmoor.cli.run_case`: ``check`` and ``run``;
* :mod:`~floatmoor.cli.campaign`, :mod:`~floatmoor.cli.study`, :mod:`~floatmoor.cli.uq`:
  ``sweep``, ``study`` and ``uq``;
* :mod:`~floatmoor.cli.hydro`, :mod:`~floatmoor.cli.hydro_info`, :mod:`~floatmoor.cli.rao`:
  ``hydro build | import | check``, ``hydro info | fit-state-space`` and ``rao``;
* :mod:`~floatmoor.cli.report`, :mod:`~floatmoor.cli.plots`, :mod:`~floatmoor.cli.scale`:
  ``report``/``compare``, ``animate``/``vtk`` and ``scale``;
* :mod:`~floatmoor.cli.moordyn`, :mod:`~floatmoor.cli.orcaflex`: ``import``/``export
  moordyn`` and ``import orcaflex``;
* :mod:`~floatmoor.cli.progress`: the progress line of a run;
* :mod:`~floatmoor.cli.case_reference`: ``python -m floatmoor.cli.case_reference``, the
  generated case-file reference page (docs/reference/case_file.md).

Importing this package loads the numerical libraries (the case loader); a Ctrl-C during that
prints one line (:data:`~floatmoor.cli.status.STARTUP_INTERRUPTED`) and exits with 130, no
traceback (``import floatmoor`` itself loads none of them: floatmoor/__init__.py).
"""

from __future__ import annotations

import sys

from floatmoor.cli.status import (
    EXIT_BAD_INPUT, EXIT_BROKEN_PIPE, EXIT_FAILED, EXIT_INTERRUPTED, EXIT_OK, STARTUP_INTERRUPTED,
)

try:  # the numerical libraries load here: a Ctrl-C during it gets one line, no traceback
    from floatmoor.cli.app import main, run
except KeyboardInterrupt:
    print(STARTUP_INTERRUPTED, file=sys.stderr)
    raise SystemExit(EXIT_INTERRUPTED) from None

__all__ = ["main", "run", "EXIT_OK", "EXIT_FAILED", "EXIT_BAD_INPUT", "EXIT_INTERRUPTED",
           "EXIT_BROKEN_PIPE"]
