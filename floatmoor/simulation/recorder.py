"""Result buffers that are filled as a run advances and written out as it goes.

The recorder owns the time series of every line, in a window of samples: the run loop makes
room for a chunk (:meth:`Recorder.reserve`), writes into views of the window's arrays
(sample ``k`` at index ``k - recorder.offset``), then calls :meth:`Recorder.advance`. With an
output file, the completed samples are appended to it every ``flush_interval`` seconds of
wall time and whenever the window is full, so the memory a run holds does not grow with its
duration, and an interrupted or killed run leaves a valid file holding everything up to the
last write (:mod:`floatmoor.io.netcdf_stream`: ``time`` is the file's record dimension). The
file is created, atomically replacing any file there, at the first write; the line shapes,
whose extent is known, are laid out whole then (NaN until written), and its ``created``
attribute is that moment (a whole-file writer gave the last write's). :meth:`Recorder.result`
writes the final state with its status and gives the results: read lazily from the file, or
from memory for a run without one (whose window holds the whole run).

Size: one class, :class:`Recorder`, whose window, flushing and resume share its state;
the two helpers beside it estimate the size of what it writes.
"""

from __future__ import annotations

import time as _time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from floatmoor.case.limits import dynamic_nodes_bound
from floatmoor.case.schema import Case
from floatmoor.errors import SolverError
from floatmoor.io.dataset import build_result_dataset, record_order
from floatmoor.io.netcdf import NETCDF_ENGINE, NETCDF_FORMAT, open_result
from floatmoor.io.variables import attributes
from floatmoor.io.netcdf3_format import NetCDF3Error
from floatmoor.io.netcdf_stream import NetCDF3Stream
from floatmoor.signals import deferred_interrupts, signal_name
from floatmoor.simulation.groups import GroupSamples, LineSamples, SystemGroup

__all__ = ["Recorder", "FLUSH_INTERVAL_S", "WINDOW_BYTES", "STATUS_ROOM", "VALIDITY_ATTRIBUTE",
           "estimated_output_bytes"]

#: Wall time between partial writes of a long run [s]: often enough that a killed run loses
#: little, rarely enough that rewriting the file costs a negligible share of the run.
FLUSH_INTERVAL_S = 10.0

#: Bytes of samples a recorder with an output file holds before appending them to it: large
#: enough that appends are rare (a coupled buoy run's samples take 0.37 kB: 5700 samples,
#: 57 s simulated), small beside the ~270 MB of a coupled run's libraries and database (an
#: append holds a few copies of the window while it encodes it: 8 MB windows added 17 MB
#: to the buoy's peak).
WINDOW_BYTES = 2 << 20

#: Bytes of room of the ``status`` attribute in a file, which changes as the run goes
#: (``running: ...``, ``complete``, ``failed: message``): a longer one makes the file be
#: rewritten with more room.
STATUS_ROOM = 4096
#: The attribute of the model-validity messages of a run (floatmoor.simulation.validity), one
#: a line ("" when it stayed valid), and its room in the file: a few conditions of ~250
#: bytes each (a longer text makes the file be rewritten with more room).
VALIDITY_ATTRIBUTE, VALIDITY_ROOM = "validity_warnings", 2048

