"""``floatmoor check`` reads a mesh hull and runs the mesh checks ``hydro build`` runs before
solving: what the build refuses without solving, check refuses with the same one line (status
2); the readers' own prints (meshio prints, then exits) become part of that line."""

from __future__ import annotations

import numpy as np
import pytest

from floatmoor.cli import main
from floatmoor.io.bem_data import BemFileError
from tests.hydro.mesh_files import half, tiny_faces, write_case, write_gdf

MESH = 'kind = "mesh"\nfile = "{file}"\n{extra}'


def _gdf_lines(tmp_path):
    write_gdf(tmp_path / "good.gdf", tiny_faces())
    return (tmp_path / "good.gdf").read_text().splitlines()


def _write(tmp_path, kind: str):
    """A broken hull file of ``kind``; its name."""
    faces = tiny_faces()
    name = "hull.gdf"
    path = tmp_path / name
    if kind == "garbage":
        path.write_text("not a mesh\n")
    elif kind == "truncated":
        path.write_text("\n".join(_gdf_lines(tmp_path)[:-3]) + "\n")
    elif kind == "nan":
        lines = _gdf_lines(tmp_path)
        path.write_text("\n".join(lines[:4] + ["nan 0 -0.1"] + lines[5:]) + "\n")
    elif kind == "huge":
        write_gdf(path, faces * 1e308)
    elif kind == "inward":
        write_gdf(path, faces[:, ::-1])
    elif kind == "open":
        write_gdf(path, faces[5:])
    elif kind.startswith("ulen"):
        write_gdf(path, faces, ulen=float(kind[4:]))
    else:  # a meshio format that meshio cannot read: it prints, then calls sys.exit
        name = f"hull.{kind}"
        (tmp_path / name).write_text("garbage garbage\n1 2 3\n")
    (tmp_path / "good.gdf").unlink(missing_ok=True)
    return name


@pytest.mark.parametrize("kind, found", [
    ("garbage", "expected a gdf mesh file capytaine can read"),
    ("truncated", "expected a gdf mesh file capytaine can read"),
    ("nan", "NaN"),
    ("huge", "expected a gdf mesh file capytaine can read"),
    ("inward", "the normals check of the immersed hull"),
    ("open", "the watertight check of the immersed hull"),
    ("ulen0", "line 2, ULEN: expected a length unit ULEN > 0 (finite), found 0"),
    ("ply", "expected a ply mesh file capytaine can read, found Expected ply; Error: Couldn't"),
    ("vtk", "Illegal VTK header"),
    ("msh", "expected a msh mesh file capytaine can read"),
    ("off", "Expected the first line to be `OFF`"),
])
def test_check_refuses_what_hydro_build_refuses_without_solving(tmp_path, capsys, kind, found):
    name = _write(tmp_path, kind)
    case = write_case(tmp_path, MESH.format(file=name, extra=""))
    assert main(["check", str(case)]) == 2
    out = capsys.readouterr()
    lines = out.err.splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"floatmoor: error: {tmp_path / name}: ")
    assert found in lines[0] and out.out == ""
    assert main(["hydro", "build", str(case), "--quiet"]) == 2
    build = capsys.readouterr()
    assert build.err.splitlines() == lines and build.out == ""  # the same refusal
    assert list((tmp_path / "hydrodb").iterdir()) == []


def test_check_of_a_good_mesh_prints_what_the_build_will_read(tmp_path, capsys):
    write_gdf(tmp_path / "hull.gdf", tiny_faces())
    case = write_case(tmp_path, MESH.format(file="hull.gdf", extra=""))
    assert main(["check", str(case)]) == 0
    out = capsys.readouterr().out
    assert "valid case" in out
    assert "  mesh hull.gdf (gdf, m, SHA-256 " in out and "216 panels read" in out
    assert "    watertight            pass" in out and "    normals               pass" in out


@pytest.mark.parametrize("ulen", ["0", "-1", "nan", "inf"])
def test_gdf_length_unit_must_be_positive_and_finite(tmp_path, ulen):
    from floatmoor.hydro.mesh_file import read_mesh_file

    lines = _gdf_lines(tmp_path)
    lines[1] = f"{ulen} 9.80665 ULEN GRAV"
    (tmp_path / "hull.gdf").write_text("\n".join(lines) + "\n")
    with pytest.raises(BemFileError, match=r"hull.gdf: line 2, ULEN: expected a length unit "
                       r"ULEN > 0 \(finite\), found " + ulen):
        read_mesh_file(str(tmp_path / "hull.gdf"), "gdf")


def test_check_states_the_haskind_requirement_before_the_build(tmp_path, capsys):
    """A full hull with one wave direction: the built database's Haskind check will be n/a,
    and check says what to change; a half hull declared symmetric about y = 0 with directions
    evenly over 0-180 deg gives the check what it needs."""
    write_gdf(tmp_path / "hull.gdf", tiny_faces())
    case = write_case(tmp_path, MESH.format(file="hull.gdf", extra=""))
    assert main(["check", str(case)]) == 0
    out = capsys.readouterr().out
    assert "hydro: the built database's haskind check will be n/a: " in out
    assert "with the mesh's \"xz\" symmetry declared" in out
    write_gdf(tmp_path / "half.gdf", half(tiny_faces()), isy=1)
    case = write_case(tmp_path, MESH.format(file="half.gdf", extra='symmetry = ["xz"]'),
                      name="half.toml")
    case.write_text(case.read_text().replace("directions_deg = [0.0]",
                                             "directions_deg = [0.0, 90.0, 180.0]"))
    assert main(["check", str(case)]) == 0
    out = capsys.readouterr().out
    assert "haskind check will be n/a" not in out and "symmetry declared xz" in out
    assert np.all(half(tiny_faces())[:, :, 1] >= 0.0)


def test_a_hull_placed_beyond_the_floats_is_one_line(tmp_path, capfd):
    """position = 1e308 m: the mesh checks' figures overflow; one refusal, no numpy warning
    printed (capfd: what numpy would print goes to the process's standard error)."""
    write_gdf(tmp_path / "hull.gdf", tiny_faces())
    case = write_case(tmp_path, MESH.format(file="hull.gdf",
                                            extra="position = [1e308, 0.0, 0.0]"))
    assert main(["check", str(case)]) == 2
    lines = capfd.readouterr().err.splitlines()
    assert len(lines) == 1 and lines[0].startswith("floatmoor: error: ")
    assert "the watertight check of the immersed hull" in lines[0]
