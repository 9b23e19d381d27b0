"""Assembly of result datasets: labelled variables, units and provenance.

Dimensions: ``line`` (names, with the line model as a ``model`` coordinate), ``time`` [s],
``component`` (x, y, z), and the mooring system's ``point`` (names, with ``point_kind``) and
``section`` (``line[index]``, with ``section_line`` and ``section_type``): point positions and
the net line force on each point, section tensions at both ends, and the sections' minimum
breaking loads when a line type gives one. When a line type of the case gives a minimum breaking load, the
variable ``minimum_breaking_load`` holds it per line (NaN for lines whose type gives none).
In files, ``time`` is the netCDF record (unlimited) dimension, which must be the first
dimension of the variables along it: they are stored time first (:func:`record_order`) and
put back in the order above when read (:func:`result_order`).
Attributes: the title, the case file's path and text, the ``--set``
overrides, the floatmoor and numba versions, the creation time (ISO 8601, UTC) and the run
status (``complete``, ``interrupted ...`` or ``failed: ...``).
"""

from __future__ import annotations

import datetime as _dt
from typing import Mapping

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from floatmoor._numba import numba_info
from floatmoor._version import __version__
from floatmoor.case.schema import Case
from floatmoor.io.variables import attributes

__all__ = ["build_result_dataset", "record_order", "result_order", "BEFORE_TIME", "COMPONENTS",
           "DOFS"]

COMPONENTS = ("x", "y", "z")
#: capytaine's names of the rigid-body DOFs
DOFS = ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")

_DIMS = {
    1: ("line",),
    2: ("line", "time"),
    3: ("line", "time", "component"),
}


def _line_mbl(line) -> float | None:
    """A line's MBL for the per-line variable, which the fairlead tension is checked against:
    the type's of its section at the fairlead (None when it gives none)."""
    return line.end_type.minimum_breaking_load