#: Attributes that change while the run goes, updated in the file at every write.
_VOLATILE = ("status", "wall_time_s", "simulated_time_s")
#: Attributes a resumed run need not share with the file it continues: the volatile ones,
#: when the file was created, the case file's path (the same case may be reached by another
#: path), the numba build that ran it, and the lines' accuracy estimated as the run went.
_NOT_COMPARED = (*_VOLATILE, VALIDITY_ATTRIBUTE, "created", "case_file", "numba_version",
                 "llvmlite_version", "numba_disable_jit", "line_accuracy")

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
        if case.waves is not None and case.waves.second_order != "none":
            values += n_time * 6  # second_order_force
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
    shape_nodes, shape_stride
        Arc lengths of every line's shape nodes, and output samples between shape samples
        (0: no shapes).
    body, prescribed
        Whether to record a floater's series, or a prescribed body motion's.
    equilibrium
        With ``body``: the floater's static equilibrium (6,) [m, rad] its displacement is
        recorded from, written to the file (``body_equilibrium``) with its first samples.
    second_order
        With ``body``: record the second-order wave force (``second_order_force``), whose
        mean the equilibrium then includes (said in ``body_equilibrium``'s attributes).
    chunk
        Most samples the run writes between two :meth:`reserve` calls: the window holds at
        least this many.
    attrs
        Further attributes of the result (known before the run, e.g. the lines' checked
        accuracy).
    """

    def __init__(self, case: Case, time: NDArray[np.float64], path: str | Path | None = None,
                 flush_interval: float = FLUSH_INTERVAL_S, *,
                 shape_nodes: list[NDArray[np.float64]] | None = None,
                 shape_stride: int = 0, body: bool = False, prescribed: bool = False,
                 equilibrium: NDArray[np.float64] | None = None, chunk: int = 1,
                 attrs: dict[str, str | float | int] | None = None,
                 second_order: bool = False) -> None:
        if body != (equilibrium is not None):
            raise ValueError("a floater's series are recorded with its equilibrium, and only "
                             "they")
        if second_order and not body:
            raise ValueError("a second-order wave force is recorded with a floater's series")
        self.second_order = second_order
        self.case = case
        #: attributes the run adds to the file's (known before its first sample)
        self.attrs = dict(attrs or {})
        self.time = np.asarray(time, dtype=float)
        self.path = Path(path) if path is not None else None
        self.flush_interval = flush_interval
        n_lines, n_total = len(case.lines), self.time.size
        self.capacity = n_total if self.path is None else min(
            n_total, max(int(chunk), WINDOW_BYTES // _sample_bytes(case, body, prescribed,
                                                                   second_order)))
        n_time = self.capacity
        #: absolute index of the window's first sample; samples written to the file
        self.offset = 0
        self.written = 0
        self._stream: NetCDF3Stream | None = None
        self.series: dict[str, NDArray[np.float64]] = {
            name: np.zeros((n_lines, n_time, size) if size > 1 else (n_lines, n_time))
            for name, size in _SERIES
        }
        #: floater series (coupled runs): displacement, velocity (time, 6), wave elevation
        self.body: dict[str, NDArray[np.float64]] | None = None
        #: the floater's static equilibrium (6,), the origin of its recorded displacement
        self.equilibrium = None if equilibrium is None else np.array(equilibrium, dtype=float)
        if body:
            self.body = {"body_displacement": np.zeros((n_time, 6)),
                         "body_velocity": np.zeros((n_time, 6)),
                         "wave_elevation": np.zeros(n_time)}
            if second_order:
                self.body["second_order_force"] = np.zeros((n_time, 6))
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
        #: the run's model-validity messages (floatmoor.simulation.validity), written to the
        #: file's attribute VALIDITY_ATTRIBUTE with every write
        self.validity_warnings: list[str] = []
        # line shapes every shape_stride samples, on each line's nodes; lines with fewer
        # nodes than the longest repeat their last node so every line shares the node axis
        self.shape_stride = shape_stride if shape_nodes else 0
        self.shape_offset = 0  #: shape index of the window's first shape
        if self.shape_stride:
            n_nodes = max(len(s) for s in shape_nodes)
            self.shape_arc_length = [np.asarray(s, dtype=float) for s in shape_nodes]
            self.shape_arc = np.array([np.pad(s, (0, n_nodes - len(s)), mode="edge")
                                       for s in self.shape_arc_length])
            self.n_shapes = (n_total - 1) // self.shape_stride + 1
            n_shapes = (self.n_shapes if self.path is None else
                        min(self.n_shapes, (self.capacity - 1) // self.shape_stride + 2))
            self.shape_position = np.zeros((n_lines, n_shapes, n_nodes, 3))
            self.shape_tension = np.zeros((n_lines, n_shapes, n_nodes))
        self._last_flush = _time.perf_counter()
        self._start = _time.perf_counter()

    # -- the window ---------------------------------------------------------------------------
    def _shapes_before(self, n: int) -> int:
        """Shape samples among the first ``n`` output samples (0 without shapes)."""
        return (n - 1) // self.shape_stride + 1 if n > 0 and self.shape_stride else 0

    def reserve(self, stop: int) -> None:
        """Make the window hold samples up to ``stop`` (exclusive), appending the completed
        samples to the file and starting the window at the first incomplete one when it is
        full.

        Raises
        ------
        ValueError
            When ``stop`` is beyond what the window can hold after that (a chunk longer than
            the recorder was made for).
        OutputWriteError
            When the file cannot be written.
        """
        if stop - self.offset <= self.capacity:
            return
        if self.path is not None and self.n_done > self.written:
            self.write(status=f"running: partial results up to t = {self.simulated_time:.6g} s")
        self._move(self.n_done)
        if stop - self.offset > self.capacity:
            raise ValueError(f"the recorder holds {self.capacity} samples, not samples "
                             f"{self.offset} to {stop}")

    def _move(self, first: int) -> None:
        """Start the window at sample ``first`` (every sample before it written), keeping
        the samples after it."""
        if first == self.offset:
            return
        if first > self.written or first < self.offset:
            raise ValueError(f"cannot move the window to sample {first}: samples from "
                             f"{self.written} are not written yet")
        shift = first - self.offset
        arrays = [(a, 1) for a in self.series.values()]
        arrays += [(a, 0) for group in (self.body, self.prescribed) if group for a in group.values()]
        arrays += [(a, 1) for a in (self.system or {}).values()]
        for array, axis in arrays:
            moved = np.moveaxis(array, axis, 0)
            keep = moved.shape[0] - shift
            if keep > 0:
                moved[:keep] = moved[shift:].copy()
            moved[max(keep, 0):] = 0.0
        if self.shape_stride:
            first_shape = -(-first // self.shape_stride)  # ceil: shapes at or after first
            move = first_shape - self.shape_offset
            for array in (self.shape_position, self.shape_tension):
                keep = array.shape[1] - move
                if keep > 0:
                    array[:, :keep] = array[:, move:].copy()
                array[:, max(keep, 0):] = 0.0
            self.shape_offset = first_shape
        self.offset = first

    def advance(self, n_done: int) -> None:
        """Mark samples ``[0, n_done)`` complete, after checking they are finite.

        Raises
        ------
        SolverError
            If a new sample is not finite, naming the line, the time and the quantity.
        """
        a, b = self.n_done - self.offset, n_done - self.offset
        if b > self.capacity:
            raise ValueError(f"sample {n_done - 1} is beyond the recorder's window (samples "
                             f"{self.offset} to {self.offset + self.capacity - 1})")
        for name, array in self.series.items():
            block = array[:, a:b]
            if not np.all(np.isfinite(block)):
                bad = np.argwhere(~np.isfinite(block))[0]
                line, index = int(bad[0]), self.n_done + int(bad[1])
                raise SolverError(f"line '{self.case.lines[line].name}': {name} is not finite "
                                  f"at t = {self.time[index]:.6g} s")
        if self.body is not None:
            for name, array in self.body.items():
                block = array[a:b]
                if not np.all(np.isfinite(block)):
                    index = self.n_done + int(np.argwhere(~np.isfinite(block))[0][0])
                    raise SolverError(f"floater: {name} is not finite at "
                                      f"t = {self.time[index]:.6g} s")
        self.n_done = n_done
        if self.path is not None and _time.perf_counter() - self._last_flush > self.flush_interval:
            self.write(status=f"running: partial results up to t = {self.simulated_time:.6g} s")

    def store_group(self, case: Case, group: SystemGroup, samples: GroupSamples,
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
        start, stop = start - self.offset, stop - self.offset  # in the window
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

    def store_line(self, line: int, samples: LineSamples, path: NDArray[np.float64],
                   start: int, stop: int) -> None:
        """Record samples [start, stop) of independent line ``line`` (``samples`` and its
        fairlead's ``path`` (n, 3) from ``start``)."""
        n = stop - start
        if n <= 0:
            return
        series = self.series
        start, stop = start - self.offset, stop - self.offset  # in the window
        series["fairlead_position"][line, start:stop] = path[:n]
        series["fairlead_force"][line, start:stop] = samples.fairlead_force[:n]
        series["anchor_force"][line, start:stop] = samples.anchor_force[:n]
        series["laid_length"][line, start:stop] = samples.laid_length[:n]
        series["solver_iterations"][line, start:stop] = samples.steps[:n]

    def store_shape(self, line: int, index: int, positions: NDArray[np.float64],
                    tension: NDArray[np.float64]) -> None:
        """Store the shape of ``line`` at shape sample ``index`` (of the whole run)."""
        local = index - self.shape_offset
        if not 0 <= local < self.shape_position.shape[1]:
            raise ValueError(f"shape sample {index} is outside the recorder's window "
                             f"({self.shape_offset} to "
                             f"{self.shape_offset + self.shape_position.shape[1]})")
        n = len(positions)
        self.shape_position[line, local, :n] = positions
        self.shape_position[line, local, n:] = positions[-1]
        self.shape_tension[line, local, :n] = tension
        self.shape_tension[line, local, n:] = tension[-1]

    @property
    def simulated_time(self) -> float:
        """Time of the last complete sample [s] (0 before the first)."""
        return float(self.time[self.n_done - 1]) if self.n_done else 0.0

    # -- datasets ----------------------------------------------------------------------------
    def dataset(self, status: str) -> xr.Dataset:
        """The completed samples in the window as a labelled dataset: the whole run's for a
        recorder without a file (whose window holds every sample)."""
        return self._dataset(self.offset, self.n_done, status, shapes="window")

    def _dataset(self, first: int, stop: int, status: str, shapes: str | None) -> xr.Dataset:
        """Samples [first, stop) (in the window) as a dataset; ``shapes``: ``"window"`` the
        shape samples among them (a window starting at sample 0), ``"template"`` the first
        shape sample of the window (its place in the file's layout), None: none."""
        a, b = first - self.offset, stop - self.offset
        variables = {name: array[:, a:b] for name, array in self.series.items()}
        variables["fairlead_tension"] = np.linalg.norm(variables["fairlead_force"], axis=-1)
        variables["anchor_tension"] = np.linalg.norm(variables["anchor_force"], axis=-1)
        variables["solver_iterations"] = variables["solver_iterations"].astype(np.int32)
        wall = _time.perf_counter() - self._start
        shape_data = None
        if self.shape_stride and shapes is not None:
            m = self._shapes_before(stop) - self.shape_offset if shapes == "window" else 1
            times = self.time[self.shape_offset * self.shape_stride::self.shape_stride]
            shape_data = {"shape_time": times[:m], "arc_length": self.shape_arc,
                          "shape_position": self.shape_position[:, :m],
                          "shape_tension": self.shape_tension[:, :m]}
        body = None if self.body is None else {k: v[a:b] for k, v in self.body.items()}
        system = line_system_series(self.case, variables, self._independent)
        if self.system is not None:  # the groups' rows from their own series
            for name, rows in (("point_position", self._owned_points),
                               ("section_start_tension", self._owned_sections),
                               ("section_end_tension", self._owned_sections)):
                system[name][rows] = self.system[name][rows, a:b]
            system["point_force"] += self.system["point_force"][:, a:b]
        if self.prescribed is not None:
            body = {**(body or {}), **{k: v[a:b] for k, v in self.prescribed.items()}}
        dataset = build_result_dataset(self.case, self.time[first:stop], variables,
                                       status=status, shapes=shape_data, body=body,
                                       system=system, body_equilibrium=self.equilibrium,
                                       extra_attrs={**self.attrs, "wall_time_s": wall,
                                                    "simulated_time_s": self.simulated_time,
                                                    VALIDITY_ATTRIBUTE:
                                                        "\n".join(self.validity_warnings)})
        if self.second_order:  # its equilibrium includes the mean drift
            dataset["body_equilibrium"].attrs.update(attributes("body_equilibrium_with_drift"))
        return dataset

    def _template(self, first: int, stop: int, status: str) -> bytes:
        """netCDF bytes of samples [first, stop) as xarray writes them, ``time`` the record
        dimension: the names, types, attributes and layout of the file, and its first
        records."""
        dataset = record_order(self._dataset(first, stop, status, shapes="template"))
        return bytes(dataset.to_netcdf(engine=NETCDF_ENGINE, format=NETCDF_FORMAT,
                                       unlimited_dims=["time"]))

    def _records(self, first: int, stop: int, status: str) -> dict[str, NDArray]:
        """Samples [first, stop) of every variable along time, time first, by name."""
        dataset = record_order(self._dataset(first, stop, status, shapes=None))
        return {name: var.values for name, var in dataset.variables.items()
                if var.dims[:1] == ("time",)}

    # -- the file ----------------------------------------------------------------------------
    def write(self, status: str) -> None:
        """Append the completed samples not yet in the output file (creating it at the
        first write) and set its status; an interrupt during the write is delivered after
        it, so the file is whole. Without an output file: nothing."""
        if self.path is not None:
            with deferred_interrupts():
                self._write(status)
        self._last_flush = _time.perf_counter()

    def _write(self, status: str) -> None:
        first, stop = self.written, self.n_done
        if self._stream is None and first > 0:  # closed after a write: append again
            self._stream = NetCDF3Stream.open(self.path)
        if self._stream is None:
            if stop == 0:
                return  # a file of no samples is not a result file
            if self.offset != 0:
                raise ValueError("the output file is created from the run's first samples")
            sizes, values = {}, {}
            if self.shape_stride:
                sizes["shape_time"] = self.n_shapes
                values["shape_time"] = self.time[::self.shape_stride][:self.n_shapes]
            # the first sample from xarray's writer (the layout), the others with it: the
            # file appears with all of them, or (a failed write) not at all
            template = self._template(0, 1, status)
            self._stream = NetCDF3Stream.create(self.path, template, sizes=sizes,
                                                values=values, reserve={"status": STATUS_ROOM,
                                                                         VALIDITY_ATTRIBUTE:
                                                                         VALIDITY_ROOM},
                                                records=self._records(1, stop, status))
        elif stop > first:
            self._stream.append(self._records(first, stop, status))
        if self.shape_stride:
            lo, hi = self._shapes_before(first), self._shapes_before(stop)
            if hi > lo:
                a, b = lo - self.shape_offset, hi - self.shape_offset
                self._stream.write_along("shape_position", "shape_time", lo,
                                         self.shape_position[:, a:b])
                self._stream.write_along("shape_tension", "shape_time", lo,
                                         self.shape_tension[:, a:b])
        attributes = {"status": status, "wall_time_s": _time.perf_counter() - self._start,
                      "simulated_time_s": self.simulated_time}
        if self._stream.header.attribute(VALIDITY_ATTRIBUTE) is not None:  # (older files: none)
            attributes[VALIDITY_ATTRIBUTE] = "\n".join(self.validity_warnings)
        self._stream.set_attributes(attributes)
        self.written = stop

    def sync(self) -> None:
        """Flush the output file, as written so far, to disk (see
        :meth:`floatmoor.io.netcdf_stream.NetCDF3Stream.sync`); nothing before it exists."""
        if self._stream is not None:
            self._stream.sync()

    def set_attribute(self, name: str, value: str) -> None:
        """Change a text attribute given at construction (``attrs``), in the file too when it
        is there (a coupled run's lines' accuracy, estimated as the run goes)."""
        if name not in self.attrs:
            raise KeyError(f"no attribute '{name}' given to the recorder")
        self.attrs[name] = value
        if self._stream is not None:
            self._stream.set_attributes({name: value})

    def close(self) -> None:
        """Close the output file (it stays valid; a later :meth:`write` reopens it)."""
        if self._stream is not None:
            stream, self._stream = self._stream, None
            stream.close()

    def result(self, status: str = "complete") -> xr.Dataset:
        """Write the final state with ``status`` and close the file; the results: read
        lazily from the file (values are read as they are asked for), or the in-memory
        dataset of a run without one."""
        self.write(status)
        if self.path is None:
            return self.dataset(status)
        self.close()
        return open_result(self.path)

    def continue_file(self, n_done: int) -> None:
        """Continue the output file of an interrupted run of this case from its sample
        ``n_done`` (what its checkpoint covers): the file is checked against what this run
        writes, then cut to ``n_done`` samples (the shapes after them blanked), and the
        recorder starts there.

        Raises
        ------
        NetCDF3Error
            When the file is not this run's or holds fewer samples (saying what differs).
        OutputWriteError
            When it cannot be opened or written.
        """
        if self.path is None:
            raise ValueError("a recorder without an output file has none to continue")
        stream = NetCDF3Stream.open(self.path)
        try:
            self._check_continued(stream)
            if stream.numrecs < n_done:
                raise NetCDF3Error(f"a file holding the {n_done} samples its checkpoint "
                                   f"covers, not {stream.numrecs}")
            stream.truncate(n_done)
            carried = stream.header.attribute(VALIDITY_ATTRIBUTE)  # kept by the resumed run
            if carried is not None:
                text = bytes(carried.raw).rstrip(b"\x00").decode("utf-8", "replace")
                self.validity_warnings = [m for m in text.split("\n") if m]
            if self.shape_stride:
                self._blank_shapes(stream, self._shapes_before(n_done))
        except BaseException:
            stream.close()
            raise
        self._stream = stream
        self.n_done = self.written = n_done
        self.offset = n_done
        self.shape_offset = self._shapes_before(n_done)

    def _blank_shapes(self, stream: NetCDF3Stream, first: int) -> None:
        """Fill the shape samples from ``first`` with NaN, a window at a time."""
        step = self.shape_position.shape[1]
        for lo in range(first, self.n_shapes, step):
            n = min(step, self.n_shapes - lo)
            stream.write_along("shape_position", "shape_time", lo,
                               np.full((*self.shape_position.shape[:1], n,
                                        *self.shape_position.shape[2:]), np.nan))
            stream.write_along("shape_tension", "shape_time", lo,
                               np.full((self.shape_tension.shape[0], n,
                                        self.shape_tension.shape[2]), np.nan))

    def _check_continued(self, stream: NetCDF3Stream) -> None:
        """Refuse a file whose layout or case differs from what this run writes."""
        from floatmoor.io.netcdf3_format import parse_header

        # the layout this run gives its file, from a one-sample template
        saved = self.n_done, self.offset
        self.n_done, self.offset = 1, 0
        try:
            ours = parse_header(self._template(0, 1, "running"))
        finally:
            self.n_done, self.offset = saved
        theirs = stream.header
        if self.shape_stride:
            ours.dims = [(d, self.n_shapes if d == "shape_time" else n) for d, n in ours.dims]
        if ours.dims != theirs.dims:
            raise NetCDF3Error(f"a file of this run's dimensions {ours.dims}, not "
                               f"{theirs.dims}")
        mine = [(v.name, ours.dim_names(v), v.nc_type, [(a.name, a.raw) for a in v.attributes])
                for v in ours.variables]
        other = [(v.name, theirs.dim_names(v), v.nc_type,
                  [(a.name, a.raw) for a in v.attributes]) for v in theirs.variables]
        if mine != other:
            names = sorted({m[0] for m in mine} ^ {o[0] for o in other}) or sorted(
                m[0] for m, o in zip(mine, other) if m != o)
            raise NetCDF3Error(f"a file of this run's variables (these differ: "
                               f"{', '.join(names) or 'their order'})")
        for att in ours.attributes:
            if att.name in _NOT_COMPARED:
                continue
            other_att = theirs.attribute(att.name)
            if other_att is None or other_att.value() != att.value():
                raise NetCDF3Error(f"a file of a run of this case (its attribute "
                                   f"'{att.name}' differs)")
        missing = [a for a in _VOLATILE if theirs.attribute(a) is None]
        if missing:
            raise NetCDF3Error(f"a result file with the attributes {missing}")

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
            self.close()
            raise
        except KeyboardInterrupt as stop:
            if self.n_done:
                self.write(status=f"{signal_name(stop)}: results up to "
                                  f"t = {self.simulated_time:.6g} s")
            self.close()
            raise


def _sample_bytes(case: Case, body: bool, prescribed: bool, second_order: bool = False) -> int:
    """Bytes the recorder's buffers take per output sample."""
    values = len(case.lines) * sum(size for _, size in _SERIES)
    values += (_BODY_VALUES if body else 0) + (12 if prescribed else 0)
    values += 6 if second_order else 0
    if case.is_system:
        values += len(case.points) * 6 + len(case.sections) * 2
    return max(values, 1) * _VALUE_BYTES
