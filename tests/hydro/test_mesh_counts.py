"""Mesh files are sized from their headers before a reader allocates: a binary STL of 1.2 M
triangles ran ``hydro build`` past 60 s and 2.7 GB, and ``.msh`` / ``.off`` headers claiming
1e9 nodes asked for 22-67 GiB. Counts beyond the bounds are a BemFileError naming the bound
(status 2 from the command line)."""

from __future__ import annotations

import struct
import time

import numpy as np
import pytest

from floatmoor.cli import main
from floatmoor.hydro.mesh_file import (MAX_FILE_PANELS, MAX_FILE_VERTICES, claimed_counts,
                                       read_mesh_file)
from floatmoor.io.bem_data import BemFileError
from tests.hydro.mesh_files import tiny_faces, write_case, write_gdf, write_meshio


@pytest.mark.parametrize("fmt", ["stl", "off", "ply", "vtk", "vtu", "obj"])
def test_counts_read_from_the_header_match_the_file(tmp_path, fmt):
    faces = tiny_faces()
    path = write_meshio(tmp_path / f"hull.{fmt}", faces, {"msh": "gmsh"}.get(fmt, fmt))
    import meshio

    with np.errstate(over="ignore"):  # meshio's ASCII-or-binary STL test overflows
        mesh = meshio.read(path)
    panels = sum(len(c.data) for c in mesh.cells)
    counts = dict(claimed_counts(str(path), fmt))
    # (legacy VTK 5.1 counts the n + 1 offsets of its CELLS: a bound, one over)
    assert counts["panels"] == panels + (fmt == "vtk")
    if "vertices" in counts:
        assert counts["vertices"] == len(mesh.points)


@pytest.mark.parametrize("version, binary", [("gmsh22", False), ("gmsh22", True),
                                             ("gmsh", False), ("gmsh", True)])
def test_gmsh_counts_match_the_file(tmp_path, version, binary):
    import meshio

    points = tiny_faces().reshape(-1, 3)
    triangles = np.arange(len(points) // 4 * 3).reshape(-1, 3)
    path = tmp_path / "hull.msh"
    meshio.write(str(path), meshio.Mesh(points, [("triangle", triangles)]),
                 file_format=version, binary=binary)
    assert dict(claimed_counts(str(path), "msh")) == {"vertices": len(points),
                                                      "panels": len(triangles)}


def test_gdf_count_is_read(tmp_path):
    path = write_gdf(tmp_path / "hull.gdf", tiny_faces())
    assert claimed_counts(str(path), "gdf") == [("panels", len(tiny_faces()))]


def _binary_stl(path, triangles: int, claimed: int | None = None):
    with open(path, "wb") as f:
        f.write(b"\0" * 80 + struct.pack("<I", triangles if claimed is None else claimed))
        f.write(b"\0" * (50 * triangles))
    return path


FORGED = {
    "claims.stl": None,  # written by _binary_stl
    "claims.off": b"OFF\n1000000000 1000000000 0\n0 0 0\n",
    "claims2.msh": b"$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1000000000\n1 0 0 0\n",
    "claims4.msh": b"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 1000000000 1 1000000000\n",
    "claims4b.msh": b"$MeshFormat\n4.1 1 8\n\x01\x00\x00\x00\n$EndMeshFormat\n$Nodes\n"
                    + struct.pack("<4Q", 1, 10**9, 1, 10**9),
    "claims.ply": b"ply\nformat ascii 1.0\nelement vertex 1000000000\nproperty float x\n"
                  b"end_header\n",
}


@pytest.mark.parametrize("name", sorted(FORGED))
def test_a_header_claiming_a_huge_mesh_is_refused_before_reading(tmp_path, name):
    path = tmp_path / name
    if name.endswith(".stl"):
        _binary_stl(path, 1, claimed=1_200_000)
    else:
        path.write_bytes(FORGED[name])
    start = time.perf_counter()
    with pytest.raises(BemFileError) as info:
        read_mesh_file(str(path), name.rsplit(".", 1)[1])
    assert time.perf_counter() - start < 5.0
    message = str(info.value)
    assert f"at most {MAX_FILE_PANELS} panels" in message or \
        f"at most {MAX_FILE_VERTICES} vertices" in message
    assert "MAX_FILE_" in message


def test_hydro_build_refuses_a_stl_of_too_many_triangles(tmp_path, capsys):
    """A real binary STL one triangle over the bound: status 2, the bound in the message,
    nothing built."""
    _binary_stl(tmp_path / "hull.stl", MAX_FILE_PANELS + 1)
    case = write_case(tmp_path, 'kind = "mesh"\nfile = "hull.stl"\n')
    status = main(["hydro", "build", str(case)])
    err = capsys.readouterr().err
    assert status == 2, err
    assert f"expected at most {MAX_FILE_PANELS} panels in the file" in err
    assert f"found {MAX_FILE_PANELS + 1}" in err
    assert list((tmp_path / "hydrodb").iterdir()) == []
