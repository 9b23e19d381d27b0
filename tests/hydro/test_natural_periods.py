"""Natural periods of the moored DeepCwind platform and its linearised mooring stiffness
against the published OC4 values (docs/cases/deepcwind.md, notes)."""

from __future__ import annotations

import numpy as np
import pytest

from floatmoor.hydro.natural_periods import mooring_stiffness, natural_periods

#: Required: heave about 17.3 s and pitch about 26.8 s, within 3 %.
PERIOD_TOLERANCE = 0.03
OC4_PERIODS = {"Heave": 17.3, "Pitch": 26.8}
#: OC4 linearised mooring stiffness (docs/cases/deepcwind.md, notes). The case uses the OC5 line properties
#: of docs/cases/deepcwind.md, quasi-dynamic paper Table 7 (835.5 m, 125.6 kg/m, EA 7.49e8 N) while the published values belong
#: to the OC4 lines (835.35 m, 113.35 kg/m in air, EA 7.536e8 N): about 1 % apart, so 2 %.
OC4_STIFFNESS = {(0, 0): 70.8e3, (2, 2): 19.1e3, (4, 4): 87.3e6}
STIFFNESS_TOLERANCE = 0.02


@pytest.fixture(scope="module")
def k_moor(deepcwind_case):
    return mooring_stiffness(deepcwind_case)


@pytest.mark.parametrize("index", sorted(OC4_STIFFNESS))
def test_mooring_stiffness_against_oc4(k_moor, index):
    assert k_moor[index] == pytest.approx(OC4_STIFFNESS[index], rel=STIFFNESS_TOLERANCE)


def test_mooring_stiffness_is_symmetric_and_symmetric_platform(k_moor):
    assert np.allclose(k_moor[0, 0], k_moor[1, 1], rtol=1e-3)
    assert np.allclose(k_moor, k_moor.T, rtol=1e-3, atol=1e-3 * np.abs(k_moor).max())


@pytest.mark.parametrize("dof", sorted(OC4_PERIODS))
def test_natural_period_against_oc4(deepcwind_db, deepcwind_case, k_moor, dof):
    periods = natural_periods(deepcwind_db, deepcwind_case.floater, k_moor)
    assert periods[dof] == pytest.approx(OC4_PERIODS[dof], rel=PERIOD_TOLERANCE)


def test_buoy_heave_period_from_its_database(buoy_db, buoy_case):
    """Case C buoy: heave period of the free-floating cylinder, sqrt((m + A33) / (rho g A_wp)),
    with A33 at that frequency: an earlier trial database (capytaine 3.0, draft 0.1721 m, depth 0.9 m) gave 1.10 s."""
    periods = natural_periods(buoy_db, buoy_case.floater)
    assert periods["Heave"] == pytest.approx(1.10, rel=0.02)


def test_coupled_pitch_mode_is_shorter_than_the_uncoupled(deepcwind_db, deepcwind_case, k_moor):
    """The coupled pitch mode drags surge along (M15 = m z_G < 0): a smaller effective inertia."""
    from floatmoor.hydro.natural_periods import coupled_natural_periods

    coupled = coupled_natural_periods(deepcwind_db, deepcwind_case.floater, k_moor)
    single = natural_periods(deepcwind_db, deepcwind_case.floater, k_moor)
    assert coupled["Heave"] == pytest.approx(single["Heave"], rel=1e-3)
    assert coupled["Pitch"] < single["Pitch"]
