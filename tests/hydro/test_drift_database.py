"""Mean drift coefficients in the databases: ``hydro build --drift``, ``hydro check``'s drift
row, and far against near field on the shipped databases (stored: no BEM here)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.cli import main
from floatmoor.hydro.drift_checks import (
    DRIFT_TOLERANCE, check_drift, drift_by_frequency, drift_differences,
)
from floatmoor.hydro.complex_values import merge_complex
from floatmoor.hydro.database import read_database
from floatmoor.hydro.drift_build import DRIFT_VARIABLES, drift_is_current, has_drift
from floatmoor.hydro.rao import rao_for_case
from tests.hydro.test_cli_hydro import TINY_ACCEPTS, tiny_case  # noqa: F401 - fixture


def test_shipped_buoy_far_and_near_field_agree_in_surge(buoy_db, buoy_case):
    """hydrodb/cylinder_buoy.nc (built with --drift, on the drift mesh graded to 5.8 mm at the
    water line, 3348 panels): far against near field within 5 % of the peak surge drift
    (4.72 %; 4.29 % on the uniform 15 mm panels) over 67 of the 85 frequencies
    (0.8-9.2 rad/s), with the RAOs of the case's mass and linearised mooring, which the
    database records and which it is current for. The 18 left out (4.9-6.6 rad/s) are the
    pitch and heave resonance (|X5| up to 40 rad/m with radiation damping alone), where the
    near field's terms cancel to 1/15-1/150 of their magnitudes and the two routes differ by
    up to 119 % of the peak."""
    assert has_drift(buoy_db)
    errors, left_out = drift_differences(buoy_db)
    assert errors["Surge"] <= DRIFT_TOLERANCE  # measured 4.72 %
    # left out: the pitch resonance, where the near field's terms cancel to < 1/10
    assert len(left_out) == 18 and left_out.min() > 4.8 and left_out.max() < 6.7
    assert check_drift(buoy_db).passed
    assert drift_is_current(buoy_db, buoy_case)
    stored = merge_complex(buoy_db, "drift_rao").transpose("omega", "wave_direction",
                                                            "radiating_dof").values
    x, _ = rao_for_case(buoy_case, buoy_db)
    assert np.allclose(stored, x.values, rtol=1e-10, atol=1e-12)


def test_shipped_deepcwind_far_and_near_field_agree(deepcwind_db):
    """hydrodb/deepcwind.nc (built with --drift on the drift mesh: 1.4 m panels, graded to the
    default waterline panel 0.143 m, 9192 panels; the case's moored RAOs): far against near
    field in surge and sway within 3.7 % of the peak force drift (139 kN/m^2) at every
    direction and frequency, the ones the row leaves out included (on the database's uniform
    2 m panels: 41 % at 1.80 rad/s). At the moored surge and sway resonance, 0.06 rad/s
    (|X1| = 25 m/m with radiation damping alone), the near field's velocity and
    pressure-gradient terms cancel for the slow flow of a translating body only on panels fine
    enough around the heave plates' sharp edges: 2.5 % of the peak on these, 17.1 % on 2 m
    panels (docs/validation/floaters.md#mean-wave-drift)."""
    assert has_drift(deepcwind_db)
    every, _ = drift_by_frequency(deepcwind_db, left_out_too=True)
    for dof in ("Surge", "Sway"):
        assert np.all(every[dof] <= DRIFT_TOLERANCE)  # measured 3.70 % (surge, 1.80 rad/s)
        assert every[dof][0] <= 0.5 * DRIFT_TOLERANCE  # 0.06 rad/s: 2.46 %
    assert check_drift(deepcwind_db).passed
    mesh = json.loads(deepcwind_db.attrs["drift_json"])["mesh"]
    assert mesh["waterline_panel_size"] == pytest.approx(0.1433, abs=1e-4)
    assert mesh["panel_size"] == 1.4
    assert mesh["hull_panels"] == 9192 and mesh["grading_ratio"] == 1.25


def test_drift_variables_have_units_and_long_names(buoy_db):
    for name in DRIFT_VARIABLES:
        assert buoy_db[name].attrs["units"] and buoy_db[name].attrs["long_name"]
    assert buoy_db["mean_drift_near_field"].dims == ("omega", "wave_direction",
                                                     "influenced_dof")
    far = buoy_db["mean_drift_far_field"].values
    assert np.all(np.isnan(far[..., 2:5])) and np.all(np.isfinite(far[..., [0, 1, 5]]))
    record = json.loads(buoy_db.attrs["drift_json"])
    assert {"mooring_stiffness", "mass_matrix", "linear_damping", "kochin_angles"} <= set(record)


def test_build_drift_adds_then_skips_then_recomputes(tiny_case, capsys):  # noqa: F811
    db = tiny_case.parent / "hydrodb" / "tiny.nc"
    assert main(["hydro", "build", str(tiny_case), "--quiet", "--set", TINY_ACCEPTS]) in (0, 1)
    assert not has_drift(read_database(db))
    capsys.readouterr()
    assert main(["hydro", "build", str(tiny_case), "--quiet", "--drift", "--set",
                 TINY_ACCEPTS]) in (0, 1)
    out = capsys.readouterr().out
    assert "mean drift added" in out and "drift " in out
    import xarray as xr
    with xr.open_dataset(db) as raw:  # (read_database sets it in memory only)
        assert "path" not in raw.attrs  # no path of this machine written into the file
    ds = read_database(db)
    assert has_drift(ds)
    case = load_case(tiny_case, [TINY_ACCEPTS])
    assert drift_is_current(ds, case) and ds.attrs["drift_source"] == "floatmoor"
    # another drift mesh (its water line panels) makes the drift stale, not the database
    graded = json.loads(ds.attrs["drift_json"])["mesh"]["waterline_panel_size"]
    finer = f"hydro.drift_waterline_panel_size={0.5 * graded if graded else 0.001}"
    assert not drift_is_current(ds, load_case(tiny_case, [TINY_ACCEPTS, finer]))
    # so do other panels below the water line; the database's own panel size keeps it current
    base = json.loads(ds.attrs["drift_json"])["mesh"]["panel_size"]
    assert drift_is_current(ds, load_case(tiny_case, [TINY_ACCEPTS,
                                                      f"hydro.drift_panel_size={base}"]))
    assert not drift_is_current(ds, load_case(tiny_case, [TINY_ACCEPTS,
                                                          f"hydro.drift_panel_size={0.7 * base}"]))
    # up to date: nothing to do
    main(["hydro", "build", str(tiny_case), "--quiet", "--drift", "--set", TINY_ACCEPTS])
    assert "nothing to do" in capsys.readouterr().out
    # another inertia leaves the first-order database up to date but the drift stale
    other = "floater.inertia=[3.0, 3.0, 1.5]"
    assert not drift_is_current(ds, load_case(tiny_case, [TINY_ACCEPTS, other]))
    main(["hydro", "build", str(tiny_case), "--quiet", "--drift", "--set", TINY_ACCEPTS,
          "--set", other])
    assert "mean drift added" in capsys.readouterr().out
    assert drift_is_current(read_database(db), load_case(tiny_case, [TINY_ACCEPTS, other]))


def test_hydro_check_shows_the_drift_row(capsys, monkeypatch):
    from tests.hydro.conftest import REPO

    monkeypatch.chdir(REPO)
    status = main(["hydro", "check", "cylinder_buoy", "--json"])
    report = json.loads(capsys.readouterr().out)
    rows = {r["name"]: r for r in report["checks"]}
    assert rows["drift"]["applicable"] and rows["drift"]["passed"]
    assert rows["drift"]["tolerance"] == pytest.approx(DRIFT_TOLERANCE)
    assert status == 0


def test_drift_check_not_applicable_without_drift(deepcwind_db):
    ds = deepcwind_db.drop_vars([v for v in DRIFT_VARIABLES if v in deepcwind_db.variables])
    result = check_drift(ds)
    assert not result.applicable and result.passed


def test_hydro_info_says_whether_the_drift_is_held(capsys, monkeypatch):
    from tests.hydro.conftest import REPO

    monkeypatch.chdir(REPO)
    assert main(["hydro", "info", "cylinder_buoy"]) == 0
    assert "mean drift: far and near field" in capsys.readouterr().out
    assert main(["hydro", "info", "deepcwind"]) == 0
    assert "mean drift: far and near field" in capsys.readouterr().out
    assert main(["hydro", "info", "deepcwind_wamit"]) == 0
    assert "mean drift: none" in capsys.readouterr().out
