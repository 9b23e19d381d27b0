"""The WEC-Sim BEMIO reader (floatmoor.io.bemio) on files this test writes with h5py in the
layout of WEC-Sim's writeBEMIOH5.m: literal HDF5 paths, MATLAB's permute-then-column-major
order, normalised values. Read back, every array must equal what was written, dimensional
and in floatmoor's order and phase convention; broken files must name the HDF5 path."""

from __future__ import annotations

import math
from pathlib import Path

import h5py
import numpy as np
import pytest

from floatmoor.io.bem_data import BemFileError
from floatmoor.io.bemio import read_bemio

RHO, G = 1025.0, 9.81
W = np.array([0.2, 0.5, 0.9, 1.4, 2.0])            # [rad/s]
THETA = np.array([0.0, 45.0, 180.0])               # [deg]


def _matlab(values) -> np.ndarray:
    """What h5py reads back from an array MATLAB's h5write stored (column-major): the array
    with its dimensions reversed."""
    return np.transpose(np.atleast_2d(np.asarray(values, dtype=float)))


def _hydro(rng, n_bodies: int) -> dict:
    """A BEMIO ``hydro`` structure (MATLAB index order, normalised), random and asymmetric."""
    n, nf, nh = 6 * n_bodies, W.size, THETA.size
    return {
        "A": rng.normal(size=(n, n, nf)), "Ainf": rng.normal(size=(n, n)),
        "B": rng.normal(size=(n, n, nf)), "Khs": rng.normal(size=(6, 6, n_bodies)),
        "ex_re": rng.normal(size=(n, nh, nf)), "ex_im": rng.normal(size=(n, nh, nf)),
        "fk_re": rng.normal(size=(n, nh, nf)), "fk_im": rng.normal(size=(n, nh, nf)),
        "cg": rng.normal(size=(3, n_bodies)), "cb": rng.normal(size=(3, n_bodies)),
        "Vo": rng.uniform(1.0, 9.0, size=n_bodies), "names": [f"float{k}" for k in
                                                               range(1, n_bodies + 1)],
    }


def _write(path: Path, hydro: dict, *, w=W, theta=THETA, depth=80.0, code="CAPYTAINE",
           parts=True) -> Path:
    """writeBEMIOH5.m transcribed: datasets, their MATLAB shapes and permutations."""
    n_bodies = len(hydro["names"])
    hydro = dict(hydro)
    hydro["sc_re"] = hydro["ex_re"] - hydro["fk_re"]
    hydro["sc_im"] = hydro["ex_im"] - hydro["fk_im"]
    with h5py.File(path, "w") as f:
        f["bem_data/code"] = np.bytes_(code)
        sp = "simulation_parameters/"
        f[sp + "scaled"] = _matlab(0.0)
        f[sp + "g"] = _matlab(G)
        f[sp + "rho"] = _matlab(RHO)
        f[sp + "T"] = _matlab(2 * np.pi / w)           # hydro.T, a 1 x Nf row
        f[sp + "w"] = _matlab(w)
        if math.isinf(depth):
            f[sp + "water_depth"] = np.bytes_("infinite")
        else:
            f[sp + "water_depth"] = _matlab(depth)
        f[sp + "wave_dir"] = _matlab(theta)
        f[sp + "wave_dir"].attrs["units"] = "deg"
        for i in range(1, n_bodies + 1):
            b = f"body{i}/"
            rows = slice(6 * (i - 1), 6 * i)
            f[b + "properties/name"] = np.bytes_(hydro["names"][i - 1])
            f[b + "properties/body_number"] = _matlab(i)
            f[b + "properties/cb"] = _matlab(hydro["cb"][:, i - 1][None, :])
            f[b + "properties/cg"] = _matlab(hydro["cg"][:, i - 1][None, :])
            f[b + "properties/disp_vol"] = _matlab(hydro["Vo"][i - 1])
            f[b + "properties/dof"] = _matlab(6)
            f[b + "properties/dof_start"] = _matlab(6 * (i - 1) + 1)
            f[b + "properties/dof_end"] = _matlab(6 * i)
            c = b + "hydro_coeffs/"
            f[c + "linear_restoring_stiffness"] = _matlab(hydro["Khs"][:, :, i - 1].T)
            f[c + "added_mass/inf_freq"] = _matlab(np.transpose(hydro["Ainf"][rows, :]))
            f[c + "added_mass/all"] = _matlab(np.transpose(hydro["A"][rows], (2, 1, 0)))
            f[c + "radiation_damping/all"] = _matlab(np.transpose(hydro["B"][rows],
                                                                  (2, 1, 0)))
            for key, where in (("ex_re", "excitation/re"), ("ex_im", "excitation/im"),
                               ("sc_re", "excitation/scattering/re"),
                               ("sc_im", "excitation/scattering/im"),
                               ("fk_re", "excitation/froude-krylov/re"),
                               ("fk_im", "excitation/froude-krylov/im")):
                if parts or key.startswith("ex"):
                    f[c + where] = _matlab(np.transpose(hydro[key][rows], (2, 1, 0)))
    return path


