"""Peer-code harness for imported MoorDyn decks: MoorDyn-C 2.7 (the ``moordyn`` package) run on
the deck itself (not an export of the case), its Coupled points driven along the imported
case's body motion, the force on each Coupled point recorded.

This is a test helper, not a test file (tests/io/test_moordyn_driver.py uses it). It reuses the
single-line harness (:mod:`tests.io.moordyn_runner`: console capture, initialisation, the
coupling path, the error type).

The deck is run as written, with these options put before its own (MoorDyn reads options in
order, so the deck's own win): the driver's ``g``, ``rho`` and ``WtrDpth`` (MoorDyn-F decks
leave them to the driver; the case's environment holds them), ``writeLog 0`` and
``disableOutput 1``. MoorDyn computes its own initial state with the Coupled points at the
motion's pose at t = 0 (its stationary solver for the deck's ``TmaxIC``).

Coupling: as :func:`tests.io.moordyn_system_runner.run_moordyn_system`, the Coupled points'
positions and velocities of the case's motion (:func:`floatmoor.simulation.forced.
body_points_state`, the path floatmoor's lines follow) at the output samples, each sample
interval refined into ``substeps`` coupling intervals by cubic Hermite interpolation; the force
on a Coupled point is MoorDyn's net force of the line end nodes at it, less their ``M a``
(:class:`tests.io.moordyn_system_runner.SystemRun`), the line's tension at the fairlead.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from floatmoor.io.moordyn.deck import POINT_COUPLED
from floatmoor.io.moordyn.parser import read_deck
from floatmoor.simulation.forced import body_points_state
from tests.io.moordyn_runner import (MoorDynError, _as_list, _check_motion, _console_tail,
                                     _coupling_path, _stdout_to, open_input)

__all__ = ["deck_run_text", "run_moordyn_deck"]


def deck_run_text(path: Path, case) -> str:
    """The deck's text with the run's options put first in its OPTIONS section."""
    lines = Path(path).read_text().splitlines()
    heading = next(i for i, line in enumerate(lines)
                   if "---" in line and "OPTIONS" in line.upper())
    env = case.environment
    extra = [f"{env.gravity!r} g", f"{env.water_density!r} rho", f"{env.water_depth!r} WtrDpth",
             "0 writeLog", "1 disableOutput"]
    return "\n".join(lines[:heading + 1] + extra + lines[heading + 1:]) + "\n"


def run_moordyn_deck(path: Path, case, time: np.ndarray, *, coupling_interval: float,
                     line_tensions: bool = False) -> dict[str, np.ndarray]:
    """Run the deck at ``path`` in MoorDyn-C, its Coupled points on ``case``'s motion.

    Parameters
    ----------
    path
        The MoorDyn deck the case was imported from (its Coupled points are the case's
        ``pointN`` body points).
    case
        The imported case (environment and motion).
    time
        Output times [s], uniform from 0.
    coupling_interval
        Longest coupling interval [s] (``moordyn.Step``).
    line_tensions
        Also record each line's ``GetLineFairTen`` (its last segment's tension, low by about
        half a segment's weight against the end node's) as ``lineN``.

    Returns
    -------
    dict
        Coupled point name (``pointN``) -> tension |F - M a| on it [N], (n,) (MoorDyn-C
        reports no force on Fixed points: ``line_tensions`` for lines between them).

    Raises
    ------
    MoorDynError
        MoorDyn rejects the deck, fails to initialise or to integrate.
    """
    import moordyn

    deck = read_deck(path)
    coupled = [p for p in deck.points if p.attachment == POINT_COUPLED]
    names = [f"point{p.number}" for p in coupled]
    t = np.asarray(time, dtype=float)
    pos, vel = body_points_state(case, names, t)
    x = pos.reshape(t.size, -1)
    v = vel.reshape(t.size, -1)
    t, x, v, step = _check_motion(t, x, v)
    substeps = max(1, math.ceil(step / coupling_interval - 1e-9))
    if x.shape[1]:
        start, secant = _coupling_path(x, v, step, substeps)
    else:  # no Coupled points: MoorDyn steps on its own
        start = secant = np.zeros(((t.size - 1) * substeps, 0))
    dt_c = step / substeps
    acc = np.gradient(v, t, axis=0).reshape(t.size, len(names), 3)
    force = np.empty((t.size, len(names), 3))
    line_ten = np.empty((t.size, len(deck.lines)))
    with open_input(deck_run_text(path, case), x[0], v[0]) as (system, log):
        handles = [moordyn.GetPoint(system, p.number) for p in coupled]
        lines = [moordyn.GetLine(system, ln.number) for ln in deck.lines] if line_tensions else []

        def record(k: int, f) -> None:
            force[k] = np.reshape(f, (len(names), 3))
            for j, h in enumerate(handles):
                force[k, j] -= np.asarray(moordyn.GetPointM(h)) @ acc[k, j]
            for j, h in enumerate(lines):
                line_ten[k, j] = moordyn.GetLineFairTen(h)

        record(0, moordyn.Step(system, _as_list(x[0]), _as_list(v[0]), 0.0, 0.0))
        i = 0
        try:
            with _stdout_to(log):
                for i in range(len(start)):
                    f = moordyn.Step(system, _as_list(start[i]), _as_list(secant[i]),
                                     i * dt_c, dt_c)
                    if (i + 1) % substeps == 0:
                        record((i + 1) // substeps, f)
        except RuntimeError as exc:
            raise MoorDynError(f"MoorDyn failed near t = {i * dt_c:.6g} s: "
                               f"{exc}{_console_tail(log)}") from exc
    if not np.all(np.isfinite(force)):
        raise MoorDynError("MoorDyn returned a non-finite force")
    tension = {n: np.linalg.norm(force[:, j], axis=1) for j, n in enumerate(names)}
    if line_tensions:
        tension.update({f"line{ln.number}": line_ten[:, j] for j, ln in enumerate(deck.lines)})
    return tension
