"""Preallocated result buffers that are filled as a run advances and written as it goes.

The recorder owns the time series of every line. The run loop writes into views of its
arrays, then calls :meth:`Recorder.advance`; every ``flush_interval`` seconds of wall time the
completed part is written to the output file (atomically), so an interrupted or killed run
leaves a valid file holding everything up to the last flush, and :meth:`Recorder.finish` writes
the final state with its status.
"""

from __future__ import annotations

import time as _time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from typing import TYPE_CHECKING

from floatmoor.case.limits import dynamic_nodes_bound
from floatmoor.case.schema import Case
from floatmoor.errors import SolverError
from floatmoor.io.dataset import build_result_dataset
from floatmoor.io.netcdf import write_dataset
from floatmoor.signals import deferred_interrupts, signal_name

if TYPE_CHECKING:
    from floatmoor.simulation.groups import GroupSamples, SystemGroup

__all__ = ["Recorder", "FLUSH_INTERVAL_S", "estimated_output_bytes"]

#: Wall time between partial writes of a long run [s]: often enough that a killed run loses
#: little, rarely enough that rewriting the file costs a negligible share of the run.
FLUSH_INTERVAL_S = 10.0

#: (name, components per sample) of the recorded time series.
_SERIES = (
    ("fairlead_force", 3),
    ("anchor_force", 3),
    ("fairlead_position", 3),
    ("laid_length", 1),
    ("solver_iterations", 1),
)

#: Floater series of coupled runs: values per sample (displacement, velocity, wave elevation).
_BODY_VALUES = 6 + 6 + 1
#: Bytes per stored value (float64; the int32 solver iterations are counted as 8 too).
_VALUE_BYTES = 8


def estimated_output_bytes(case: Case) -> float:
    """Size of a run's output file [bytes], from its samples, lines and variables: what the
    folder must have room for before the run starts (the header and attributes, a few kB,
    are left out).
    """
    from floatmoor.mooring.quasidynamic import SHAPE_NODES
    from floatmoor.mooring.quasistatic import SHAPE_POINTS

    sim = case.simulation
    n_time = sim.duration / sim.output_interval + 1.0
    per_line = sum(size for _, size in _SERIES) + 2  # and the two tensions
    values = len(case.lines) * n_time * per_line
    # the points' positions and forces, the sections' end tensions
    values += (len(case.points) * 6 + len(case.sections) * 2) * n_time
    if case.floater is not None:
        values += n_time * _BODY_VALUES
    if getattr(case.motion, "kind", None) == "body":  # the prescribed DOFs and their rates
        values += n_time * 12
    if sim.shape_output_interval is not None:
        nodes = max((dynamic_nodes_bound(line.dynamic) if line.model == "dynamic"
                     else max(SHAPE_NODES, SHAPE_POINTS)) for line in case.lines)
        n_shapes = sim.duration / max(sim.shape_output_interval, sim.output_interval) + 1.0
        values += len(case.lines) * n_shapes * nodes * (3 + 1) + nodes * len(case.lines)
    return float(values * _VALUE_BYTES)


def line_system_series(case: Case, variables: dict[str, NDArray[np.float64]],
                       lines: NDArray[np.bool_] | None = None) -> dict[str, NDArray[np.float64]]:
    """The point and section series that follow from independent one-section lines' own: a
    section's tensions are its line's anchor and fairlead tensions, a body point is where its
    lines' fairlead is, a point's force the sum of its lines' end forces (other points and
    sections: at rest, zero).

    Parameters
    ----------
    case
        The case.
    variables
        The recorded line series, cut to the completed samples.
    lines
        Which lines are independent (default: all).
    """
    n = variables["fairlead_force"].shape[1]
    index = {p.name: i for i, p in enumerate(case.points)}
    first = {(s.line, s.index): k for k, s in enumerate(case.sections)}
    position = np.zeros((len(case.points), n, 3))
    force = np.zeros((len(case.points), n, 3))
    start_tension = np.zeros((len(case.sections), n))
    end_tension = np.zeros((len(case.sections), n))
    for i, p in enumerate(case.points):
        position[i] = p.position
    for i, line in enumerate(case.lines):
        if lines is not None and not lines[i]:
            continue
        position[index[line.end]] = variables["fairlead_position"][i]
        force[index[line.end]] += variables["fairlead_force"][i]
        force[index[line.start]] += variables["anchor_force"][i]
        start_tension[first[(line.name, 0)]] = variables["anchor_tension"][i]
        end_tension[first[(line.name, 0)]] = variables["fairlead_tension"][i]
    return {"point_position": position, "point_force": force,
            "section_start_tension": start_tension, "section_end_tension": end_tension}


