"""``floatmoor hydro import`` with second-order files: the shipped DeepCwind database written
as WAMIT ``.1``/``.3``/``.hst`` plus a ``.8``, ``.9`` and ``.12d`` of known values, and as a
BEMIO ``.h5`` with mean drift datasets: the database's mean drift and QTF variables (SI,
turned by ``--yaw-deg``), ``drift_source``, the recorded files, what ``hydro info`` and
``hydro check`` say; a broken second-order file is exit 2, one line, nothing written."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from floatmoor.cli import main
from floatmoor.hydro.database import file_sha256, merge_complex, read_database
from floatmoor.hydro.drift_build import drift_is_current, drift_is_imported, has_drift
from tests.hydro.test_import_cli import write_bemio
from tests.io.wamit_files import drift_lines, qtf_lines, write, write_wamit

RHO, G = 1025.0, 9.80665


def drift_nd(per, beta, i):
    """Non-dimensional (ULEN = 1) mean drift: rho g times this is the SI value."""
    return (0.5 + 0.1 * i) * (1.0 + per / 100.0) * math.cos(math.radians(beta) / 4.0)


@pytest.fixture
def wamit_set(tmp_path, deepcwind_db):
    """The DeepCwind database as WAMIT files with a .8, .9 (same drift: the routes agree)
    and a .12d on 3 of its periods whose diagonal is the .9's drift."""
    (tmp_path / "hydrodb").mkdir()
    files = write_wamit(tmp_path, deepcwind_db)
    periods = [float(x.split()[0]) for x in files[".1"].read_text().splitlines()
               if x.split()[1:3] == ["1", "1"] and float(x.split()[0]) > 0]
    betas = np.degrees(deepcwind_db["wave_direction"].values)
    files[".8"] = write(tmp_path, "body.8", drift_lines(periods, betas, drift_nd,
                                                        modes=(1, 2, 6)))
    files[".9"] = write(tmp_path, "body.9", drift_lines(periods, betas, drift_nd))
    chosen = periods[10:13]

    def qtf(p1, p2, i):
        return drift_nd(p1, 0.0, i) if p1 == p2 else \
            (0.3 + 0.01 * i) * complex(math.cos(p1 - p2), math.sin(p1 - p2))

    files[".12d"] = write(tmp_path, "body.12d", qtf_lines(chosen, qtf))
    return tmp_path, files, periods, chosen


def options(ds):
    cob = ds["center_of_buoyancy"].values
    return ["--water-density", str(RHO), "--gravity", str(G), "--water-depth", "200",
            "--displaced-volume", repr(float(ds["disp_volume"])),
            "--centre-of-buoyancy", *[f"{float(v):.6f}" for v in cob]]


def _import(folder, files, ds, *extra):
    return main(["hydro", "import", *[str(p) for p in files.values()], "-o",
                 str(folder / "hydrodb" / "w.nc"), *options(ds), *extra])


