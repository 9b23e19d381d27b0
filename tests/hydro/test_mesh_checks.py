"""The checks of a hull mesh read from a file (floatmoor.hydro.mesh_checks): each fails on a
mesh made to fail it and passes on the good one; ``hydro build`` refuses a broken file or a
hull that is not closed (status 2, one message, nothing written) and reports the others."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from floatmoor.cli import main
from floatmoor.hydro.build import wavenumber
from floatmoor.hydro.hydrostatics import hull_hydrostatics
from floatmoor.hydro.mesh_checks import (
    VOLUME_AGREEMENT, check_irregular_frequencies, check_normals, check_panel_size,
    check_watertight, divergence_volumes, hull_topology, reference_hydrostatics,
)
from floatmoor.hydro.database import read_database
from tests.hydro.mesh_files import TINY_CASE, tiny_faces, write_case, write_gdf

G = 9.81


def _mesh(faces: np.ndarray):
    """A capytaine mesh of ``faces`` (n, 4, 3), each panel with its own vertices."""
    import capytaine as cpt

    return cpt.Mesh(vertices=faces.reshape(-1, 3), faces=np.arange(4 * len(faces)).reshape(-1, 4),
                    auto_clean=False, auto_check=False)


def _wavelength(omega: float) -> float:
    return 2.0 * math.pi / wavenumber(omega, 2.0, G)


def _bottom_centre_panel(faces: np.ndarray) -> int:
    """A quad of the bottom disc (z = -0.3 everywhere)."""
    flat = np.all(np.abs(faces[:, :, 2] + 0.3) < 1e-12, axis=1)
    quads = ~np.all(faces[:, 3] == faces[:, 2], axis=1)
    return int(np.nonzero(flat & quads)[0][0])


def test_good_cylinder_passes_every_check():
    mesh = _mesh(tiny_faces())
    topology = hull_topology(mesh)
    watertight, normals = check_watertight(topology), check_normals(topology)
    assert watertight.passed and watertight.value == 0.0 and len(topology.waterline_edges) == 24
    assert normals.passed and normals.value < 1e-12
    assert check_panel_size(mesh, None, 6.0, _wavelength(6.0)).passed
    assert check_irregular_frequencies(topology, None, 6.0, G).passed


def test_hole_below_the_waterline_fails_watertight():
    faces = tiny_faces()
    k = _bottom_centre_panel(faces)
    holed = np.delete(faces, k, axis=0)
    check = check_watertight(hull_topology(_mesh(holed)))
    perimeter = sum(np.linalg.norm(faces[k][i] - faces[k][(i + 1) % 4]) for i in range(4))
    assert not check.passed and check.fatal and check.value == 4.0
    assert f"({perimeter:.4g} m long" in check.detail
    # the normals check alone would not see it: the volume components still agree roughly
    assert "open edges" in check.detail and check.fix


def test_t_junctions_of_a_non_conforming_mesh_are_closed():
    """One side panel split in two along its height: its neighbours' long edges meet two
    short ones (hanging nodes), which close the hull."""
    faces = tiny_faces()
    side = np.nonzero(np.ptp(faces[:, :, 2], axis=1) > 0.01)[0][5]
    a, b, c, d = faces[side]
    ab, dc = 0.5 * (a + b), 0.5 * (d + c)
    split = np.array([[a, ab, dc, d], [ab, b, c, dc]])
    refined = np.concatenate([np.delete(faces, side, axis=0), split])
    topology = hull_topology(_mesh(refined))
    # each hanging node: the neighbour's long edge and the two short edges along it
    assert topology.tjunction_edges > 0 and topology.tjunction_edges % 3 == 0
    assert check_watertight(topology).passed
    assert check_normals(topology).passed
    # a hole next to the T-junction is still a hole
    holed = np.delete(refined, len(refined) - 1, axis=0)
    assert not check_watertight(hull_topology(_mesh(holed))).passed


def test_flipped_normals_fail():
    faces = tiny_faces()
    inward = check_normals(hull_topology(_mesh(faces[:, ::-1])))
    assert not inward.passed and inward.value == math.inf and "negative volume" in inward.detail
    one = faces.copy()
    k = _bottom_centre_panel(faces)
    one[k] = one[k][::-1]
    topology = hull_topology(_mesh(one))
    flipped = check_normals(topology)
    assert not flipped.passed and topology.misoriented_edges == 4
    # the volume components part too (the figure in VOLUME_AGREEMENT's comment)
    vols = divergence_volumes(topology.triangles)
    assert (vols.max() - vols.min()) / vols.max() > 100 * VOLUME_AGREEMENT
    assert check_watertight(topology).passed  # closed, only misoriented


def test_coarse_mesh_for_the_top_frequency_warns():
    mesh = _mesh(tiny_faces())
    radius = float(mesh.faces_radiuses.max())
    # the wavelength 8 x the largest radius at omega_limit (finite depth 2 m: deep water)
    omega_limit = math.sqrt(2.0 * math.pi * G / (8.0 * radius))
    fine = check_panel_size(mesh, None, 0.95 * omega_limit, _wavelength(0.95 * omega_limit))
    coarse = check_panel_size(mesh, None, 1.05 * omega_limit, _wavelength(1.05 * omega_limit))
    assert fine.passed and not coarse.passed and not coarse.fatal
    assert coarse.value == pytest.approx(1.05 ** 2, rel=1e-3)
    assert f"{4.0 / 1.05 ** 2:.3g} panel diameters per wavelength" in coarse.detail


def test_band_above_the_first_irregular_frequency_warns_without_lid():
    mesh = _mesh(tiny_faces())
    topology = hull_topology(mesh)
    below = check_irregular_frequencies(topology, None, 9.0, G)
    above = check_irregular_frequencies(topology, None, 10.0, G)
    # capytaine's estimate for a 0.5 m x 0.5 m box 0.3 m deep: 9.38 rad/s
    p = math.hypot(1 / 0.5, 1 / 0.5)
    estimate = math.sqrt(math.pi * G * p / math.tanh(math.pi * 0.3 * p))
    assert below.passed and not above.passed and not above.fatal
    assert above.value == pytest.approx(10.0 / estimate, rel=1e-3)
    import capytaine as cpt

    lid = mesh.generate_lid(z=-0.02)
    with_lid = check_irregular_frequencies(topology, lid, 10.0, G)
    assert with_lid.passed and "harmless with the lid" in with_lid.detail
    assert isinstance(lid, cpt.Mesh)


@pytest.mark.parametrize("shift", [(0.0, 0.0, 0.0), (1.0, 0.5, 0.0)])
def test_reference_hydrostatics_agree_with_the_database_integrals(shift):
    """The independent integration (n_x, n_y volumes, waterline line integrals) gives the
    n_z integrals of floatmoor.hydro.hydrostatics to round-off, about a rotation centre off
    the hull's axis too."""
    faces = tiny_faces() + np.asarray(shift)
    mesh = _mesh(faces)
    centre = (0.2, -0.1, -0.05)
    ref = reference_hydrostatics(hull_topology(mesh), centre)
    hs = hull_hydrostatics(mesh, rho=1000.0, g=G, rotation_center=centre)
    k = hs["hydrostatic_stiffness"] / (1000.0 * G)
    vz = hs["disp_volume"] * (hs["center_of_buoyancy"][2] - centre[2])
    assert ref["disp_volume"] == pytest.approx(hs["disp_volume"], rel=1e-12)
    assert ref["center_of_buoyancy_z"] == pytest.approx(hs["center_of_buoyancy"][2], rel=1e-12)
    assert ref["waterplane_area"] == pytest.approx(hs["waterplane_area"], rel=1e-12)
    assert ref["waterplane_yy"] + vz == pytest.approx(k[3, 3], rel=1e-10)
    assert ref["waterplane_xx"] + vz == pytest.approx(k[4, 4], rel=1e-10)


