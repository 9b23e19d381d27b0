"""Database files: round trip, metadata, stale and damaged detection."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.case.schema import HYDRO_CHECKS
from floatmoor.errors import AcceptedCheckWarning, CaseError
from floatmoor.hydro.checks import run_checks
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


def _corrupted(buoy_db, path):
    """The buoy database with its excitation 20 % too large, inputs and hash kept: it fails
    the Haskind check only (0.44 against 0.05)."""
    bad = buoy_db.copy(deep=True)
    bad["excitation_force"] = bad["excitation_force"] * 1.2
    bad.attrs.pop("path", None)
    write_database(bad, path)
    return path


def test_database_failing_a_check_is_refused_naming_check_value_tolerance(buoy_db, tmp_path,
                                                                         capsys):
    """The checks are recomputed at load, not trusted from the file: an edited database with
    its recorded inputs (and hash) kept is refused."""
    path = _corrupted(buoy_db, tmp_path / "edited.nc")
    case = load_case(BUOY_CASE)
    with pytest.raises(HydroDatabaseError) as info:
        load_for_case(case, path)
    message = str(info.value)
    assert message.startswith(f"{path}: hydrodynamic database fails its checks: haskind "
                              "(worst 0.441, tolerance 0.05)")
    assert "kernel_decay" not in message
    assert f'accept in {BUOY_CASE}: [hydro] accept_failed_checks = ["haskind"]' in message
    # staleness alone (as hydro build asks) does not run the checks
    load_for_case(case, path, checks=False)
    assert capsys.readouterr().err == ""


def test_check_accepted_by_the_case_is_reported_once_not_fatal(buoy_db, tmp_path, capsys):
    """The library warns (the command line prints); it never writes to standard error."""
    path = _corrupted(buoy_db, tmp_path / "accepted.nc")
    case = load_case(BUOY_CASE, ['hydro.accept_failed_checks=["haskind"]'])
    with pytest.warns(AcceptedCheckWarning) as caught:
        ds = load_for_case(case, path)
    assert ds.attrs["path"] == str(path)
    assert [str(w.message) for w in caught] == [
        f"{path}: failed checks accepted by {BUOY_CASE} ([hydro] accept_failed_checks): "
        "haskind (worst 0.441, tolerance 0.05)"]
    with warnings.catch_warnings(record=True) as again:
        warnings.simplefilter("always")
        load_for_case(case, path)
    assert again == []
    assert capsys.readouterr().err == ""
    # accepting another check does not accept this one
    other = load_case(BUOY_CASE, ['hydro.accept_failed_checks=["kernel_decay"]'])
    with pytest.raises(HydroDatabaseError, match="haskind"):
        load_for_case(other, path)


@pytest.mark.parametrize("value", ['["kernel-decay"]', '"haskind"', '["haskind", "haskind"]',
                                   "[1]"])
def test_accept_failed_checks_takes_only_names_of_checks(value):
    with pytest.raises(CaseError) as info:
        load_case(BUOY_CASE, [f"hydro.accept_failed_checks={value}"])
    assert info.value.key == "hydro.accept_failed_checks"
    assert '"kernel_decay"' in info.value.expected


def test_check_names_are_those_a_case_may_accept(buoy_db):
    assert tuple(r.name for r in run_checks(buoy_db)) == HYDRO_CHECKS
