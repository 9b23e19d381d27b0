"""The BEMIO reader on hostile .h5 files (docs/guide/safeguards.md#files-from-elsewhere): a
dataset whose bytes live in another file (external raw storage, a virtual dataset, an external
or soft link) is refused and that file's bytes never reach the result; datasets are refused by
type and shape before their data are read (a few-kB file declaring gigabytes); odd names and
FIFOs give one line naming the file, never a traceback. Files are built tiny with h5py."""

from __future__ import annotations

import os
from pathlib import Path

import h5py
import numpy as np
import pytest

from floatmoor.cli import main
from floatmoor.io.bem_data import BemFileError
from floatmoor.io.bemio import MAX_READ_BYTES, read_bemio
from tests.io.test_bemio import _hydro, _write

STIFFNESS = "body1/hydro_coeffs/linear_restoring_stiffness"


@pytest.fixture
def decoy(tmp_path) -> Path:
    """A file outside the BEMIO file whose 36 float64 would pass every value check."""
    path = tmp_path / "decoy.bin"
    path.write_bytes(np.full(36, 7.25e3).tobytes())
    return path


@pytest.fixture
def bemio(tmp_path, rng) -> Path:
    return _write(tmp_path / "hostile.h5", _hydro(rng, 1))


def _error(path, **kwargs) -> str:
    with pytest.raises(BemFileError) as info:
        read_bemio(path, **kwargs)
    message = str(info.value)
    assert message.startswith(f"{path}: ") and "\n" not in message
    return message


def test_external_raw_storage_is_refused_unread(bemio, decoy):
    with h5py.File(bemio, "r+") as f:
        del f[STIFFNESS]
        f.create_dataset(STIFFNESS, (6, 6), "<f8", external=[(str(decoy), 0, 36 * 8)])
        assert np.all(f[STIFFNESS][()] == 7.25e3)  # HDF5 itself would read the decoy
    message = _error(bemio)
    assert f"/{STIFFNESS}: expected a dataset" in message
    assert "external raw storage" in message


def test_external_raw_storage_of_bytes_is_refused(bemio, decoy):
    """The probe's /etc/passwd as uint8: refused (type and storage), whatever its values."""
    with h5py.File(bemio, "r+") as f:
        del f[STIFFNESS]
        f.create_dataset(STIFFNESS, (6, 6), "u1", external=[(str(decoy), 0, 36)])
    assert "external raw storage" in _error(bemio)


def test_integer_data_is_refused_by_type(bemio):
    with h5py.File(bemio, "r+") as f:
        del f[STIFFNESS]
        f[STIFFNESS] = np.arange(36, dtype="u1").reshape(6, 6)
    assert f"/{STIFFNESS}: expected floating-point numbers" in _error(bemio)


def test_virtual_dataset_is_refused(bemio, tmp_path):
    other = tmp_path / "other.h5"
    with h5py.File(other, "w") as f:
        f["k"] = np.full((6, 6), 3.0)
    layout = h5py.VirtualLayout(shape=(6, 6), dtype="f8")
    layout[:] = h5py.VirtualSource(str(other), "k", shape=(6, 6))
    with h5py.File(bemio, "r+") as f:
        del f[STIFFNESS]
        f.create_virtual_dataset(STIFFNESS, layout)
    assert "a virtual dataset" in _error(bemio)


def test_external_link_is_not_followed(bemio, tmp_path):
    other = tmp_path / "other.h5"
    with h5py.File(other, "w") as f:
        f["k"] = np.full((6, 6), 3.0)
    with h5py.File(bemio, "r+") as f:
        del f[STIFFNESS]
        f[STIFFNESS] = h5py.ExternalLink(str(other), "/k")
    assert "an external link to another file" in _error(bemio)


