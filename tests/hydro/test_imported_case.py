"""Cases naming an imported database (``[hydro] source = "imported"``): the strict
``[hydro]`` table, the staleness rules of an import (case values, source files), the two kinds
of database not mistaken for each other, ``hydro build`` refusing, and runs: still water and
wind run, a run with waves on a database without excitation exits 2 saying why."""

from __future__ import annotations

import re
import shutil

import pytest

from floatmoor.case.load import load_case
from floatmoor.cli import main
from floatmoor.errors import CaseError
from floatmoor.hydro.database import HydroDatabaseError, load_for_case, write_database
from floatmoor.hydro.importing import imported_dataset
from tests.hydro.conftest import BUOY_CASE, DEEPCWIND_CASE, REPO
from tests.hydro.test_importing import as_imported, options_of

WAMIT_CASE = REPO / "cases" / "deepcwind" / "deepcwind_free_decay_wamit.toml"
OC4 = REPO / "tests" / "data" / "wamit_oc4"
IMPORTED_HYDRO = '[hydro]\ndatabase = "buoy_imported"\nsource = "imported"\n\n'
#: The buoy case, quick: quasi-static lines, half a second.
QUICK = ['lines.*.model="quasi-static"', "simulation.duration=0.5",
         "simulation.output_interval=0.1"]


def _with_hydro(text: str, table: str) -> str:
    """A case's text with its [hydro] table replaced."""
    return re.sub(r"\[hydro\]\n.*?(?=\n\[)", table.rstrip("\n") + "\n", text, flags=re.S)


@pytest.fixture
def buoy_imported(tmp_path, buoy_db):
    """The buoy's database imported (no excitation) from a stand-in source file, and the buoy
    case naming it, in a project folder of their own."""
    (tmp_path / "hydrodb").mkdir()
    source = tmp_path / "buoy.1"
    source.write_text("stands in for the file the data came from\n")
    ds = imported_dataset(as_imported(buoy_db, excitation="none", files=(str(source),)),
                          options_of(buoy_db), name="buoy_imported",
                          command=f"floatmoor hydro import {source} -o hydrodb/buoy_imported.nc")
    write_database(ds, tmp_path / "hydrodb" / "buoy_imported.nc")
    case = tmp_path / "buoy.toml"
    case.write_text(_with_hydro(BUOY_CASE.read_text(), IMPORTED_HYDRO))
    return case, source


def test_imported_hydro_table_takes_no_build_keys(tmp_path):
    case = load_case(WAMIT_CASE)
    assert case.hydro.source == "imported" and case.hydro.database == "deepcwind_wamit"
    assert case.hydro.frequencies == () and case.hydro.panel_size is None
    assert load_case(DEEPCWIND_CASE).hydro.source == "bem"
    with pytest.raises(CaseError) as info:
        load_case(WAMIT_CASE, ["hydro.panel_size=2.0"])
    assert info.value.key == "hydro.panel_size"
    assert "belong to 'floatmoor hydro build'" in info.value.expected
    with pytest.raises(CaseError) as info:
        load_case(WAMIT_CASE, ['hydro.source="wamit"'])
    assert info.value.key == "hydro.source" and '"imported"' in info.value.expected


def test_shipped_imported_database_is_up_to_date_for_its_case():
    ds = load_for_case(load_case(WAMIT_CASE))
    assert ds.attrs["source"] == "wamit"


@pytest.mark.parametrize("override, key", [
    ("environment.water_density=1000.0", "water_density (database 1025.0, case 1000.0)"),
    ("environment.gravity=9.81", "gravity"),
    ("floater.reference_point=[0.0, 0.0, -1.0]", "reference_point"),
    ("environment.water_depth=220.0", "water_depth (database 200.0, case 220.0)"),
])
def test_case_values_an_import_must_match(override, key):
    with pytest.raises(HydroDatabaseError) as info:
        load_for_case(load_case(WAMIT_CASE, [override]))
    message = str(info.value)
    assert "stale hydrodynamic database" in message and key in message
    assert message.endswith("; re-import it with 'floatmoor hydro import FILE... -o PATH.nc "
                            "--force' (the files and options 'floatmoor hydro info' lists, with "
                            "the case's values)")


def test_deep_water_import_fits_any_case_depth(buoy_imported, buoy_db, tmp_path):
    case_path, source = buoy_imported
    ds = imported_dataset(as_imported(buoy_db, excitation="none", files=(str(source),)),
                          options_of(buoy_db, water_depth=float("inf")), name="buoy_imported")
    write_database(ds, tmp_path / "hydrodb" / "buoy_imported.nc")
    load_for_case(load_case(case_path, ["environment.water_depth=3.0"]), checks=False)


