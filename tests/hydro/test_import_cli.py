"""``floatmoor hydro import``: the OC4 WAMIT files in, a checked database out; provenance in
``hydro info``; broken files and bad options exit 2 with one line and write nothing."""

from __future__ import annotations

import json
import os
import shutil

import pytest

from floatmoor.cli import main
from floatmoor.hydro.database import file_sha256, read_database
from tests.hydro.conftest import REPO

OC4 = REPO / "tests" / "data" / "wamit_oc4"
#: The options of the shipped hydrodb/deepcwind_wamit.nc (cases/deepcwind/
#: deepcwind_free_decay_wamit.toml's header).
OPTIONS = ["--water-density", "1025", "--gravity", "9.80665", "--water-depth", "200",
           "--reference-point", "0", "0", "0", "--displaced-volume", "13917",
           "--centre-of-buoyancy", "0", "0", "-13.17", "--yaw-deg", "180"]


@pytest.fixture
def oc4_copy(tmp_path):
    """The OC4 files copied to a project folder with a hydrodb/ folder."""
    (tmp_path / "hydrodb").mkdir()
    for name in ("marin_semi.1", "marin_semi.hst"):
        shutil.copy(OC4 / name, tmp_path / name)
    return tmp_path


def _import(folder, *extra, files=("marin_semi.1", "marin_semi.hst"), out="hydrodb/w.nc"):
    return main(["hydro", "import", *[str(folder / f) for f in files], "-o",
                 str(folder / out), *OPTIONS, *extra])


def test_import_checks_and_records_where_the_data_came_from(oc4_copy, capsys):
    assert _import(oc4_copy) == 0
    out = capsys.readouterr().out
    assert "498 frequencies" in out and "A_inf file (WAMIT .1, PER = 0)" in out
    assert "haskind         n/a" in out and "hydrostatics    n/a" in out
    assert "all checks pass (2 not applicable)" in out
    # the orientation said in the case's terms (printed whether or not the files have waves)
    assert "the file's +x axis is the case's (-1, 0, 0)" in out
    assert "waves.direction_deg = BETA + 180 (its heading 0 travels towards -180 deg)" in out
    ds = read_database(oc4_copy / "hydrodb" / "w.nc")
    assert ds.attrs["source"] == "wamit" and ds.attrs["checks_failed"] == "none"
    files = json.loads(ds.attrs["source_files_json"])
    assert [f["path"] for f in files] == [str(oc4_copy / "marin_semi.1"),
                                          str(oc4_copy / "marin_semi.hst")]
    assert files[0]["sha256"] == file_sha256(OC4 / "marin_semi.1")
    assert files[0]["size"] == (OC4 / "marin_semi.1").stat().st_size
    options = json.loads(ds.attrs["import_options_json"])
    assert options["yaw_deg"] == 180.0 and options["water_depth"] == 200.0
    assert ds.attrs["import_command"].startswith("floatmoor hydro import ")
    assert "--displaced-volume 13917" in ds.attrs["import_command"]
    assert main(["hydro", "info", str(oc4_copy / "hydrodb" / "w.nc")]) == 0
    info = capsys.readouterr().out
    assert "source: wamit files, imported by floatmoor" in info
    assert f"marin_semi.1  494496 bytes  SHA-256 {files[0]['sha256']}" in info
    assert "A_inf: file (WAMIT .1, PER = 0)" in info
    assert "excitation: none" in info and "source files unchanged" in info
    assert "Orientation: the file's body frame turned by 180 deg about z" in info


def test_info_says_where_a_built_database_came_from(capsys):
    assert main(["hydro", "info", str(REPO / "hydrodb" / "deepcwind.nc")]) == 0
    info = capsys.readouterr().out
    assert "source: capytaine ('floatmoor hydro build'" in info
    assert "A_inf: capytaine (omega = infinity solved)" in info
    assert "excitation: excitation_force, Froude_Krylov_force, diffraction_force" in info


