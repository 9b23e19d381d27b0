"""A database whose values were edited after the build (its
recorded inputs hash kept) is refused by a run whatever the case accepts, and ``hydro check``
reports it in a row instead of a traceback."""

from __future__ import annotations

import shutil

import numpy as np
import pytest

from floatmoor.cli import main
from floatmoor.hydro.values import MAX_HYDRO_MAGNITUDE, value_problems
from tests.hydro.conftest import BUOY_CASE, BUOY_DB


def _edit(ds, variant: str):
    out = ds.copy(deep=True)
    if variant == "negated damping":
        out["radiation_damping"] = -out["radiation_damping"]
    elif variant == "negative added mass":
        out["added_mass"] = -out["added_mass"]
        out["added_mass_infinite"] = -out["added_mass_infinite"]
    elif variant == "added mass 1e300":
        out["added_mass"] = out["added_mass"] * 0.0 + 1e300
        out["added_mass_infinite"] = out["added_mass_infinite"] * 0.0 + 1e300
    elif variant == "zero volume":
        out["disp_volume"] = out["disp_volume"] * 0.0
    elif variant == "negative C33":
        out["hydrostatic_stiffness"] = -out["hydrostatic_stiffness"]
    return out


VARIANTS = {"negated damping": "radiation_damping Surge-Surge is negative",
            "negative added mass": "added_mass_infinite is not positive semidefinite",
            "added mass 1e300": f"more than {MAX_HYDRO_MAGNITUDE:g}",
            "zero volume": "disp_volume is 0, not positive",
            "negative C33": "C33 is -"}


def test_shipped_databases_have_possible_values(buoy_db, deepcwind_db, buoy_case,
                                                deepcwind_case):
    assert value_problems(buoy_db, buoy_case.floater.mass_matrix()) == []
    assert value_problems(deepcwind_db, deepcwind_case.floater.mass_matrix()) == []


def test_mass_plus_infinite_added_mass_must_be_positive_definite(buoy_db):
    # A_inf within its own sign tolerance, but nothing to make the total positive definite
    problems = value_problems(buoy_db, np.zeros((6, 6)) - np.eye(6))
    assert any("M + added_mass_infinite is not positive definite" in p for p in problems)


@pytest.fixture
def edited_copy(tmp_path, buoy_db):
    """A folder with the buoy case and an edited copy of its database (hash kept)."""
    def make(variant: str):
        (tmp_path / "hydrodb").mkdir(exist_ok=True)
        case = tmp_path / "buoy.toml"
        shutil.copy(BUOY_CASE, case)
        db = tmp_path / "hydrodb" / BUOY_DB.name
        _edit(buoy_db, variant).to_netcdf(db)
        return case, db
    return make


@pytest.mark.parametrize("variant", list(VARIANTS))
def test_run_refuses_edited_values_with_status_2(variant, edited_copy, capsys):
    case, db = edited_copy(variant)
    out = case.parent / "out.nc"
    # accepting every accuracy check must not let impossible values through
    status = main(["run", str(case), "-o", str(out), "--quiet",
                   "--set", "simulation.duration=0.5",
                   "--set", 'hydro.accept_failed_checks=["symmetry", "damping_psd", '
                   '"kramers_kronig", "kernel_decay", "haskind", "hydrostatics"]'])
    err = capsys.readouterr().err
    assert status == 2
    assert "impossible values" in err and VARIANTS[variant] in err
    assert len(err.strip().splitlines()) == 1
    assert not out.exists()


@pytest.mark.parametrize("variant", list(VARIANTS))
def test_hydro_check_reports_edited_values_in_a_row(variant, edited_copy, capsys):
    _, db = edited_copy(variant)
    status = main(["hydro", "check", str(db)])
    out = capsys.readouterr().out
    assert status == 1
    row = next(line for line in out.splitlines() if line.strip().startswith("values"))
    assert "FAIL" in row and VARIANTS[variant] in row
    assert "a check FAILED" in out
