"""Mesh files and case files for the mesh-hull tests: the parametric cylinder's own panels
written as WAMIT GDF (a small writer, the format is 4 header lines and 4 vertices a panel)
or through meshio, and a tiny floater case around them."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from floatmoor.case.schema import CylinderGeometry
from floatmoor.hydro.geometry import cylinder_mesh

#: The tiny cylinder of tests/hydro/test_cli_hydro.py, meshed finer: 24 panels around, 4
#: across the bottom radius and 5 up the side, 216 panels.
TINY_CYLINDER = CylinderGeometry(diameter=0.5, draft=0.3, height=0.6, draft_from_mass=False)
TINY_PANEL = 0.07

TINY_CASE = """
title = "tiny floating cylinder ({kind})"
[environment]
water_density = 1000.0
water_depth = 2.0
gravity = 9.81
[seabed]
stiffness = 1.0e6
damping_ratio = 1.0
friction_coefficient = 0.0
slip_speed = 0.01
[floater]
name = "tiny"
mass = 58.9
centre_of_mass = [0.0, 0.0, -0.1]
inertia = [2.0, 2.0, 1.5]
reference_point = [0.0, 0.0, 0.0]
[floater.geometry]
{geometry}
[hydro]
database = "{database}"
frequencies = [2.0, 4.0, 6.0]
directions_deg = [0.0]
panel_size = 0.07
lid = false
{hydro}
[simulation]
duration = 1.0
output_interval = 0.1
"""

CYLINDER_GEOMETRY = 'kind = "cylinder"\ndiameter = 0.5\nheight = 0.6\ndraft = 0.3'


def tiny_faces() -> np.ndarray:
    """(n, 4, 3) panels of the tiny cylinder's wetted hull (triangles repeat a vertex)."""
    mesh = cylinder_mesh(TINY_CYLINDER, panel_size=TINY_PANEL)
    return np.asarray(mesh.full_hull.as_array_of_faces(), dtype=float)


def write_gdf(path: Path, faces: np.ndarray, *, isx: int = 0, isy: int = 0,
              ulen: float = 1.0) -> Path:
    """A WAMIT GDF file of ``faces`` (n, 4, 3) [file units]."""
    rows = ["floatmoor test mesh", f"{ulen:g} 9.80665 ULEN GRAV", f"{isx} {isy} ISX ISY",
            f"{len(faces)}"]
    rows += [f"{x:.17g} {y:.17g} {z:.17g}" for face in faces for x, y, z in face]
    path.write_text("\n".join(rows) + "\n")
    return path


def write_meshio(path: Path, faces: np.ndarray, fmt: str) -> Path:
    """``faces`` written by meshio (STL: quads split into triangles)."""
    import meshio

    points = faces.reshape(-1, 3)
    index = np.arange(len(points)).reshape(-1, 4)
    triangle = np.all(faces[:, 3] == faces[:, 2], axis=1)
    if fmt == "stl":
        cells = [("triangle", np.concatenate([index[:, [0, 1, 2]],
                                              index[~triangle][:, [0, 2, 3]]]))]
    else:
        cells = [("quad", index[~triangle])]
        if np.any(triangle):
            cells.append(("triangle", index[triangle][:, :3]))
    meshio.write(str(path), meshio.Mesh(points, cells), file_format=fmt)
    return path


def quarter(faces: np.ndarray) -> np.ndarray:
    """The panels with x >= 0 and y >= 0 (centres), of a mesh whose panel edges lie on both
    planes."""
    centres = faces.mean(axis=1)
    return faces[(centres[:, 0] > 0.0) & (centres[:, 1] > 0.0)]


def half(faces: np.ndarray) -> np.ndarray:
    """The panels with y >= 0 (centres)."""
    return faces[faces.mean(axis=1)[:, 1] > 0.0]


def write_case(folder: Path, geometry: str, *, database: str = "tiny", hydro: str = "",
               name: str = "tiny.toml", kind: str = "mesh") -> Path:
    """A tiny floater case in ``folder`` (with a hydrodb folder)."""
    (folder / "hydrodb").mkdir(exist_ok=True)
    path = folder / name
    path.write_text(TINY_CASE.format(kind=kind, geometry=geometry, database=database,
                                     hydro=hydro))
    return path
