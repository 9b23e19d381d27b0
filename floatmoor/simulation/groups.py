"""Mooring systems solved as one: the lines joined by free points (or of several sections).

A case's lines are independent when each is one section from a fixed to a body point; every
other line belongs to a :class:`SystemGroup`, the lines connected through free points, of one
model (the loader refuses a free point joining lines of two models). A quasi-static group is
solved by the system statics (:class:`~floatmoor.mooring.statics_solver.SystemStatics`: the
equilibrium of its free points at every instant), a dynamic one by the DG system
(:class:`~floatmoor.mooring.dg.system.DynamicSystem`: sections and points advanced together).
Both take the positions (and velocities) of their body points and give the forces of every
section on its two points, every point's position and the sections' laid lengths.

A forced-motion run solves an independent line as a :class:`SingleLine`, a group of one
section to one body point with the same interface (``lines``, ``path_lines``,
``empty_samples``, ``solve_path(time, path, velocity, samples)``, ``line_shape``, ``store``,
``failed_index``), so that one chunk loop (:mod:`floatmoor.simulation.forced`) serves both.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from types import SimpleNamespace
from typing import Protocol

import numpy as np
from numpy.typing import NDArray

from floatmoor.case.schema import Case, Line
from floatmoor.disjoint_sets import DisjointSets
from floatmoor.errors import CaseError, SolverError
from floatmoor.mooring.dg.system import DynamicSystem
from floatmoor.mooring.stepping import MooringSolver, PathStepper
from floatmoor.mooring.statics_solver import SystemStatics, build_static_system

__all__ = ["SystemGroup", "GroupSamples", "SingleLine", "LineSamples", "system_groups",
           "body_point_line"]


def body_point_line(case: Case, name: str) -> Line:
    """A line as the prescribed motions see body point ``name``: one of the lines at the
    point, with its ``fairlead`` at the point (at rest) and its ``anchor`` at the line's
    other end (the direction of a circular motion's plane)."""
    for line in case.lines:
        if name in (line.start, line.end):
            other = line.anchor if line.end == name else line.fairlead
            return replace(line, anchor=other, fairlead=case.point(name).position)
    raise KeyError(name)


@dataclass
class GroupSamples:
    """A group's outputs over a run of samples (the solvers' arrays, solver order)."""

    positions: NDArray[np.float64]  #: (n, points, 3) [m]
    start_force: NDArray[np.float64]  #: (n, sections, 3) on each section's start point [N]
    end_force: NDArray[np.float64]  #: (n, sections, 3) on each section's end point [N]
    laid_length: NDArray[np.float64]  #: (n, sections) [m]
    iterations: NDArray[np.float64]  #: (n,) Newton iterations or time steps per sample

    @classmethod
    def empty(cls, n: int, points: int, sections: int) -> "GroupSamples":
        return cls(np.zeros((n, points, 3)), np.zeros((n, sections, 3)),
                   np.zeros((n, sections, 3)), np.zeros((n, sections)), np.zeros(n))

    def part(self, rows: slice) -> "GroupSamples":
        """The samples ``rows`` (views)."""
        return GroupSamples(self.positions[rows], self.start_force[rows],
                            self.end_force[rows], self.laid_length[rows], self.iterations[rows])


class SampleSink(Protocol):
    """Where a forced-motion run's units record their samples (the run's recorder)."""

    def store_line(self, line: int, samples: "LineSamples", path: NDArray[np.float64],
                   start: int, stop: int) -> None:
        """Record samples [start, stop) of an independent line."""

    def store_group(self, case: Case, group: "SystemGroup", samples: GroupSamples,
                    start: int, stop: int) -> None:
        """Record samples [start, stop) of a system group."""


@dataclass
class LineSamples:
    """An independent line's outputs over a run of samples (its model's arrays)."""

    fairlead_force: NDArray[np.float64]  #: (n, 3) [N]
    anchor_force: NDArray[np.float64]  #: (n, 3) [N]
    laid_length: NDArray[np.float64]  #: (n,) [m]
    steps: NDArray[np.float64]  #: (n,) Newton iterations or time steps per sample

    @classmethod
    def empty(cls, n: int) -> "LineSamples":
        return cls(np.zeros((n, 3)), np.zeros((n, 3)), np.zeros(n), np.zeros(n))

    def part(self, rows: slice) -> "LineSamples":
        """The samples ``rows`` (views)."""
        return LineSamples(self.fairlead_force[rows], self.anchor_force[rows],
                           self.laid_length[rows], self.steps[rows])


@dataclass
class SingleLine:
    """An independent line (one section from a fixed point to a body point) as a group of
    one: its model, stepped along the path of its fairlead.

    Attributes
    ----------
    index
        Its index in ``case.lines``.
    model
        Its line model.
    """

    index: int
    model: PathStepper
    failed_index: int = -1

    @property
    def lines(self) -> tuple[int, ...]:
        """The case's lines it solves (its own)."""
        return (self.index,)

    def path_lines(self, case: Case) -> list[Line]:
        """The line whose prescribed fairlead motion drives it."""
        return [case.lines[self.index]]

    def empty_samples(self, n: int) -> LineSamples:
        """Outputs for ``n`` samples."""
        return LineSamples.empty(n)

    def store(self, case: Case, sink: SampleSink, samples: LineSamples,
              path: NDArray[np.float64], start: int, stop: int) -> None:
        """Record samples [start, stop) (``samples`` and ``path`` from ``start``)."""
        sink.store_line(self.index, samples, path[:, 0], start, stop)

    def solve_path(self, time: NDArray[np.float64], path: NDArray[np.float64],
                   velocity: NDArray[np.float64], out: LineSamples) -> None:
        """Step the line along its fairlead's path (n, 1, 3), writing ``out``.

        Raises
        ------
        SolverError
            As the model; :attr:`failed_index` is the first sample not solved.
        """
        try:
            self.model.solve_path(time, path[:, 0], velocity[:, 0], out.fairlead_force,
                                  out.anchor_force, out.laid_length, out.steps)
        except SolverError:
            self.failed_index = self.model.failed_index
            raise
        self.failed_index = -1

    def line_shape(self, case: Case, line_index: int, path: NDArray[np.float64]
                   ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Node positions (n, 3) [m] and tensions (n,) [N] of the line now, its fairlead at
        ``path`` (1, 3)."""
        return self.model.current_shape(path[0])


@dataclass
class SystemGroup:
    """Lines of one model joined through free points, with their solver.

    Attributes
    ----------
    model
        "quasi-static" or "dynamic".
    lines
        Indices of its lines in ``case.lines``.
    points, sections
        Indices in ``case.points`` / ``case.sections`` of the solver's points and sections,
        in the solver's order.
    body_points
        Indices in ``case.points`` of its body points, in the order the solver takes them.
    solver
        The statics (quasi-static) or the DG system (dynamic): a
        :class:`~floatmoor.mooring.stepping.MooringSolver`.
    """

    model: str
    lines: tuple[int, ...]
    points: tuple[int, ...]
    sections: tuple[int, ...]
    body_points: tuple[int, ...]
    solver: MooringSolver
    #: unstretched arc length of every shape node of each of its lines, from the line's start
    arc_lengths: dict[int, NDArray[np.float64]] = field(default_factory=dict)
    #: the last solved point positions (quasi-static shapes are drawn between them)
    last_positions: NDArray[np.float64] | None = None
    failed_index: int = -1
    #: solver point index of each section's start and end (solver order)
    _start: tuple[int, ...] = ()
    _end: tuple[int, ...] = ()
    #: a dynamic group's laid lengths at its last step [m]
    _laid: NDArray[np.float64] | None = None

    def solve_path(self, time: NDArray[np.float64], body_positions: NDArray[np.float64],
                   body_velocities: NDArray[np.float64], out: GroupSamples) -> None:
        """Solve along the body points' paths (n, body points, 3), writing ``out``.

        Raises
        ------
        SolverError
            As the solver; :attr:`failed_index` is the first sample not solved.
        """
        try:
            self.solver.solve_path(time, body_positions, body_velocities, out.start_force,
                                   out.end_force, out.laid_length, out.positions,
                                   out.iterations)
        except SolverError:
            self.failed_index = max(int(self.solver.failed_index), 0)
            raise
        self.failed_index = -1
        self.last_positions = out.positions[-1].copy()

    # -- coupled runs: one body step at a time ------------------------------------------------
    def advance(self, t1: float, body_positions: NDArray[np.float64],
                body_velocities: NDArray[np.float64]) -> None:
        """Advance a dynamic group to ``t1``, its body points moving to the given positions
        and velocities (bodies, 3); a quasi-static group has no memory (nothing to do)."""
        if self.solver.has_memory:
            sample = self._one()
            self.solver.solve_path(np.array([float(t1)]), body_positions[None],
                                   body_velocities[None], sample.start_force,
                                   sample.end_force, sample.laid_length, sample.positions,
                                   sample.iterations)
            self._laid = sample.laid_length[0].copy()

    def current(self, body_positions: NDArray[np.float64],
                body_velocities: NDArray[np.float64]) -> GroupSamples:
        """The group now (one sample), its body points at ``body_positions`` moving at
        ``body_velocities`` (bodies, 3): a quasi-static group's equilibrium there (warm
        started), a dynamic group's state with the end fluxes answering those velocities."""
        sample = self._one()
        if not self.solver.has_memory:
            sol = self.solver.solve(body_positions)
            sample.positions[0] = sol.positions
            sample.start_force[0], sample.end_force[0] = sol.start_force, sol.end_force
            sample.laid_length[0] = sol.laid_length
            sample.iterations[0] = sol.iterations
            self.last_positions = sol.positions.copy()
        else:
            sf, ef = self.solver.section_end_forces(body_velocities)
            sample.positions[0] = self.solver.x
            sample.start_force[0], sample.end_force[0] = sf, ef
            sample.laid_length[0] = self._laid
        return sample

    def body_forces(self, sample: GroupSamples) -> NDArray[np.float64]:
        """Forces of the group's sections on each of its body points [N], (bodies, 3), from
        a sample of :meth:`current`."""
        where = {k: j for j, k in enumerate(self.points)}
        body = {where[k]: b for b, k in enumerate(self.body_points)}
        out = np.zeros((len(self.body_points), 3))
        for j in range(len(self.sections)):
            for column, force in ((self._start[j], sample.start_force[0, j]),
                                  (self._end[j], sample.end_force[0, j])):
                if column in body:
                    out[body[column]] += force
        return out

    def _one(self) -> GroupSamples:
        return GroupSamples.empty(1, len(self.points), len(self.sections))

    def path_lines(self, case: Case) -> list[Line]:
        """For each of its body points, the line whose prescribed fairlead motion moves it
        (:func:`body_point_line`)."""
        return [body_point_line(case, case.points[k].name) for k in self.body_points]

    def empty_samples(self, n: int) -> GroupSamples:
        """Outputs for ``n`` samples."""
        return GroupSamples.empty(n, len(self.points), len(self.sections))

    def store(self, case: Case, sink: SampleSink, samples: GroupSamples,
              path: NDArray[np.float64], start: int, stop: int) -> None:
        """Record samples [start, stop) of its lines, points and sections (``samples``
        from ``start``; the body points' ``path`` is in the samples' positions)."""
        sink.store_group(case, self, samples, start, stop)

    def line_shape(self, case: Case, line_index: int, path: NDArray[np.float64] | None = None
                   ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Node positions (n, 3) [m] and tensions (n,) [N] of one of its lines now, its
        sections one after another (``path``, its body points now, is not needed: the last
        solved point positions place the sections)."""
        line = case.lines[line_index]
        positions, tensions = [], []
        for section in line.sections:
            j = self._solver_section(case, section.line, section.index)
            p, t = self.solver.section_shape(j, self.last_positions)
            positions.append(p)
            tensions.append(t)
        return np.concatenate(positions), np.concatenate(tensions)

    def _solver_section(self, case: Case, line: str, index: int) -> int:
        labels = [case.sections[k] for k in self.sections]
        for j, s in enumerate(labels):
            if s.line == line and s.index == index:
                return j
        raise KeyError((line, index))

    def state_arrays(self) -> dict[str, NDArray[np.float64]]:
        """The solver's state (warm start, or the DG state) for a checkpoint."""
        return self.solver.state_arrays()

    def set_state_arrays(self, arrays: dict[str, NDArray[np.float64]]) -> None:
        """Restore a state of :meth:`state_arrays`."""
        self.solver.set_state_arrays(arrays)


def _components(case: Case, lines: list[int]) -> list[list[int]]:
    """The lines (indices) joined through free points, in file order."""
    kinds = {p.name: p.kind for p in case.points}
    joined = DisjointSets(lines)
    owner: dict[str, int] = {}
    for i in lines:
        for s in case.lines[i].sections:
            for name in (s.start, s.end):
                if kinds[name] != "free":
                    continue
                if name in owner:
                    joined.union(i, owner[name])
                else:
                    owner[name] = i
    groups: dict[int, list[int]] = {}
    for i in lines:
        groups.setdefault(joined.find(i), []).append(i)
    return sorted(groups.values())


def system_groups(case: Case, body_positions: dict[str, NDArray[np.float64]] | None = None
                  ) -> list[SystemGroup]:
    """The case's lines that are not independent, grouped and given their solvers (the
    quasi-static ones solved at rest, the dynamic ones settled), with the body points at rest
    or where ``body_positions`` (name -> position) puts them (a floater's equilibrium).

    Raises
    ------
    CaseError
        When a group has no static equilibrium at rest (the system as given cannot hold
        itself: a buoy that would surface, a point that keeps landing and lifting off), naming
        the point.
    """
    rest = [i for i, line in enumerate(case.lines) if not case.is_independent(line)]
    index = {p.name: k for k, p in enumerate(case.points)}
    section_index = {(s.line, s.index): k for k, s in enumerate(case.sections)}
    groups = []
    for members in _components(case, rest):
        lines = [case.lines[i] for i in members]
        model = lines[0].model
        used = {n for ln in lines for s in ln.sections for n in (s.start, s.end)}
        moved = body_positions or {}
        points = [replace(p, position=tuple(float(c) for c in moved[p.name]))
                  if p.name in moved else p for p in case.points if p.name in used]
        sections = [s for ln in lines for s in ln.sections]
        if model == "quasi-static":
            try:
                statics = SystemStatics(build_static_system(points, lines, case.environment,
                                                            case.seabed))
                statics.solve()
            except SolverError as err:
                raise CaseError(case.source, f"lines[{members[0]}]", "a mooring system with a "
                                "static equilibrium at rest", str(err)) from None
            solver: MooringSolver = statics
            body = [index[n] for n in statics.system.body_point_names]
            order = [section_index[_label_key(n)] for n in statics.system.section_names]
            point_order = [index[n] for n in statics.system.point_names]
        elif model == "dynamic":
            sub = SimpleNamespace(lines=lines, sections=tuple(sections), points=tuple(points),
                                  environment=case.environment, seabed=case.seabed)
            solver = DynamicSystem.from_case(sub)
            body = [index[solver.points[p].name] for p in solver.body_points]
            order = [section_index[(s.line, s.index)] for s in solver.sections]
            point_order = [index[p.name] for p in solver.points]
        else:  # the loader admits quasi-dynamic lines only as independent lines
            raise ValueError(f"no system solver for model {model!r}")
        where = {k: j for j, k in enumerate(point_order)}
        group = SystemGroup(model=model, lines=tuple(members), points=tuple(point_order),
                            sections=tuple(order), body_points=tuple(body), solver=solver,
                            _start=tuple(where[index[case.sections[k].start]] for k in order),
                            _end=tuple(where[index[case.sections[k].end]] for k in order),
                            _laid=np.zeros(len(order)))
        for i, line in zip(members, lines):
            arcs, offset = [], 0.0
            for s in line.sections:
                j = group._solver_section(case, s.line, s.index)
                arcs.append(offset + solver.section_arc_length(j))
                offset += s.length
            group.arc_lengths[i] = np.concatenate(arcs)
        if not solver.has_memory:
            group.last_positions = solver.state_arrays()["positions"]
        groups.append(group)
    return groups


def _label_key(name: str) -> tuple[str, int]:
    """``line[3]`` -> ("line", 3)."""
    line, _, rest = name.rpartition("[")
    return line, int(rest.rstrip("]"))
