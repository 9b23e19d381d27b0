"""``floatmoor run`` with ``[waves] second_order``: every refusal is bad input (status 2, one
line naming the case file, the key, the database, what was expected and what was found;
nothing written), and a full-QTF run through the command line."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from floatmoor.cli import main
from floatmoor.hydro.database import read_database, write_database
from floatmoor.io.netcdf import read_dataset
from tests.conftest import CASES, LINDAHL_CASE

BUOY_CASE = CASES / "cylinder_buoy" / "buoy_regular_T1.20.toml"
SHORT = ["--set", "simulation.duration=0.3", "--set", "simulation.output_interval=0.02",
         "--set", 'lines.*.model="quasi-static"']
DRIFT = ["mean_drift_far_field", "mean_drift_near_field", "mean_drift_near_field_terms"]
DOFS = ["Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw"]


def _project(tmp_path, change) -> tuple:
    """A copy of the buoy case beside a copy of its database changed by ``change``."""
    (tmp_path / "hydrodb").mkdir()
    ds = read_database(CASES.parent / "hydrodb" / "cylinder_buoy.nc")
    ds.attrs.pop("path")
    database = tmp_path / "hydrodb" / "cylinder_buoy.nc"
    write_database(change(ds), database)
    case = tmp_path / "buoy.toml"
    case.write_text(BUOY_CASE.read_text())
    return case, database


def _newman_qtf(ds: xr.Dataset, direction: float = 0.0) -> xr.Dataset:
    """``ds`` with a QTF on its frequencies built as (D_p + D_q) / 2 from its far-field route,
    at ``direction``."""
    far = ds["mean_drift_far_field"].isel(wave_direction=0).values
    near = ds["mean_drift_near_field"].isel(wave_direction=0).values
    d = far.copy()
    d[:, 2:5] = near[:, 2:5]
    q = 0.5 * (d[:, None, :] + d[None, :, :])
    w = ds["omega"].values
    values = np.stack([q, np.zeros_like(q)])[:, None]
    return ds.assign(qtf_difference=xr.DataArray(
        values, dims=("complex", "qtf_direction", "qtf_omega_1", "qtf_omega_2",
                      "influenced_dof"),
        coords={"qtf_direction": [direction], "qtf_omega_1": w, "qtf_omega_2": w},
        attrs={"qtf_source": "test: Newman's off-diagonals", "units": "N/m^2"}))


def _refused(capsys, args, out) -> str:
    assert main(["run", *map(str, args), "-o", str(out), "--quiet"] + SHORT) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("floatmoor: error: ") and "Traceback" not in err[0]
    assert not out.exists()
    return err[0]


def test_drift_models_refuse_a_database_without_drift(tmp_path, capsys) -> None:
    case, database = _project(tmp_path, lambda ds: ds.drop_vars(DRIFT + ["drift_rao"]))
    for model in ("mean", "newman"):
        err = _refused(capsys, [case, "--set", f'waves.second_order="{model}"'],
                       tmp_path / "out.nc")
        assert f"{case} (--set waves.second_order=\"{model}\"): waves.second_order: " in err
        assert f"found \"{model}\" with {database}, which has no mean drift" in err
        assert "hydro build CASE --drift" in err


def test_drift_route_the_database_lacks_is_refused_on_its_key(tmp_path, capsys) -> None:
    case, database = _project(tmp_path, lambda ds: ds.drop_vars("mean_drift_far_field"))
    err = _refused(capsys, [case, "--set", 'waves.second_order="newman"'], tmp_path / "o.nc")
    assert f"{case}: waves.drift_coefficients: expected \"near_field\"" in err
    assert f"found \"far_field\" with {database}, which has no far field mean drift" in err


def test_full_without_a_qtf_is_refused(capsys, tmp_path) -> None:
    err = _refused(capsys, [BUOY_CASE, "--set", 'waves.second_order="full"'], tmp_path / "o.nc")
    assert "waves.second_order: expected" in err and "hydrodb/cylinder_buoy.nc" in err
    assert "no difference-frequency QTF (qtf_difference)" in err


def test_a_sea_the_coefficients_do_not_cover_is_refused(tmp_path, capsys) -> None:
    """A QTF for waves towards 30 deg only, a sea towards 0 deg (which the first-order
    excitation covers); and a sea towards 30 deg, which the excitation does not cover."""
    case, database = _project(tmp_path, lambda ds: _newman_qtf(ds, np.radians(30.0)))
    err = _refused(capsys, [case, "--set", 'waves.second_order="full"'], tmp_path / "o.nc")
    assert f"{case}: waves.direction_deg: expected a sea the QTF coefficients of {database} " \
           "cover, found wave direction 0 deg outside the database directions (30 deg)" in err
    err = _refused(capsys, [case, "--set", "waves.direction_deg=30"], tmp_path / "o.nc")
    assert f"(--set waves.direction_deg=30): waves.direction_deg: expected a wave direction " \
           f"the excitation forces of {database} cover" in err


@pytest.mark.parametrize("overrides, key", [
    (['waves={kind = "still", second_order = "mean"}'], "waves.second_order"),
    (['waves={kind = "regular", height = 0.04, period = 1.2, second_order = "quadratic"}'],
     "waves.second_order"),
    (['waves={kind = "regular", height = 0.04, period = 1.2, drift_coefficients = "mid"}'],
     "waves.drift_coefficients"),
])
def test_keys_are_checked_when_the_case_loads(tmp_path, capsys, overrides, key) -> None:
    args = [BUOY_CASE] + [x for o in overrides for x in ("--set", o)]
    err = _refused(capsys, args, tmp_path / "o.nc")
    assert f": {key}: expected" in err


def test_second_order_needs_a_floater(tmp_path, capsys) -> None:
    out = tmp_path / "o.nc"
    assert main(["run", str(LINDAHL_CASE), "-o", str(out), "--quiet", "--set",
                 'waves={kind = "regular", height = 0.04, period = 1.2, '
                 'second_order = "mean"}']) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "waves: expected a [floater] table" in err[0] and not out.exists()


def test_full_qtf_run_of_newmans_off_diagonals_equals_the_newman_run(tmp_path) -> None:
    """Through the command line, a database holding a QTF made of Newman's off-diagonals:
    the ``full`` run records the ``newman`` run's force and moves the buoy the same way (to
    round-off), and says where its QTF came from."""
    case, database = _project(tmp_path, _newman_qtf)
    sea = ["--set", 'waves={kind = "jonswap", hs = 0.04, tp = 1.2, seed = 4, '
           'spacing = "random-in-bin", n_components = 40, ramp_duration = 0.2}']
    runs = {}
    for model in ("newman", "full"):
        out = tmp_path / f"{model}.nc"
        assert main(["run", str(case), "-o", str(out), "--quiet"] + sea + [
            "--set", f'waves.second_order="{model}"'] + SHORT) == 0
        runs[model] = read_dataset(out)
    force = runs["newman"]["second_order_force"].values
    np.testing.assert_allclose(runs["full"]["second_order_force"].values, force, rtol=0,
                               atol=1e-11 * np.abs(force).max())
    np.testing.assert_allclose(runs["full"]["body_displacement"].values,
                               runs["newman"]["body_displacement"].values, rtol=0, atol=1e-12)
    assert runs["full"].attrs["second_order_coefficients"] == \
        "qtf_difference (qtf_source: test: Newman's off-diagonals)"
    assert runs["full"].attrs["drift_inputs_current"].startswith("not applicable")


def test_a_case_with_second_order_loads_scales_keeping_the_choice(tmp_path) -> None:
    """``floatmoor scale`` keeps ``second_order`` and ``drift_coefficients`` (words, not
    dimensional values)."""
    from floatmoor.similitude.case_scaling import scale_case_file
    from floatmoor.similitude.laws import ScaleLaw

    case = tmp_path / "buoy.toml"
    case.write_text(BUOY_CASE.read_text().replace(
        'ramp_duration = 20.0', 'ramp_duration = 20.0\nsecond_order = "newman"\n'
        'drift_coefficients = "near_field"'))
    scaled = scale_case_file(case, ScaleLaw(10.0, 10.0, 1.0), output=tmp_path / "big.toml",
                             hydro_database="buoy_x10").case
    assert scaled.waves.second_order == "newman"
    assert scaled.waves.drift_coefficients == "near_field"


def test_unusable_coefficients_are_refused_on_the_model_key(tmp_path, capsys) -> None:
    """A QTF with NaN where the sea needs it, or with different frequency axes: refused on
    ``waves.second_order``, naming the database and what is wrong."""
    def with_nan(ds):
        out = _newman_qtf(ds)
        out["qtf_difference"][0, 0, 40, 41, 0] = np.nan
        return out

    case, database = _project(tmp_path, with_nan)
    err = _refused(capsys, [case, "--set", 'waves.second_order="full"'], tmp_path / "o.nc")
    assert f"waves.second_order: expected \"none\", or a database whose QTF coefficients are " \
           f"usable, found \"full\" with {database}: QTF not finite on its grid" in err


def test_drift_with_nan_where_the_sea_needs_it_is_refused(tmp_path, capsys) -> None:
    def with_nan(ds):
        ds["mean_drift_far_field"][44, 0, 0] = np.nan
        return ds

    case, database = _project(tmp_path, with_nan)
    err = _refused(capsys, [case, "--set", 'waves.second_order="mean"'], tmp_path / "o.nc")
    assert f"found \"mean\" with {database}: drift coefficients not finite at 5.23599 rad/s" in err
