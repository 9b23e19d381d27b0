"""Minimum breaking load (MBL): loading, the static check, the strain rule without an MBL, and
the largest tension of a run against the MBL."""

from __future__ import annotations

import math

import numpy as np
import pytest
import xarray as xr

from floatmoor.case.load import load_case
from floatmoor.errors import CaseError
from floatmoor.mooring.quasistatic import QuasiStaticLine
from floatmoor.mooring.static_strength import (
    STRAIN_WARNING_WITHOUT_MBL, check_static_below_mbl, static_line_loads, strain_warnings,
)
from floatmoor.post.run_strength import largest_tension, line_mbl, line_strength
from tests.conftest import CASES, LINDAHL_CASE

KEY = "line_types.chain.minimum_breaking_load"
DEEPCWIND = CASES / "deepcwind" / "deepcwind_lc34.toml"


def test_mbl_is_optional_and_read_in_newtons():
    assert load_case(LINDAHL_CASE).line_types["chain"].minimum_breaking_load is None
    case = load_case(LINDAHL_CASE, [f"{KEY}=250.0"])
    assert case.line_types["chain"].minimum_breaking_load == 250.0
    assert case.lines[0].line_type.minimum_breaking_load == 250.0
    # no source gives the DeepCwind chain's MBL: the case leaves it out
    assert load_case(DEEPCWIND).line_types["chain"].minimum_breaking_load is None


@pytest.mark.parametrize("value, found", [
    ("-1.0", "-1.0"), ("0.0", "0.0"), ("0", "0"), ('"5 kN"', 'the string "5 kN"'),
    ("true", "true"), ("inf", "inf"), ("nan", "nan"), ("[1.0]", "[1.0]"),
])
def test_bad_mbl_is_a_case_error_naming_the_key(value, found):
    with pytest.raises(CaseError) as info:
        load_case(LINDAHL_CASE, [f"{KEY}={value}"])
    assert info.value.key == KEY
    assert "a finite number > 0 [N]" in info.value.expected
    assert found in info.value.found


def test_static_loads_match_the_catenary_and_refuse_tension_at_the_mbl():
    case = load_case(LINDAHL_CASE, [f"{KEY}=100.0"])
    (load,) = static_line_loads(case)
    line = case.lines[0]
    sol = QuasiStaticLine.from_case(line, case.environment, case.seabed).solve(
        np.asarray(line.fairlead))
    assert load.fairlead_tension == sol.fairlead_tension
    assert load.strain == pytest.approx(sol.fairlead_tension / 1.0e4, rel=1e-15)
    assert load.ratio == pytest.approx(sol.fairlead_tension / 100.0, rel=1e-15)
    assert load.safety_factor == pytest.approx(100.0 / sol.fairlead_tension, rel=1e-15)
    check_static_below_mbl(case, [load])  # 23 N against 100 N: fine
    # an MBL equal to the static tension is refused, naming the line, key, tension and MBL
    at = load_case(LINDAHL_CASE, [f"{KEY}={sol.fairlead_tension!r}"])
    with pytest.raises(CaseError) as info:
        check_static_below_mbl(at, static_line_loads(at))
    err = info.value
    assert err.key == KEY and err.source == str(LINDAHL_CASE)
    assert "line 'chain'" in err.expected and f"{sol.fairlead_tension:.6g} N" in err.expected
    assert repr(sol.fairlead_tension) in err.found


def test_strain_warning_only_without_mbl_and_above_the_threshold():
    # DeepCwind line 1 shortened from 835.5 m to 700 m: ~17 % strain at the fairlead
    short = ["lines.line1.length=700.0"]
    no_mbl = load_case(DEEPCWIND, short)
    loads = static_line_loads(no_mbl)
    assert loads[0].strain > 0.15 and loads[1].strain < STRAIN_WARNING_WITHOUT_MBL
    warnings = strain_warnings(loads)
    assert len(warnings) == 1 and "'line1'" in warnings[0] and KEY in warnings[0]
    assert f"{loads[0].strain:.1%}" in warnings[0]
    # with an MBL (DNV-OS-E302 studless R3 at 77.9 mm, 5.111e6 N: the case file's comment)
    # the same case is no longer a warning but an error
    with_mbl = load_case(DEEPCWIND, [*short, f"{KEY}=5.111e6"])
    loads = static_line_loads(with_mbl)
    assert strain_warnings(loads) == []
    with pytest.raises(CaseError, match="line 'line1'"):
        check_static_below_mbl(with_mbl, loads)


def _dataset(fairlead, anchor, mbl=None):
    time = np.arange(len(fairlead)) * 0.5
    ds = xr.Dataset({"fairlead_tension": (("line", "time"), [fairlead]),
                     "anchor_tension": (("line", "time"), [anchor])},
                    coords={"line": ["a"], "time": time})
    if mbl is not None:
        ds["minimum_breaking_load"] = ("line", [mbl])
    return ds


def test_largest_tension_takes_either_end_and_the_window():
    # a start-up peak at the fairlead (t = 0.5), a later snap at the anchor (t = 2.0)
    ds = _dataset([10.0, 90.0, 20.0, 30.0, 25.0], [5.0, 10.0, 15.0, 10.0, 40.0])
    assert largest_tension(ds, "a") == (90.0, "fairlead", 0.5)
    assert largest_tension(ds, "a", start=1.0) == (40.0, "anchor", 2.0)
    s = line_strength(ds, "a", 80.0, start=1.0)
    assert s["max_tension_N"] == 40.0 and s["max_tension_end"] == "anchor"
    assert s["max_tension_over_mbl"] == 0.5 and s["safety_factor"] == 2.0
    assert s["whole_run_max_tension_N"] == 90.0
    assert s["whole_run_max_tension_over_mbl"] == 90.0 / 80.0
    none = line_strength(ds, "a", None, start=1.0)
    assert none["max_tension_over_mbl"] is None and none["safety_factor"] is None
    slack = line_strength(_dataset([0.0, 0.0], [0.0, 0.0]), "a", 10.0, start=0.0)
    assert slack["max_tension_over_mbl"] == 0.0 and math.isinf(slack["safety_factor"])


def test_line_mbl_from_the_dataset_or_the_case():
    case = load_case(LINDAHL_CASE, [f"{KEY}=250.0"])
    assert line_mbl(_dataset([1.0], [1.0], mbl=300.0), "a", case) == 300.0
    assert line_mbl(_dataset([1.0], [1.0], mbl=math.nan), "a") is None
    ds = _dataset([1.0], [1.0]).assign_coords(line=["chain"])
    assert line_mbl(ds, "chain", case) == 250.0  # a dataset without the variable
    assert line_mbl(ds, "chain", None) is None


def test_summary_of_a_floater_without_lines_is_printed():
    """A free-floating body has no lines: the summary says so instead of failing."""
    from floatmoor.post.summary import format_summary

    body = {"Surge": {"mean": 0.0, "std": 0.1, "min": -0.2, "max": 0.2}}
    text = format_summary({"title": "free body", "lines": {}, "body_displacement": body})
    assert text.splitlines()[:2] == ["free body", "no mooring lines"]
    assert "Surge" in text
