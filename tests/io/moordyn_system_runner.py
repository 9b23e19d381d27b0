"""Peer-code harness for mooring systems: a floatmoor case exported to a MoorDyn v2 deck
(``floatmoor export moordyn``: :func:`floatmoor.io.moordyn.exporter.export_case`), run in
MoorDyn 2.7 with its coupled points driven along the case's prescribed motion.

This is a test helper, not a test file (tests/simulation/test_system_moordyn.py uses it). It reuses
the single-line harness (:mod:`tests.io.moordyn_runner`: console capture, initialisation,
the coupling path, the error type) and its mapping notes, which hold for systems too: every
section is a MoorDyn line, every point a MoorDyn point (fixed -> Fixed, body -> Coupled, free
-> Free with mass, volume, CdA and Ca), line types by ``floatmoor.io.moordyn.line_types``.

What differs between the two codes on a system, besides the discretisations:

- seabed: MoorDyn has one kBot/cBot per unit of its diameter, the exporter writes those of the
  first section's line type, so only sections of that type have the same contact in both codes;
  a free point has no seabed contact in MoorDyn-C 2.7, while floatmoor gives a point with a
  displaced volume one of its own. Cases for comparison keep other types and the points off the
  seabed;
- friction: MoorDyn's ramp is linear per node, floatmoor's smooth: cases compare without;
- a MoorDyn point takes the end nodes of its lines into its mass (their half segments' mass,
  added mass, weight and drag): a lumped-mass effect that vanishes with the segment length;
- the initial state: each code solves its own (MoorDyn's stationary solver for ``TmaxIC``
  pseudo-seconds from its catenaries and the deck's point positions, floatmoor's statics then
  its settling), so a comparison starts from rest and ramps the motion in.

Coupling: MoorDyn's coupled DOFs are its Coupled points in the deck's order (the exporter
numbers the points in the case's order), three each; the harness feeds them the body points'
positions and velocities of floatmoor's own forced run
(:func:`floatmoor.simulation.forced.body_points_state`) as the single-line harness does: within a
coupling interval MoorDyn moves a coupled point at the interval's secant velocity; the interval
starts are the cubic Hermite interpolant of the samples, the path floatmoor's DG system follows
between its samples too. The coupling interval must be short: at the end of an interval, where
MoorDyn returns the force, the secant velocity differs from the path's by ``a dt_c / 2``, and
MoorDyn's internal damping of the last segment (``c_int / l`` per unit of relative velocity,
growing with the segment count) turns that into a force error in phase with the acceleration.
On the lazy-wave line's top chain (120 m, 50 segments) it is 1.5 kN of a 14 kN tension range
with one interval per 0.02 s sample, 0.32 kN with 4, 33 N with 16, 5 N with 50 (floatmoor and a
separate lumped-mass integration agree with the last); hence :data:`COUPLING_INTERVAL`.

Fairlead force of a line: the force MoorDyn returns on the Coupled point at the line's end, i.e.
the net force of the end node of the line's last section (module docstring of
:mod:`tests.io.moordyn_runner`); so a body point must end one line only. That force
excludes the end node's inertia: the node (half a segment of line, with its added mass) is
moved by the body, so the force the line exerts on the body is ``F - M a``, ``M`` the point's
mass matrix (``GetPointM``: the node's mass and added mass) and ``a`` the prescribed
acceleration. :meth:`SystemRun.fairlead_tension` subtracts it by default (``inertia=True``),
which is the continuous line's end tension that floatmoor records; the difference is O(segment
length): on the lazy-wave line at 50 segments ~0.15 kN, 1.2 % of its tension range. Free
points: ``GetPointPos`` after each output step.
"""

from __future__ import annotations

import math
import time as _time
from collections.abc import Mapping
from dataclasses import dataclass, replace

import numpy as np

from floatmoor.io.moordyn.deck import Deck, DeckOption
from floatmoor.io.moordyn.exporter import export_case
from floatmoor.io.moordyn.writer import deck_text
from floatmoor.mooring.deck_numerics import deck_numerics
from floatmoor.mooring.statics_solver import build_static_system, solve_statics
from floatmoor.simulation.forced import body_points_state
from tests.io.moordyn_runner import (MoorDynError, _as_list, _check_motion,
                                     _console_tail, _coupling_path, _stdout_to, open_input)

#: Pseudo-time [s] of MoorDyn's stationary initial-condition solver (TmaxIC) on systems: from
#: the static positions of the free points, the lazy-wave line's fairlead tension is 1.8 % low
#: after 10 s (the single-line harness's value) and within 1e-4 of floatmoor's statics after 60.
SYSTEM_IC_MAX_TIME = 60.0

#: Longest coupling interval [s] (``moordyn.Step``): the secant velocity's error at the interval's
#: end, ``a dt_c / 2``, reaches MoorDyn's fairlead force through the last segment's internal
#: damping (module docstring); 0.4 ms keeps it below ~0.1 % of the tension range on both test
#: systems up to 200 segments per section (5 N at 50 segments on the lazy wave's top chain).
COUPLING_INTERVAL = 4e-4