# -- hydro build ---------------------------------------------------------------------------

def _build(case, capsys):
    status = main(["hydro", "build", str(case), "--quiet"])
    return status, capsys.readouterr()


def _mesh_geometry(file: str) -> str:
    return f'kind = "mesh"\nfile = "{file}"'


@pytest.mark.parametrize("content, found", [
    ("not a mesh\n", "expected a gdf mesh file capytaine can read"),
    ("holed", "the watertight check of the immersed hull: expected a watertight hull"),
    ("inward", "the normals check of the immersed hull: expected outward normals"),
])
def test_build_refuses_broken_file_or_hull_with_status_2(tmp_path, capsys, content, found):
    """One message (file, check, figure, fix) on standard error, status 2, nothing written."""
    faces = tiny_faces()
    path = tmp_path / "hull.gdf"
    if content == "holed":
        write_gdf(path, np.delete(faces, _bottom_centre_panel(faces), axis=0))
    elif content == "inward":
        write_gdf(path, faces[:, ::-1])
    else:
        path.write_text(content)
    case = write_case(tmp_path, _mesh_geometry("hull.gdf"))
    status, out = _build(case, capsys)
    assert status == 2 and out.out == ""
    lines = out.err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"floatmoor: error: {path}: ")
    assert found in lines[0]
    assert list((tmp_path / "hydrodb").iterdir()) == []
    assert sorted(p.name for p in tmp_path.iterdir()) == ["hull.gdf", "hydrodb", "tiny.toml"]