def test_existing_output_needs_force(oc4_copy, capsys):
    assert _import(oc4_copy) == 0
    target = oc4_copy / "hydrodb" / "w.nc"
    before = target.read_bytes()
    capsys.readouterr()
    assert _import(oc4_copy) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err == [f"floatmoor: error: -o/--output: expected a new file (--force "
                   f"overwrites), found the existing file '{target}'"]
    assert target.read_bytes() == before
    assert _import(oc4_copy, "--force") == 0


def _broken(folder, name, edit):
    lines = (OC4 / name).read_text().splitlines(keepends=True)
    (folder / name).write_text("".join(edit(lines)))


def _replace(index, text):
    return lambda lines: lines[:index] + [text] + lines[index + 1:]


#: A .3 whose period (10 s) is none of the .1's.
FOREIGN_3 = "".join(f"  0.100000E+02   0.000000E+00 {i}  1.0 0.0 1.0 0.0\n"
                    for i in range(1, 7))


@pytest.mark.parametrize("name, edit, files, message", [
    ("marin_semi.1", _replace(40, "  0.628319E+03     3     3  NaN  1.805970E+02\n"), None,
     "marin_semi.1: line 41: expected a finite number"),
    ("marin_semi.1", _replace(40, "  0.628319E+03     3     3  1.499195E+04\n"), None,
     "marin_semi.1: line 41"),
    ("marin_semi.hst", _replace(14, "     3     3\n"), None, "marin_semi.hst: line 15"),
    (None, None, ("marin_semi.1", "marin_semi.hst", "missing.3"), "missing.3"),
    ("marin_semi.3", None, ("marin_semi.1", "marin_semi.hst", "marin_semi.3"),
     "marin_semi.3: wave periods: expected the finite periods of"),
], ids=["nan", "columns-1", "columns-hst", "missing-file", "inconsistent-frequencies"])
def test_broken_files_exit_2_with_one_line_and_nothing_written(oc4_copy, capsys, name, edit,
                                                              files, message):
    if name == "marin_semi.3":
        (oc4_copy / name).write_text(FOREIGN_3)
    elif name is not None:
        _broken(oc4_copy, name, edit)
    args = {} if files is None else {"files": files}
    assert _import(oc4_copy, **args) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("floatmoor: error: ") and message in err[0]
    assert "Traceback" not in err[0]
    assert list((oc4_copy / "hydrodb").iterdir()) == []


@pytest.mark.parametrize("change, message", [
    (["--water-depth", "deep"], "--water-depth: expected a water depth > 0 [m] or "
     "'infinite', found 'deep'"),
    (["--water-density", "-1"], "--water-density: expected a number > 0 [kg/m^3], found '-1'"),
    (["--gravity", "nan"], "--gravity: expected a number > 0"),
    (["--body", "2"], "--body: expected no --body with WAMIT files"),
    (["--length-scale", "0"], "--length-scale: expected a number > 0 [m]"),
])
def test_bad_options_exit_2(oc4_copy, capsys, change, message):
    assert _import(oc4_copy, *change) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and message in err[0], err
    assert list((oc4_copy / "hydrodb").iterdir()) == []


@pytest.mark.parametrize("drop, message", [
    ("--displaced-volume", "marin_semi.hst: --displaced-volume: expected everything a WAMIT "
     "import needs"),
    ("--centre-of-buoyancy", ": --centre-of-buoyancy: expected everything"),
    ("--water-density", ": --water-density: expected everything"),
    ("--water-depth", ": --water-depth: expected everything"),
])
def test_missing_options_are_named(oc4_copy, capsys, monkeypatch, drop, message):
    i = OPTIONS.index(drop)
    n = 3 if drop == "--centre-of-buoyancy" else 1
    monkeypatch.setattr(f"{__name__}.OPTIONS", OPTIONS[:i] + OPTIONS[i + 1 + n:])
    assert _import(oc4_copy) == 2
    err = capsys.readouterr().err
    assert message in err and err.rstrip().endswith("found 1 missing")


