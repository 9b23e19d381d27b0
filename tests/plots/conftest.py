"""The short buoy run every test of the views looks at, made once per session."""

from __future__ import annotations

from pathlib import Path

import pytest

from floatmoor.cli import main
from floatmoor.io.netcdf import read_dataset
from tests.conftest import CASES

BUOY = CASES / "cylinder_buoy" / "buoy_regular_T1.20.toml"
#: 2 s of the buoy on quasi-static lines, shapes every 0.1 s: 21 shape samples.
RUN = ["--set", "simulation.duration=2", "--set", "simulation.shape_output_interval=0.1",
       "--set", 'lines.*.model="quasi-static"', "--quiet"]
SHAPES = 21


@pytest.fixture(scope="session")
def buoy_run(tmp_path_factory) -> dict[str, Path]:
    """One short buoy run through ``floatmoor run --plot --vtk`` (session-wide)."""
    folder = tmp_path_factory.mktemp("views")
    out, png, vtk = folder / "buoy.nc", folder / "buoy.png", folder / "vtk"
    assert main(["run", str(BUOY), *RUN, "-o", str(out), "--plot", str(png),
                 "--vtk", str(vtk)]) == 0
    return {"nc": out, "png": png, "vtk": vtk, "folder": folder}


@pytest.fixture(scope="session")
def dataset(buoy_run):
    return read_dataset(buoy_run["nc"])
