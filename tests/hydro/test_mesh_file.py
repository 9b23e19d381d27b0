"""Hull meshes from files (``[floater.geometry] kind = "mesh"``): loading, reading,
placing, symmetry, and the databases built on them against the parametric cylinder's."""

from __future__ import annotations

import dataclasses
import json
import math
import shutil
import time

import numpy as np
import pytest

from floatmoor.body.morison import DragSettings, build_strips
from floatmoor.case.load import load_case
from floatmoor.case.schema import Column, SemisubmersibleGeometry
from floatmoor.errors import CaseError
from floatmoor.hydro.database import build_database
from floatmoor.hydro.checks import geometry_from_dataset, run_checks
from floatmoor.hydro.database import database_inputs, inputs_hash, merge_complex
from floatmoor.hydro.geometry import build_mesh
from floatmoor.hydro.hydrostatics import hull_hydrostatics
from floatmoor.io.bem_data import BemFileError
from tests.hydro.conftest import BUOY_CASE, BUOY_DB
from tests.hydro.mesh_files import (
    CYLINDER_GEOMETRY, half, quarter, tiny_faces, write_case, write_gdf, write_meshio,
)

#: The mesh-file build solves the very panels of the parametric build (written to 17
#: significant digits), on capytaine's dense rather than its rotation-symmetric solver:
#: the results agree to the solvers' round-off.
SAME_PANELS = 1e-6
#: Hydrostatic integrals of the same panels read from another file format: round-off.
ROUND_OFF = 1e-9
#: The required check: the mesh database within 1 % of the built-in cylinder's over the band,
#: per DOF, as the largest |difference| over the band relative to the DOF's peak |value| over
#: the band (the pointwise differences are reported).
BAND_TOLERANCE = 0.01

MESH = 'kind = "mesh"\nfile = "{file}"\n{extra}'


def _mesh_case(tmp_path, file, extra="", **kw):
    return write_case(tmp_path, MESH.format(file=file, extra=extra), **kw)


def _arrays(ds) -> dict[str, np.ndarray]:
    out = {name: ds[name].transpose("omega", "radiating_dof", "influenced_dof").values
           for name in ("added_mass", "radiation_damping")}
    out["excitation_force"] = merge_complex(ds, "excitation_force").transpose(
        "omega", "wave_direction", "influenced_dof").values
    out["added_mass_infinite"] = ds["added_mass_infinite"].values
    out["hydrostatic_stiffness"] = ds["hydrostatic_stiffness"].values
    return out


def _relative(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.abs(a - b).max() / np.abs(b).max())


@pytest.fixture(scope="module")
def cylinder_db(tmp_path_factory):
    """The tiny cylinder built as kind = "cylinder" (216 panels, 3 frequencies, 2 m deep)."""
    folder = tmp_path_factory.mktemp("cylinder")
    return build_database(load_case(write_case(folder, CYLINDER_GEOMETRY, kind="cylinder")))


@pytest.fixture(scope="module")
def mesh_db(tmp_path_factory):
    """The same panels written to a GDF file and built as kind = "mesh"."""
    folder = tmp_path_factory.mktemp("mesh")
    write_gdf(folder / "hull.gdf", tiny_faces())
    return build_database(load_case(_mesh_case(folder, "hull.gdf")))


def test_mesh_build_equals_the_cylinder_build(cylinder_db, mesh_db):
    """The parametric cylinder's own panels through kind = "mesh" give its database."""
    assert mesh_db.attrs["hull_panels"] == cylinder_db.attrs["hull_panels"] == 216
    assert mesh_db.attrs["mesh_hash"] == cylinder_db.attrs["mesh_hash"]
    mesh, cylinder = _arrays(mesh_db), _arrays(cylinder_db)
    for name in mesh:
        assert _relative(mesh[name], cylinder[name]) < SAME_PANELS, name
    assert mesh_db.attrs["geometry_kind"] == "mesh"
    info = json.loads(mesh_db.attrs["mesh_file_json"])
    assert info["file"] == "hull.gdf" and info["panels_immersed"] == 216
    checks = {c["name"]: c["passed"] for c in json.loads(mesh_db.attrs["mesh_checks_json"])}
    assert checks == {"watertight": True, "normals": True, "panel_size": True,
                      "irregular_frequencies": True}


