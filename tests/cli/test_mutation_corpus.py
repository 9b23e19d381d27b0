"""The probe's families again, as a seeded mutation corpus of the shipped cases.

Every numeric key of a few shipped cases is set, in turn for a seeded sample, to extreme or
wrong values through ``--set``; ``floatmoor check`` and a short ``floatmoor run`` must then
end (no hang: a timeout), with status 0, 1 or 2, without a traceback, with one-line errors,
and a result file of a successful run must hold no NaN. Slow (minutes): ``pytest -m slow``.
"""

from __future__ import annotations

import os
import random
import subprocess
import sys
import tomllib
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from tests.conftest import CASES, REPO

pytestmark = pytest.mark.slow

#: Seed of the corpus, so a failure reproduces.
SEED = 20261124
#: Mutations per case and command.
SAMPLES = 25
#: Values a numeric key is set to: extremes, signs, zero, wrong types, deep nesting.
VALUES = ("1e308", "-1e308", "1e-300", "0", "-1", "1e9", "1e-9", '"x"', "true", "[]",
          "[" * 40 + "]" * 40)
#: Cases mutated: a forced dynamic line, a quasi-dynamic study case, a floater.
CORPUS = ("lindahl/lindahl_r0.20_T1.25.toml", "qd_verification/s1_d1.toml",
          "cylinder_buoy/buoy_regular_T1.20.toml")
#: Short runs: enough to start every model, seconds each.
SHORT = {"lindahl/lindahl_r0.20_T1.25.toml": ["simulation.duration=0.5",
                                              "motion.ramp_duration=0.25"],
         "qd_verification/s1_d1.toml": [],
         "cylinder_buoy/buoy_regular_T1.20.toml": ["simulation.duration=0.5"]}


def _keys(table: dict, prefix: tuple = ()) -> list[str]:
    """Addressable dotted paths of the numeric leaves (entries of [[lines]] by name)."""
    out = []
    for key, value in table.items():
        path = prefix + (key,)
        if isinstance(value, dict):
            out += _keys(value, path)
        elif isinstance(value, list) and value and all(isinstance(v, dict) for v in value):
            out += [k for v in value if "name" in v for k in _keys(v, path + (v["name"],))]
        elif isinstance(value, (int, float)) and not isinstance(value, bool):
            out.append(".".join(path))
    return [k for k in out if not k.startswith("campaign")]


def _corpus(case: str) -> list[tuple[str, str]]:
    raw = tomllib.loads((CASES / case).read_text())
    rng = random.Random(f"{SEED}-{case}")
    pairs = [(k, v) for k in _keys(raw) for v in VALUES]
    return rng.sample(pairs, min(SAMPLES, len(pairs)))


def _cli(args: list[str], timeout: float) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "floatmoor.cli", *args], capture_output=True,
                          text=True, timeout=timeout, cwd=REPO,
                          env={**os.environ, "PYTHONPATH": str(REPO)})


def _assert_clean(result: subprocess.CompletedProcess, what: str) -> None:
    assert result.returncode in (0, 1, 2), f"{what}: status {result.returncode}"
    assert "Traceback" not in result.stderr, f"{what}:\n{result.stderr[-2000:]}"
    if result.returncode == 2:
        lines = result.stderr.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("floatmoor: error: "), what


@pytest.mark.parametrize("case", CORPUS)
def test_mutated_cases_check_and_run_cleanly(case: str, tmp_path: Path):
    for key, value in _corpus(case):
        what = f"{case} --set {key}={value[:20]}"
        _assert_clean(_cli(["check", str(CASES / case), "--set", f"{key}={value}"], 120),
                      "check " + what)
        out = tmp_path / "out.nc"
        out.unlink(missing_ok=True)
        args = ["run", str(CASES / case), "--quiet", "-o", str(out), "--set",
                f"{key}={value}"]
        for extra in SHORT[case]:
            if not extra.startswith(key + "="):
                args += ["--set", extra]
        result = _cli(args, 300)
        _assert_clean(result, "run " + what)
        if result.returncode == 0:
            with xr.open_dataset(out) as ds:
                for name, var in ds.data_vars.items():
                    if np.issubdtype(var.dtype, np.floating):
                        assert not np.isnan(var.values).any(), f"run {what}: NaN in {name}"