def test_everything_missing_is_listed_at_once_with_the_file_that_states_it(
        oc4_copy, capsys, monkeypatch):
    """No options and no .hst: one status-2 line naming all five options and the .hst, each
    with where it comes from (the .out for all but the density), not one per attempt."""
    monkeypatch.setattr(f"{__name__}.OPTIONS", [])
    assert _import(oc4_copy, files=("marin_semi.1",)) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("floatmoor: error: "), err
    line = err[0]
    assert (": --water-density, --gravity, --water-depth, --displaced-volume, "
            "--centre-of-buoyancy, .hst: expected everything a WAMIT import needs") in line
    assert "--water-density RHO (the water density of the WAMIT run [kg/m^3]; no WAMIT file " \
        "states it)" in line
    for option in ("--gravity G", "--water-depth DEPTH", "--displaced-volume V",
                   "--centre-of-buoyancy X Y Z"):
        assert f"{option} (" in line
    assert line.count("stated by the run's .out: give the .out among the files, or the "
                      "option") == 4
    assert "a .hst file (the hydrostatic stiffness; no option gives it)" in line
    assert line.endswith("found 6 missing")
    assert list((oc4_copy / "hydrodb").iterdir()) == []


#: The body parameters of the OC4 run as a WAMIT .out prints them (tests/io/test_wamit.py
#: OUT_EXCERPT), the header given by OUT_HEADER.
OUT_BODY = """
 XBODY =    0.0000 YBODY =    0.0000 ZBODY =    0.0000 PHIBODY =   0.0
 Volumes (VOLX,VOLY,VOLZ):     13917.4     13916.9     13917.0
 Center of Buoyancy (Xb,Yb,Zb):     -0.000000    0.000000  -13.170000
"""


def test_the_run_summary_gives_volume_and_centre_of_buoyancy(oc4_copy, capsys, monkeypatch):
    """With the .out only the density is asked; the volume and the centre of buoyancy (placed
    and turned by the yaw) come from it and are printed as such."""
    (oc4_copy / "marin_semi.out").write_text(OUT_HEADER.replace("DEPTH", "200.000000")
                                             + OUT_BODY)
    monkeypatch.setattr(f"{__name__}.OPTIONS", ["--yaw-deg", "180"])
    files = ("marin_semi.1", "marin_semi.hst", "marin_semi.out")
    assert _import(oc4_copy, files=files) == 2
    err = capsys.readouterr().err
    assert ": --water-density: expected" in err and err.rstrip().endswith("found 1 missing")
    assert _import(oc4_copy, "--water-density", "1025", files=files) == 0
    out = capsys.readouterr().out
    assert "displaced volume 13917 m^3 (its VOLZ)" in out
    assert "centre of buoyancy (-0, 0, -13.17) m in the WAMIT body frame" in out
    ds = read_database(oc4_copy / "hydrodb" / "w.nc")
    assert float(ds["disp_volume"]) == 13917.0
    assert ds["center_of_buoyancy"].values.tolist() == pytest.approx([0.0, 0.0, -13.17])
    # a value given must be the one the file states
    assert _import(oc4_copy, "--water-density", "1025", "--displaced-volume", "13000",
                   "--force", files=files) == 2
    assert "marin_semi.out: displaced volume: expected the --displaced-volume given (13000), " \
        "found 13917 in the file" in capsys.readouterr().err


@pytest.mark.parametrize("files", [("marin_semi.1", "marin_semi.h5"),
                                   ("marin_semi.1", "marin_semi.txt")])
def test_mixed_or_unknown_formats_exit_2(oc4_copy, capsys, files):
    assert _import(oc4_copy, files=files) == 2
    assert "expected WAMIT files" in capsys.readouterr().err
    assert list((oc4_copy / "hydrodb").iterdir()) == []


def test_output_must_be_a_database_file(oc4_copy, capsys):
    assert _import(oc4_copy, out="hydrodb/w.txt") == 2
    assert "a database file PATH.nc" in capsys.readouterr().err


#: The header lines of a WAMIT run summary (.out) as WAMIT prints them (the rest of the file,
#: the run's tables, is not read); DEPTH is replaced.
OUT_HEADER = """ WAMIT  Version 7.3
 ...
 Gravity:     9.80665                Length scale:        1.00000
 Water depth:        DEPTH
 Logarithmic singularity index:              ILOG =     1
"""


def _with_out(folder, depth: str) -> tuple[str, ...]:
    (folder / "marin_semi.out").write_text(OUT_HEADER.replace("DEPTH", depth))
    return ("marin_semi.1", "marin_semi.hst", "marin_semi.out")