def test_mesh_database_hydrostatics_check_against_the_recorded_integration(mesh_db):
    """A mesh has no analytic geometry: the database's hydrostatics are checked against the
    independent integration recorded at build time, and fail when the values are changed."""
    result = {r.name: r for r in run_checks(mesh_db)}["hydrostatics"]
    assert result.passed and result.worst < 1e-9
    assert "independent integration" in result.detail
    edited = mesh_db.copy(deep=True)
    edited["hydrostatic_stiffness"].values[2, 2] *= 1.02
    result = {r.name: r for r in run_checks(edited)}["hydrostatics"]
    assert not result.passed and result.worst == pytest.approx(0.02, rel=1e-6)
    edited.attrs.pop("mesh_reference_json")
    result = {r.name: r for r in run_checks(edited)}["hydrostatics"]
    assert not result.passed and "mesh_reference_json" in result.detail


def test_geometry_from_dataset_reads_the_mesh_geometry(mesh_db):
    geometry = geometry_from_dataset(mesh_db)
    assert geometry.kind == "mesh" and geometry.file == "hull.gdf" and geometry.path is None
    assert geometry.sha256 == json.loads(mesh_db.attrs["mesh_file_json"])["sha256"]


@pytest.mark.parametrize("fmt", ["stl", "obj", "vtk"])
def test_meshio_round_trip_reads_the_same_hydrostatics(tmp_path, fmt):
    """The cylinder written by meshio (STL as triangles) reads back to the GDF's hull."""
    faces = tiny_faces()
    write_gdf(tmp_path / "hull.gdf", faces)
    write_meshio(tmp_path / f"hull.{fmt}", faces, fmt)
    reference = _hydrostatics(tmp_path, "hull.gdf")
    other = _hydrostatics(tmp_path, f"hull.{fmt}")
    for key in ("disp_volume", "waterplane_area"):
        assert other[key] == pytest.approx(reference[key], rel=ROUND_OFF)
    assert other["center_of_buoyancy"] == pytest.approx(reference["center_of_buoyancy"],
                                                        abs=ROUND_OFF)
    np.testing.assert_allclose(other["hydrostatic_stiffness"],
                               reference["hydrostatic_stiffness"], rtol=ROUND_OFF, atol=1e-9)


def _mesh(tmp_path, file, extra="", lid_depth=None, symmetry=True):
    case = load_case(_mesh_case(tmp_path, file, extra, name=f"{file}.toml"))
    return build_mesh(case.floater.geometry, panel_size=0.07, lid_depth=lid_depth,
                      symmetry=symmetry, water_depth=2.0)


def _hydrostatics(tmp_path, file, extra="", rotation_center=(0.0, 0.0, 0.0)):
    mesh = _mesh(tmp_path, file, extra)
    return hull_hydrostatics(mesh.full_hull, rho=1000.0, g=9.81,
                             rotation_center=rotation_center)


def test_length_unit_and_position_are_applied(tmp_path):
    """A hull written in millimetres with its keel at z = 0 and its axis at x = -500 mm,
    placed by position, is the cylinder at the origin."""
    faces = tiny_faces()
    moved = (faces + np.array([-0.5, 0.0, 0.3])) * 1000.0
    write_gdf(tmp_path / "hull.gdf", faces)
    write_gdf(tmp_path / "hull_mm.gdf", moved)
    reference = _hydrostatics(tmp_path, "hull.gdf")
    placed = _hydrostatics(tmp_path, "hull_mm.gdf",
                           'length_unit = "mm"\nposition = [0.5, 0.0, -0.3]')
    assert placed["disp_volume"] == pytest.approx(reference["disp_volume"], rel=ROUND_OFF)
    assert placed["center_of_buoyancy"] == pytest.approx(reference["center_of_buoyancy"],
                                                         abs=ROUND_OFF)
    np.testing.assert_allclose(placed["hydrostatic_stiffness"],
                               reference["hydrostatic_stiffness"], rtol=ROUND_OFF, atol=1e-9)
    # without the position the hull stands on the water (nothing below it): an error
    with pytest.raises(BemFileError, match="panels below the waterline"):
        _mesh(tmp_path, "hull_mm.gdf", 'length_unit = "mm"')
    # placed 0.1 m higher, the clip at z = 0 leaves 0.2 m of the 0.3 m hull under water
    higher = _hydrostatics(tmp_path, "hull_mm.gdf",
                           'length_unit = "mm"\nposition = [0.5, 0.0, -0.2]')
    assert higher["disp_volume"] == pytest.approx(reference["disp_volume"] * 2 / 3, rel=1e-9)