def test_wamit_second_order_lands_in_the_database(wamit_set, deepcwind_db, capsys):
    folder, files, periods, chosen = wamit_set
    assert _import(folder, files, deepcwind_db) == 0
    printed = capsys.readouterr().out
    assert "mean drift imported from wamit files" in printed
    assert "difference-frequency QTF: 3 x 3 frequencies" in printed
    assert "drift           pass" in printed            # far vs near: the same values
    ds = read_database(folder / "hydrodb" / "w.nc")
    assert ds.attrs["drift_source"] == "wamit" and "drift_inputs_hash" not in ds.attrs
    assert has_drift(ds) and drift_is_imported(ds)
    assert drift_is_current(ds, None)                    # never stale against a case
    rho_g = RHO * G
    betas = np.degrees(ds["wave_direction"].values)
    near = ds["mean_drift_near_field"].transpose("omega", "wave_direction",
                                                 "influenced_dof").values
    far = ds["mean_drift_far_field"].transpose("omega", "wave_direction",
                                               "influenced_dof").values
    for w, per in enumerate(periods):                    # the .1's periods: omega ascending
        for b, beta in enumerate(betas):
            expected = [drift_nd(per, beta, i) * rho_g for i in range(1, 7)]
            np.testing.assert_allclose(near[w, b], expected, rtol=1e-6)
            np.testing.assert_allclose(far[w, b, [0, 1, 5]], np.array(expected)[[0, 1, 5]],
                                       rtol=1e-6)
            assert np.all(np.isnan(far[w, b, 2:5]))
    assert ds["mean_drift_near_field"].attrs["units"].startswith("N/m^2")
    assert "body.9 (WAMIT .9, pressure integration)" in \
        ds["mean_drift_near_field"].attrs["drift_source"]
    q = merge_complex(ds, "qtf_difference")
    assert q.dims == ("qtf_direction", "qtf_omega_1", "qtf_omega_2", "influenced_dof")
    np.testing.assert_allclose(ds["qtf_omega_1"].values, 2 * np.pi / np.array(chosen),
                               rtol=1e-12)
    assert ds["qtf_omega_1"].attrs["units"] == "rad/s"
    assert "WAMIT .12d" in ds["qtf_difference"].attrs["qtf_source"]
    # an off-diagonal entry: WAMIT's (PER1 = chosen[2] < PER2 = chosen[0]) conjugated
    p1, p2 = chosen[2], chosen[0]
    expected = np.conj((0.3 + 0.01) * complex(math.cos(p1 - p2), math.sin(p1 - p2))) * rho_g
    assert complex(q.values[0, 2, 0, 0]) == pytest.approx(expected, rel=1e-6)
    assert complex(q.values[0, 0, 2, 0]) == pytest.approx(np.conj(expected), rel=1e-6)
    records = json.loads(ds.attrs["source_files_json"])
    assert [r["path"] for r in records][-3:] == [str(files[k]) for k in (".8", ".9", ".12d")]
    assert records[-1]["sha256"] == file_sha256(files[".12d"])
    notes = json.loads(ds.attrs["import_notes_json"])
    assert any("diagonal agrees with" in n for n in notes)

    assert main(["hydro", "info", str(folder / "hydrodb" / "w.nc")]) == 0
    info = capsys.readouterr().out
    assert "mean drift imported from wamit files (the source program's RAOs" in info
    assert "far field (momentum) from" in info and "near field (pressure) from" in info
    assert "body.12d (WAMIT .12d, difference-frequency QTF" in info
    assert main(["hydro", "check", str(folder / "hydrodb" / "w.nc")]) == 0
    assert "drift           pass" in capsys.readouterr().out


def test_one_route_alone_and_the_check_row(wamit_set, deepcwind_db, capsys):
    folder, files, *_ = wamit_set
    nine = {k: v for k, v in files.items() if k not in (".8", ".12d")}
    assert _import(folder, nine, deepcwind_db) == 0
    out = capsys.readouterr().out
    assert "only the near field (pressure) mean drift (imported from wamit files)" in out
    ds = read_database(folder / "hydrodb" / "w.nc")
    assert "mean_drift_far_field" not in ds and has_drift(ds)
    eight = {k: v for k, v in files.items() if k not in (".9", ".12d")}
    assert _import(folder, eight, deepcwind_db, "--force") == 0
    assert "only the far field (momentum) mean drift" in capsys.readouterr().out
    ds = read_database(folder / "hydrodb" / "w.nc")
    assert "mean_drift_near_field" not in ds and has_drift(ds)   # either route is drift


def test_disagreeing_routes_warn_on_import_and_fail_hydro_check(wamit_set, deepcwind_db,
                                                                 capsys):
    folder, files, periods, _ = wamit_set
    betas = np.degrees(deepcwind_db["wave_direction"].values)
    write(folder, "body.8", drift_lines(periods, betas,
                                        lambda *a: 1.3 * drift_nd(*a), modes=(1, 2, 6)))
    files = {k: v for k, v in files.items() if k != ".12d"}
    # 0.3 / 1.3 of the far field's peak; a run uses the route its case chooses: exit 0
    assert _import(folder, files, deepcwind_db) == 0
    captured = capsys.readouterr()
    assert "drift           FAIL" in captured.out
    assert "imported mean drift far and near field differ by 23.1% of the peak" in \
        captured.err
    assert main(["hydro", "check", str(folder / "hydrodb" / "w.nc")]) == 1


