"""floatmoor.hydro.importing on synthetic ImportedBem objects (from the shipped capytaine
databases) and on the OC4 WAMIT files: the database layout, the yaw rotation, A_inf from the
file or derived, options against the files, and the excitation group."""

from __future__ import annotations

import dataclasses
import json
import math

import numpy as np
import pytest

from floatmoor.errors import CaseError
from floatmoor.hydro.checks import check_haskind, run_checks
from floatmoor.hydro.database import (
    EXCITATION_VARIABLES, HydroDatabaseError, merge_complex, read_database, write_database,
)
from floatmoor.hydro.excitation_transfer import ExcitationInterpolator
from floatmoor.hydro.importing import (
    ImportOptions, file_format, imported_dataset, yaw_transform,
)
from floatmoor.io.bem_data import BemFileError, ImportedBem
from floatmoor.io.wamit import read_wamit
from tests.hydro.conftest import REPO

OC4 = REPO / "tests" / "data" / "wamit_oc4"
OC4_FILES = [str(OC4 / "marin_semi.1"), str(OC4 / "marin_semi.hst")]
RHO, G = 1025.0, 9.80665
#: Options the WAMIT files need (OC4: volume of docs/cases/deepcwind.md; any centre of buoyancy on the axis).
OC4_OPTIONS = ImportOptions(water_depth=200.0, disp_volume=13917.0,
                            centre_of_buoyancy=(0.0, 0.0, -13.17))
#: A_inf derived from the OC4 file's damping and added mass (0.01-4.98 rad/s) against the
#: file's own (PER = 0): measured within 1.7e-4 (heave), 1.6e-5 (surge).
DERIVED_A_INF_RTOL = 1e-3


def _matrices(ds, name):
    return ds[name].transpose("omega", "radiating_dof", "influenced_dof").values


def as_imported(ds, *, excitation: str = "all", **changes) -> ImportedBem:
    """A built database's arrays as a reader would return them (``excitation``: "all",
    "total" or "none")."""
    x = {v: merge_complex(ds, v).transpose("omega", "wave_direction", "influenced_dof").values
         for v in EXCITATION_VARIABLES}
    bem = ImportedBem(
        format="wamit", files=("synthetic.1",), omega=ds["omega"].values,
        added_mass=_matrices(ds, "added_mass"),
        radiation_damping=_matrices(ds, "radiation_damping"),
        water_density=float(ds.attrs["water_density"]), gravity=float(ds.attrs["gravity"]),
        added_mass_infinite=ds["added_mass_infinite"].transpose(
            "radiating_dof", "influenced_dof").values,
        directions=ds["wave_direction"].values if excitation != "none" else None,
        excitation_force=x["excitation_force"] if excitation != "none" else None,
        froude_krylov_force=x["Froude_Krylov_force"] if excitation == "all" else None,
        diffraction_force=x["diffraction_force"] if excitation == "all" else None,
        hydrostatic_stiffness=ds["hydrostatic_stiffness"].transpose(
            "influenced_dof", "radiating_dof").values,
        rotation_center=np.zeros(3), notes=("synthetic",))
    return dataclasses.replace(bem, **changes)


def options_of(ds, **changes) -> ImportOptions:
    depth = ds.attrs["bem_water_depth"]
    return dataclasses.replace(ImportOptions(
        water_depth=math.inf if depth == "infinite" else float(depth),
        disp_volume=float(ds["disp_volume"]),
        centre_of_buoyancy=tuple(ds["center_of_buoyancy"].values.tolist())), **changes)


@pytest.fixture(scope="module")
def oc4():
    return read_wamit(OC4_FILES, water_density=RHO, gravity=G, water_depth=200.0)


def test_layout_is_the_built_databases(buoy_db, tmp_path):
    """Same variables, dimensions, coordinates, units and long names as hydro build's."""
    source = tmp_path / "synthetic.1"
    source.write_text("0.1 1 1 1.0 1.0\n")
    ds = imported_dataset(as_imported(buoy_db, files=(str(source),)), options_of(buoy_db),
                          name="copy")
    from floatmoor.hydro.drift_build import DRIFT_VARIABLES

    # the first-order layout: the buoy's drift coefficients (hydro build --drift) aside
    built = {n for n in buoy_db.variables if not n.startswith("state_space")
             and n not in DRIFT_VARIABLES and n != "drift_term"}
    assert set(ds.variables) == built
    for name in ds.variables:
        assert ds[name].dims == buoy_db[name].dims, name
        for key in ("units", "long_name"):
            assert ds[name].attrs[key] == buoy_db[name].attrs[key], (name, key)
    for name in ("added_mass", "radiation_damping", "excitation_force", "wavenumber",
                 "hydrostatic_stiffness", "added_mass_infinite", "Froude_Krylov_force"):
        np.testing.assert_allclose(ds[name].values, buoy_db[name].values, rtol=1e-12,
                                   atol=1e-12 * float(np.abs(buoy_db[name].values).max()))
    assert float(ds["waterplane_area"]) == pytest.approx(float(buoy_db["waterplane_area"]),
                                                         rel=2e-3)  # C33 / (rho g) vs mesh
    assert ds.attrs["source"] == "wamit" and buoy_db.attrs.get("source", "capytaine") == \
        "capytaine"
    assert ds.attrs["added_mass_infinite_source"].startswith("file")
    assert json.loads(ds.attrs["source_files_json"]) == [{
        "path": str(source), "size": 16,
        "sha256": "70db252c55e496d5ce702e0900206ef0d1ac0a7499a7fd11489586369ddf3fec"}]


