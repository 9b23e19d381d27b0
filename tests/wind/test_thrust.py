"""The NREL 5 MW thrust curve against its source table and the quoted rated thrust."""

import numpy as np
import pytest

from floatmoor.wind.thrust import (CUT_IN_SPEED, CUT_OUT_SPEED, NREL_5MW, RATED_SPEED,
                                   ThrustCurve)

#: Rows of NREL/turbine-models Offshore/NREL_5MW_126_RWT.csv (Wind Speed [m/s], Thrust [kN]).
SOURCE_ROWS = [(3.0, 171.7), (8.0, 478.0), (11.0, 790.615), (11.4, 805.112), (13.0, 608.4),
               (18.0, 448.4), (25.0, 369.3)]
#: Rated thrust of the NREL 5 MW rotor, "about 800 kN" (Jonkman et al. 2009, NREL/TP-500-38060,
#: Figure 9-3, steady-state rotor thrust); the figure is read to +-5 %, our tolerance.
RATED_THRUST = 800.0e3
RATED_THRUST_RTOL = 0.05


@pytest.mark.parametrize("speed, thrust_kn", SOURCE_ROWS)
def test_thrust_matches_source_rows(speed, thrust_kn):
    assert NREL_5MW(speed) == pytest.approx(1e3 * thrust_kn, rel=1e-12)


def test_interpolates_linearly_between_rows():
    # halfway between 13 and 14 m/s: (608.4 + 557.9) / 2 kN
    assert NREL_5MW(13.5) == pytest.approx(0.5e3 * (608.4 + 557.9), rel=1e-12)


def test_rated_thrust_about_800_kn():
    assert abs(NREL_5MW(RATED_SPEED) - RATED_THRUST) <= RATED_THRUST_RTOL * RATED_THRUST
    u = np.linspace(CUT_IN_SPEED, CUT_OUT_SPEED, 2201)
    peak = float(u[np.argmax(NREL_5MW(u))])
    assert abs(peak - RATED_SPEED) <= 0.15  # the peak sits at rated, to the table's 0.1 m/s


def test_parked_outside_operating_range():
    assert NREL_5MW(CUT_IN_SPEED - 0.01) == 0.0
    assert NREL_5MW(CUT_OUT_SPEED + 0.01) == 0.0


def test_thrust_slope_positive_below_and_negative_above_rated():
    """Below rated dT/dU > 0 (aerodynamic damping); above rated pitch control sheds thrust,
    dT/dU < 0: the quasi-steady rotor's 'negative damping' (Larsen & Hanson 2007)."""
    for u in (5.0, 8.0, 10.5):
        assert NREL_5MW.slope(u) > 0.0
    for u in (12.0, 13.05, 16.0, 22.0):
        assert NREL_5MW.slope(u) < 0.0
    # LC43: -50.5 kN s/m between the 13 and 14 m/s rows
    assert NREL_5MW.slope(13.05) == pytest.approx(-50.5e3, rel=1e-12)


def test_curve_rejects_bad_tables():
    with pytest.raises(ValueError, match="increase"):
        ThrustCurve(np.array([1.0, 1.0]), np.array([0.0, 1.0]))
    with pytest.raises(ValueError, match="equal length"):
        ThrustCurve(np.array([1.0, 2.0]), np.array([0.0]))