def test_soft_link_loop_is_one_line_exit_2(bemio, capsys):
    with h5py.File(bemio, "r+") as f:
        del f["body1/hydro_coeffs/added_mass"]
        f["body1/hydro_coeffs/added_mass"] = h5py.SoftLink("/body1/hydro_coeffs/loop")
        f["body1/hydro_coeffs/loop"] = h5py.SoftLink("/body1/hydro_coeffs/added_mass")
    assert "/body1/hydro_coeffs/added_mass: expected" in _error(bemio)
    out = bemio.parent / "hydrodb" / "x.nc"
    out.parent.mkdir()
    assert main(["hydro", "import", str(bemio), "-o", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("floatmoor: error: ") and "soft link" in err[0]
    assert not out.exists()


def test_declared_shape_is_checked_before_reading(bemio):
    """(6, 6, 2e9) float64, compressed, in a few kB: refused by shape, nothing allocated."""
    with h5py.File(bemio, "r+") as f:
        del f["body1/hydro_coeffs/added_mass/all"]
        f.create_dataset("body1/hydro_coeffs/added_mass/all", (6, 6, 2_000_000_000), "f8",
                         chunks=(1, 1, 1 << 20), compression="gzip")
    assert os.path.getsize(bemio) < 1 << 20
    message = _error(bemio)
    assert "expected shape (6, 6, 5)" in message and "found shape (6, 6, 2000000000)" in message


def test_declared_frequencies_are_bounded_before_reading(bemio):
    n = MAX_READ_BYTES // 8 + 1
    with h5py.File(bemio, "r+") as f:
        for name in ("w", "T"):
            del f["simulation_parameters/" + name]
            f.create_dataset("simulation_parameters/" + name, (n, 1), "f8", chunks=(1 << 16, 1),
                             compression="gzip", fillvalue=1.0)
    message = _error(bemio)
    assert "/simulation_parameters/w: expected at most" in message


def test_huge_string_is_refused_before_reading(bemio):
    """A 3e9-byte fixed-length string, compressed to a few kB, is refused by its type."""
    with h5py.File(bemio, "r+") as f:
        del f["bem_data/code"]
        string = h5py.h5t.C_S1.copy()
        string.set_size(3_000_000_000)  # beyond numpy's dtypes: made with the low-level API
        plist = h5py.h5p.create(h5py.h5p.DATASET_CREATE)
        plist.set_chunk((1,))
        plist.set_deflate(6)
        h5py.h5d.create(f["bem_data"].id, b"code", string, h5py.h5s.create_simple((1,)),
                        plist)
    assert os.path.getsize(bemio) < 1 << 20
    message = _error(bemio)
    assert "/bem_data/code: expected a string of at most 4096 bytes" in message


def test_names_with_escapes_and_5000_digit_groups(tmp_path):
    path = tmp_path / "odd.h5"
    with h5py.File(path, "w") as f:
        f.create_group("body" + "9" * 5000)
        f.create_group("\x1b]0;owned\x07")
    message = _error(path)
    assert "\x1b" not in message and "\\x1b]0;owned\\x07" in message
    assert "more characters)" in message  # the 5000-digit name is cut


def test_escapes_in_a_body_name_are_shown_escaped(tmp_path, rng):
    hydro = _hydro(rng, 2)
    hydro["names"] = ["a", "b"]
    path = _write(tmp_path / "two.h5", hydro)
    with h5py.File(path, "r+") as f:
        for k, name in ((1, "a\x1b[2Jb"), (2, "c\u202ed")):
            del f[f"body{k}/properties/name"]
            f[f"body{k}/properties/name"] = name  # a variable-length UTF-8 string
    message = _error(path)
    assert "a\\x1b[2Jb" in message and "c\\u202ed" in message


@pytest.mark.parametrize("kind, found", [("fifo", "a FIFO (named pipe)"),
                                         ("device", "a character device")])
def test_fifo_and_device_are_refused_unopened(tmp_path, kind, found):
    path = tmp_path / "x.h5"
    if kind == "fifo":
        os.mkfifo(path)
    else:
        path.symlink_to("/dev/zero")
    assert f"found {found}, not a regular file" in _error(path)


@pytest.mark.parametrize("where, data, found", [
    ("simulation_parameters/rho", h5py.Empty("f8"), "found an empty (null) dataset"),
    ("bem_data/code", h5py.Empty("S5"), "found an empty (null) dataset"),
    ("simulation_parameters/g", np.array([[9.81]], dtype=[("a", "f8")]),
     "expected floating-point numbers (gravity [m/s^2]), found data of type another type"),
])
def test_null_and_compound_datasets_are_one_line(bemio, where, data, found):
    with h5py.File(bemio, "r+") as f:
        del f[where]
        f[where] = data
    assert found in _error(bemio)