def build_result_dataset(case: Case, time: NDArray[np.float64],
                         variables: Mapping[str, NDArray[np.floating]], *, status: str,
                         shapes: Mapping[str, NDArray[np.floating]] | None = None,
                         body: Mapping[str, NDArray[np.floating]] | None = None,
                         system: Mapping[str, NDArray[np.floating]] | None = None,
                         body_equilibrium: NDArray[np.floating] | None = None,
                         extra_attrs: Mapping[str, str | float | int] | None = None) -> xr.Dataset:
    """Label the arrays of a run.

    Parameters
    ----------
    case
        The case that was run.
    time
        Output times [s], shape (n,).
    variables
        Name (a key of :data:`~floatmoor.io.variables.VARIABLE_ATTRIBUTES`) -> array of shape
        (line, time) or (line, time, component), already cut to ``n`` samples.
    status
        ``"complete"``, or how the run ended early.
    shapes
        Optional line shapes: ``shape_time`` (m,), ``arc_length`` (line, node),
        ``shape_position`` (line, m, node, component), ``shape_tension`` (line, m, node).
    body
        Optional floater series: ``body_displacement`` and ``body_velocity`` (time, dof),
        ``wave_elevation`` (time,).
    system
        Optional point and section series: ``point_position``, ``point_force`` (point, time,
        component), ``section_start_tension``, ``section_end_tension`` (section, time).
    body_equilibrium
        With ``body``: the floater's static equilibrium (dof,) that ``body_displacement`` is
        measured from, relative to the case's position [m, rad].
    extra_attrs
        More dataset attributes (e.g. wall time).
    """
    if body_equilibrium is not None and body is None:
        raise ValueError("body_equilibrium is the origin of a floater's body series: give them")
    coords = {
        "time": ("time", np.asarray(time, dtype=float), attributes("time")),
        "line": ("line", np.array(case.line_names, dtype=str), attributes("line")),
        "component": ("component", np.array(COMPONENTS, dtype=str), attributes("component")),
        "model": ("line", np.array([ln.model for ln in case.lines], dtype=str),
                  attributes("model")),
    }
    data_vars = {}
    for name, array in variables.items():
        values = np.asarray(array)
        if values.dtype.kind == "i":
            values = values.astype(np.int32)  # netCDF-3 has no 64-bit integers
        data_vars[name] = (_DIMS[values.ndim], values, attributes(name))
    if system is not None:
        coords["point"] = ("point", np.array([p.name for p in case.points], dtype=str),
                           attributes("point"))
        coords["point_kind"] = ("point", np.array([p.kind for p in case.points], dtype=str),
                                attributes("point_kind"))
        sections = case.sections
        coords["section"] = ("section", np.array([s.label for s in sections], dtype=str),
                             attributes("section"))
        coords["section_line"] = ("section", np.array([s.line for s in sections], dtype=str),
                                  attributes("section_line"))
        coords["section_type"] = ("section", np.array([s.line_type.name for s in sections],
                                                      dtype=str), attributes("section_type"))
        for name, array in system.items():
            values = np.asarray(array, dtype=float)
            dim = "point" if name.startswith("point") else "section"
            data_vars[name] = ((dim, "time", "component")[:values.ndim], values,
                               attributes(name))
        section_mbl = [s.line_type.minimum_breaking_load for s in sections]
        if any(m is not None for m in section_mbl):
            data_vars["section_minimum_breaking_load"] = (
                ("section",), np.array([np.nan if m is None else m for m in section_mbl],
                                       dtype=float), attributes("section_minimum_breaking_load"))
    mbl = [_line_mbl(ln) for ln in case.lines]
    if any(m is not None for m in mbl):
        data_vars["minimum_breaking_load"] = (
            ("line",), np.array([np.nan if m is None else m for m in mbl], dtype=float),
            attributes("minimum_breaking_load"))
    if shapes is not None:
        coords["shape_time"] = ("shape_time", shapes["shape_time"], attributes("shape_time"))
        coords["arc_length"] = (("line", "node"), shapes["arc_length"], attributes("arc_length"))
        data_vars["shape_position"] = (("line", "shape_time", "node", "component"),
                                       shapes["shape_position"], attributes("shape_position"))
        data_vars["shape_tension"] = (("line", "shape_time", "node"), shapes["shape_tension"],
                                      attributes("shape_tension"))
    if body is not None:
        coords["dof"] = ("dof", np.array(DOFS, dtype=str), attributes("dof"))
        for name, array in body.items():
            values = np.asarray(array, dtype=float)
            data_vars[name] = (("time", "dof") if values.ndim == 2 else ("time",), values,
                               attributes(name))
        if body_equilibrium is not None:
            data_vars["body_equilibrium"] = (("dof",), np.asarray(body_equilibrium, dtype=float)
                                             .reshape(len(DOFS)), attributes("body_equilibrium"))
    attrs: dict[str, str | float | int] = {
        "title": case.title,
        "case_file": case.source,
        "case_toml": case.text,
        "case_overrides": "\n".join(case.overrides) if case.overrides else "none",
        "floatmoor_version": __version__,
        "created": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
        "status": status,
        "Conventions": "CF-1.8",
    }
    attrs.update(numba_info())
    if extra_attrs:
        attrs.update(extra_attrs)
    return xr.Dataset(data_vars=data_vars, coords=coords, attrs=attrs)


#: The dimensions that come before ``time`` in a result dataset's variables.
BEFORE_TIME = ("line", "point", "section")


def record_order(dataset: xr.Dataset) -> xr.Dataset:
    """``dataset`` with ``time`` first in every variable along it, as a netCDF file whose
    record dimension is ``time`` stores them (lazy for lazily read data)."""
    return dataset.transpose("time", ...) if "time" in dataset.dims else dataset


def result_order(dataset: xr.Dataset) -> xr.Dataset:
    """A result dataset read from a file (``time`` first, :func:`record_order`) with its
    variables' dimensions in the order :func:`build_result_dataset` gives them: ``line``,
    ``point`` or ``section``, then ``time``. Other datasets are returned as they are."""
    if "time" not in dataset.dims:
        return dataset
    moved = {name: var.transpose(var.dims[1], "time", *var.dims[2:])
             for name, var in dataset.data_vars.items()
             if len(var.dims) >= 2 and var.dims[0] == "time" and var.dims[1] in BEFORE_TIME}
    if not moved:
        return dataset
    return dataset.assign(moved)
