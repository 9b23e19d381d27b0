"""The dimensionless groups of a case (chain-experiment paper eqs. 29-31, section 3.1)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.cli import main
from floatmoor.errors import ImplausibleInputWarning
from floatmoor.similitude import cable_groups

ROOT = Path(__file__).parents[2]
LINDAHL = ROOT / "cases" / "lindahl" / "lindahl_r0.20_T1.25.toml"
BUOY = ROOT / "cases" / "cylinder_buoy" / "buoy_regular_T1.00.toml"
SYSTEM = ROOT / "cases" / "systems" / "three_line_clump_buoy.toml"

#: The groups are closed-form: equal to the hand formulas to round-off.
ROUND_OFF = 1e-12


def test_lindahl_groups_against_the_papers_forms() -> None:
    """The paper's interpreted forms (eqs. 31a-e, with C_v and the wave celerity) against
    floatmoor's definitions (eqs. 29a-e with C_a on the material area)."""
    g = cable_groups(load_case(LINDAHL)).sel(section="chain[0]")
    m, ea, d, rho_c, rho_w = 0.0818, 1.0e4, 2.2e-3, 7800.0, 1000.0
    length, period, radius = 33.0, 1.25, 0.2
    c_v = m / (rho_c * math.pi * d ** 2 / 4)
    c_mn = 3.8 * c_v  # the paper's added-mass coefficient on pi d^2 / 4
    expected = {
        "alpha_1": c_mn * rho_w / (c_v * rho_c),  # eq. 31a
        "alpha_2": (math.sqrt(ea / m) * period / length) ** 2,  # eq. 31b
        "alpha_3": (1 - rho_w / rho_c) * 9.81 * period ** 2 / length,  # eq. 31c
        "alpha_4": 2 * 0.5 * length * rho_w / (math.pi * c_v * d * rho_c),  # eq. 31d
        "alpha_5": 2 * 2.5 * length * rho_w / (math.pi * c_v * d * rho_c),  # eq. 31e
        "reynolds_number": 2 * math.pi * radius * d / (period * 1e-6),  # section 3.1
        "keulegan_carpenter_number": 2 * math.pi * radius / d,
        "volume_coefficient": c_v,
    }
    for name, value in expected.items():
        assert float(g[name]) == pytest.approx(value, rel=ROUND_OFF), name
    # section 3.1: 300 < Re_max < 2200 and 210 < KC < 570 over the experiment's runs
    assert float(g.reynolds_number) == pytest.approx(2212, abs=1)
    assert float(g.keulegan_carpenter_number) == pytest.approx(571.2, abs=0.1)


def test_every_variable_has_units_and_a_long_name() -> None:
    groups = cable_groups(load_case(SYSTEM))
    assert groups.sizes["section"] == len(load_case(SYSTEM).sections)
    for name in list(groups.data_vars) + list(groups.coords):
        assert groups[name].attrs["units"] and groups[name].attrs["long_name"], name
    for key in ("case_toml", "floatmoor_version", "created"):
        assert groups.attrs[key]


def test_a_floater_case_takes_the_wave_period_and_half_the_height() -> None:
    groups = cable_groups(load_case(BUOY))
    assert np.all(groups.period.values == 1.0)
    assert np.all(groups.amplitude.values == pytest.approx(0.02))
    assert "regular waves" in groups.attrs["characteristic_motion"]


def test_check_prints_the_groups(capsys) -> None:
    assert main(["check", str(LINDAHL)]) == 0
    out = capsys.readouterr().out
    assert "dimensionless groups" in out
    row = next(line for line in out.splitlines() if line.strip().startswith("chain[0]"))
    assert row.split()[1:] == ["0.4872", "175.4", "0.4049", "221.9", "1109", "2212", "571.2"]


@pytest.mark.parametrize("override, group, expected", [
    ("line_types.chain.diameter=1e-300", "volume_coefficient", math.inf),
    ("motion.period=1e308", "alpha_2", math.inf),
])
def test_extreme_valid_inputs_give_infinite_groups_not_an_exception(override, group,
                                                                    expected) -> None:
    """A diameter whose square underflows or a period whose square overflows is valid input
    (the loader asks only > 0): the groups come out infinite, as `floatmoor check` prints
    them, instead of a ZeroDivisionError or OverflowError (found by the mutation corpus)."""
    if "diameter" in override:  # valid, but implausible: the loader warns
        with pytest.warns(ImplausibleInputWarning, match="line_types.chain.diameter"):
            case = load_case(LINDAHL, [override])
    else:
        case = load_case(LINDAHL, [override])
    groups = cable_groups(case)
    assert float(groups[group].values[0]) == expected
