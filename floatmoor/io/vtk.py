"""Line shapes as a VTK time series for ParaView: one ``.vtu`` file per shape sample and a
``.pvd`` collection naming them with their times.

Each ``.vtu`` (written by meshio) holds every line as a chain of two-node ``line`` cells
through its nodes, anchor to fairlead, with the point data ``tension`` (effective tension
[N]) and ``arc_length`` (unstretched, from the anchor [m]) and the cell data ``line_index``
(the line's position in the result's ``line`` coordinate, whose names the ``.pvd`` lists in a
comment). With a body (a floater's panels placed at each time, or the polygon through a
forced body's points, given by the caller), each shape sample also gets a
``body_NNNNNN.vtu`` of its triangle and quad panels or its polygon, listed in the ``.pvd`` as
part 1 of the same time step (ParaView shows both parts together). The ``.pvd`` is
written last, so a folder without it holds no finished series.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Callable, Sequence
from xml.sax.saxutils import escape, quoteattr

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from floatmoor.io.output_files import atomic_target
from floatmoor.io.shape_samples import line_shape

__all__ = ["write_vtk_series", "vtk_file_name", "body_file_name", "PVD_NAME", "BodyAtTime"]

#: Name of the collection file in the output folder.
PVD_NAME = "lines.pvd"


#: The body at a time [s]: its vertices (n, 3) [m] and panels (m, 4) (vertex indices; a
#: triangle repeats its third vertex), or one polygon (1, k) through k points.
BodyAtTime = Callable[[float], tuple[NDArray[np.float64], NDArray[np.int64]]]


def vtk_file_name(sample: int) -> str:
    """The ``.vtu`` file of shape sample ``sample``."""
    return f"lines_{sample:06d}.vtu"


def body_file_name(sample: int) -> str:
    """The body's ``.vtu`` file of shape sample ``sample``."""
    return f"body_{sample:06d}.vtu"


def _body_mesh(vertices: NDArray[np.float64], faces: NDArray[np.int64]):
    """Panels (m, 4) as triangles and quads; rows of another width k as one cell type (a
    line for 2, a triangle for 3, a polygon above 4)."""
    import meshio

    if faces.shape[1] != 4:
        kind = {2: "line", 3: "triangle"}.get(faces.shape[1], "polygon")
        return meshio.Mesh(vertices, [(kind, faces)])
    triangle = faces[:, 3] == faces[:, 2]
    cells = [(kind, block) for kind, block in (("triangle", faces[triangle, :3]),
                                               ("quad", faces[~triangle])) if len(block)]
    return meshio.Mesh(vertices, cells)


def _mesh(dataset: xr.Dataset, sample: int):
    import meshio

    points, tension, arc, cells, index = [], [], [], [], []
    offset = 0
    for j, name in enumerate(dataset["line"].values):
        shape = line_shape(dataset, str(name), sample)
        n = shape.arc_length.size
        points.append(shape.position)
        tension.append(shape.tension)
        arc.append(shape.arc_length)
        nodes = offset + np.arange(n)
        cells.append(np.column_stack([nodes[:-1], nodes[1:]]))
        index.append(np.full(n - 1, j, dtype=np.int32))
        offset += n
    return meshio.Mesh(np.concatenate(points), [("line", np.concatenate(cells))],
                       point_data={"tension": np.concatenate(tension),
                                   "arc_length": np.concatenate(arc)},
                       cell_data={"line_index": [np.concatenate(index)]})


def write_vtk_series(dataset: xr.Dataset, folder: str | os.PathLike[str],
                     samples: Sequence[int],
                     progress: Callable[[int, int], None] | None = None,
                     body: BodyAtTime | None = None) -> Path:
    """Write the shape samples ``samples`` of ``dataset`` into ``folder`` (created if its
    parent exists), with the body's panels at each when ``body`` is given; returns the
    ``.pvd`` file.

    Parameters
    ----------
    dataset
        A run's result dataset with line shapes.
    folder
        The output folder.
    samples
        Indices of the shape samples to write.
    progress
        Called with (done, total) after each sample.
    body
        The body's panels at a time (:mod:`floatmoor.plots.body_pose`), or None.

    Returns
    -------
    pathlib.Path
        The ``.pvd`` collection file.

    Raises
    ------
    ShapeDataError
        Without shapes.
    OutputWriteError
        When a file cannot be written (each is written atomically).
    """
    folder = Path(folder)
    folder.mkdir(exist_ok=True)
    times = np.asarray(dataset["shape_time"].values, dtype=float)
    entries = []
    for i, k in enumerate(samples):
        name = vtk_file_name(int(k))
        with atomic_target(folder / name, suffix=".vtu") as tmp:
            _mesh(dataset, int(k)).write(tmp, file_format="vtu")
        entries.append(f'    <DataSet timestep="{float(times[k])!r}" group="" part="0" '
                       f'file={quoteattr(name)}/>')
        if body is not None:
            name = body_file_name(int(k))
            with atomic_target(folder / name, suffix=".vtu") as tmp:
                _body_mesh(*body(float(times[k]))).write(tmp, file_format="vtu")
            entries.append(f'    <DataSet timestep="{float(times[k])!r}" group="" part="1" '
                           f'file={quoteattr(name)}/>')
        if progress is not None:
            progress(i + 1, len(samples))
    names = ", ".join(f"{j}: {n}" for j, n in enumerate(dataset["line"].values))
    text = "\n".join([
        '<?xml version="1.0"?>',
        f"<!-- {escape(str(dataset.attrs.get('title', '')))}; line_index {escape(names)}; "
        f"floatmoor {escape(str(dataset.attrs.get('floatmoor_version', '')))} -->",
        '<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">',
        "  <Collection>", *entries, "  </Collection>", "</VTKFile>", ""])
    pvd = folder / PVD_NAME
    with atomic_target(pvd, suffix=".pvd") as tmp:
        tmp.write_text(text, encoding="utf-8")
    return pvd