def test_yaw_turns_the_drift_and_the_qtf(wamit_set, deepcwind_db):
    folder, files, *_ = wamit_set
    assert _import(folder, files, deepcwind_db) == 0
    plain = read_database(folder / "hydrodb" / "w.nc")
    assert _import(folder, files, deepcwind_db, "--yaw-deg", "90", "--force") == 0
    turned = read_database(folder / "hydrodb" / "w.nc")
    # the file's surge is the case's sway (+x of the file along +y of the case)
    surge = plain["mean_drift_near_field"].sel(influenced_dof="Surge").values
    sway = turned["mean_drift_near_field"].sel(influenced_dof="Sway")
    # the file's headings 0-180 deg are the case's 90-270 deg (the set moved as a whole)
    np.testing.assert_allclose(turned["wave_direction"].values,
                               plain["wave_direction"].values + math.pi / 2, rtol=1e-12)
    np.testing.assert_allclose(sway.values, surge, rtol=1e-12)
    q_plain = merge_complex(plain, "qtf_difference").sel(influenced_dof="Surge").values
    q_turned = merge_complex(turned, "qtf_difference").sel(influenced_dof="Sway").values
    np.testing.assert_allclose(q_turned, q_plain, rtol=1e-12)
    assert turned["qtf_direction"].values[0] == pytest.approx(math.pi / 2)


@pytest.mark.parametrize("kind, edit, fragment", [
    (".12d", lambda text: "\n".join(text.splitlines()[:-2]) + "\n",
     "found none (a hole in the QTF)"),
    (".9", lambda text: text.replace(" 3 ", " 9 ", 1), "a mode index I in 1..6"),
    (".8", lambda text: text + "  5.0  0.0  0.0  1  1.0  0.0  1.0\n", "8 columns"),
])
def test_broken_second_order_file_is_exit_2_one_line_nothing_written(
        wamit_set, deepcwind_db, capsys, kind, edit, fragment):
    folder, files, *_ = wamit_set
    files[kind].write_text(edit(files[kind].read_text()))
    assert _import(folder, files, deepcwind_db) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"floatmoor: error: {files[kind]}"), err
    assert fragment in err[0]
    assert list((folder / "hydrodb").iterdir()) == []


def test_mean_drift_without_the_3_is_refused(wamit_set, deepcwind_db, capsys):
    folder, files, *_ = wamit_set
    del files[".3"]
    assert _import(folder, files, deepcwind_db) == 2
    err = capsys.readouterr().err
    assert "expected the .3 file with it (the mean drift is stored at the excitation's " \
        "wave directions), found no .3" in err
    assert list((folder / "hydrodb").iterdir()) == []


def _bemio_with_drift(path, ds, md_mc=None, md_pi=None):
    import h5py

    write_bemio(path, ds)
    with h5py.File(path, "a") as f:
        base = "body1/hydro_coeffs/mean_drift/"
        for group, values in (("momentum_conservation", md_mc),
                              ("pressure_integration", md_pi)):
            if values is not None:
                f[base + group + "/val"] = values
    return path