def test_a_changed_source_file_makes_the_import_stale(buoy_imported, capsys):
    case_path, source = buoy_imported
    case = load_case(case_path)
    load_for_case(case, checks=False)
    text = source.read_text()
    source.write_text(text.replace("stands", "Stands"))
    with pytest.raises(HydroDatabaseError) as info:
        load_for_case(case, checks=False)
    assert f"source file {source} (changed since the import" in str(info.value)
    assert "re-import it with 'floatmoor hydro import FILE... -o PATH.nc --force'" \
        in str(info.value)
    database = str(case_path.parent / "hydrodb" / "buoy_imported.nc")
    assert main(["hydro", "check", database]) == 2
    assert "changed since the import" in capsys.readouterr().err
    source.unlink()  # a missing source file cannot be checked: not stale
    load_for_case(case, checks=False)
    assert main(["hydro", "info", database]) == 0
    assert "source files not found: staleness not checked" in capsys.readouterr().out


def test_editing_a_shipped_wamit_file_makes_the_database_stale(tmp_path):
    """The shipped database's files are found from the project root above hydrodb/."""
    project = tmp_path / "project"
    shutil.copytree(OC4, project / "tests" / "data" / "wamit_oc4")
    (project / "hydrodb").mkdir()
    shutil.copy(REPO / "hydrodb" / "deepcwind_wamit.nc", project / "hydrodb")
    (project / "cases").mkdir()
    shutil.copy(WAMIT_CASE, project / "cases")
    case = load_case(project / "cases" / WAMIT_CASE.name)
    load_for_case(case, checks=False)
    hst = project / "tests" / "data" / "wamit_oc4" / "marin_semi.hst"
    hst.write_text(hst.read_text().replace("3.800615E+02", "3.900615E+02"))
    with pytest.raises(HydroDatabaseError, match="source file tests/data/wamit_oc4/"
                       "marin_semi.hst \\(changed since the import"):
        load_for_case(case, checks=False)


def test_built_and_imported_databases_are_not_mistaken():
    with pytest.raises(HydroDatabaseError) as info:
        load_for_case(load_case(DEEPCWIND_CASE, ['hydro.database="deepcwind_wamit"']))
    assert "imported from wamit files" in str(info.value)
    assert '([hydro] source = "bem")' in str(info.value)
    with pytest.raises(HydroDatabaseError) as info:
        load_for_case(load_case(WAMIT_CASE, ['hydro.database="deepcwind"']))
    assert "built by capytaine" in str(info.value)
    assert 'names an imported database ([hydro] source = "imported")' in str(info.value)


