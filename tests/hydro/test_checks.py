"""The check suite on the shipped databases, and on broken copies (the checks can fail)."""

from __future__ import annotations

import pytest

from floatmoor.hydro.checks import (
    check_damping_psd, check_haskind, check_hydrostatics, check_kramers_kronig,
    check_symmetry, haskind_damping, run_checks,
)


@pytest.mark.parametrize("db", ["buoy_db", "deepcwind_db"])
def test_shipped_database_passes_every_check(db, request):
    results = run_checks(request.getfixturevalue(db))
    failed = [f"{r.name}: {r.detail}" for r in results if not r.passed]
    assert not failed
    assert [r.name for r in results] == ["symmetry", "damping_psd", "kramers_kronig",
                                         "kernel_decay", "haskind", "hydrostatics"]


def _copy(ds):
    return ds.copy(deep=True)


def test_asymmetric_added_mass_fails(buoy_db):
    bad = _copy(buoy_db)
    bad["added_mass"].loc[dict(radiating_dof="Surge", influenced_dof="Pitch")] *= 1.2
    assert not check_symmetry(bad).passed


def test_negative_damping_fails(buoy_db):
    bad = _copy(buoy_db)
    bad["radiation_damping"].loc[dict(radiating_dof="Heave", influenced_dof="Heave")] *= -1.0
    assert not check_damping_psd(bad).passed


def test_inconsistent_added_mass_fails_kramers_kronig(buoy_db):
    bad = _copy(buoy_db)
    bad["added_mass_infinite"].loc[dict(radiating_dof="Heave", influenced_dof="Heave")] *= 1.1
    assert not check_kramers_kronig(bad).passed


def test_scaled_excitation_fails_haskind(buoy_db):
    bad = _copy(buoy_db)
    bad["excitation_force"] *= 1.1  # damping from it grows by 21 %
    assert not check_haskind(bad).passed


def test_wrong_stiffness_fails_hydrostatics(buoy_db):
    bad = _copy(buoy_db)
    bad["hydrostatic_stiffness"].loc[dict(influenced_dof="Heave", radiating_dof="Heave")] *= 1.02
    assert not check_hydrostatics(bad).passed


@pytest.mark.parametrize("symmetry, passes", [(["xz"], True), ([], False)])
def test_haskind_mirrors_a_half_span_only_for_a_hull_symmetric_about_y0(deepcwind_db, symmetry,
                                                                        passes):
    """Directions over 0-180 deg stand for the full circle only on a hull symmetric about
    y = 0: a mesh hull must declare the "xz" plane for it. Without it the check cannot apply:
    n/a (as for imported files), saying what to change, not a failure."""
    import json

    ds = _copy(deepcwind_db)
    ds.attrs["geometry_kind"] = "mesh"
    ds.attrs["geometry_json"] = json.dumps({"kind": "mesh", "symmetry": symmetry})
    if passes:
        assert check_haskind(ds).passed
    else:
        with pytest.raises(ValueError, match="symmetric about y = 0"):
            haskind_damping(ds, 0)
        result = [r for r in run_checks(ds) if r.name == "haskind"][0]
        assert result.passed and not result.applicable
        assert "symmetric about y = 0: declare the mesh's \"xz\" symmetry" in result.detail
