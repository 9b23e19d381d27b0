"""Response amplitude operators (floatmoor.hydro.rao) and ``floatmoor rao``."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from floatmoor.cli import main
from floatmoor.hydro.complex_values import merge_complex
from floatmoor.hydro.natural_periods import mooring_stiffness
from floatmoor.hydro.radiation import hydrostatic_stiffness_total
from floatmoor.hydro.rao import RAO_TITLE, rao
from tests.hydro.conftest import DEEPCWIND_CASE

#: capytaine's RAO solves the same 6 x 6 systems: agreement to round-off.
RAO_RTOL = 1e-9


def _capytaine_dataset(ds, floater, k_moor):
    """The database in the form capytaine.post_pro.rao reads."""
    dofs = list(ds["radiating_dof"].values)
    stiff = hydrostatic_stiffness_total(ds, floater) + k_moor
    out = xr.Dataset({
        "added_mass": ds["added_mass"], "radiation_damping": ds["radiation_damping"],
        "excitation_force": merge_complex(ds, "excitation_force"),
        "inertia_matrix": (("influenced_dof", "radiating_dof"), floater.mass_matrix()),
        "hydrostatic_stiffness": (("influenced_dof", "radiating_dof"), stiff),
    }, coords={"omega": ds["omega"].values, "wave_direction": ds["wave_direction"].values,
               "influenced_dof": dofs, "radiating_dof": dofs})
    return out


def test_rao_equals_capytaines_with_the_mooring(deepcwind_db, deepcwind_case):
    from capytaine.post_pro.rao import rao as capytaine_rao

    k_moor = mooring_stiffness(deepcwind_case)
    ours = rao(deepcwind_db, deepcwind_case.floater, k_moor)
    theirs = capytaine_rao(_capytaine_dataset(deepcwind_db, deepcwind_case.floater, k_moor))
    theirs = theirs.transpose("omega", "wave_direction", "radiating_dof").values
    scale = np.abs(theirs).max(axis=(0, 1))
    assert np.all(np.abs(ours.values - theirs) <= RAO_RTOL * scale)
    assert ours.dims == ("omega", "wave_direction", "radiating_dof")
    assert "units" in ours.attrs and "long_name" in ours.attrs


def test_mooring_sets_the_low_frequency_surge(deepcwind_db, deepcwind_case):
    """At 0.06 rad/s (105 s, near the moored surge period of 107-112 s) the moored RAO is
    resonant; free floating, surge follows the water particle (finite depth: 1/tanh(kh) >
    1 horizontal excursion per unit amplitude, minus nothing)."""
    k_moor = mooring_stiffness(deepcwind_case)
    moored = np.abs(rao(deepcwind_db, deepcwind_case.floater, k_moor).values[0, 0, 0])
    free = np.abs(rao(deepcwind_db, deepcwind_case.floater).values[0, 0, 0])
    kh = float(deepcwind_db["wavenumber"].values[0]) * 200.0
    assert moored > 10.0
    assert free == pytest.approx(1.0 / np.tanh(kh), rel=0.1)


def test_rao_command_writes_units_and_plot(tmp_path, capsys):
    out, fig = tmp_path / "rao.nc", tmp_path / "rao.png"
    assert main(["rao", str(DEEPCWIND_CASE), "-o", str(out), "--plot", str(fig),
                 "--damping", "Surge=1e5"]) == 0
    ds = xr.open_dataset(out)
    assert ds.attrs["title"] == RAO_TITLE
    assert ds["rao"].dims == ("complex", "omega", "wave_direction", "radiating_dof")
    assert ds["rao_amplitude"].attrs["units"].startswith("m/m")
    assert "Surge  max |RAO|" in capsys.readouterr().out
    assert fig.stat().st_size > 0
    # the same command again may replace its own RAO file
    assert main(["rao", str(DEEPCWIND_CASE), "-o", str(out)]) == 0


@pytest.mark.parametrize("option", [["--damping", "Foo=1"], ["--damping", "Surge=-1"]])
def test_rao_command_bad_option_exits_2_writing_nothing(tmp_path, capsys, option):
    out = tmp_path / "rao.nc"
    assert main(["rao", str(DEEPCWIND_CASE), "-o", str(out), *option]) == 2
    err = capsys.readouterr().err
    assert err.startswith("floatmoor: error: --damping") and err.count("\n") == 1
    assert not out.exists()


def test_rao_command_does_not_replace_other_files(tmp_path, capsys):
    other = tmp_path / "other.nc"
    xr.Dataset({"a": ("x", [1.0])}).to_netcdf(other, format="NETCDF3_64BIT")
    before = other.read_bytes()
    assert main(["rao", str(DEEPCWIND_CASE), "-o", str(other)]) == 2
    assert other.read_bytes() == before


def test_rao_command_refuses_a_database_without_excitation(tmp_path, capsys):
    """The imported OC4 WAMIT database has no excitation file: exit 2, one line, nothing
    written."""
    from tests.hydro.conftest import REPO

    out = tmp_path / "rao.nc"
    case = REPO / "cases" / "deepcwind" / "deepcwind_free_decay_wamit.toml"
    assert main(["rao", str(case), "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("floatmoor: error: ") and err.count("\n") == 1
    assert "excitation" in err
    assert not out.exists()


def test_rao_command_refuses_a_case_without_floater(tmp_path, capsys):
    from tests.hydro.conftest import REPO

    case = next((REPO / "cases" / "lindahl").glob("*.toml"))
    out = tmp_path / "rao.nc"
    assert main(["rao", str(case), "-o", str(out)]) == 2
    assert "[floater] and [hydro]" in capsys.readouterr().err
    assert not out.exists()