def test_no_excitation_variables_when_the_files_have_none(buoy_db, tmp_path):
    ds = imported_dataset(as_imported(buoy_db, excitation="none"), options_of(buoy_db),
                          name="bare", files=[])
    assert not set(EXCITATION_VARIABLES) & set(ds.variables)
    assert "wave_direction" not in ds.coords
    assert ds.attrs["excitation"] == "none in the files"
    write_database(ds, tmp_path / "bare.nc")
    back = read_database(tmp_path / "bare.nc")
    names = {r.name: r for r in run_checks(back)}
    assert not names["haskind"].applicable and "no excitation" in names["haskind"].detail
    assert not names["hydrostatics"].applicable
    assert all(r.passed for r in names.values())


def test_total_excitation_alone_is_complete_partial_group_is_damage(buoy_db, tmp_path):
    total = imported_dataset(as_imported(buoy_db, excitation="total"), options_of(buoy_db),
                             name="total", files=[])
    assert "excitation_force" in total and "Froude_Krylov_force" not in total
    write_database(total, tmp_path / "total.nc")
    read_database(tmp_path / "total.nc")
    full = imported_dataset(as_imported(buoy_db), options_of(buoy_db), name="f", files=[])
    for drop in (["excitation_force"], ["diffraction_force"],
                 ["excitation_force", "Froude_Krylov_force"]):
        path = tmp_path / f"part{len(drop)}{drop[0]}.nc"
        write_database(full.drop_vars(drop), path)
        with pytest.raises(HydroDatabaseError, match="damaged.*partial excitation"):
            read_database(path)


def test_yaw_turns_matrices_as_t_m_tt():
    """A waterplane patch S at (x0, 0) couples heave with pitch, C35 = -rho g S x0; turned by
    90 degrees it sits at (0, x0) and couples heave with roll, C34 = +rho g S x0 (heave of a
    point is z + y roll - x pitch). T^T M T would give -rho g S x0."""
    s, x0 = 2.0, 3.0
    c = np.zeros((6, 6))
    c[2, 2] = RHO * G * s
    c[2, 4] = c[4, 2] = -RHO * G * s * x0
    c[4, 4] = RHO * G * s * x0 ** 2
    omega = np.array([0.5, 1.0, 1.5])
    a = np.zeros((3, 6, 6))
    a[:, 0, 0], a[:, 1, 1], a[:, 0, 4] = 1.0, 2.0, 5.0  # surge-pitch coupling
    x = np.zeros((3, 2, 6), complex)
    x[:, 0, 0] = 7.0  # surge force of the waves towards +x
    bem = ImportedBem(format="wamit", files=("t.1",), omega=omega, added_mass=a,
                      radiation_damping=a.copy(), water_density=RHO, gravity=G,
                      added_mass_infinite=a[0], directions=np.radians([0.0, 90.0]),
                      excitation_force=x, hydrostatic_stiffness=c)
    ds = imported_dataset(bem, ImportOptions(water_depth=math.inf, disp_volume=1.0,
                                             centre_of_buoyancy=(0.0, 0.0, -1.0),
                                             yaw_deg=90.0), name="t", files=[])
    turned = ds["hydrostatic_stiffness"].transpose("influenced_dof", "radiating_dof").values
    assert turned[2, 3] == pytest.approx(RHO * G * s * x0)
    assert turned[2, 4] == pytest.approx(0.0, abs=1e-9) and turned[3, 3] == \
        pytest.approx(c[4, 4])
    am = _matrices(ds, "added_mass")[0]
    assert (am[0, 0], am[1, 1]) == (2.0, 1.0)
    assert am[1, 3] == pytest.approx(-5.0)  # sway-roll: surge-pitch turned by 90 degrees
    # waves towards +x in the file travel towards +y in the case, and push along +y
    np.testing.assert_allclose(np.degrees(ds["wave_direction"].values), [90.0, 180.0])
    xt = merge_complex(ds, "excitation_force").sel(wave_direction=math.pi / 2).values
    np.testing.assert_allclose(xt[0], [0.0, 7.0, 0, 0, 0, 0], atol=1e-12)
    np.testing.assert_allclose(yaw_transform(180.0), np.diag([-1, -1, 1, -1, -1, 1.0]))