def _check_body(bem, hydro, k: int, *, rho=RHO) -> None:
    """Every array of body ``k`` (1-based) against the hydro structure written."""
    rows = cols = slice(6 * (k - 1), 6 * k)
    np.testing.assert_allclose(bem.omega, W, rtol=1e-15)
    for f in range(W.size):
        # floatmoor [f, radiating j, influenced i] = BEMIO A(i, j, f) x rho
        np.testing.assert_allclose(bem.added_mass[f], hydro["A"][rows, cols, f].T * rho,
                                   rtol=1e-14)
        np.testing.assert_allclose(bem.radiation_damping[f],
                                   hydro["B"][rows, cols, f].T * rho * W[f], rtol=1e-14)
        for h in range(THETA.size):
            x = hydro["ex_re"][rows, h, f] + 1j * hydro["ex_im"][rows, h, f]
            np.testing.assert_allclose(bem.excitation_force[f, h], np.conj(x) * rho * G,
                                       rtol=1e-14)
            fk = hydro["fk_re"][rows, h, f] + 1j * hydro["fk_im"][rows, h, f]
            np.testing.assert_allclose(bem.froude_krylov_force[f, h], np.conj(fk) * rho * G,
                                       rtol=1e-14)
            np.testing.assert_allclose(bem.diffraction_force[f, h],
                                       np.conj(x - fk) * rho * G, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(bem.added_mass_infinite, hydro["Ainf"][rows, cols].T * rho,
                               rtol=1e-14)
    np.testing.assert_allclose(bem.hydrostatic_stiffness, hydro["Khs"][:, :, k - 1] * rho * G,
                               rtol=1e-14)
    np.testing.assert_allclose(bem.directions, np.radians(THETA), rtol=1e-15)
    np.testing.assert_array_equal(bem.center_of_gravity, hydro["cg"][:, k - 1])
    np.testing.assert_array_equal(bem.rotation_center, hydro["cg"][:, k - 1])
    np.testing.assert_array_equal(bem.center_of_buoyancy, hydro["cb"][:, k - 1])
    assert bem.disp_volume == hydro["Vo"][k - 1]
    assert bem.body_name == hydro["names"][k - 1]
    assert bem.water_density == rho and bem.gravity == G
    assert bem.added_mass_zero is None


def test_single_body_round_trip(tmp_path, rng):
    hydro = _hydro(rng, 1)
    path = _write(tmp_path / "one.h5", hydro)
    bem = read_bemio(path)
    _check_body(bem, hydro, 1)
    assert bem.format == "bemio" and bem.files == (str(path),)
    assert bem.water_depth == 80.0
    assert bem.added_mass.shape == (W.size, 6, 6)
    assert bem.excitation_force.shape == (W.size, THETA.size, 6)
    # the index order is really exercised: the written matrices are not symmetric
    assert not np.allclose(bem.added_mass[0], bem.added_mass[0].T)
    assert any("BEMIO's estimate" in note for note in bem.notes)


def test_two_body_file_selects_body_2(tmp_path, rng):
    hydro = _hydro(rng, 2)
    path = _write(tmp_path / "two.h5", hydro)
    bem = read_bemio(path, body=2)
    _check_body(bem, hydro, 2)
    assert any("Body 2 of 2" in note and "dropped" in note for note in bem.notes)
    _check_body(read_bemio(path, body=1), hydro, 1)
    with pytest.raises(BemFileError) as info:
        read_bemio(path)
    assert str(info.value) == (f"{path}: expected a body number (the file has 2 bodies: "
                               "1 'float1', 2 'float2'), found none given")
    with pytest.raises(BemFileError, match=r"/body3: expected one of the file's bodies 1\.\.2"):
        read_bemio(path, body=3)


def test_unsorted_frequencies_infinite_depth_and_density(tmp_path, rng):
    hydro = _hydro(rng, 1)
    perm, heads = np.array([3, 0, 4, 2, 1]), np.array([2, 0, 1])
    shuffled = {**hydro, **{k: hydro[k][..., perm] for k in ("A", "B")},
                **{k: hydro[k][:, heads][..., perm] for k in ("ex_re", "ex_im", "fk_re",
                                                              "fk_im")}}
    path = _write(tmp_path / "s.h5", shuffled, w=W[perm], theta=THETA[heads],
                  depth=math.inf)
    bem = read_bemio(path, water_density=1000.0)
    _check_body(bem, hydro, 1, rho=1000.0)
    assert bem.water_depth == math.inf
    assert any("sorted" in note for note in bem.notes)


def test_parts_absent_or_not_computed(tmp_path, rng):
    hydro = _hydro(rng, 1)
    bem = read_bemio(_write(tmp_path / "p.h5", hydro, parts=False))
    assert bem.froude_krylov_force is None and bem.diffraction_force is None
    path = _write(tmp_path / "nan.h5", hydro)
    with h5py.File(path, "r+") as f:
        for part in ("froude-krylov", "scattering"):
            for c in ("re", "im"):
                f[f"body1/hydro_coeffs/excitation/{part}/{c}"][...] = np.nan
    bem = read_bemio(path)
    assert bem.froude_krylov_force is None and bem.excitation_force is not None
    assert any("all NaN" in note for note in bem.notes)


# --- broken files ----------------------------------------------------------------------

def _broken(tmp_path, rng, edit) -> BemFileError:
    path = _write(tmp_path / "b.h5", _hydro(rng, 1))
    with h5py.File(path, "r+") as f:
        edit(f)
    with pytest.raises(BemFileError) as info:
        read_bemio(path)
    assert str(info.value).startswith(f"{path}: ")
    return info.value


def _replace(where, values):
    def edit(f):
        del f[where]
        f[where] = values
    return edit


def _set(where, index, value):
    def edit(f):
        data = f[where][()]
        data[index] = value
        f[where][...] = data
    return edit


@pytest.mark.parametrize("edit, message", [
    (lambda f: f.__delitem__("body1/hydro_coeffs/added_mass/inf_freq"),
     "/body1/hydro_coeffs/added_mass/inf_freq: expected a dataset (infinite-frequency added "
     "mass / rho), found none"),
    (lambda f: f.__delitem__("simulation_parameters/rho"),
     "/simulation_parameters/rho: expected a dataset"),
    (_replace("body1/hydro_coeffs/radiation_damping/all", np.zeros((6, 6, 4))),
     "/body1/hydro_coeffs/radiation_damping/all: expected shape (6, 6, 5) (radiation damping "
     "/ (rho omega)), found shape (6, 6, 4)"),
    (_replace("body1/hydro_coeffs/excitation/im", np.zeros((6, 5, 3))),
     "/body1/hydro_coeffs/excitation/im: expected shape (6, 3, 5)"),
    (_replace("body1/hydro_coeffs/linear_restoring_stiffness", np.zeros((6, 6, 1))),
     "linear_restoring_stiffness: expected shape (6, 6)"),
    (_set("body1/hydro_coeffs/excitation/re", (2, 1, 3), np.nan),
     "/body1/hydro_coeffs/excitation/re: expected finite numbers, found nan at index "
     "[2, 1, 3] (1 such value)"),
    (_set("body1/hydro_coeffs/added_mass/all", (0, 0, 0), np.inf),
     "added_mass/all: expected finite numbers, found inf at index [0, 0, 0]"),
    (_set("body1/hydro_coeffs/excitation/froude-krylov/im", (0, 0, 0), np.nan),
     "froude-krylov/im: expected finite numbers, found nan"),
    (_set("body1/hydro_coeffs/excitation/scattering/re", (1, 0, 0), 99.0),
     "excitation/re, im: expected froude-krylov + scattering"),
    (_set("simulation_parameters/w", (1, 0), -0.5),
     "/simulation_parameters/w: expected frequencies > 0 [rad/s], found -0.5 at index 1"),
    (_replace("simulation_parameters/w", _matlab([0.2, 0.5, 0.5, 1.4, 2.0])),
     "/simulation_parameters/T: expected the periods 2 pi / w"),
    (_replace("simulation_parameters/T", _matlab(2 * np.pi / W[:4])),
     "/simulation_parameters/T: expected 5 values (wave periods [s]), found 4"),
    (_set("simulation_parameters/scaled", (0, 0), 1.0),
     "/simulation_parameters/scaled: expected 0 (coefficients normalised by rho and g"),
    (_replace("simulation_parameters/water_depth", np.bytes_("deep")),
     "water_depth: expected a depth [m] or the string 'infinite', found 'deep'"),
    (_replace("body1/properties/dof", _matlab(8)),
     "/body1/properties/dof_end: expected dof_start + dof - 1 = 8, found 6"),
    (lambda f: f.move("body1", "body2"), "/: expected body groups numbered 1..1, found body2"),
])
def test_broken_files_name_the_path(tmp_path, rng, edit, message):
    assert message in str(_broken(tmp_path, rng, edit))


def test_repeated_frequencies(tmp_path, rng):
    w = np.array([0.2, 0.5, 0.5, 1.4, 2.0])

    def edit(f):
        for name, values in (("w", w), ("T", 2 * np.pi / w)):
            del f["simulation_parameters/" + name]
            f["simulation_parameters/" + name] = _matlab(values)
    err = _broken(tmp_path, rng, edit)
    assert "/simulation_parameters/w: expected distinct frequencies, found 0.5 rad/s more " \
           "than once" in str(err)


def test_not_a_bemio_file(tmp_path):
    with pytest.raises(BemFileError, match="no such file"):
        read_bemio(tmp_path / "none.h5")
    text = tmp_path / "text.h5"
    text.write_text("not HDF5")
    with pytest.raises(BemFileError, match=r"text\.h5: expected an HDF5 file \(WEC-Sim BEMIO "
                       r"\.h5\), found a file HDF5 cannot open"):
        read_bemio(text)
    other = tmp_path / "other.h5"
    with h5py.File(other, "w") as f:
        f["data"] = np.zeros(3)
    with pytest.raises(BemFileError, match=r"other\.h5: /: expected groups body1, body2, \.\.\. "
                       r"\(a WEC-Sim BEMIO file\), found none; top-level entries: data"):
        read_bemio(other)
    with pytest.raises(ValueError):
        read_bemio(other, body=0)