def test_declared_symmetry_gives_the_full_mesh_result(tmp_path, mesh_db):
    """A quarter (GDF flags ISX = ISY = 1) and a half (OBJ, no flags) declared symmetric
    give the full mesh's database; the BEM uses the planes."""
    faces = tiny_faces()
    write_gdf(tmp_path / "quarter.gdf", quarter(faces), isx=1, isy=1)
    write_meshio(tmp_path / "half.obj", half(faces), "obj")
    full = _arrays(mesh_db)
    for file, extra, label in (("quarter.gdf", 'symmetry = ["xz", "yz"]',
                                "mirror-xOz+mirror-yOz"),
                               ("half.obj", 'symmetry = ["xz"]', "mirror-xOz")):
        folder = tmp_path / file.split(".")[0]
        folder.mkdir()
        shutil.copy(tmp_path / file, folder / file)
        ds = build_database(load_case(_mesh_case(folder, file, extra)))
        assert ds.attrs["mesh_symmetry"] == label and ds.attrs["hull_panels"] == 216
        for name, values in _arrays(ds).items():
            assert _relative(values, full[name]) < SAME_PANELS, (file, name)


def test_symmetry_flags_must_agree_with_the_declaration(tmp_path):
    faces = tiny_faces()
    write_gdf(tmp_path / "quarter.gdf", quarter(faces), isx=1, isy=1)
    write_gdf(tmp_path / "full.gdf", faces)
    with pytest.raises(BemFileError, match="symmetry xz, yz flagged in the file"):
        _mesh(tmp_path, "quarter.gdf")
    with pytest.raises(BemFileError, match="no symmetry flagged in the file"):
        _mesh(tmp_path, "full.gdf", 'symmetry = ["xz"]')
    # a meshio file has no flags: a full hull declared a half is found by its vertices
    write_meshio(tmp_path / "full.stl", faces, "stl")
    with pytest.raises(BemFileError, match=r"vertices down to y = -0\.25"):
        _mesh(tmp_path, "full.stl", 'symmetry = ["xz"]')


def test_symmetry_off_or_moved_plane_expands_the_mesh(tmp_path):
    """[hydro] symmetry = false, or a position off the plane, gives the whole hull to the
    BEM (said in the notes when the position is the reason)."""
    faces = tiny_faces()
    write_gdf(tmp_path / "quarter.gdf", quarter(faces), isx=1, isy=1)
    sym = 'symmetry = ["xz", "yz"]'
    kept = _mesh(tmp_path, "quarter.gdf", sym)
    assert kept.symmetry == "mirror-xOz+mirror-yOz" and kept.hull.nb_faces == 216
    off = _mesh(tmp_path, "quarter.gdf", sym, symmetry=False)
    assert off.symmetry == "none" and off.hull.nb_faces == 216
    moved = _mesh(tmp_path, "quarter.gdf", sym + "\nposition = [1.0, 0.0, 0.0]")
    assert moved.symmetry == "mirror-xOz"
    assert any("yz not used" in note for note in moved.source.notes)
    assert moved.full_hull.vertices[:, 0].min() == pytest.approx(0.75)


def test_lid_follows_the_symmetry_and_is_not_empty(tmp_path):
    """capytaine's lid of the hull, cut to the kept symmetry and mirrored: inside the hull,
    at the lid depth, normals down, about the full hull's lid (capytaine's lid is not
    exactly symmetric: its inside test at points on panel edges goes by round-off; cut to
    the quarter, the tiny cylinder's lid loses 4.8 % of its area)."""
    faces = tiny_faces()
    write_gdf(tmp_path / "quarter.gdf", quarter(faces), isx=1, isy=1)
    write_gdf(tmp_path / "full.gdf", faces)
    full = _mesh(tmp_path, "full.gdf", lid_depth=0.02)
    sym = _mesh(tmp_path, "quarter.gdf", 'symmetry = ["xz", "yz"]', lid_depth=0.02)
    # the lid is generated on the whole hull and cut to the quarter: panels across the
    # planes are cut, the area stays
    assert full.lid_panels > 0 and sym.lid_panels > 0
    area = full.lid.faces_areas.sum()
    lid = sym.lid.merged()
    assert lid.faces_areas.sum() == pytest.approx(area, rel=0.1)
    assert np.all(lid.faces_normals[:, 2] < 0)  # capytaine: lid normals down
    assert np.allclose(lid.vertices[:, 2], -0.02) and np.allclose(full.lid.vertices[:, 2], -0.02)
    assert np.hypot(lid.vertices[:, 0], lid.vertices[:, 1]).max() < 0.25