def test_build_reports_the_mesh_and_its_warnings(tmp_path, capsys):
    """A mesh build prints what it read and the four checks; the failed warnings go to
    standard error too, and everything is recorded in the database."""
    write_gdf(tmp_path / "hull.gdf", tiny_faces())
    accepts = 'accept_failed_checks = ["symmetry", "kramers_kronig", "kernel_decay", ' \
        '"haskind"]'
    case = write_case(tmp_path, _mesh_geometry("hull.gdf"), hydro=accepts)
    case.write_text(case.read_text().replace("frequencies = [2.0, 4.0, 6.0]",
                                             "frequencies = [2.0, 6.0, 15.0]"))
    status, out = _build(case, capsys)
    assert status == 0, out.err
    lines = out.out.splitlines()
    head = next(i for i, line in enumerate(lines) if line.startswith("mesh hull.gdf (gdf, m"))
    assert "216 panels read" in lines[head] and "0 lid panels" in lines[head]
    rows = {line.split()[0]: line.split()[1] for line in lines[head + 2:head + 6]}
    assert rows == {"watertight": "pass", "normals": "pass", "panel_size": "WARN",
                    "irregular_frequencies": "WARN"}
    assert "floatmoor: warning: mesh hull.gdf: panel_size: wavelength" in out.err
    assert "floatmoor: warning: mesh hull.gdf: irregular_frequencies:" in out.err
    ds = read_database(tmp_path / "hydrodb" / "tiny.nc")
    info = json.loads(ds.attrs["mesh_file_json"])
    assert info["file"] == "hull.gdf" and len(info["sha256"]) == 64
    assert info["panels_immersed"] == ds.attrs["hull_panels"] == 216
    checks = json.loads(ds.attrs["mesh_checks_json"])
    assert [c["name"] for c in checks if not c["passed"]] == ["panel_size",
                                                               "irregular_frequencies"]
    # up to date: the recorded findings are printed again, no warnings
    status, out = _build(case, capsys)
    assert status == 0 and "up to date" in out.out and "panel_size            WARN" in out.out
    assert "warning: mesh" not in out.err
    assert TINY_CASE  # the shared case text is the one these tests edit