def test_hydro_build_refuses_an_imported_case(capsys):
    assert main(["hydro", "build", str(WAMIT_CASE)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "re-import it with 'floatmoor hydro import " in err[0]


def test_hydro_build_replaces_an_imported_database_only_with_force(buoy_imported, capsys,
                                                                    tmp_path):
    target = tmp_path / "hydrodb" / "buoy_imported.nc"
    before = target.read_bytes()
    assert main(["hydro", "build", str(BUOY_CASE), "-o", str(target)]) == 2
    assert "replaces it only with --force" in capsys.readouterr().err
    assert target.read_bytes() == before


def test_still_water_and_wind_runs_use_an_imported_database(buoy_imported, tmp_path):
    case_path, _ = buoy_imported
    for extra in (['waves={kind = "still"}'],
                  ['waves={kind = "still"}', 'wind={mean_speed = 2.0, spectrum = "steady"}']):
        out = tmp_path / "run.nc"
        assert main(["run", str(case_path), "--quiet", "-o", str(out),
                     *[a for o in QUICK + extra for a in ("--set", o)]]) == 0
        assert out.is_file()
        out.unlink()


def test_a_run_with_waves_on_a_database_without_excitation_exits_2(buoy_imported, tmp_path,
                                                                  capsys):
    case_path, source = buoy_imported
    out = tmp_path / "waves.nc"
    assert main(["run", str(case_path), "--quiet", "-o", str(out),
                 *[a for o in QUICK for a in ("--set", o)]]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1
    assert "the hydrodynamic database has no excitation forces (imported from wamit files " \
        f"({source}) that give none)" in err[0]
    assert not out.exists()


# --- an imported floater needs mass properties, not a hull (docs/guide/hydro_databases.md) ---

NO_GEOMETRY_CASE = REPO / "tests" / "data" / "imported_floater" / "deepcwind_no_geometry.toml"


def _without_geometry(text: str) -> str:
    """A case's text without its [floater.geometry] table."""
    return re.sub(r"\[floater\.geometry\]\n.*?(?=\n\[hydro\])", "", text, flags=re.S)


def test_an_imported_floater_needs_no_geometry_and_is_not_checked_against_one(buoy_imported):
    """No [floater.geometry]: the case loads (no draft-from-mass check: a mass no 0.515 m
    cylinder 0.401 m high could float is fine), its database too; a built database still
    needs the hull, and drag still needs members."""
    case_path, _ = buoy_imported
    case_path.write_text(_without_geometry(case_path.read_text()))
    case = load_case(case_path, ["floater.mass=200.0"])
    assert case.floater.geometry is None
    load_for_case(load_case(case_path), checks=False)
    with pytest.raises(CaseError) as info:
        load_case(case_path, ['floater.drag={preset = "deepcwind_oc4"}'])
    assert info.value.key == "floater.drag" and "[floater.geometry]" in info.value.expected
    with pytest.raises(CaseError) as info:
        load_case(case_path,
                  ['hydro={database = "cylinder_buoy", frequency_ranges = [[0.8, 9.2, 5]], '
                   'directions_deg = [0.0], panel_size = 0.05}'])
    assert info.value.key == "floater.geometry"


def test_an_imported_database_is_named_by_its_path_relative_to_the_case(buoy_imported,
                                                                       tmp_path):
    """database = a path to the .nc (relative to the case file's folder, or absolute), with
    no hydrodb/ folder search; a bare name still finds hydrodb/NAME.nc."""
    from floatmoor.hydro.database import database_path

    case_path, _ = buoy_imported
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    moved = elsewhere / "case.toml"
    moved.write_text(case_path.read_text())
    relative = load_case(moved, ['hydro.database="../hydrodb/buoy_imported.nc"'])
    assert database_path(relative) == elsewhere / ".." / "hydrodb" / "buoy_imported.nc"
    load_for_case(relative, checks=False)
    absolute = str(tmp_path / "hydrodb" / "buoy_imported.nc")
    load_for_case(load_case(moved, [f'hydro.database="{absolute}"']), checks=False)
    assert database_path(load_case(case_path)) == tmp_path / "hydrodb" / "buoy_imported.nc"
    with pytest.raises(CaseError) as info:  # a path only for an imported database
        load_case(BUOY_CASE, ['hydro.database="../hydrodb/cylinder_buoy.nc"'])
    assert info.value.key == "hydro.database"


def test_a_missing_imported_database_says_import_it(buoy_imported, tmp_path, capsys):
    case_path, _ = buoy_imported
    case = load_case(case_path, ['hydro.database="db/missing.nc"'])
    with pytest.raises(HydroDatabaseError) as info:
        load_for_case(case)
    message = str(info.value)
    assert message.startswith(f"{case_path.parent / 'db' / 'missing.nc'}: no hydrodynamic "
                              "database")
    assert "import it with 'floatmoor hydro import FILE... -o PATH.nc'" in message
    assert "hydro build" not in message
    out = tmp_path / "run.nc"
    assert main(["run", str(case_path), "--quiet", "-o", str(out), "--set",
                 'hydro.database="db/missing.nc"', *[a for o in QUICK for a in ("--set", o)]]) \
        == 2
    err = capsys.readouterr().err
    assert "import it with 'floatmoor hydro import" in err and not out.exists()


def test_a_hydro_table_without_source_or_build_keys_says_source_imported_is_missing():
    with pytest.raises(CaseError) as info:
        load_case(WAMIT_CASE, ['hydro={database = "deepcwind_wamit"}'])
    assert info.value.key == "hydro.source"
    assert info.value.expected.startswith('source = "imported" for a database made by '
                                          "'floatmoor hydro import' (probably missing")
    assert "frequency ranges" not in str(info.value)
    with pytest.raises(CaseError) as info:  # said first, even without a hull
        load_case(NO_GEOMETRY_CASE, ['hydro={database = "../../../hydrodb/deepcwind_wamit.nc"}'])
    assert info.value.key == "hydro.source"


@pytest.mark.slow  # ~12 s, two coupled runs; the imported database's own runs (still water,
# wind) stay in the default run
def test_a_floater_without_geometry_moves_as_the_one_with_it_when_drag_is_off(tmp_path):
    """tests/data/imported_floater/deepcwind_no_geometry.toml (no hull, database by path)
    against the shipped WAMIT case with its drag off: the same decay, bit for bit."""
    import numpy as np
    import xarray as xr

    quick = ["simulation.duration=1.0"]
    bare, full = tmp_path / "bare.nc", tmp_path / "full.nc"
    assert main(["run", str(NO_GEOMETRY_CASE), "--quiet", "-o", str(bare),
                 *[a for o in quick for a in ("--set", o)]]) == 0
    assert main(["run", str(WAMIT_CASE), "--quiet", "-o", str(full),
                 *[a for o in quick + ['floater.drag.preset="none"'] for a in ("--set", o)]]) == 0
    with xr.open_dataset(bare) as a, xr.open_dataset(full) as b:
        assert float(a["body_displacement"].isel(time=-1, dof=0)) < 16.58  # it moved
        for name in ("body_displacement", "fairlead_tension"):
            assert np.array_equal(a[name].values, b[name].values), name
        from floatmoor.plots.body_pose import body_model

        model = body_model(load_case(NO_GEOMETRY_CASE), a)  # the views: fairleads, no hull
        assert model is not None and model.surface is None and len(model.points) == 3


def test_a_campaign_bundle_carries_an_imported_database_named_by_path(tmp_path):
    """The bundle a cluster campaign ships holds the database named by path under its file
    name, and the workers' copy of the case finds it there."""
    from floatmoor.campaign.bundle import load_bundled_case, make_bundle, materialise

    case = load_case(NO_GEOMETRY_CASE)
    bundle, blobs = make_bundle([case])
    folder = materialise(bundle, blobs, tmp_path / "worker")
    bundled, database = load_bundled_case(bundle, folder, [])
    assert bundled.floater.geometry is None and database.name == "deepcwind_wamit.nc"
    assert database.read_bytes() == (REPO / "hydrodb" / "deepcwind_wamit.nc").read_bytes()