def test_broken_files_are_bem_file_errors(tmp_path):
    write_gdf(tmp_path / "hull.gdf", tiny_faces())
    text = (tmp_path / "hull.gdf").read_text().splitlines()
    cases = {
        "garbage.gdf": "not a mesh\n",
        "short.gdf": "\n".join(text[:-3]) + "\n",  # a panel's last vertices missing
        "nan.gdf": "\n".join(text[:4] + ["nan 0 -1"] + text[5:]) + "\n",
        "empty.stl": "solid empty\nendsolid empty\n",
    }
    for name, content in cases.items():
        (tmp_path / name).write_text(content)
        with pytest.raises(BemFileError) as info:
            _mesh(tmp_path, name)
        assert str(info.value).startswith(str(tmp_path / name)), name
    faces = tiny_faces()
    write_gdf(tmp_path / "below_seabed.gdf", faces * np.array([1.0, 1.0, 10.0]))
    with pytest.raises(BemFileError, match="above the seabed"):
        _mesh(tmp_path, "below_seabed.gdf")


def test_panel_bounds(tmp_path, monkeypatch):
    """More immersed panels than MAX_BEM_PANELS, or a lid that would have more, is an error
    before anything is solved."""
    import floatmoor.hydro.mesh_file as mesh_file

    write_gdf(tmp_path / "hull.gdf", tiny_faces())
    monkeypatch.setattr(mesh_file, "MAX_BEM_PANELS", 200)
    with pytest.raises(BemFileError, match="at most 200 panels below the waterline"):
        _mesh(tmp_path, "hull.gdf")
    monkeypatch.setattr(mesh_file, "MAX_BEM_PANELS", 1000)
    case = load_case(_mesh_case(tmp_path, "hull.gdf"))
    with pytest.raises(BemFileError, match="a lid of at most 1000 panels"):
        build_mesh(case.floater.geometry, panel_size=0.01, lid_depth=0.02)


def test_waterplane_panels_are_dropped(tmp_path):
    """A closed box sunk to its top: the top panels on z = 0 are not wetted hull (dropped,
    said in the notes); the box below is the hull, closed by the waterplane."""
    from floatmoor.hydro.mesh_checks import check_watertight, hull_topology

    import capytaine as cpt

    box = cpt.mesh_parallelepiped(size=(1.0, 1.0, 1.0), center=(0.0, 0.0, 0.0),
                                  resolution=(2, 2, 2))
    write_gdf(tmp_path / "box.gdf", np.asarray(box.as_array_of_faces()))
    mesh = _mesh(tmp_path, "box.gdf", "position = [0.0, 0.0, -0.5]")
    assert mesh.full_hull.nb_faces == box.nb_faces - 4
    assert any("dropped 4 panels lying on the waterplane" in n for n in mesh.source.notes)
    assert check_watertight(hull_topology(mesh.full_hull)).passed
    hs = hull_hydrostatics(mesh.full_hull, rho=1000.0, g=9.81, rotation_center=(0, 0, 0))
    assert hs["disp_volume"] == pytest.approx(1.0) and hs["waterplane_area"] == pytest.approx(1.0)


def test_changed_file_after_load_is_refused(tmp_path):
    faces = tiny_faces()
    write_gdf(tmp_path / "hull.gdf", faces)
    case = load_case(_mesh_case(tmp_path, "hull.gdf"))
    write_gdf(tmp_path / "hull.gdf", faces * 1.01)
    with pytest.raises(BemFileError, match="changed since"):
        build_mesh(case.floater.geometry, panel_size=0.07)


