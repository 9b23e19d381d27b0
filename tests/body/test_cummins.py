"""The Cummins body on the committed buoy database (docs/cases/cylinder_buoy.md): regular-wave response against
the frequency-domain RAO of the database, heave free decay against the linear natural period,
and a body on quasi-static lines against the linearised mooring stiffness."""

from __future__ import annotations

import math

import numpy as np
import pytest

from floatmoor.body.model import build_body
from floatmoor.case.load import load_case
from floatmoor.hydro.database import read_database
from floatmoor.hydro.excitation_transfer import ExcitationInterpolator
from floatmoor.hydro.radiation import added_mass_at, hydrostatic_stiffness_total
from floatmoor.simulation.coupled import MooredBody, equilibrium, line_force_quasi_static
from floatmoor.waves.excitation_series import WaveExcitation
from floatmoor.waves.realisation import WaveField
from tests.conftest import CASES, REPO

BUOY_CASE = CASES / "cylinder_buoy" / "buoy_regular_T1.20.toml"
BUOY_DB = REPO / "hydrodb" / "cylinder_buoy.nc"
#: The required criteria for the regular-wave response against the database's RAO.
RAO_AMPLITUDE_RTOL = 0.02
RAO_PHASE_TOL_DEG = 2.0
#: Heave free decay against the linear natural period (1 % required).
DECAY_PERIOD_RTOL = 0.01
#: Surge on quasi-static lines against sqrt((M + A11) / K11) of the linearised mooring: the
#: decay is small-amplitude (1 cm on 6.7 m chains) but the catenary stiffens; 2 %.
MOORED_PERIOD_RTOL = 0.02
#: Surge spring of the regular-wave test [N/m] (the free buoy has no surge stiffness): surge
#: natural period ~5 s, away from the wave periods.
SURGE_SPRING = 50.0
WAVE_AMPLITUDE = 0.02  # m: H = 0.04 m, docs/cases/cylinder_buoy.md
STEPS_PER_PERIOD = 60


def _setup():
    case = load_case(BUOY_CASE)
    ds = read_database(BUOY_DB)
    return case, ds


def _damping_at(ds, omega: float) -> np.ndarray:
    w = ds["omega"].values
    b = ds["radiation_damping"].transpose("omega", "radiating_dof", "influenced_dof").values
    return np.array([[np.interp(omega, w, b[:, i, j]) for j in range(6)] for i in range(6)])


def _frequency_domain_rao(case, ds, omega: float, extra: np.ndarray) -> np.ndarray:
    """x = Re{Z e^{-i w t}}: (-w^2 (M + A) - i w B + C) Z = X a (capytaine's convention)."""
    M = case.floater.mass_matrix()
    C = hydrostatic_stiffness_total(ds, case.floater) + extra
    A = added_mass_at(ds, omega).T  # (influenced, radiating)
    B = _damping_at(ds, omega).T
    X = ExcitationInterpolator(ds)(np.array([omega]), 0.0)[0]
    return np.linalg.solve(-omega**2 * (M + A) - 1j * omega * B + C, X * WAVE_AMPLITUDE)


@pytest.mark.parametrize("period", [1.0, 1.4, 2.0])
def test_regular_wave_response_reaches_the_database_rao(period: float) -> None:
    case, ds = _setup()
    omega = 2.0 * math.pi / period
    dt = period / STEPS_PER_PERIOD
    extra = np.zeros((6, 6))
    extra[0, 0] = SURGE_SPRING
    body = build_body(case.floater, ds, case.environment, dt, extra_stiffness=extra)
    sea = WaveField.regular(2.0 * WAVE_AMPLITUDE, period, depth=case.environment.water_depth,
                            gravity=case.environment.gravity)
    X = ExcitationInterpolator(ds)(sea.omega, 0.0)
    excitation = WaveExcitation(sea, X)
    ramp_time = 20.0 * period

    def force(stage, tau, x, v):
        t = body.time + tau
        ramp = 0.5 - 0.5 * math.cos(math.pi * min(t / ramp_time, 1.0))
        return ramp * excitation(t)

    body.start(0.0, np.zeros(6))
    n = int(round(100 * period / dt))
    t = np.zeros(n)
    x = np.zeros((n, 6))
    for i in range(n):
        body.step(force)
        t[i], x[i] = body.time, body.x
    last = t > t[-1] - 10.0 * period
    basis = np.column_stack([np.cos(omega * t[last]), np.sin(omega * t[last])])
    rao = _frequency_domain_rao(case, ds, omega, extra)
    for dof, name in ((0, "surge"), (2, "heave"), (4, "pitch")):
        c, s = np.linalg.lstsq(basis, x[last, dof], rcond=None)[0]
        z = c + 1j * s  # x = Re{z e^{-i w t}} = Re z cos + Im z sin
        ratio = abs(z) / abs(rao[dof])
        phase = math.degrees(np.angle(z / rao[dof]))
        print(f"T = {period} s {name}: amplitude ratio {ratio:.4f}, phase {phase:+.2f} deg")
        assert abs(ratio - 1.0) <= RAO_AMPLITUDE_RTOL
        assert abs(phase) <= RAO_PHASE_TOL_DEG