__all__ = ["SystemRun", "COUPLING_INTERVAL", "system_deck", "run_moordyn_system", "relative_error"]


@dataclass(frozen=True)
class SystemRun:
    """MoorDyn's record of a system run, at the output samples."""

    time: np.ndarray  #: [s], (n,)
    fairlead_force: dict[str, np.ndarray]  #: line name -> force on its end point [N], (n, 3)
    fairlead_inertia: dict[str, np.ndarray]  #: line name -> M a of its end node [N], (n, 3)
    body_force: dict[str, np.ndarray]  #: body point name -> MoorDyn's force on it [N], (n, 3)
    body_inertia: dict[str, np.ndarray]  #: body point name -> M a of the point [N], (n, 3)
    point_position: dict[str, np.ndarray]  #: free point name -> position [m], (n, 3)
    segments: dict[str, int]  #: section label ``line[index]`` -> MoorDyn segments
    dt: float  #: MoorDyn's dtM [s]
    wall: float  #: wall-clock seconds in ``moordyn.Step`` (initialisation excluded)

    def fairlead_tension(self, line: str, *, inertia: bool = True) -> np.ndarray:
        """|force| of ``line`` on its end point [N], (n,): with ``inertia`` the force on the
        body (MoorDyn's coupled force less its end node's ``M a``), without it MoorDyn's."""
        force = self.fairlead_force[line]
        if inertia:
            force = force - self.fairlead_inertia[line]
        return np.linalg.norm(force, axis=1)


def _set_option(deck: Deck, key: str, value: str) -> Deck:
    options = [o for o in deck.options if o.key != key]
    return replace(deck, options=tuple(options) + (DeckOption(key, value),))


def static_positions(case) -> dict[str, tuple[float, float, float]]:
    """The free points' positions in the system's static equilibrium (floatmoor's statics,
    body points at rest), name -> position [m]."""
    statics = solve_statics(build_static_system(case.points, case.lines, case.environment,
                                                case.seabed))
    kinds = {p.name: p.kind for p in case.points}
    return {n: tuple(float(c) for c in p) for n, p in zip(statics.point_names, statics.positions)
            if kinds[n] == "free"}


def system_deck(case, *, segment_scale: float = 1.0, dt: float | None = None,
                ic_max_time: float = SYSTEM_IC_MAX_TIME, start_at_statics: bool = True,
                extra_options: Mapping[str, object] | None = None) -> tuple[str, Deck]:
    """The exported deck of ``case`` (text and :class:`Deck`) with every line's segment count
    multiplied by ``segment_scale`` (rounded, at least 2; a damping ratio BA = -zeta_md scaled
    with it, so that the internal damping coefficient stays floatmoor's), dtM = ``dt`` (default the
    exporter's), ``TmaxIC`` and no output files; with ``start_at_statics`` its free points
    placed at the static equilibrium (:func:`static_positions`), MoorDyn's initial guess."""
    deck = export_case(case, deck_numerics(case)).deck
    if start_at_statics:
        numbers = {p.name: k for k, p in enumerate(case.points, start=1)}
        at = {numbers[n]: x for n, x in static_positions(case).items()}
        deck = replace(deck, points=tuple(replace(p, position=at.get(p.number, p.position))
                                          for p in deck.points))
    lines = tuple(replace(ln, segments=max(2, int(round(ln.segments * segment_scale))))
                  for ln in deck.lines)
    # a negative BA is a ratio of a segment's critical damping, -zeta_md, and the exporter
    # chose it for N segments (c_int = zeta_md (L / N) sqrt(EA m)): the same c_int on N' is
    # zeta_md N' / N, the same factor for every line of a type
    factor: dict[str, float] = {}
    for old, new in zip(deck.lines, lines):
        f = new.segments / old.segments
        if factor.setdefault(old.line_type, f) != f:
            raise ValueError(f"line type {old.line_type!r}: lines refined unequally")
    types = tuple(replace(lt, internal_damping=lt.internal_damping * factor.get(lt.name, 1.0))
                  if lt.internal_damping < 0.0 else lt for lt in deck.line_types)
    deck = replace(deck, lines=lines, line_types=types)
    if dt is not None:
        deck = _set_option(deck, "dtM", repr(float(dt)))
    deck = _set_option(deck, "TmaxIC", repr(float(ic_max_time)))
    deck = _set_option(deck, "disableOutput", "1")
    for key, value in (extra_options or {}).items():
        deck = _set_option(deck, key, str(value))
    return deck_text(deck), deck


def _dt(deck: Deck) -> float:
    return float(next(o.value for o in deck.options if o.key == "dtM"))