def test_database_inputs_follow_the_file_not_its_folder(tmp_path):
    """A changed mesh file makes the database stale; moving the project does not; Morison
    elements (drag only) are not BEM inputs."""
    faces = tiny_faces()
    one = tmp_path / "one"
    one.mkdir()
    write_gdf(one / "hull.gdf", faces)
    case = load_case(_mesh_case(one, "hull.gdf"))
    inputs = database_inputs(case.floater, case.hydro, case.environment)
    assert inputs["geometry"]["file"] == "hull.gdf"
    assert str(one) not in json.dumps(inputs)
    moved = tmp_path / "moved"
    shutil.copytree(one, moved)
    again = load_case(moved / "tiny.toml")
    assert again.floater.geometry.path == str((moved / "hull.gdf").resolve())
    assert inputs_hash(database_inputs(again.floater, again.hydro, again.environment)) == \
        inputs_hash(inputs)
    write_gdf(moved / "hull.gdf", faces * 1.001)
    changed = load_case(moved / "tiny.toml")
    assert inputs_hash(database_inputs(changed.floater, changed.hydro,
                                       changed.environment)) != inputs_hash(inputs)
    column = ('[[floater.geometry.columns]]\nx = 0.0\ny = 0.0\ndiameter = 0.5\nz_top = 0.3\n'
              'z_bottom = -0.3\n')
    drag = load_case(_mesh_case(one, "hull.gdf", column, name="drag.toml"))
    assert inputs_hash(database_inputs(drag.floater, drag.hydro, drag.environment)) == \
        inputs_hash(inputs)


def test_loader_errors_name_the_key(tmp_path):
    write_gdf(tmp_path / "hull.gdf", tiny_faces())
    (tmp_path / "hull.dat").write_text("x")
    bad = {
        ('file = "none.gdf"', ""): ("floater.geometry.file", "no file"),
        ('file = "hull.dat"', ""): ("floater.geometry.file", '"hull.dat"'),
        ('file = "hull.gdf"', 'length_unit = "yd"'): ("floater.geometry.length_unit", "yd"),
        ('file = "hull.gdf"', 'symmetry = ["xy"]'): ("floater.geometry.symmetry", "xy"),
        ('file = "hull.gdf"', 'format = "step"'): ("floater.geometry.format", "step"),
        ('file = "hull.gdf"', 'position = [0.0, 0.0]'): ("floater.geometry.position", ""),
        ('file = "../hull.gdf"', ""): ("floater.geometry.file", "leads out of"),
    }
    for (file, extra), (key, found) in bad.items():
        geometry = f'kind = "mesh"\n{file}\n{extra}'
        with pytest.raises(CaseError) as info:
            load_case(write_case(tmp_path, geometry, name="bad.toml"))
        assert info.value.key == key and found in info.value.found, (file, extra)


def test_drag_on_a_mesh_needs_morison_elements(tmp_path):
    """[floater.drag] on a mesh without columns or members is a CaseError; with a column it
    gives the strips a semisubmersible's same column gives."""
    write_gdf(tmp_path / "hull.gdf", tiny_faces())
    drag = '\n[floater.drag]\ncolumn_transverse = 0.6\n'
    path = _mesh_case(tmp_path, "hull.gdf")
    text = path.read_text().replace("[hydro]", drag + "[hydro]")
    path.write_text(text)
    with pytest.raises(CaseError) as info:
        load_case(path)
    assert info.value.key == "floater.drag" and "without any" in info.value.found
    column = ('[[floater.geometry.columns]]\nx = 0.0\ny = 0.0\ndiameter = 0.5\nz_top = 0.3\n'
              'z_bottom = -0.3\n')
    path.write_text(text.replace('file = "hull.gdf"\n', 'file = "hull.gdf"\n' + column))
    case = load_case(path)
    strips = build_strips(case.floater, case.floater.drag, 1000.0)
    assert strips.count("column") > 0
    same = dataclasses.replace(case.floater, geometry=SemisubmersibleGeometry(
        columns=(Column(x=0.0, y=0.0, diameter=0.5, z_top=0.3, z_bottom=-0.3),)))
    expected = build_strips(same, DragSettings.from_settings({"column_transverse": 0.6}),
                            1000.0)
    np.testing.assert_allclose(strips.points, expected.points)
    np.testing.assert_allclose(strips.normal, expected.normal)