@pytest.mark.parametrize("depth, option, given, stated", [
    ("200.000000", "inf", "infinite", "200"),
    ("infinite", "200", "200", "infinite"),
    ("200.000000", "320", "320", "200"),
])
def test_water_depth_against_the_wamit_run_summary_exits_2_naming_both(
        oc4_copy, capsys, monkeypatch, depth, option, given, stated):
    """A depth given that is not the one the WAMIT run used (deep-water coefficients taken as
    finite-depth ones, or the reverse) is refused, naming both values."""
    i = OPTIONS.index("--water-depth")
    monkeypatch.setattr(f"{__name__}.OPTIONS", OPTIONS[:i] + OPTIONS[i + 2:])
    assert _import(oc4_copy, "--water-depth", option, files=_with_out(oc4_copy, depth)) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("floatmoor: error: "), err
    assert "marin_semi.out: water depth: expected the --water-depth given " \
        f"({given}), found {stated} in the file" in err[0]
    assert list((oc4_copy / "hydrodb").iterdir()) == []


def test_water_depth_and_gravity_come_from_the_run_summary_when_not_given(
        oc4_copy, capsys, monkeypatch):
    kept = list(OPTIONS)
    for flag in ("--water-depth", "--gravity"):
        i = kept.index(flag)
        del kept[i:i + 2]
    monkeypatch.setattr(f"{__name__}.OPTIONS", kept)
    assert _import(oc4_copy, files=_with_out(oc4_copy, "200.000000")) == 0
    out = capsys.readouterr().out
    assert "From the WAMIT run summary" in out and "water depth 200 m (no --water-depth " \
        "given)" in out and "gravity 9.80665 m/s^2 (no --gravity given)" in out
    ds = read_database(oc4_copy / "hydrodb" / "w.nc")
    assert ds.attrs["bem_water_depth"] == "200.0" and float(ds.attrs["gravity"]) == 9.80665


