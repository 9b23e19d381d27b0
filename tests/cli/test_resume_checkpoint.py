"""``floatmoor run --resume`` with checkpoints that are not this run's own: a
crafted pickle is never unpickled, an empty, truncated or foreign file is one
message with status 2, another run's checkpoint names the overrides that differ; nothing is
run, and the partial results and the checkpoint are left as they were."""

from __future__ import annotations

import os
import pickle
import subprocess
import sys
import zipfile
from pathlib import Path

import numpy as np
import pytest

from floatmoor.cli import main
from tests.conftest import CASES, REPO

BUOY_CASE = CASES / "cylinder_buoy" / "buoy_regular_T1.20.toml"
WAVES = 'waves={kind = "regular", height = 0.04, period = 1.2}'
RUN = ["--set", "simulation.duration=1.0", "--set", "simulation.output_interval=0.02",
       "--set", 'lines.*.model="quasi-static"', "--set", WAVES]


@pytest.fixture(scope="module")
def interrupted(tmp_path_factory) -> tuple[Path, bytes, bytes]:
    """A floater run stopped after 30 body steps: (its output, the partial file's bytes, the
    checkpoint's bytes)."""
    from tests.simulation.interrupted import interrupt_at_body_step

    folder = tmp_path_factory.mktemp("interrupted")
    out = folder / "cut.nc"
    with pytest.MonkeyPatch.context() as patch:
        interrupt_at_body_step(patch, 30)
        assert main(["run", str(BUOY_CASE), "-o", str(out), "--quiet"] + RUN) == 130
    return out, out.read_bytes(), Path(f"{out}.checkpoint").read_bytes()


def _copy(interrupted, folder: Path, checkpoint: bytes | None = None) -> Path:
    """The interrupted run's output in ``folder``, with its checkpoint or ``checkpoint``."""
    out, partial, original = interrupted
    target = folder / out.name
    target.write_bytes(partial)
    Path(f"{target}.checkpoint").write_bytes(original if checkpoint is None else checkpoint)
    return target


def _resume(out: Path, capsys, extra: list[str] = ()) -> tuple[int, str]:
    status = main(["run", str(BUOY_CASE), "-o", str(out), "--quiet", "--resume"] + RUN
                  + list(extra))
    return status, capsys.readouterr().err


def _assert_untouched(out: Path, interrupted, checkpoint: bytes | None = None) -> None:
    _, partial, original = interrupted
    assert out.read_bytes() == partial
    assert Path(f"{out}.checkpoint").read_bytes() == (original if checkpoint is None
                                                     else checkpoint)


def test_checkpoint_is_numeric_arrays_only(interrupted) -> None:
    """Every member of a checkpoint is a ``.npy`` array that loads without pickle, with the
    format, its version and the run's overrides."""
    _, _, data = interrupted
    path = interrupted[0].parent / "probe.npz"
    path.write_bytes(data)
    with zipfile.ZipFile(path) as zf:
        assert all(name.endswith(".npy") for name in zf.namelist())
    with np.load(path, allow_pickle=False) as npz:
        arrays = {name: npz[name] for name in npz.files}
    assert not any(a.dtype.hasobject for a in arrays.values())
    assert str(arrays["meta/format"]) == "floatmoor coupled-run checkpoint"
    assert int(arrays["meta/version"]) == 2
    assert WAVES in [str(o) for o in arrays["meta/overrides"]]
    assert "state/body/position" in arrays and "state/line0/warm_start" in arrays


class _CreatesFile:
    """Unpickled, creates the file ``path``."""

    def __init__(self, path: Path) -> None:
        self.path = path

    def __reduce__(self):
        return (open, (str(self.path), "w"))


def test_crafted_pickle_checkpoint_is_never_unpickled(tmp_path, capsys, interrupted) -> None:
    marker = tmp_path / "pwned"
    crafted = pickle.dumps({"moored": _CreatesFile(marker)})
    out = _copy(interrupted, tmp_path, crafted)
    status, err = _resume(out, capsys)
    assert status == 2 and not marker.exists()
    assert "a pickle, which is never loaded" in err and "without --resume" in err
    assert "Traceback" not in err and "partial results" not in err
    _assert_untouched(out, interrupted, crafted)


