"""The internal damping ratio means what the case file says; the implicit internal damping and
the implicit seabed contact change results by less than the discretisation does, at a
fraction of the cost."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.case.schema import DynamicSettings
from floatmoor.mooring.dg.line import CableProperties, DynamicLine
from floatmoor.simulation.forced import run_forced_motion
from floatmoor.mooring.dg import _kernels as kernels
from tests.conftest import CASES, LINDAHL_CASE


pytestmark = pytest.mark.verification

#: Log-decrement estimate of a Kelvin-Voigt mode's damping ratio over 6 cycles, with the
#: Lax-Friedrichs dissipation (O(h^(p+1)) for a smooth mode) on top: 3 % of the ratio.
DAMPING_RATIO_RTOL = 0.03
#: Implicit (backward Euler, CFL step) against explicit (resolved) seabed contact on the
#: Lindahl chain: the mean cycle maxima differ by 0.4 % (T = 1.25 s) and 0.1 % (3.5 s); 1 %
#: is the accuracy the benchmark asks of a discretisation.
CONTACT_RTOL = 0.01
#: Implicit (backward Euler after each step, at the undamped CFL step) against explicit
#: (in the right-hand side, at its ~10 times smaller step) Kelvin-Voigt damping on a DeepCwind
#: line in regular fairlead motion: the splitting error is first order in dt on a term whose
#: own rate on the resolved modes is small; measured 4e-4 of the tension range. 0.5 %
#: of the range is below the line's time-discretisation error at the explicit step under
#: snap loads (1-3 %).
IMPLICIT_DAMPING_RTOL = 5e-3
#: Reusing the factored damping system until a tangent turns by 1e-3 rad, against
#: rebuilding it every step: measured 1.3e-4 of the tension range.
DAMPING_REUSE_RTOL = 1e-3


def test_internal_damping_ratio_is_that_of_the_first_axial_mode():
    zeta, L, m, EA = 0.02, 20.0, 2.0, 2.0e5
    # the case-file mapping: c_int = 2 zeta L sqrt(EA m) / pi
    case = load_case(LINDAHL_CASE, [f"line_types.chain.internal_damping_ratio={zeta}"])
    line = case.lines[0]
    props = CableProperties.from_case(line, case.environment, case.seabed)
    lt = line.line_type
    assert props.internal_damping == pytest.approx(
        2 * zeta * line.length * math.sqrt(lt.axial_stiffness * lt.mass_per_length) / math.pi)
    # a taut line in vacuum, released from its first axial mode shape
    c_int = 2 * zeta * L * math.sqrt(EA * m) / math.pi
    props = CableProperties(length=L, mass_per_length=m, axial_stiffness=EA, diameter=0.05,
                            material_density=7800.0, internal_damping=c_int, water_density=0.0,
                            gravity=0.0)
    settings = DynamicSettings(elements=8, order=5, cfl=0.8, max_time_step=None,
                               slack_filter=False, seabed_contact="implicit")
    end = np.array([1.01 * L, 0.0, 0.0])
    dg = DynamicLine(props, settings, np.zeros(3), end)
    s = dg.arc_length
    dg.r[..., 0] += (0.002 * L * np.sin(np.pi * s / L)).reshape(dg.r.shape[:2])
    omega = math.pi / L * math.sqrt(EA / m)
    period = 2 * math.pi / omega
    t = np.linspace(0.0, 6 * period, 6 * 200 + 1)
    n = t.size
    fair = np.tile(end, (n, 1))
    af = np.zeros((n, 3))
    dg.solve_path(t, fair, np.zeros_like(fair), np.zeros((n, 3)), af, np.zeros(n), np.zeros(n))
    swing = af[:, 0] - 0.01 * EA  # the anchor force about the static pretension
    peaks = np.array([np.abs(swing[k * 200:(k + 1) * 200]).max() for k in range(6)])
    delta = np.log(peaks[0] / peaks[-1]) / 5  # per cycle
    measured = delta / math.sqrt(4 * math.pi ** 2 + delta ** 2)
    print(f"\ndamping ratio {measured:.5f} (set {zeta}); error {measured / zeta - 1:+.2%}")
    assert measured == pytest.approx(zeta, rel=DAMPING_RATIO_RTOL)


@pytest.mark.slow
@pytest.mark.parametrize("period", [1.25, 3.5])
def test_implicit_contact_matches_resolved_contact_on_lindahl(period):
    from floatmoor.post.statistics import channel_statistics

    results = {}
    for method in ("implicit", "explicit"):
        case = load_case(LINDAHL_CASE, [f"motion.period={period}",
                                        f"motion.ramp_duration={2 * period}",
                                        f"simulation.duration={8 * period}",
                                        f'lines.chain.dynamic.seabed_contact="{method}"'])
        ds = run_forced_motion(case).dataset
        stats = channel_statistics(ds["time"].values,
                                   ds["fairlead_tension"].sel(line="chain").values,
                                   start=2 * period, period=period)
        steps = float(ds["solver_iterations"].sel(line="chain").values[1:].mean())
        results[method] = (stats["mean_cycle_max"], steps)
    (imp, imp_steps), (exp, exp_steps) = results["implicit"], results["explicit"]
    print(f"\nT = {period} s: implicit {imp:.3f} N ({imp_steps:.1f} steps per output), explicit "
          f"{exp:.3f} N ({exp_steps:.1f}); difference {imp / exp - 1:+.2%}")
    assert imp == pytest.approx(exp, rel=CONTACT_RTOL)
    assert exp_steps >= 4 * imp_steps  # the resolved contact needs a much smaller step


def _deepcwind_line_tension(method: str, tangent_tol: float | None = None):
    """Fairlead tension of DeepCwind line 2 (c_int 4.9e6 N s: damping number 0.19) with its
    fairlead in 1.5 m surge and 0.5 m heave at 10 s after a 10 s ramp; steps per sample."""
    case = load_case(CASES / "deepcwind" / "deepcwind_lc34.toml", ['lines.line2.model="dynamic"'])
    ln = case.lines[1]
    settings = dataclasses.replace(ln.dynamic, internal_damping=method, elements=10, order=5,
                                   time_integration="explicit")
    line = DynamicLine(CableProperties.from_case(ln, case.environment, case.seabed), settings,
                       np.asarray(ln.anchor), np.asarray(ln.fairlead))
    line.settle()
    if tangent_tol is not None:
        line.prm[kernels.P_DAMPING_TOL] = tangent_tol
    t = np.arange(0.0, 30.0 + 1e-9, 0.05)
    amp, omega = np.array([1.5, 0.0, 0.5]), 2.0 * math.pi / 10.0
    ramp = np.minimum(t / 10.0, 1.0)
    path = np.asarray(ln.fairlead) + np.outer(ramp * np.sin(omega * t), amp)
    vel = np.outer(ramp * omega * np.cos(omega * t) + (t < 10.0) * np.sin(omega * t) / 10.0,
                   amp)
    n = t.size
    ff, steps = np.zeros((n, 3)), np.zeros(n)
    line.solve_path(t, path, vel, ff, np.zeros((n, 3)), np.zeros(n), steps)
    return np.linalg.norm(ff, axis=1), steps[1:].mean(), line


@pytest.mark.slow  # 8-17 s: the default-run budget (docs/development.md)
def test_implicit_internal_damping_matches_explicit_at_ten_times_the_step():
    explicit, explicit_steps, _ = _deepcwind_line_tension("explicit")
    implicit, implicit_steps, line = _deepcwind_line_tension("implicit")
    rebuilt, _, _ = _deepcwind_line_tension("implicit", tangent_tol=0.0)
    span = np.ptp(explicit)
    error = np.abs(implicit - explicit).max() / span
    reuse = np.abs(implicit - rebuilt).max() / span
    factorisations = line._work.damping[-1][3]
    print(f"\nimplicit vs explicit damping: {error:.2e} of the range {span:.4g} N; steps per "
          f"sample {implicit_steps:.1f} vs {explicit_steps:.1f}; reused factors vs rebuilt "
          f"{reuse:.2e}; rebuilt {factorisations:.0f} times in {implicit_steps * 600:.0f} steps")
    assert error <= IMPLICIT_DAMPING_RTOL
    assert reuse <= DAMPING_REUSE_RTOL
    assert explicit_steps >= 8 * implicit_steps  # the damping no longer sets the step
    assert factorisations <= 0.2 * implicit_steps * 600