@pytest.mark.parametrize("value", ["1.025", "1025000", "800"])
def test_implausible_water_density_exits_2(oc4_copy, capsys, value):
    """1.025 is t/m^3 typed for kg/m^3: every value of the import would be 1000 times too
    small. Outside 900-1100 kg/m^3 the option is refused."""
    i = OPTIONS.index("--water-density")
    assert main(["hydro", "import", str(oc4_copy / "marin_semi.1"),
                 str(oc4_copy / "marin_semi.hst"), "-o", str(oc4_copy / "hydrodb" / "w.nc"),
                 *OPTIONS[:i], "--water-density", value, *OPTIONS[i + 2:]]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("floatmoor: error: --water-density: expected "
                                               "a water density of 900 to 1100 kg/m^3"), err
    assert f"found '{value}'" in err[0]
    assert list((oc4_copy / "hydrodb").iterdir()) == []


def write_bemio(path, ds, *, cg=(0.0, 0.0, 0.0), cb=None, rho=None, code="CAPYTAINE"):
    """A floatmoor database in WEC-Sim's BEMIO layout (writeBEMIOH5.m, as
    floatmoor/io/bemio.py documents it: normalised by rho and g, BEMIO's (force, motion)
    order, e^{+i omega t} amplitudes, shapes as h5py reads MATLAB's column-major arrays),
    with the coefficients about ``cg``."""
    import h5py
    import numpy as np

    from floatmoor.hydro.database import merge_complex

    rho = float(ds.attrs["water_density"]) if rho is None else rho
    g = float(ds.attrs["gravity"])
    w = ds["omega"].values
    order = ("omega", "radiating_dof", "influenced_dof")
    a = ds["added_mass"].transpose(*order).values          # [f, j, i]
    b = ds["radiation_damping"].transpose(*order).values
    col = lambda v: np.asarray(v, float).reshape(-1, 1)    # noqa: E731 - MATLAB column
    with h5py.File(path, "w") as f:
        f["bem_data/code"] = np.bytes_(code)
        sp = "simulation_parameters/"
        f[sp + "scaled"], f[sp + "g"], f[sp + "rho"] = col(0.0), col(g), col(rho)
        f[sp + "w"], f[sp + "T"] = col(w), col(2 * np.pi / w)
        depth = ds.attrs["bem_water_depth"]
        f[sp + "water_depth"] = np.bytes_("infinite") if depth == "infinite" else \
            col(float(depth))
        f[sp + "wave_dir"] = col(np.degrees(ds["wave_direction"].values))
        f[sp + "wave_dir"].attrs["units"] = "deg"
        p = "body1/properties/"
        f[p + "name"] = np.bytes_("hull")
        f[p + "body_number"], f[p + "dof"] = col(1), col(6)
        f[p + "dof_start"], f[p + "dof_end"] = col(1), col(6)
        f[p + "cg"] = col(cg)
        f[p + "cb"] = col(ds["center_of_buoyancy"].values if cb is None else cb)
        f[p + "disp_vol"] = col(float(ds["disp_volume"]))
        c = "body1/hydro_coeffs/"
        f[c + "linear_restoring_stiffness"] = ds["hydrostatic_stiffness"].transpose(
            "influenced_dof", "radiating_dof").values / (rho * g)
        f[c + "added_mass/all"] = np.transpose(a, (2, 1, 0)) / rho
        f[c + "added_mass/inf_freq"] = ds["added_mass_infinite"].transpose(
            "radiating_dof", "influenced_dof").values.T / rho
        f[c + "radiation_damping/all"] = np.transpose(b, (2, 1, 0)) / (rho * w)
        for var, where in (("excitation_force", "excitation/"),
                           ("Froude_Krylov_force", "excitation/froude-krylov/"),
                           ("diffraction_force", "excitation/scattering/")):
            x = np.conj(merge_complex(ds, var).transpose(
                "omega", "wave_direction", "influenced_dof").values) / (rho * g)
            f[c + where + "re"] = np.transpose(x.real, (2, 1, 0))
            f[c + where + "im"] = np.transpose(x.imag, (2, 1, 0))
    return path


def test_bemio_file_round_trips_through_import(tmp_path, capsys, deepcwind_db):
    """Our DeepCwind database written as a WEC-Sim BEMIO file and imported again: the same
    values (the files' rho, g and depth; volume and centre of buoyancy from the file), and
    the checks, Haskind included, pass."""
    import numpy as np

    from floatmoor.hydro.database import EXCITATION_VARIABLES, merge_complex

    (tmp_path / "hydrodb").mkdir()
    h5 = write_bemio(tmp_path / "deepcwind.h5", deepcwind_db)
    out = tmp_path / "hydrodb" / "back.nc"
    assert main(["hydro", "import", str(h5), "-o", str(out), "--water-density", "1025"]) == 0
    printed = capsys.readouterr().out
    assert "haskind         pass" in printed and "all checks pass (1 not applicable)" in printed
    back = read_database(out)
    assert back.attrs["source"] == "bemio" and back.attrs["bem_water_depth"] == "200.0"
    assert back.attrs["added_mass_infinite_source"] == \
        "file (BEMIO hydro_coeffs/added_mass/inf_freq)"
    for name in ("added_mass", "radiation_damping", "added_mass_infinite",
                 "hydrostatic_stiffness", "disp_volume", "center_of_buoyancy",
                 "rotation_center", "wavenumber", "wave_direction"):
        np.testing.assert_allclose(back[name].values, deepcwind_db[name].values, rtol=1e-12,
                                   atol=1e-9 * float(np.abs(deepcwind_db[name].values).max()),
                                   err_msg=name)
    for name in EXCITATION_VARIABLES:
        np.testing.assert_allclose(merge_complex(back, name).values,
                                   merge_complex(deepcwind_db, name).values, rtol=1e-12,
                                   atol=1e-9, err_msg=name)


def test_bemio_values_conflicting_with_options_exit_2(tmp_path, capsys, deepcwind_db):
    (tmp_path / "hydrodb").mkdir()
    h5 = write_bemio(tmp_path / "deepcwind.h5", deepcwind_db)
    out = str(tmp_path / "hydrodb" / "back.nc")
    for extra, message in (
            (["--water-depth", "infinite"], "water depth: expected the --water-depth given "
             "(infinite), found 200 in the file"),
            (["--displaced-volume", "1"], "displaced volume: expected the --displaced-volume "
             "given (1), found"),
            (["--length-scale", "1"], "--length-scale: expected no --length-scale with a "
             "BEMIO file"),
            (["--body", "2"], "/body2: expected one of the file's bodies 1..1")):
        assert main(["hydro", "import", str(h5), "-o", out, *extra]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and message in err[0], (extra, err)
        assert list((tmp_path / "hydrodb").iterdir()) == []


def test_bemio_reference_point_and_yaw_place_the_file(tmp_path, capsys, deepcwind_db):
    """The coefficients are about the file's cg: that point goes to --reference-point, the
    file's frame turned by --yaw-deg (a point p of the file: ref + R (p - cg))."""
    (tmp_path / "hydrodb").mkdir()
    h5 = write_bemio(tmp_path / "moved.h5", deepcwind_db, cg=(1.0, 2.0, -3.0),
                     cb=(2.0, 2.0, -16.0))
    out = tmp_path / "hydrodb" / "moved.nc"
    assert main(["hydro", "import", str(h5), "-o", str(out), "--reference-point", "0", "0",
                 "5", "--yaw-deg", "90"]) == 0
    back = read_database(out)
    assert back["rotation_center"].values.tolist() == [0.0, 0.0, 5.0]
    assert back["center_of_buoyancy"].values == pytest.approx([0.0, 1.0, -8.0], abs=1e-12)
    assert main(["hydro", "import", str(h5), "-o", str(out), "--force", "--yaw-deg", "90",
                 "--centre-of-buoyancy", "0", "1", "-13"]) == 0
    capsys.readouterr()
    assert main(["hydro", "import", str(h5), "-o", str(out), "--force",
                 "--centre-of-buoyancy", "0", "1", "-13"]) == 2
    assert "centre of buoyancy: expected the --centre-of-buoyancy given (0, 1, -13 m)" in \
        capsys.readouterr().err


def test_bemio_water_density_given_redimensionalises(tmp_path, deepcwind_db):
    """BEMIO's values are normalised by rho (its readWAMIT records 1000 kg/m^3 whatever the
    run's density): a --water-density re-dimensionalises them exactly and the notes say so."""
    import json

    import numpy as np

    (tmp_path / "hydrodb").mkdir()
    h5 = write_bemio(tmp_path / "deepcwind.h5", deepcwind_db)
    out = tmp_path / "hydrodb" / "back.nc"
    assert main(["hydro", "import", str(h5), "-o", str(out), "--water-density", "1000"]) == 0
    back = read_database(out)
    assert float(back.attrs["water_density"]) == 1000.0
    np.testing.assert_allclose(back["added_mass"].values,
                               deepcwind_db["added_mass"].values * 1000.0 / 1025.0, rtol=1e-12,
                               atol=1e-6)
    notes = " ".join(json.loads(back.attrs["import_notes_json"]))
    assert "given; the file says 1025" in notes


def test_overflowing_length_scale_is_one_line_and_nothing_written(oc4_copy, capsys):
    """--length-scale 1e308 overflows the scaling (L^5): one line, no NumPy warning before it
    (pytest turns a floatmoor warning into an error), no database with infinite values."""
    assert _import(oc4_copy, "--length-scale", "1e308") == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err == [f"floatmoor: error: {oc4_copy / 'marin_semi.1'} "
                   f"{oc4_copy / 'marin_semi.hst'}: added_mass: expected finite dimensional "
                   "values (the files' values scaled with rho = 1025, g = 9.80665, ULEN = "
                   "1e+308), found values that overflow"]
    assert list((oc4_copy / "hydrodb").iterdir()) == []


def test_fifo_source_is_refused_unopened(oc4_copy, capsys):
    os.mkfifo(oc4_copy / "pipe.hst")
    assert _import(oc4_copy, files=("marin_semi.1", "pipe.hst")) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err == [f"floatmoor: error: {oc4_copy / 'pipe.hst'}: expected a readable regular "
                   "file, found a FIFO (named pipe), not a regular file"]
