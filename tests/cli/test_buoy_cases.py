"""The moored cylinder buoy in regular waves H = 0.04 m, T = 1.0, 1.2, 1.4 s (docs/cases/cylinder_buoy.md):
the three case files load, share the up-to-date database, and run (briefly, on quasi-static
lines) to finite motions in waves of the right height and period."""

from __future__ import annotations

import json
import math
import tomllib

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.cli import main
from floatmoor.hydro.database import database_path, read_database, stale_keys
from floatmoor.io.netcdf import read_dataset
from tests.conftest import CASES

PERIODS = (1.00, 1.20, 1.40)
BUOY_FILES = {T: CASES / "cylinder_buoy" / f"buoy_regular_T{T:.2f}.toml" for T in PERIODS}
#: docs/cases/cylinder_buoy.md: regular waves of height 0.04 m.
WAVE_HEIGHT = 0.04
#: The sampled half range of a cosine misses its amplitude by at most 1 - cos(pi dt / T):
#: 4.9e-4 at dt = 0.01 s, T = 1.0 s.
ELEVATION_RTOL = 1e-3
#: Up-crossing times interpolated linearly between samples 0.01 s apart: the period to 1e-3.
PERIOD_RTOL = 1e-3
#: Tables that must be the same in the three files (the database and the mooring).
SHARED_TABLES = ("environment", "seabed", "line_types", "lines", "floater", "hydro")
#: A short run: 4 s with a 1 s wave ramp, quasi-static lines (about 3 s of wall time).
SHORT = ["--set", "simulation.duration=4.0", "--set", "waves.ramp_duration=1.0",
         "--set", 'lines.*.model="quasi-static"']


def test_the_three_cases_differ_only_in_title_and_wave_period() -> None:
    raw = {T: tomllib.loads(path.read_text()) for T, path in BUOY_FILES.items()}
    for T, table in raw.items():
        assert table["waves"] == {"kind": "regular", "height": WAVE_HEIGHT, "period": T,
                                  "ramp_duration": raw[1.2]["waves"]["ramp_duration"]}
        assert table["title"] == raw[1.2]["title"]  # filled from waves.period
        for name in SHARED_TABLES + ("simulation", "description"):
            assert table[name] == raw[1.2][name], (T, name)
        assert set(table) == set(raw[1.2])


@pytest.mark.parametrize("period", PERIODS)
def test_buoy_case_loads_on_its_up_to_date_database(period: float) -> None:
    case = load_case(BUOY_FILES[period])
    assert case.waves is not None and case.waves.settings.period == period
    assert f"H = 0.04 m, T = {period:.2f} s" in case.title
    assert case.waves.settings.height == WAVE_HEIGHT
    # docs/cases/cylinder_buoy.md reference numerics: body step 0.01 s, dynamic lines of 10 elements of order 5
    assert case.simulation.time_step == 0.01
    assert all(ln.model == "dynamic" and (ln.dynamic.elements, ln.dynamic.order) == (10, 5)
               for ln in case.lines)
    assert case.waves.ramp_duration < case.simulation.duration
    path = database_path(case)
    assert path.name == "cylinder_buoy.nc" and path.is_file()
    assert stale_keys(read_database(path), case) == []


def _upcrossings(t: np.ndarray, s: np.ndarray) -> np.ndarray:
    i = np.nonzero((s[:-1] < 0.0) & (s[1:] >= 0.0))[0]
    return t[i] - s[i] * (t[i + 1] - t[i]) / (s[i + 1] - s[i])


@pytest.mark.parametrize("period", PERIODS)
def test_short_buoy_run_in_its_waves(period: float, tmp_path, capsys) -> None:
    out = tmp_path / "buoy.nc"
    assert main(["run", str(BUOY_FILES[period]), "-o", str(out), "--quiet", "--json",
                 *SHORT]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert set(summary["body_displacement"]) == {"Surge", "Sway", "Heave", "Roll", "Pitch",
                                                 "Yaw"}
    ds = read_dataset(out)
    assert ds.attrs["status"] == "complete"
    assert np.all(np.isfinite(ds["body_displacement"].values))
    assert np.all(np.isfinite(ds["fairlead_tension"].values))
    after = ds["time"].values >= 1.0  # the ramp
    t, eta = ds["time"].values[after], ds["wave_elevation"].values[after]
    half_range = 0.5 * (eta.max() - eta.min())
    assert half_range == pytest.approx(0.5 * WAVE_HEIGHT, rel=ELEVATION_RTOL)
    assert np.diff(_upcrossings(t, eta)).mean() == pytest.approx(period, rel=PERIOD_RTOL)
    # the waves move the buoy in heave and pitch
    heave = summary["body_displacement"]["Heave"]
    assert heave["std"] > 0.1 * WAVE_HEIGHT / (2.0 * math.sqrt(2.0))
    assert summary["body_displacement"]["Pitch"]["std"] > 0.0
