"""The finished runs of a quasi-dynamic verification study, one small JSON file each.

``floatmoor study qd-verification -o DIR`` writes each combination's result, as soon as it is
finished, to ``DIR/runs/<config>_<amplitude>_alpha<alpha>.json`` (a temporary file flushed to
disk and renamed: :func:`floatmoor.io.output_files.atomic_target`), so that ``--resume``
continues an interrupted study without recomputing them (docs/cases/qd_verification.md#resuming).
Floats are written by ``repr`` (JSON), which reads back to the same binary value: a stored run
gives the dataset an uninterrupted study gives.

A file records what the run depends on besides the code (:func:`identity`); ``--resume``
refuses a folder whose runs were computed otherwise (another dynamic resolution) rather than
mixing them. A failed run is not stored (``--resume`` runs it again).
"""

from __future__ import annotations

import json
import math
import os
from pathlib import Path
from typing import Any

import numpy as np

from floatmoor.errors import CaseError
from floatmoor.io.output_files import atomic_target, sync_folder, write_errors

__all__ = ["RUNS_DIR", "FORMAT", "identity", "run_file", "write_run", "read_run",
           "stored_runs", "count_runs", "clear_runs"]

#: Folder of the run files inside the study's output folder.
RUNS_DIR = "runs"
#: The ``format`` field of a run file (bumped when the content changes meaning).
FORMAT = "floatmoor qd-verification run 1"
#: Scalar results of a run (the error measures, T_S0, the cycle's samples, its times [s]).
SCALARS = ("t_s0", "samples", "rmse_qd", "rmse_s", "e_tmin", "e_tmax", "seconds",
           "cpu_seconds")
#: The names of run files (run_file).
_PATTERN = "C??_A?_alpha*.json"
#: Largest run file read: 3 x 201 floats of about 20 characters.
_MAX_BYTES = 1 << 20


def identity(spec: Any, constants: dict[str, Any]) -> dict[str, Any]:
    """What a run's result depends on besides the code: its combination, the dynamic
    resolution and the study's cycle and sampling constants."""
    return {"config": spec.config, "amplitude_index": spec.amplitude_index,
            "alpha_index": spec.alpha_index, "dynamic_elements": spec.dynamic_elements,
            **constants}


def run_file(folder: str | os.PathLike[str], spec: Any, amplitude_name: str) -> Path:
    """Path of the run file of ``spec`` under the study's output ``folder``."""
    return Path(folder) / RUNS_DIR / f"{spec.config}_{amplitude_name}_alpha{spec.alpha:g}.json"


def write_run(path: Path, ident: dict[str, Any], result: dict[str, Any]) -> None:
    """Write one finished run durably (temporary file, fsync, rename, folder flush).

    Raises
    ------
    OutputWriteError
        Naming the file when it cannot be written.
    """
    data = {"format": FORMAT, "identity": ident,
            "result": {**{k: result[k] for k in SCALARS},
                       "cycle": np.asarray(result["cycle"], dtype=float).tolist()}}
    text = json.dumps(data, allow_nan=True) + "\n"
    with write_errors(path.parent):
        path.parent.mkdir(exist_ok=True)
    with atomic_target(path) as tmp:
        tmp.write_text(text, encoding="utf-8")
    with write_errors(path.parent):
        sync_folder(path.parent)


def read_run(path: Path) -> tuple[dict[str, Any], dict[str, Any]] | None:
    """(identity, result with ``cycle`` an array) of a run file, or None when the file is
    missing or is not a whole run file of this format (it is then computed again)."""
    try:
        if path.stat().st_size > _MAX_BYTES:
            return None
        data = json.loads(path.read_text(encoding="utf-8"))
        if not isinstance(data, dict) or data.get("format") != FORMAT:
            return None
        ident, res = data["identity"], data["result"]
        result = {k: res[k] for k in SCALARS}
        if not all(isinstance(v, (int, float)) for v in result.values()):
            return None
        result["cycle"] = np.asarray(res["cycle"], dtype=float)
    except (OSError, ValueError, KeyError, TypeError):
        return None
    if not isinstance(ident, dict):
        return None
    return ident, result


def stored_runs(folder: str | os.PathLike[str], specs: list[Any], names: list[str],
                constants: dict[str, Any]) -> dict[Any, dict[str, Any]]:
    """The stored results of ``specs`` (``names``: their amplitude names) under ``folder``.

    Raises
    ------
    CaseError
        When a run file of one of the specs was computed with another identity (another
        ``--dynamic-elements``, other cycle constants), naming the file and the difference.
    """
    out = {}
    for spec, name in zip(specs, names):
        path = run_file(folder, spec, name)
        got = read_run(path)
        if got is None:
            continue
        ident, result = got
        want = identity(spec, constants)
        if ident != want:
            key = next((k for k in want if ident.get(k) != want[k]), "identity")
            option = " (--dynamic-elements)" if key == "dynamic_elements" else ""
            raise CaseError("--resume", "", f"the runs of the same study in the output folder "
                            f"({key} {_fmt(want[key])}{option})",
                            f"{path} computed with {key} {_fmt(ident.get(key))}")
        out[spec] = result
    return out


def count_runs(folder: str | os.PathLike[str]) -> int:
    """Run files in ``folder``'s runs folder (what an interrupted study leaves)."""
    try:
        return sum(1 for _ in (Path(folder) / RUNS_DIR).glob(_PATTERN))
    except OSError:
        return 0


def clear_runs(folder: str | os.PathLike[str]) -> None:
    """Remove the run files an earlier study left in ``folder`` (a fresh study's start: its
    runs replace them)."""
    runs = Path(folder) / RUNS_DIR
    if not runs.is_dir():
        return
    for path in runs.glob(_PATTERN):
        with write_errors(path):
            path.unlink(missing_ok=True)


def _fmt(value: Any) -> str:
    if isinstance(value, float) and math.isfinite(value):
        return f"{value:g}"
    return str(value)
