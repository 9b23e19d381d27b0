"""The checkpoint format (floatmoor.simulation.checkpoint): plain arrays written atomically,
read back exactly, and refused -- with a message saying why -- when anything differs from
what the run resuming it expects."""

from __future__ import annotations

import zipfile

import numpy as np
import pytest

from floatmoor.errors import CaseError
from floatmoor.simulation import checkpoint as ck

IDENTITY = ck.RunIdentity.of("title = 'a'\n", ["a=1", "b=2"], "settings", "case.toml")
ARRAYS = {"state/x": np.array([1.0, -0.0, 1e-300]), "state/n": np.array(3, dtype=np.int64),
          "recorded/f": np.arange(6.0).reshape(2, 3)}
EXPECTED = {k: (v.shape, v.dtype) for k, v in ARRAYS.items()}


def test_round_trip_is_exact_and_leaves_no_temporary(tmp_path) -> None:
    path = tmp_path / "run.nc.checkpoint"
    ck.write_checkpoint(path, ARRAYS, IDENTITY)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run.nc.checkpoint"]
    back = ck.read_checkpoint(path, IDENTITY, EXPECTED)
    for k, v in ARRAYS.items():
        assert back[k].dtype == v.dtype and np.array_equal(back[k], v)
        assert back[k].tobytes() == v.tobytes()  # -0.0 and subnormals too


def test_object_arrays_are_never_written(tmp_path) -> None:
    path = tmp_path / "c"
    with pytest.raises(ValueError, match="objects"):
        ck.write_checkpoint(path, {"state/x": np.array([object()])}, IDENTITY)
    assert not list(tmp_path.iterdir())


def test_a_failed_write_removes_its_temporary_and_keeps_the_old_checkpoint(tmp_path,
                                                                          monkeypatch) -> None:
    path = tmp_path / "c"
    ck.write_checkpoint(path, ARRAYS, IDENTITY)
    before = path.read_bytes()

    def full(*args, **kwargs):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(np, "savez", full)
    with pytest.raises(OSError):
        ck.write_checkpoint(path, ARRAYS, IDENTITY)
    assert path.read_bytes() == before
    assert [p.name for p in tmp_path.iterdir()] == ["c"]  # no temporary left


@pytest.mark.parametrize("identity, message", [
    (ck.RunIdentity.of("title = 'b'\n", ["a=1", "b=2"], "settings", "case.toml"),
     "the case file case.toml has changed"),
    (ck.RunIdentity.of("title = 'a'\n", ["a=1", "b=3"], "settings", "case.toml"),
     "the checkpoint's run had --set b=2; this run has --set b=3"),
    (ck.RunIdentity.of("title = 'a'\n", ["a=1"], "settings", "case.toml"),
     "the checkpoint's run had --set b=2"),
    (ck.RunIdentity.of("title = 'a'\n", ["b=2", "a=1"], "settings", "case.toml"),
     "the same ones in another order"),
    (ck.RunIdentity.of("title = 'a'\n", ["a=1", "b=2"], "other", "case.toml"),
     "the run settings differ"),
])
def test_another_runs_checkpoint_names_what_differs(tmp_path, identity, message) -> None:
    path = tmp_path / "c"
    ck.write_checkpoint(path, ARRAYS, IDENTITY)
    for check in (lambda: ck.check_checkpoint(path, identity),
                  lambda: ck.read_checkpoint(path, identity, EXPECTED)):
        with pytest.raises(ck.CheckpointError, match="of another run") as err:
            check()
        assert message in str(err.value) and "without --resume to start over" in str(err.value)
        assert isinstance(err.value, CaseError)  # bad input: exit 2


def _rewrite(path, **changes) -> None:
    """Rewrite the checkpoint with members replaced (None: removed)."""
    with np.load(path, allow_pickle=False) as npz:
        members = {k: npz[k] for k in npz.files}
    for k, v in changes.items():
        key = k.replace("__", "/")
        if v is None:
            members.pop(key)
        else:
            members[key] = v
    with open(path, "wb") as fh:
        np.savez(fh, **members)


@pytest.mark.parametrize("changes, message", [
    ({"meta__version": np.array(1, dtype=np.int64)}, "found version 1"),
    ({"meta__format": np.array("something else")}, "of format 'something else'"),
    ({"meta__format": None}, "without 'meta/format'"),
    ({"meta__floatmoor_version": np.array("0.0.1")}, "written by floatmoor 0.0.1"),
    ({"state__x": np.array([1.0, np.nan, 0.0])}, "finite values in array 'state/x'"),
    ({"state__x": np.zeros(4)}, "array 'state/x' of shape (3,)"),
    ({"state__n": np.array(3, dtype=np.int32)}, "dtype int64"),
    ({"state__n": None}, "no array state/n"),
    ({"state__extra": np.zeros(1)}, "unexpected array state/extra"),
])
def test_a_checkpoint_that_does_not_fit_is_refused(tmp_path, changes, message) -> None:
    path = tmp_path / "c"
    ck.write_checkpoint(path, ARRAYS, IDENTITY)
    _rewrite(path, **changes)
    with pytest.raises(ck.CheckpointError) as err:
        ck.read_checkpoint(path, IDENTITY, EXPECTED)
    assert message in str(err.value) and str(err.value).startswith(f"{path}: ")


def test_a_member_that_is_not_an_array_is_refused(tmp_path) -> None:
    path = tmp_path / "c"
    ck.write_checkpoint(path, ARRAYS, IDENTITY)
    with zipfile.ZipFile(path, "a") as zf:
        zf.writestr("payload.pkl", b"\x80\x04K\x01.")
    with pytest.raises(ck.CheckpointError, match="'payload.pkl' is not an array"):
        ck.check_checkpoint(path, IDENTITY)


def test_a_corrupted_array_is_refused(tmp_path) -> None:
    """A flipped byte inside an array's data fails the zip's CRC: refused, not read as
    other numbers."""
    path = tmp_path / "c"
    ck.write_checkpoint(path, ARRAYS, IDENTITY)
    data = bytearray(path.read_bytes())
    at = bytes(data).index(np.array([1.0, -0.0, 1e-300]).tobytes())
    data[at + 3] ^= 0xFF
    path.write_bytes(bytes(data))
    with pytest.raises(ck.CheckpointError, match="damaged"):
        ck.read_checkpoint(path, IDENTITY, EXPECTED)