class Recorder:
    """Time series of a run, written to ``path`` as they fill.

    Parameters
    ----------
    case
        The case being run.
    time
        All output times [s].
    path
        netCDF file to write, or None to keep the results in memory only.
    flush_interval
        Wall time between partial writes [s].
    """

    def __init__(self, case: Case, time: NDArray[np.float64], path: str | Path | None = None,
                 flush_interval: float = FLUSH_INTERVAL_S, *,
                 shape_nodes: list[NDArray[np.float64]] | None = None,
                 shape_stride: int = 0, body: bool = False, prescribed: bool = False) -> None:
        self.case = case
        self.time = np.asarray(time, dtype=float)
        self.path = Path(path) if path is not None else None
        self.flush_interval = flush_interval
        n_lines, n_time = len(case.lines), self.time.size
        self.series: dict[str, NDArray[np.float64]] = {
            name: np.zeros((n_lines, n_time, size) if size > 1 else (n_lines, n_time))
            for name, size in _SERIES
        }
        #: floater series (coupled runs): displacement, velocity (time, 6), wave elevation
        self.body: dict[str, NDArray[np.float64]] | None = None
        if body:
            self.body = {"body_displacement": np.zeros((n_time, 6)),
                         "body_velocity": np.zeros((n_time, 6)),
                         "wave_elevation": np.zeros(n_time)}
        #: prescribed body motion (forced runs with [motion] kind = "body"): its 6 DOFs and
        #: their rates (time, 6)
        self.prescribed: dict[str, NDArray[np.float64]] | None = None
        if prescribed:
            self.prescribed = {"prescribed_displacement": np.zeros((n_time, 6)),
                               "prescribed_displacement_rate": np.zeros((n_time, 6))}
        #: point and section series of the system groups (their rows only; the rest follow
        #: from the independent lines' series), None without groups
        self.system: dict[str, NDArray[np.float64]] | None = None
        self._independent = np.array([case.is_independent(ln) for ln in case.lines],
                                     dtype=bool)
        # the points and sections of the lines solved as systems (the groups' rows)
        grouped = [ln for ln, solo in zip(case.lines, self._independent) if not solo]
        used = {n for ln in grouped for sec in ln.sections for n in (sec.start, sec.end)}
        self._owned_points = np.array([p.name in used for p in case.points], dtype=bool)
        solo = {ln.name: flag for ln, flag in zip(case.lines, self._independent)}
        self._owned_sections = np.array([not solo[sec.line] for sec in case.sections],
                                        dtype=bool)
        if case.is_system:
            n_points, n_sections = len(case.points), len(case.sections)
            self.system = {"point_position": np.zeros((n_points, n_time, 3)),
                           "point_force": np.zeros((n_points, n_time, 3)),
                           "section_start_tension": np.zeros((n_sections, n_time)),
                           "section_end_tension": np.zeros((n_sections, n_time))}
        self.n_done = 0
        # line shapes every shape_stride samples, on each line's nodes; lines with fewer
        # nodes than the longest repeat their last node so every line shares the node axis
        self.shape_stride = shape_stride if shape_nodes else 0
        if self.shape_stride:
            n_nodes = max(len(s) for s in shape_nodes)
            self.shape_arc_length = [np.asarray(s, dtype=float) for s in shape_nodes]
            self.shape_arc = np.array([np.pad(s, (0, n_nodes - len(s)), mode="edge")
                                       for s in self.shape_arc_length])
            n_shapes = (n_time - 1) // self.shape_stride + 1
            self.shape_position = np.zeros((n_lines, n_shapes, n_nodes, 3))
            self.shape_tension = np.zeros((n_lines, n_shapes, n_nodes))
        self._last_flush = _time.perf_counter()
        self._start = _time.perf_counter()

    def advance(self, n_done: int) -> None:
        """Mark samples ``[0, n_done)`` complete, after checking they are finite.

        Raises
        ------
        SolverError
            If a new sample is not finite, naming the line, the time and the quantity.
        """
        for name, array in self.series.items():
            block = array[:, self.n_done:n_done]
            if not np.all(np.isfinite(block)):
                bad = np.argwhere(~np.isfinite(block))[0]
                line, index = int(bad[0]), self.n_done + int(bad[1])
                raise SolverError(f"line '{self.case.lines[line].name}': {name} is not finite "
                                  f"at t = {self.time[index]:.6g} s")
        if self.body is not None:
            for name, array in self.body.items():
                block = array[self.n_done:n_done]
                if not np.all(np.isfinite(block)):
                    index = self.n_done + int(np.argwhere(~np.isfinite(block))[0][0])
                    raise SolverError(f"floater: {name} is not finite at "
                                      f"t = {self.time[index]:.6g} s")
        self.n_done = n_done
        if self.path is not None and _time.perf_counter() - self._last_flush > self.flush_interval:
            self.write(status=f"running: partial results up to t = {self.simulated_time:.6g} s")

    def store_group(self, case: Case, group: "SystemGroup", samples: "GroupSamples",
                    start: int, stop: int) -> None:
        """Record samples [start, stop) of a system group (``samples`` from ``start``): its
        lines' series (fairlead and anchor forces: of the end sections on the line's end
        points; laid length: the sections' sum), its points' positions and net line forces,
        its sections' end tensions."""
        n = stop - start
        if n <= 0 or self.system is None:
            return
        where = {k: j for j, k in enumerate(group.points)}
        section_at = {k: j for j, k in enumerate(group.sections)}
        flat = {(s.line, s.index): k for k, s in enumerate(case.sections)}
        series, system = self.series, self.system
        for i in group.lines:
            line = case.lines[i]
            first = section_at[flat[(line.name, 0)]]
            last = section_at[flat[(line.name, len(line.sections) - 1)]]
            series["fairlead_force"][i, start:stop] = samples.end_force[:n, last]
            series["anchor_force"][i, start:stop] = samples.start_force[:n, first]
            series["fairlead_position"][i, start:stop] = \
                samples.positions[:n, where[case.points.index(case.point(line.end))]]
            series["laid_length"][i, start:stop] = sum(
                samples.laid_length[:n, section_at[flat[(line.name, k)]]]
                for k in range(len(line.sections)))
            series["solver_iterations"][i, start:stop] = samples.iterations[:n]
        force = np.zeros((n, len(group.points), 3))
        for j, k in enumerate(group.sections):
            s = case.sections[k]
            force[:, where[case.points.index(case.point(s.start))]] += samples.start_force[:n, j]
            force[:, where[case.points.index(case.point(s.end))]] += samples.end_force[:n, j]
            system["section_start_tension"][k, start:stop] = np.linalg.norm(
                samples.start_force[:n, j], axis=-1)
            system["section_end_tension"][k, start:stop] = np.linalg.norm(
                samples.end_force[:n, j], axis=-1)
        for j, k in enumerate(group.points):
            system["point_position"][k, start:stop] = samples.positions[:n, j]
            system["point_force"][k, start:stop] = force[:, j]

    def store_shape(self, line: int, index: int, positions: NDArray[np.float64],
                    tension: NDArray[np.float64]) -> None:
        """Store the shape of ``line`` at shape sample ``index``."""
        n = len(positions)
        self.shape_position[line, index, :n] = positions
        self.shape_position[line, index, n:] = positions[-1]
        self.shape_tension[line, index, :n] = tension
        self.shape_tension[line, index, n:] = tension[-1]

    @property
    def simulated_time(self) -> float:
        """Time of the last complete sample [s] (0 before the first)."""
        return float(self.time[self.n_done - 1]) if self.n_done else 0.0

    def dataset(self, status: str) -> xr.Dataset:
        """The completed part as a labelled dataset."""
        n = self.n_done
        variables = {name: array[:, :n] for name, array in self.series.items()}
        variables["fairlead_tension"] = np.linalg.norm(variables["fairlead_force"], axis=-1)
        variables["anchor_tension"] = np.linalg.norm(variables["anchor_force"], axis=-1)
        variables["solver_iterations"] = variables["solver_iterations"].astype(np.int32)
        wall = _time.perf_counter() - self._start
        shapes = None
        if self.shape_stride:
            m = (n - 1) // self.shape_stride + 1 if n else 0
            shapes = {"shape_time": self.time[:n:self.shape_stride][:m],
                      "arc_length": self.shape_arc,
                      "shape_position": self.shape_position[:, :m],
                      "shape_tension": self.shape_tension[:, :m]}
        body = None if self.body is None else {k: v[:n] for k, v in self.body.items()}
        system = line_system_series(self.case, variables, self._independent)
        if self.system is not None:  # the groups' rows from their own series
            for name, rows in (("point_position", self._owned_points),
                               ("section_start_tension", self._owned_sections),
                               ("section_end_tension", self._owned_sections)):
                system[name][rows] = self.system[name][rows, :n]
            system["point_force"] += self.system["point_force"][:, :n]
        if self.prescribed is not None:
            body = {**(body or {}), **{k: v[:n] for k, v in self.prescribed.items()}}
        return build_result_dataset(self.case, self.time[:n], variables, status=status,
                                    shapes=shapes, body=body, system=system,
                                    extra_attrs={"wall_time_s": wall,
                                                 "simulated_time_s": self.simulated_time})

    @contextmanager
    def partial_on_failure(self) -> Iterator[None]:
        """Write the completed part, with how the run ended, when the block raises a
        :class:`SolverError` or is interrupted (SIGINT, or SIGTERM as
        :class:`floatmoor.signals.Terminated`); the exception goes on. Before the first
        sample nothing is written (a file of no samples is not a valid result file)."""
        try:
            yield
        except SolverError as err:
            if self.n_done:
                self.write(status=f"failed: {err}")
            raise
        except KeyboardInterrupt as stop:
            if self.n_done:
                self.write(status=f"{signal_name(stop)}: results up to "
                                  f"t = {self.simulated_time:.6g} s")
            raise

    def write(self, status: str) -> xr.Dataset:
        """Write the completed part to the output file (if any) and return it; an interrupt
        during the write is delivered after it, so the file is whole."""
        dataset = self.dataset(status)
        if self.path is not None:
            with deferred_interrupts():
                write_dataset(dataset, self.path)
        self._last_flush = _time.perf_counter()
        return dataset