def test_haskind_of_a_turned_database_is_the_databases(deepcwind_db):
    """Turned by 180 degrees, 0-180 deg becomes -180-0 deg: the check mirrors that half too."""
    turned = imported_dataset(as_imported(deepcwind_db), options_of(deepcwind_db,
                                                                    yaw_deg=180.0),
                              name="t", files=[])
    assert np.degrees(turned["wave_direction"].values)[[0, -1]].tolist() == [-180.0, 0.0]
    a, b = check_haskind(deepcwind_db), check_haskind(turned)
    assert b.applicable and b.worst == pytest.approx(a.worst, rel=1e-9)
    # waves towards 180 deg (the case's) are the file's towards 0 deg, forces turned
    omega = deepcwind_db["omega"].values[10]
    x_file = ExcitationInterpolator(deepcwind_db)(omega, 0.0)
    for beta in (math.pi, -math.pi):
        np.testing.assert_allclose(ExcitationInterpolator(turned)(omega, beta),
                                   yaw_transform(180.0) @ x_file, rtol=1e-12)


def test_infinite_added_mass_from_the_file_or_derived(oc4):
    given = imported_dataset(oc4, OC4_OPTIONS, name="given")
    assert given.attrs["added_mass_infinite_source"] == "file (WAMIT .1, PER = 0)"
    derived = imported_dataset(dataclasses.replace(oc4, added_mass_infinite=None),
                               OC4_OPTIONS, name="derived")
    source = derived.attrs["added_mass_infinite_source"]
    assert source.startswith("derived: Kramers-Kronig") and "decay" in source
    assert len(json.loads(derived.attrs["added_mass_infinite_tail_exponents"])) == 6
    a0 = np.diag(given["added_mass_infinite"].values)
    a1 = np.diag(derived["added_mass_infinite"].values)
    np.testing.assert_allclose(a1, a0, rtol=DERIVED_A_INF_RTOL)
    assert all(r.passed for r in run_checks(derived))


def test_what_the_files_lack_must_be_given(oc4):
    with pytest.raises(CaseError) as info:
        imported_dataset(oc4, ImportOptions(water_depth=200.0), name="x")
    assert "--displaced-volume and --centre-of-buoyancy" in str(info.value)
    with pytest.raises(CaseError, match="--centre-of-buoyancy"):
        imported_dataset(oc4, dataclasses.replace(OC4_OPTIONS, centre_of_buoyancy=None),
                         name="x")
    with pytest.raises(CaseError, match="--water-depth"):
        imported_dataset(dataclasses.replace(oc4, water_depth=None),
                         dataclasses.replace(OC4_OPTIONS, water_depth=None), name="x")
    with pytest.raises(BemFileError, match="hydrostatic stiffness"):
        imported_dataset(dataclasses.replace(oc4, hydrostatic_stiffness=None), OC4_OPTIONS,
                         name="x")


def test_a_value_the_file_states_must_equal_the_option(oc4):
    stated = dataclasses.replace(oc4, disp_volume=13900.0, water_depth=200.0)
    imported_dataset(stated, dataclasses.replace(OC4_OPTIONS, disp_volume=13900.0), name="x")
    with pytest.raises(BemFileError) as info:
        imported_dataset(stated, OC4_OPTIONS, name="x")
    assert "--displaced-volume given (13917)" in str(info.value)
    assert "13900 in the file" in str(info.value)


@pytest.mark.parametrize("files, found", [
    (["a.1", "b.h5"], "both"),
    (["a.1", "a.txt"], "the extension '.txt'"),
    (["a.h5", "b.h5"], "2 files"),
    (["a.1", "b.1"], "two .1 files"),
])
def test_format_from_the_extensions(files, found):
    with pytest.raises(CaseError) as info:
        file_format(files)
    assert found in str(info.value)


def test_formats():
    assert file_format(["x.1", "x.HST", "x.3", "x.3fk", "x.3sc"]) == "wamit"
    assert file_format(["x.h5"]) == "bemio"


def test_haskind_on_the_full_circle_of_directions(deepcwind_db):
    """An imported file of any body may give the full circle: the periodic trapezoid on it.
    The DeepCwind data mirrored to 0-345 deg (|X_j(-beta)| = |X_j(beta)| for surge and
    heave by the body's symmetry about y = 0) give the half-circle rule's result."""
    bem = as_imported(deepcwind_db)
    beta = bem.directions                       # 0, 15, ..., 180 deg
    mirrored = 2.0 * math.pi - beta[-2:0:-1]    # 195, ..., 345 deg
    x = np.concatenate([bem.excitation_force, bem.excitation_force[:, -2:0:-1, :]], axis=1)
    full = dataclasses.replace(bem, directions=np.concatenate([beta, mirrored]),
                               excitation_force=x, froude_krylov_force=None,
                               diffraction_force=None)
    ds = imported_dataset(full, options_of(deepcwind_db), name="full", files=[])
    assert ds.sizes["wave_direction"] == 24
    result = check_haskind(ds)
    assert result.applicable
    assert result.worst == pytest.approx(check_haskind(deepcwind_db).worst, rel=1e-9)
    partial = imported_dataset(dataclasses.replace(full, directions=full.directions[:20],
                                                   excitation_force=x[:, :20]),
                               options_of(deepcwind_db), name="partial", files=[])
    result = check_haskind(partial)
    assert not result.applicable and "full circle" in result.detail