def test_npz_with_an_object_array_is_refused_unread(tmp_path, capsys, interrupted) -> None:
    """A zip of arrays holding a pickled object array (as ``np.savez`` writes one) is refused
    from its header: the object is never unpickled."""
    marker = tmp_path / "pwned"
    crafted = tmp_path / "crafted.npz"
    with np.load(Path(f"{interrupted[0]}.checkpoint"), allow_pickle=False) as npz:
        arrays = {name: npz[name] for name in npz.files}
    arrays["state/body/position"] = np.array([_CreatesFile(marker)], dtype=object)
    with open(crafted, "wb") as fh:
        np.savez(fh, **arrays)
    out = _copy(interrupted, tmp_path, crafted.read_bytes())
    status, err = _resume(out, capsys)
    assert status == 2 and not marker.exists()
    assert "object array 'state/body/position'" in err and "Traceback" not in err
    _assert_untouched(out, interrupted, crafted.read_bytes())


@pytest.mark.parametrize("damage, message", [
    (lambda data: b"", "an empty file"),
    (lambda data: data[:len(data) // 2], "damaged or truncated"),
    (lambda data: data[:-40], "damaged or truncated"),
    (lambda data: b"CDF\x02" + data[4:200], "another kind of file"),
])
def test_empty_truncated_or_foreign_checkpoint_is_one_message(tmp_path, capsys, interrupted,
                                                              damage, message) -> None:
    bad = damage(interrupted[2])
    out = _copy(interrupted, tmp_path, bad)
    status, err = _resume(out, capsys)
    lines = err.strip().splitlines()
    assert status == 2 and len(lines) == 1, err
    assert lines[0].startswith(f"floatmoor: error: {out}.checkpoint: ") and message in err
    assert "Traceback" not in err
    _assert_untouched(out, interrupted, bad)


def test_checkpoint_with_a_misshapen_array_names_it(tmp_path, capsys, interrupted) -> None:
    """A checkpoint of this run whose state does not fit it (an array reshaped, one missing)
    names the array."""
    with np.load(Path(f"{interrupted[0]}.checkpoint"), allow_pickle=False) as npz:
        arrays = {name: npz[name] for name in npz.files}
    reshaped = dict(arrays, **{"state/body/history": arrays["state/body/history"][:-1]})
    missing = {k: v for k, v in arrays.items() if k != "state/line1/warm_start"}
    for crafted, name in ((reshaped, "state/body/history"),
                          (missing, "state/line1/warm_start")):
        path = tmp_path / "crafted.npz"
        with open(path, "wb") as fh:
            np.savez(fh, **crafted)
        out = _copy(interrupted, tmp_path, path.read_bytes())
        status, err = _resume(out, capsys)
        assert status == 2 and name in err and "Traceback" not in err, err
        _assert_untouched(out, interrupted, path.read_bytes())


def test_checkpoint_of_other_overrides_names_them(tmp_path, capsys, interrupted) -> None:
    """Resumed with another wave height, the message names both overrides; the checkpoint
    is kept for the run it belongs to."""
    out = _copy(interrupted, tmp_path)
    other = 'waves={kind = "regular", height = 0.05, period = 1.2}'
    status, err = _resume(out, capsys, ["--set", other])
    assert status == 2 and "Traceback" not in err
    assert "the --set overrides differ" in err
    assert f"this run has --set {other}" in err
    assert "without --resume to start over" in err
    _assert_untouched(out, interrupted)
    # without the extra override it is this run's: it resumes and completes
    status, err = _resume(out, capsys)
    assert status == 0 and not Path(f"{out}.checkpoint").exists()


def test_checkpoint_of_a_changed_case_file_says_so(tmp_path, capsys, interrupted) -> None:
    case = tmp_path / "buoy.toml"
    case.write_text(BUOY_CASE.read_text().replace("friction_coefficient = 0.3",
                                                  "friction_coefficient = 0.31"))
    (tmp_path / "hydrodb").symlink_to(REPO / "hydrodb")
    out = _copy(interrupted, tmp_path)
    status = main(["run", str(case), "-o", str(out), "--quiet", "--resume"] + RUN)
    err = capsys.readouterr().err
    assert status == 2 and f"the case file {case} has changed" in err
    _assert_untouched(out, interrupted)


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs on this platform")
def test_fifo_checkpoint_is_refused_without_hanging(tmp_path) -> None:
    """A FIFO in the checkpoint's place would block a reader forever: refused from its
    type (a separate process, so that a hang fails the test instead of blocking it)."""
    out = tmp_path / "cut.nc"
    os.mkfifo(f"{out}.checkpoint")
    env = dict(os.environ, PYTHONPATH=str(REPO))
    proc = subprocess.run([sys.executable, "-m", "floatmoor.cli", "run", str(BUOY_CASE), "-o",
                           str(out), "--quiet", "--resume"] + RUN, capture_output=True,
                          text=True, timeout=120, env=env)
    assert proc.returncode == 2, proc.stderr
    assert "a FIFO" in proc.stderr and "Traceback" not in proc.stderr
    assert not out.exists()
