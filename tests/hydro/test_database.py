"""Database files: round trip, metadata, stale and damaged detection."""

from __future__ import annotations


import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.hydro.database import (
    REQUIRED_VARIABLES, HydroDatabaseError, database_path, load_for_case, merge_complex,
    read_database, write_database,
)
from tests.hydro.conftest import BUOY_CASE, BUOY_DB, DEEPCWIND_CASE, DEEPCWIND_DB


@pytest.mark.parametrize("case_path, db_path", [(BUOY_CASE, BUOY_DB),
                                                (DEEPCWIND_CASE, DEEPCWIND_DB)])
def test_shipped_databases_are_up_to_date_with_their_cases(case_path, db_path):
    case = load_case(case_path)
    assert database_path(case) == db_path
    ds = load_for_case(case)
    assert ds.attrs["database"] == case.hydro.database
    for key in ("floatmoor_version", "capytaine_version", "created", "case_toml", "mesh_hash",
                "hull_panels", "water_depth", "water_density", "gravity", "build_seconds",
                "inputs_hash", "dof_definition"):
        assert key in ds.attrs
    for name in REQUIRED_VARIABLES:
        assert "units" in ds[name].attrs and "long_name" in ds[name].attrs
    assert np.allclose(ds["omega"].values, case.hydro.frequencies)


def test_round_trip_keeps_values_and_complex_split(buoy_db, tmp_path):
    path = tmp_path / "copy.nc"
    write_database(buoy_db, path)
    back = read_database(path)
    for name in REQUIRED_VARIABLES:
        np.testing.assert_array_equal(back[name].values, buoy_db[name].values)
    x = merge_complex(back, "excitation_force")
    assert np.iscomplexobj(x.values) and x.dims == ("omega", "wave_direction", "influenced_dof")
    assert back["excitation_force"].dims[0] == "complex"
    assert back.attrs["inputs_hash"] == buoy_db.attrs["inputs_hash"]


@pytest.mark.parametrize("override, key", [
    ("hydro.panel_size=0.02", "panel_size"),
    ("environment.water_depth=1.0", "water_depth"),
    ("floater.mass=36.0", "geometry"),  # the draft follows from the mass
    ("hydro.directions_deg=[0.0, 90.0]", "directions"),
])
def test_stale_database_is_reported_naming_the_input(override, key):
    case = load_case(BUOY_CASE, [override])
    with pytest.raises(HydroDatabaseError, match=f"stale.*{key}"):
        load_for_case(case, BUOY_DB)


def test_inertia_change_does_not_make_the_database_stale():
    case = load_case(BUOY_CASE, ["floater.inertia=[0.9, 0.9, 1.2]"])
    load_for_case(case, BUOY_DB)


def test_truncated_file_is_damaged(tmp_path):
    path = tmp_path / "cut.nc"
    data = BUOY_DB.read_bytes()
    path.write_bytes(data[: len(data) // 2])
    with pytest.raises(HydroDatabaseError, match="damaged"):
        read_database(path)


def test_missing_file_is_reported(tmp_path):
    with pytest.raises(HydroDatabaseError, match="no hydrodynamic database"):
        read_database(tmp_path / "none.nc")


def test_missing_variable_and_nan_are_damage(buoy_db, tmp_path):
    path = tmp_path / "novar.nc"
    write_database(buoy_db.drop_vars("added_mass_infinite"), path)
    with pytest.raises(HydroDatabaseError, match="missing added_mass_infinite"):
        read_database(path)
    bad = buoy_db.copy(deep=True)
    bad["radiation_damping"][3, 2, 2] = np.nan
    write_database(bad, path)
    with pytest.raises(HydroDatabaseError, match="non-finite values in radiation_damping"):
        read_database(path)


def test_database_files_are_small():
    for path in (BUOY_DB, DEEPCWIND_DB):
        assert path.stat().st_size < 5e6