@pytest.mark.slow
def test_buoy_mesh_database_matches_the_cylinder_database(tmp_path, capsys):
    """The required check: the shipped buoy's cylinder meshed by floatmoor at the case's panel
    size, written to GDF as its positive quarter (ISX = ISY = 1, both planes declared),
    built through kind = "mesh" at 22 of the shipped database's frequencies spread over the
    band: A, B and the excitation within 1 % of hydrodb/cylinder_buoy.nc, per DOF (largest
    difference over the band relative to the DOF's peak)."""
    from floatmoor.hydro.database import read_database
    from floatmoor.hydro.geometry import cylinder_mesh

    case = load_case(BUOY_CASE)
    shipped = read_database(BUOY_DB)
    omega = shipped["omega"].values
    picked = omega[np.unique(np.round(np.linspace(0, len(omega) - 1, 22)).astype(int))]
    hull = cylinder_mesh(case.floater.geometry, panel_size=case.hydro.panel_size).full_hull
    write_gdf(tmp_path / "buoy.gdf", quarter(np.asarray(hull.as_array_of_faces())),
              isx=1, isy=1)
    text = BUOY_CASE.read_text()
    start = text.index("\n[floater.geometry]\n")
    end = text.index("\n[hydro]\n")
    text = (text[:start] + '\n[floater.geometry]\nkind = "mesh"\nfile = "buoy.gdf"\n'
            'symmetry = ["xz", "yz"]\n' + text[end:])
    text = text.replace("frequency_ranges = [[0.8, 9.2, 85]]",
                        "frequencies = [" + ", ".join(repr(float(w)) for w in picked) + "]")
    (tmp_path / "hydrodb").mkdir()
    path = tmp_path / "buoy_mesh.toml"
    path.write_text(text)
    t0 = time.perf_counter()
    ds = build_database(load_case(path))
    seconds = time.perf_counter() - t0
    assert ds.attrs["hull_panels"] == 3240 and ds.attrs["mesh_symmetry"] == \
        "mirror-xOz+mirror-yOz"
    ref = shipped.sel(omega=picked)
    mine, theirs = _arrays(ds), _arrays(ref)
    rows = []
    # every DOF but yaw (no added mass on a cylinder); excitation in the DOFs waves along x
    # excite
    for name, dofs in (("added_mass", (0, 1, 2, 3, 4)), ("radiation_damping", (0, 1, 2, 3, 4)),
                       ("excitation_force", (0, 2, 4))):
        for i in dofs:
            if name == "excitation_force":
                a, b = mine[name][:, 0, i], theirs[name][:, 0, i]
            else:
                a, b = mine[name][:, i, i], theirs[name][:, i, i]
            band = float(np.abs(a - b).max() / np.abs(b).max())
            strong = np.abs(b) >= 0.5 * np.abs(b).max()
            pointwise = float((np.abs(a - b)[strong] / np.abs(b)[strong]).max())
            rows.append((name, i, band, pointwise))
    with capsys.disabled():
        print(f"\nbuoy mesh database: {len(picked)} frequencies, {seconds:.0f} s")
        for name, i, band, pointwise in rows:
            print(f"  {name} {i}: band {band:.2e}, pointwise (>= half peak) {pointwise:.2e}")
    assert all(band <= BAND_TOLERANCE for _, _, band, _ in rows), rows
    assert math.isfinite(seconds)


def test_panel_size_is_needed_only_to_panel_something(tmp_path):
    """A mesh hull without a lid meshes nothing: [hydro] panel_size may be left out; with a
    lid (its panels) or for a parametric hull it is required."""
    write_gdf(tmp_path / "hull.gdf", tiny_faces())
    case = load_case(_mesh_case(tmp_path, "hull.gdf"), ["hydro.panel_size=0.07"])
    text = case.text.replace("panel_size = 0.07\n", "")
    bare = tmp_path / "bare.toml"
    bare.write_text(text)
    assert load_case(bare).hydro.panel_size is None
    with pytest.raises(CaseError, match=r"hydro.panel_size: expected a panel size \[m\] "
                       r"\(the lid's panel edge of a mesh hull\), found nothing \(the key is missing\)"):
        load_case(bare, ["hydro.lid=true"])
    cylinder = tmp_path / "cylinder.toml"
    cylinder.write_text(load_case(write_case(tmp_path, CYLINDER_GEOMETRY, kind="cylinder",
                                             name="c.toml")).text
                        .replace("panel_size = 0.07\n", ""))
    with pytest.raises(CaseError, match="hull's target panel edge"):
        load_case(cylinder)
