"""Build time and panel counts of the hydrodynamic databases.

Run with ``pytest -m benchmark tests/benchmarks/test_bench_hydro.py -s``. The buoy database
(docs/cases/cylinder_buoy.md) is rebuilt into a temporary folder and timed; the DeepCwind build (about 20 to 40
minutes on a shared machine) is not repeated: its time and panel count are read from the
shipped file's metadata.
"""

from __future__ import annotations

import time
from pathlib import Path

import pytest

from floatmoor.case.load import load_case
from floatmoor.hydro.database import build_database
from floatmoor.hydro.database import read_database, write_database

REPO = Path(__file__).resolve().parents[2]


@pytest.mark.benchmark
def test_bench_buoy_build_and_report_semisub(tmp_path):
    case = load_case(REPO / "cases" / "cylinder_buoy" / "buoy_regular_T1.20.toml")
    start = time.perf_counter()
    ds = build_database(case)
    write_database(ds, tmp_path / "buoy.nc")
    wall = time.perf_counter() - start
    shipped = read_database(REPO / "hydrodb" / "cylinder_buoy.nc")
    assert ds.attrs["inputs_hash"] == shipped.attrs["inputs_hash"]
    assert ds.attrs["mesh_hash"] == shipped.attrs["mesh_hash"]
    n = ds.sizes["omega"]
    print(f"\nbuoy: {ds.attrs['hull_panels']} hull + {ds.attrs['lid_panels']} lid panels "
          f"({ds.attrs['mesh_symmetry']}), {n} frequencies + infinity: {wall:.1f} s "
          f"({wall / (n + 1):.2f} s per frequency; shipped file: "
          f"{float(shipped.attrs['build_seconds']):.1f} s)")
    semi = read_database(REPO / "hydrodb" / "deepcwind.nc")
    m = semi.sizes["omega"]
    print(f"deepcwind (from the shipped file): {semi.attrs['hull_panels']} hull + "
          f"{semi.attrs['lid_panels']} lid panels ({semi.attrs['mesh_symmetry']}), {m} "
          f"frequencies + infinity x {semi.sizes['wave_direction']} directions: "
          f"{float(semi.attrs['build_seconds']):.0f} s "
          f"({float(semi.attrs['build_seconds']) / (m + 1):.1f} s per frequency)")