def _upcrossing_periods(t: np.ndarray, s: np.ndarray) -> np.ndarray:
    i = np.nonzero((s[:-1] < 0.0) & (s[1:] >= 0.0))[0]
    crossings = t[i] - s[i] * (t[i + 1] - t[i]) / (s[i + 1] - s[i])
    return np.diff(crossings)


def test_heave_free_decay_has_the_linear_natural_period() -> None:
    case, ds = _setup()
    M = case.floater.mass_matrix()
    C = hydrostatic_stiffness_total(ds, case.floater)
    omega = math.sqrt(C[2, 2] / M[2, 2])
    for _ in range(50):  # w^2 (M33 + A33(w)) = C33
        omega = math.sqrt(C[2, 2] / (M[2, 2] + added_mass_at(ds, omega)[2, 2]))
    period = 2.0 * math.pi / omega
    dt = period / STEPS_PER_PERIOD
    body = build_body(case.floater, ds, case.environment, dt)
    start = np.zeros(6)
    start[2] = 0.01
    body.start(0.0, start)
    n = int(round(5 * period / dt))
    t, z = np.zeros(n), np.zeros(n)
    for i in range(n):
        body.step(lambda stage, tau, x, v: np.zeros(6))
        t[i], z[i] = body.time, body.x[2]
    periods = _upcrossing_periods(t, z)
    print(f"heave natural period {period:.4f} s (A33 at it); decay periods "
          + ", ".join(f"{p:.4f}" for p in periods))
    assert len(periods) >= 2
    assert abs(periods[0] / period - 1.0) <= DECAY_PERIOD_RTOL


@pytest.mark.slow  # ~9 s of decay; the free-floating periods stay in the default run
def test_body_on_quasi_static_lines_has_the_linearised_stiffness_period() -> None:
    case, ds = _setup()
    lines = [ln for ln in load_case(BUOY_CASE, ['lines.*.model="quasi-static"']).lines]
    dt = 0.02
    body = build_body(case.floater, ds, case.environment, dt)
    moored = MooredBody(body, lines, case.environment, case.seabed,
                        np.asarray(case.floater.reference_point))
    x_eq = equilibrium(body, lines, moored.arms, moored.centre, case.environment, case.seabed)
    # linearised surge stiffness of the lines about the equilibrium
    h = 1e-4

    def surge_force(dx: float) -> float:
        return sum(line_force_quasi_static(ln, case.environment, case.seabed,
                                           np.add(ln.fairlead, [x_eq[0] + dx, 0.0, x_eq[2]]))[0]
                   for ln in lines)

    k11 = -(surge_force(h) - surge_force(-h)) / (2.0 * h)
    mass = case.floater.mass_matrix()[0, 0]
    omega = math.sqrt(k11 / mass)
    for _ in range(50):
        omega = math.sqrt(k11 / (mass + added_mass_at(ds, omega)[0, 0]))
    expected = 2.0 * math.pi / omega
    start = x_eq.copy()
    start[0] += 0.01
    moored.start(start)
    n = int(round(3.2 * expected / dt))
    t, s = np.zeros(n), np.zeros(n)
    for i in range(n):
        moored.step()
        t[i], s[i] = body.time, body.x[0] - x_eq[0]
    periods = _upcrossing_periods(t, s)
    print(f"K11 = {k11:.2f} N/m, linearised surge period {expected:.3f} s; decay periods "
          + ", ".join(f"{p:.3f}" for p in periods))
    assert len(periods) >= 2
    assert abs(periods[0] / expected - 1.0) <= MOORED_PERIOD_RTOL
