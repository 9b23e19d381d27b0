"""Plausibility warnings at load: valid values that are implausible by orders of magnitude (a
unit typed wrong) warn, naming the file, the key and what was expected; every shipped case
loads without one."""

from __future__ import annotations

import tomllib
import warnings

import pytest

from floatmoor.case.load import load_case
from floatmoor.case.plausibility import (
    GRAVITY_RANGE, LINE_DENSITY_RANGE, MATERIAL_DENSITY_RANGE, WATER_DENSITY_RANGE,
)
from floatmoor.cli import main
from floatmoor.errors import ImplausibleInputWarning
from tests.conftest import CASES, LINDAHL_CASE

#: The shipped case files (TOML files with a [simulation] table; not the studies).
SHIPPED = sorted(p for p in CASES.rglob("*.toml")
                 if "simulation" in tomllib.loads(p.read_text(encoding="utf-8")))


@pytest.mark.parametrize("override, key, expected", [
    ("line_types.chain.diameter=108", "line_types.chain.diameter",
     "implied density mass_per_length / (pi d^2 / 4)"),
    ("line_types.chain.mass_per_length=8.18e-5", "line_types.chain.mass_per_length",
     "implied density"),
    ("environment.water_density=1.025", "environment.water_density",
     "a water density of 900 to 1100 kg/m^3"),
    # (981, cm/s^2 typed as m/s^2, is refused: gravity is bounded to 1-30 m/s^2)
    ("environment.gravity=12", "environment.gravity", "the Earth's gravity"),
    ("line_types.chain.material_density=7.8", "line_types.chain.material_density",
     "the density of a mooring material"),
])
def test_implausible_values_warn_naming_file_and_key(override, key, expected) -> None:
    with pytest.warns(ImplausibleInputWarning) as record:
        load_case(LINDAHL_CASE, [override])
    (w,) = [w for w in record if issubclass(w.category, ImplausibleInputWarning)]
    text = str(w.message)
    assert text.startswith(f"{LINDAHL_CASE} (--set {override}): {key}: expected ")
    assert expected in text and "found" in text


@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: str(p.relative_to(CASES)))
def test_shipped_cases_load_without_plausibility_warnings(path) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error", ImplausibleInputWarning)
        load_case(path)


def test_bounds_hold_the_references_they_cite() -> None:
    """Chain's nominal-diameter convention (19.9 d^2 t/m studless, 21.9 studlink) and the
    floating fibres lie inside the implied-density bounds with room; sea and fresh water,
    g and steel inside theirs."""
    import math

    for tonnes_per_d2 in (19.9, 21.9):
        implied = tonnes_per_d2 * 1000.0 / (math.pi / 4.0)
        assert LINE_DENSITY_RANGE[0] < implied < LINE_DENSITY_RANGE[1] / 2.0
    assert LINE_DENSITY_RANGE[0] * 4 < 500.0  # HMPE rope
    assert WATER_DENSITY_RANGE[0] < 998.0 and 1030.0 < WATER_DENSITY_RANGE[1]
    assert GRAVITY_RANGE[0] < 9.78 and 10.0 <= GRAVITY_RANGE[1]
    assert MATERIAL_DENSITY_RANGE[0] < 252.0 / 2 and 19_300.0 < MATERIAL_DENSITY_RANGE[1]


def test_check_prints_the_warnings_with_the_case(capsys) -> None:
    assert main(["check", str(LINDAHL_CASE), "--set", "line_types.chain.diameter=108", "--set",
                 'lines.chain.model="quasi-static"']) == 0
    out = capsys.readouterr().out.splitlines()
    assert "[line_types.chain.diameter=108" in out[0] and "valid case" in out[0]
    assert out[1].startswith("  warning: ") and "line_types.chain.diameter" in out[1]
    assert "Re" in "\n".join(out)  # the groups are still printed