def test_bemio_mean_drift_imported(tmp_path, deepcwind_db, capsys):
    (tmp_path / "hydrodb").mkdir()
    n_w, n_h = deepcwind_db.sizes["omega"], deepcwind_db.sizes["wave_direction"]
    rng = np.random.default_rng(3)
    pi = rng.uniform(-1.0, 1.0, (6, n_h, n_w))           # (DOF, direction, frequency) / (rho g)
    mc = pi.copy()
    mc[2:5] = 0.0                                        # BEMIO writes 0 where WAMIT prints none
    h5 = _bemio_with_drift(tmp_path / "b.h5", deepcwind_db, md_mc=mc, md_pi=pi)
    out = tmp_path / "hydrodb" / "b.nc"
    assert main(["hydro", "import", str(h5), "-o", str(out), "--water-density", "1025"]) == 0
    assert "drift           pass" in capsys.readouterr().out
    ds = read_database(out)
    assert ds.attrs["drift_source"] == "bemio"
    near = ds["mean_drift_near_field"].transpose("omega", "wave_direction",
                                                 "influenced_dof").values
    np.testing.assert_allclose(near, np.transpose(pi, (2, 1, 0)) * RHO * G, rtol=1e-12)
    far = ds["mean_drift_far_field"].transpose("omega", "wave_direction",
                                               "influenced_dof").values
    assert np.all(np.isnan(far[..., 2:5]))
    assert "momentum_conservation/val (BEMIO" in ds["mean_drift_far_field"].attrs["drift_source"]
    # a drift dataset of another shape: exit 2, one line naming the HDF5 path
    bad = _bemio_with_drift(tmp_path / "bad.h5", deepcwind_db, md_pi=pi[:, :, :-1])
    assert main(["hydro", "import", str(bad), "-o", str(tmp_path / "hydrodb" / "x.nc"),
                 "--water-density", "1025"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "/body1/hydro_coeffs/mean_drift/pressure_integration/val: " \
        f"expected shape (6, {n_h}, {n_w})" in err[0]
    assert not (tmp_path / "hydrodb" / "x.nc").exists()


def test_bemio_qtf_is_left_out_with_the_reason(tmp_path, deepcwind_db, capsys):
    """BEMIO's QTF groups are not read (their (i, j) orientation depends on the source .12d's
    line order): the import says so and where to go instead, and stores no QTF."""
    import h5py

    (tmp_path / "hydrodb").mkdir()
    n_w, n_h = deepcwind_db.sizes["omega"], deepcwind_db.sizes["wave_direction"]
    pi = np.random.default_rng(4).uniform(-1.0, 1.0, (6, n_h, n_w))
    h5 = _bemio_with_drift(tmp_path / "q.h5", deepcwind_db, md_pi=pi)
    with h5py.File(h5, "a") as f:
        group = "body1/hydro_coeffs/excitation/QTF1/Diff1/"
        f[group + "PER_i"] = np.array([10.0, 8.0])
        f[group + "Re_F_ij"] = np.ones(4)
        f[group + "Im_F_ij"] = np.zeros(4)
    out = tmp_path / "hydrodb" / "q.nc"
    assert main(["hydro", "import", str(h5), "-o", str(out), "--water-density", "1025"]) == 0
    ds = read_database(out)
    notes = " ".join(json.loads(ds.attrs["import_notes_json"]))   # what `hydro info` shows
    assert "excitation/QTF1 (BEMIO's QTFs) not imported" in notes
    assert "import that .12d with the WAMIT files" in notes
    assert "qtf_difference" not in ds and "mean_drift_near_field" in ds


def test_info_of_a_tampered_second_order_database(wamit_set, deepcwind_db, capsys):
    """A database edited by another hand (QTF without its frequency coordinates, a source
    with a terminal escape) still gets its info, escaped, without a traceback."""
    from floatmoor.hydro.database import write_database

    folder, files, *_ = wamit_set
    assert _import(folder, files, deepcwind_db) == 0
    path = folder / "hydrodb" / "w.nc"
    ds = read_database(path).load().drop_vars(["qtf_omega_1", "qtf_omega_2"])
    ds["qtf_difference"].attrs["qtf_source"] = "evil\x1b[31m.12d"
    write_database(ds, path)
    capsys.readouterr()
    assert main(["hydro", "info", str(path)]) == 0
    out = capsys.readouterr().out
    assert "difference-frequency QTF: 3 x 3 frequencies" in out  # xarray's 0, 1, 2: no crash
    assert "from evil\\x1b[31m.12d" in out and "\x1b" not in out


def test_imported_qtf_and_drift_read_by_the_run_lookups(wamit_set, deepcwind_db):
    """What the import writes is what a run reads: the time domain's lookups
    (floatmoor.hydro.second_order) give the imported QTF and mean drift back unchanged."""
    from floatmoor.hydro.second_order import DriftLookup, QTFLookup, missing_coefficients

    folder, files, periods, chosen = wamit_set
    assert _import(folder, files, deepcwind_db) == 0
    ds = read_database(folder / "hydrodb" / "w.nc")
    for model, route in (("mean", "far_field"), ("newman", "near_field"), ("full", "far_field")):
        assert missing_coefficients(ds, model, route) is None
    q = merge_complex(ds, "qtf_difference").sel(qtf_direction=0.0)
    np.testing.assert_array_equal(QTFLookup(ds).at(0.0),
                                  q.transpose("qtf_omega_1", "qtf_omega_2",
                                              "influenced_dof").values)
    lookup = DriftLookup(ds, "near_field")
    near = ds["mean_drift_near_field"].transpose("omega", "wave_direction",
                                                 "influenced_dof").values
    w = ds["omega"].values
    np.testing.assert_allclose(lookup.at(np.array([w[5]]), np.array([0.0]))[0], near[5, 0],
                               rtol=1e-12)
