"""Shared fixtures of the hydro tests: the shipped databases and cases (read, never built)."""

from __future__ import annotations

from pathlib import Path

import pytest

from floatmoor.case.load import load_case
from floatmoor.hydro.database import read_database

REPO = Path(__file__).resolve().parents[2]
HYDRODB = REPO / "hydrodb"
BUOY_CASE = REPO / "cases" / "cylinder_buoy" / "buoy_regular_T1.20.toml"
DEEPCWIND_CASE = REPO / "cases" / "deepcwind" / "deepcwind_free_decay.toml"
BUOY_DB = HYDRODB / "cylinder_buoy.nc"
DEEPCWIND_DB = HYDRODB / "deepcwind.nc"


@pytest.fixture(scope="session")
def buoy_case():
    return load_case(BUOY_CASE)


@pytest.fixture(scope="session")
def deepcwind_case():
    return load_case(DEEPCWIND_CASE)


@pytest.fixture(scope="session")
def buoy_db():
    return read_database(BUOY_DB)


@pytest.fixture(scope="session")
def deepcwind_db():
    return read_database(DEEPCWIND_DB)
