"""The database checks judge what matters and say what to change: symmetry against the matrix's
scale, Haskind n/a (not FAIL) when the directions cannot give its integral, kernel decay naming
the frequencies to add; and a tiny mesh of an axisymmetric hull builds with no false FAIL."""

from __future__ import annotations

import json

import numpy as np
import pytest

from floatmoor.cli import main
from floatmoor.hydro.checks import (
    check_kernel_decay, check_symmetry, finer_frequencies, run_checks,
)
from floatmoor.hydro.database import read_database
from tests.hydro.mesh_files import tiny_faces, write_case, write_gdf


def _with_weak_yaw(ds, coupling: float):
    """The buoy's database with a yaw that hardly radiates (active, A_66 and B_66 ~ 1e-4 and
    1e-5 of the roll's) and a heave-yaw damping coupling B_36 = ``coupling`` x the matrix's
    scale sqrt(D_trans D_rot), B_63 = 0."""
    bad = ds.copy(deep=True)
    a, b = bad["added_mass"], bad["radiation_damping"]
    yaw = dict(radiating_dof="Yaw", influenced_dof="Yaw")
    a.loc[yaw] = 1e-4 * a.sel(radiating_dof="Roll", influenced_dof="Roll")
    b.loc[yaw] = 1e-5 * b.sel(radiating_dof="Roll", influenced_dof="Roll")
    diag = np.abs(np.diagonal(b.transpose("omega", "radiating_dof", "influenced_dof").values,
                              axis1=1, axis2=2)).max(axis=0)
    scale = np.sqrt(diag[:3].max() * diag[3:].max())
    b.loc[dict(radiating_dof="Heave", influenced_dof="Yaw")] = coupling * scale
    b.loc[dict(radiating_dof="Yaw", influenced_dof="Heave")] = 0.0
    return bad


def test_symmetry_is_judged_against_the_matrix_scale(buoy_db):
    """A coupling of 0.2 % of the matrix's scale with a DOF that hardly radiates passes (it
    was 100 x the tolerance against sqrt(B_33 B_66)); 5 % of it still fails."""
    small = check_symmetry(_with_weak_yaw(buoy_db, 0.002))
    assert small.passed and "Heave-Yaw" not in small.detail, small.detail  # not the worst
    large = check_symmetry(_with_weak_yaw(buoy_db, 0.05))
    assert not large.passed and large.worst == pytest.approx(0.05, rel=1e-9)
    assert "Heave-Yaw" in large.detail


def test_haskind_is_na_when_the_directions_cannot_give_its_integral(deepcwind_db):
    """A built mesh database with one direction and no declared symmetry: n/a with what to
    change (it was a FAIL, while an imported database said n/a)."""
    ds = deepcwind_db.isel(wave_direction=[0]).copy(deep=True)
    ds.attrs["geometry_kind"] = "mesh"
    ds.attrs["geometry_json"] = json.dumps({"kind": "mesh", "symmetry": []})
    result = next(r for r in run_checks(ds) if r.name == "haskind")
    assert result.passed and not result.applicable, result.detail
    assert "directions evenly spanning 0 to 180 deg" in result.detail
    assert "with the mesh's \"xz\" symmetry declared" in result.detail
    assert result.detail.endswith("the database's directions are 0 deg")


def test_kernel_decay_failure_names_the_frequencies_to_add(buoy_db):
    coarse = buoy_db.isel(omega=[0, 10, 20, 30])
    omega = coarse["omega"].values
    result = check_kernel_decay(coarse)
    assert not result.passed
    added = ", ".join(f"{w:.4g}" for w in finer_frequencies(omega))
    assert f"add the midpoints {added} rad/s (7 frequencies in all)" in result.detail
    assert np.allclose(finer_frequencies(np.array([1.0, 2.0, 4.0])), [1.5, 3.0])


def test_tiny_axisymmetric_mesh_builds_without_false_failures(tmp_path, capsys):
    """The tiny cylinder's mesh (216 panels, 3 frequencies, one direction: seconds; coarser
    meshes part B_15 from B_51 by 1.2-1.8 %, a real discretisation error): symmetry passes,
    Haskind is n/a saying what to change (check said so before the build), and what fails is
    what 3 frequencies cannot give (the kernel's decay, Kramers-Kronig), the kernel's row
    naming the frequencies to add."""
    faces = tiny_faces()
    write_gdf(tmp_path / "hull.gdf", faces)
    case = write_case(tmp_path, 'kind = "mesh"\nfile = "hull.gdf"')
    assert main(["check", str(case)]) == 0
    assert "haskind check will be n/a" in capsys.readouterr().out
    status = main(["hydro", "build", str(case), "--quiet"])
    out = capsys.readouterr().out
    ds = read_database(tmp_path / "hydrodb" / "tiny.nc")
    results = {r.name: r for r in run_checks(ds)}
    assert results["symmetry"].passed, results["symmetry"].detail
    assert not results["haskind"].applicable and "haskind         n/a" in out
    failed = {name for name, r in results.items() if not r.passed}
    assert failed <= {"kernel_decay", "kramers_kronig"}
    assert status == (1 if failed else 0)
    if "kernel_decay" in failed:
        assert "add the midpoints 3, 5 rad/s" in results["kernel_decay"].detail