def run_moordyn_system(case, time: np.ndarray, *, segment_scale: float = 1.0,
                       dt: float | None = None, substeps: int | None = None,
                       ic_max_time: float = SYSTEM_IC_MAX_TIME, start_at_statics: bool = True,
                       extra_options: Mapping[str, object] | None = None) -> SystemRun:
    """Run ``case``'s exported deck in MoorDyn, its Coupled points on the case's motion.

    Parameters
    ----------
    case
        A :class:`floatmoor.case.schema.Case` with a prescribed motion.
    time
        Output times [s], uniform from 0 (the samples of the body points' paths).
    segment_scale, dt, ic_max_time, start_at_statics, extra_options
        As :func:`system_deck`.
    substeps
        Coupling intervals per sample interval
        (:func:`tests.io.moordyn_runner.run_moordyn_forced`); default: as many as make them at
        most :data:`COUPLING_INTERVAL`.

    Raises
    ------
    MoorDynError
        If MoorDyn rejects the deck, fails to initialise or its integration fails.
    """
    import moordyn

    text, deck = system_deck(case, segment_scale=segment_scale, dt=dt, ic_max_time=ic_max_time,
                             start_at_statics=start_at_statics, extra_options=extra_options)
    numbers = {p.name: k for k, p in enumerate(case.points, start=1)}
    body = [p.name for p in case.points if p.kind == "body"]
    free = [p.name for p in case.points if p.kind == "free"]
    owner: dict[str, str] = {}  # body point at a line's end -> the line
    for sec in case.sections:
        for name in (sec.start, sec.end):
            if name in body:
                if name in owner:
                    raise ValueError(f"body point {name!r} joins more than one section: "
                                     "MoorDyn's coupled force is their sum")
                owner[name] = sec.line
    ends = {n: owner[n] for n in body if n in owner
            and any(s.end == n and s.line == owner[n] for s in case.sections)}
    t = np.asarray(time, dtype=float)
    pos, vel = body_points_state(case, body, t)
    x = pos.reshape(t.size, -1)
    v = vel.reshape(t.size, -1)
    t, x, v, step = _check_motion(t, x, v)
    if substeps is None:
        substeps = max(1, math.ceil(step / COUPLING_INTERVAL - 1e-9))
    start, secant = _coupling_path(x, v, step, substeps)
    dt_c = step / substeps
    starts = [_as_list(p) for p in start]
    vels = [_as_list(p) for p in secant]
    # the prescribed accelerations at the samples (second order; the paths are smooth)
    acc = np.gradient(v, t, axis=0).reshape(t.size, len(body), 3)
    force = np.empty((t.size, len(body), 3))
    inertia = np.empty((t.size, len(body), 3))
    points = np.empty((t.size, len(free), 3))
    k = 0
    with open_input(text, x[0], v[0]) as (system, log):
        handles = [moordyn.GetPoint(system, numbers[n]) for n in free]
        coupled = [moordyn.GetPoint(system, numbers[n]) for n in body]

        def record(f) -> None:
            force[k] = np.reshape(f, (len(body), 3))
            for j, h in enumerate(coupled):
                inertia[k, j] = np.asarray(moordyn.GetPointM(h)) @ acc[k, j]
            for j, h in enumerate(handles):
                points[k, j] = moordyn.GetPointPos(h)

        record(moordyn.Step(system, _as_list(x[0]), _as_list(v[0]), 0.0, 0.0))
        i = 0
        try:
            with _stdout_to(log):
                wall_start = _time.perf_counter()
                for i in range(len(starts)):
                    f = moordyn.Step(system, starts[i], vels[i], i * dt_c, dt_c)
                    if (i + 1) % substeps == 0:
                        k += 1
                        record(f)
                wall = _time.perf_counter() - wall_start
        except RuntimeError as exc:
            raise MoorDynError(f"MoorDyn failed near t = {i * dt_c:.6g} s: "
                               f"{exc}{_console_tail(log)}") from exc
    if not (np.all(np.isfinite(force)) and np.all(np.isfinite(points))):
        raise MoorDynError("MoorDyn returned a non-finite force or position")
    labels = [f"{s.line}[{s.index}]" for s in case.sections]
    return SystemRun(time=t.copy(),
                     fairlead_force={ends[n]: force[:, j] for j, n in enumerate(body)
                                     if n in ends},
                     fairlead_inertia={ends[n]: inertia[:, j] for j, n in enumerate(body)
                                       if n in ends},
                     body_force={n: force[:, j] for j, n in enumerate(body)},
                     body_inertia={n: inertia[:, j] for j, n in enumerate(body)},
                     point_position={n: points[:, j] for j, n in enumerate(free)},
                     segments={lab: ln.segments for lab, ln in zip(labels, deck.lines)},
                     dt=_dt(deck), wall=wall)


def relative_error(ours: np.ndarray, theirs: np.ndarray) -> float:
    """max |ours - theirs| over the range of ``theirs`` [-]."""
    return float(np.abs(ours - theirs).max() / (theirs.max() - theirs.min()))

