"""The quasi-dynamic line model: the compiled kernel against the plain NumPy oracle
(tests/oracles/quasidynamic_numpy.py), the step API shared with the dynamic line (pieces equal
one path, state round trip, sub-steps), failure reporting, case settings, shape output, and
the start of a fairlead already moving at t = 0."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.errors import CaseError, ModelValidityWarning, SolverError
from floatmoor.motion.fairlead import fairlead_state
from floatmoor.mooring._quasidynamic_kernels import CHAIN_STEPS
from floatmoor.mooring.dg._kernels import hermite
from floatmoor.mooring.quasidynamic import SHAPE_NODES, QuasiDynamicLine
from floatmoor.mooring.quasistatic import QuasiStaticLine
from floatmoor.simulation.assembly import build_line_models
from floatmoor.simulation.forced import run_forced_motion
from tests.conftest import CASES, LINDAHL_CASE
from tests.oracles import quasidynamic_numpy as oracle


pytestmark = pytest.mark.oracle

CASE_B = CASES / "qd_verification" / "s2_d2.toml"
QD = 'lines.chain.model="quasi-dynamic"'

#: Kernel against oracle, on k_QD and on the end forces relative to the largest static force.
#: Both evaluate the same formulas in a different order and form (the oracle: arcsinh and
#: scipy's Simpson; the kernel: chained logs, cancellation-prone but ulp-accurate z), so the
#: positions differ by a few ulps of their size (up to 33 m: ~1e-14 m). Eq. (4) amplifies that
#: by about 4 / dt^2 = 4e4 s^-2 at dt = 0.01 s, and (m + m_a) / W ~ 0.1 s^2/m turns it into
#: ~1e-10 of k_QD at most; observed up to 2e-11.
KERNEL_VS_ORACLE_TOL = 1e-10
#: Oracle step [s]: coarse enough to keep the round-off amplification above small.
ORACLE_DT = 0.01
#: A line started on a fairlead moving at t = 0 against the same line run along the same path
#: from a period earlier, on k_QD and relative on the fairlead tension over the first samples.
#: The start takes the fairlead one and two steps back on the cubic Hermite curve of the
#: first sample interval, whose error (~A (omega dt)^4) eq. (4) divides by dt^2: observed
#: 1.7e-7 in k_QD (with sub-steps 6.8e-8) and 1.4e-7 in tension. Started at rest, k_QD was 0.2
#: off at t = 0 and 12.8 on the first step.
MOVING_START_TOL = 1e-6
#: Steps per period of the moving-start tests: the output interval T / 360 (~2.5 ms, case B's).
STEPS_PER_PERIOD = 360

_ORACLE_CASES = {
    # touchdown, frictionless seabed, horizontal motion (the verification case B line)
    "case-b-touchdown": (CASE_B, []),
    # touchdown with seabed friction 0.3, circular motion, slack phases (k_QD clamped at 0)
    "lindahl-friction-slack": (LINDAHL_CASE, [QD, "motion.period=3.5"]),
    # no seabed contact (deep water) and motion along all three axes: the vertical plane turns
    "suspended-3d": (CASE_B, ["environment.water_depth=3.0", 'motion={kind = "harmonic", '
                              'amplitude = [0.05, 0.1, 0.03], period = [1.3, 1.7, 1.1]}']),
}


def _model(path, overrides=()):
    case = load_case(path, list(overrides))
    line = case.lines[0]
    return case, line, QuasiDynamicLine.from_case(line, case.environment, case.seabed)


def _run(model, t, p, v):
    n = t.size
    out = {"ff": np.zeros((n, 3)), "af": np.zeros((n, 3)), "lb": np.zeros(n),
           "it": np.zeros(n), "k": np.zeros(n)}
    model.solve_path(t, p, v, out["ff"], out["af"], out["lb"], out["it"], factor=out["k"])
    return out


@pytest.mark.parametrize("name", list(_ORACLE_CASES))
def test_kernel_matches_numpy_oracle(name):
    """k_QD and both end forces at every step against the literal NumPy implementation fed
    with the same static catenary solutions (those of the quasi-static model)."""
    path_, overrides = _ORACLE_CASES[name]
    case, line, model = _model(path_, overrides)
    lt = line.line_type
    t = np.arange(301) * ORACLE_DT
    p, v = fairlead_state(case.motion, line, t)
    qd = _run(model, t, p, v)
    qs = QuasiStaticLine.from_case(line, case.environment, case.seabed)
    n = t.size
    sf, sa = np.zeros((n, 3)), np.zeros((n, 3))
    qs.solve_path(t, p, np.zeros_like(p), sf, sa, np.zeros(n), np.zeros(n))
    ref = oracle.run(
        oracle.QDLine(anchor=line.anchor, L=line.length, EA=lt.axial_stiffness,
                      W=lt.weight_in_water(case.environment), CB=qs.friction,
                      seabed=abs(line.anchor[2] - case.environment.seabed_z) < 1e-9,
                      m=lt.mass_per_length, rho_w=case.environment.water_density,
                      Cdn=lt.normal_drag_coefficient, d=lt.diameter,
                      Ca=lt.added_mass_coefficient, rho_c=lt.material_density,
                      spacing=model.station_spacing),
        t, p, np.hypot(sf[:, 0], sf[:, 1]), -sf[:, 2], sf, sa)
    scale = np.abs(sf).max()
    errors = {"k": np.abs(qd["k"] - ref["factor"]).max(),
              "fairlead": np.abs(qd["ff"] - ref["fairlead_force"]).max() / scale,
              "anchor": np.abs(qd["af"] - ref["anchor_force"]).max() / scale}
    print(f"{name}: k_QD in [{qd['k'].min():.4f}, {qd['k'].max():.4f}]; kernel - oracle: "
          + ", ".join(f"{key} {value:.2e}" for key, value in errors.items()))
    assert max(errors.values()) < KERNEL_VS_ORACLE_TOL
    assert np.ptp(qd["k"]) > 0.1  # the motion does load the line dynamically
    if name == "lindahl-friction-slack":
        assert qd["k"].min() == 0.0  # the clamp is exercised


def test_chained_logs_stay_exact_over_long_runs():
    """The logs of the stations are chained from step to step and evaluated directly every
    CHAIN_STEPS steps: after thousands of steps the kernel still matches the oracle (whose
    step i uses samples i-2..i only, so short windows of the path suffice), and every stored
    reference pair keeps log q = log(q)."""
    case, line, model = _model(CASE_B)
    lt = line.line_type
    t = np.arange(2 * CHAIN_STEPS + 600) * ORACLE_DT
    p, v = fairlead_state(case.motion, line, t)
    qd = _run(model, t, p, v)
    qs = QuasiStaticLine.from_case(line, case.environment, case.seabed)
    n = t.size
    sf, sa = np.zeros((n, 3)), np.zeros((n, 3))
    qs.solve_path(t, p, np.zeros_like(p), sf, sa, np.zeros(n), np.zeros(n))
    qd_line = oracle.QDLine(anchor=line.anchor, L=line.length, EA=lt.axial_stiffness,
                            W=lt.weight_in_water(case.environment), CB=qs.friction, seabed=True,
                            m=lt.mass_per_length, rho_w=case.environment.water_density,
                            Cdn=lt.normal_drag_coefficient, d=lt.diameter,
                            Ca=lt.added_mass_coefficient, rho_c=lt.material_density,
                            spacing=model.station_spacing)
    worst = 0.0
    for end in (CHAIN_STEPS - 1, CHAIN_STEPS + 1, 2 * CHAIN_STEPS + 3, n - 1):
        w = slice(end - 3, end + 1)
        ref = oracle.run(qd_line, t[w], p[w], np.hypot(sf[w, 0], sf[w, 1]), -sf[w, 2], sf[w],
                         sa[w])
        worst = max(worst, abs(qd["k"][end] - ref["factor"][-1]))
    invariant = max(np.abs(model.refs[1] - np.log(model.refs[0])).max(),
                    np.abs(model.refs[3] - np.log(model.refs[2])).max())
    print(f"{n} steps: kernel - oracle on k_QD around the chain restarts {worst:.2e}; "
          f"max |log q - log(q)| of the references {invariant:.1e}")
    assert worst < KERNEL_VS_ORACLE_TOL
    assert invariant < 1e-13


def test_advance_in_pieces_equals_one_path_and_state_round_trip():
    """The step API of the dynamic line: ``advance`` sample by sample gives the same numbers
    as ``solve_path`` over the whole path, bit for bit, with and without sub-steps; a saved
    state restored later reproduces the continuation exactly."""
    for overrides in ([], ["lines.chain.quasi_dynamic.max_time_step=0.001"]):
        case, line, whole = _model(CASE_B, overrides)
        t = np.arange(401) * 0.0025
        p, v = fairlead_state(case.motion, line, t)
        ref = _run(whole, t, p, v)
        pieces = QuasiDynamicLine.from_case(line, case.environment, case.seabed)
        forces = np.array([pieces.advance(t[k], p[k], v[k]) for k in range(1, t.size)])
        np.testing.assert_array_equal(forces, ref["ff"][1:])
        assert pieces.time == t[-1] and np.array_equal(pieces.fairlead, p[-1])
        assert np.array_equal(pieces.fairlead_velocity, v[-1])
        # state round trip in the middle of the path
        model = QuasiDynamicLine.from_case(line, case.environment, case.seabed)
        first = _run(model, t[:201], p[:201], v[:201])
        state = model.get_state()
        after = _run(model, t[200:], p[200:], v[200:])
        model.advance(1.5, p[-1], v[-1])  # move on, then go back
        model.set_state(state)
        again = _run(model, t[200:], p[200:], v[200:])
        for key in ("ff", "af", "k"):
            np.testing.assert_array_equal(after[key], again[key])
            np.testing.assert_array_equal(np.concatenate((first[key], after[key][1:])), ref[key])
        assert ref["it"][1:].min() >= 1  # every sample solved the catenary


def test_substeps_follow_the_hermite_path_of_the_fairlead():
    """With ``max_time_step`` each sample interval is split into equal steps with the fairlead
    on the cubic Hermite curve: the same as giving those sub-samples explicitly."""
    dt, sub = 0.01, 4
    case, line, coarse = _model(CASE_B, [f"lines.chain.quasi_dynamic.max_time_step={dt / sub}"])
    t = np.arange(101) * dt
    p, v = fairlead_state(case.motion, line, t)
    out = _run(coarse, t, p, v)
    tf = np.arange(100 * sub + 1) * (dt / sub)
    pf, vf = np.zeros((tf.size, 3)), np.zeros((tf.size, 3))
    for i, ti in enumerate(tf):
        k = min(i // sub, 99)
        hermite(t[k], t[k + 1], p[k], v[k], p[k + 1], v[k + 1], ti, pf[i], vf[i])
    fine = _run(QuasiDynamicLine.from_case(line, case.environment, case.seabed), tf, pf, vf)
    diff = np.abs(out["k"] - fine["k"][::sub]).max()
    print(f"sub-steps against explicit sub-samples: max |dk_QD| = {diff:.2e}")
    assert diff < 1e-9  # sub-step times t0 + i dt against arange: ulps, over dt^2
    assert np.all(out["it"][1:] >= sub)  # one catenary solve (>= 1 iteration) per sub-step


def test_failure_names_line_time_and_reason():
    case, line, model = _model(LINDAHL_CASE, [QD])
    t = np.linspace(0.0, 5.0, 501)
    p, v = fairlead_state(case.motion, line, t)
    p[300:, 2] = -3.5  # fairlead driven below the seabed from sample 300 on
    n = t.size
    ff = np.zeros((n, 3))
    with pytest.raises(SolverError) as info:
        model.solve_path(t, p, v, ff, np.zeros((n, 3)), np.zeros(n), np.zeros(n))
    message = str(info.value)
    assert "line 'chain' (quasi-dynamic)" in message and f"t = {t[300]:.6g} s" in message
    assert "below" in message
    assert model.failed_index == 300
    assert np.all(np.isfinite(ff[:300])) and np.linalg.norm(ff[:300], axis=1).max() > 10.0
    with pytest.raises(ValueError, match="increase"):
        model.solve_path(t[::-1], p, v, ff, np.zeros((n, 3)), np.zeros(n), np.zeros(n))


def test_case_settings_defaults_and_validation():
    case = load_case(LINDAHL_CASE, [QD])
    line = case.lines[0]
    assert line.model == "quasi-dynamic"
    assert line.quasi_dynamic.integration_points == 31  # the paper's Table 3
    assert line.quasi_dynamic.max_time_step is None
    case = load_case(CASE_B, ["lines.chain.quasi_dynamic.integration_points=21",
                              "lines.chain.quasi_dynamic.max_time_step=0.001"])
    assert case.lines[0].quasi_dynamic.integration_points == 21
    assert case.lines[0].quasi_dynamic.max_time_step == 0.001
    with pytest.raises(CaseError) as info:
        load_case(CASE_B, ["lines.chain.quasi_dynamic.integration_points=20"])
    assert info.value.key == "lines[0].quasi_dynamic.integration_points"
    assert "odd" in info.value.expected
    with pytest.raises(CaseError) as info:
        load_case(CASE_B, ["lines.chain.quasi_dynamic.stations=21"])
    assert "unknown key" in info.value.found
    # a line built without the new field keeps working (the dataclass default)
    fields = {f.name: getattr(line, f.name) for f in dataclasses.fields(line)
              if f.name != "quasi_dynamic"}
    assert type(line)(**fields).quasi_dynamic.integration_points == 31


def test_shape_output_of_a_forced_run():
    """Line shapes through run_forced_motion: the static shape on SHAPE_NODES points, ending
    at the fairlead, with the apparent-weight tension (k_QD times the static one up there)."""
    case = load_case(LINDAHL_CASE, [QD, "simulation.duration=1.0", "motion.ramp_duration=0.5",
                                    "simulation.shape_output_interval=0.25"])
    with pytest.warns(ModelValidityWarning, match="alpha"):  # T = 1.25 s: alpha ~1.3 > 0.6
        ds = run_forced_motion(case).dataset
    assert ds.sizes["node"] == SHAPE_NODES and ds.sizes["shape_time"] == 5
    positions = ds["shape_position"].values[0]
    tension = ds["shape_tension"].values[0]
    for j, ts in enumerate(ds["shape_time"].values):
        i = int(np.argmin(np.abs(ds["time"].values - ts)))
        np.testing.assert_allclose(positions[j, -1], ds["fairlead_position"].values[0, i],
                                   atol=1e-9)
        np.testing.assert_allclose(tension[j, -1], ds["fairlead_tension"].values[0, i],
                                   rtol=1e-9)
    assert np.all(np.isfinite(positions)) and np.all(tension >= 0.0)


def _moving_case(overrides=()):
    """Case B without its ramp: x = A sin(omega t), the fairlead a quarter period (pi/2) past
    its extreme at t = 0, at its largest velocity; the output interval a whole fraction of
    the period. Returns the case, its line, the step and the path's exact state at any t."""
    period = float(load_case(CASE_B).motion.period[0])
    dt = period / STEPS_PER_PERIOD
    case = load_case(CASE_B, ["motion.ramp_duration=0.0", f"simulation.output_interval={dt!r}",
                              f"simulation.duration={10 * dt!r}", *overrides])
    line = case.lines[0]
    return case, line, dt, lambda t: fairlead_state(case.motion, line, np.asarray(t))


def _steady_reference(case, line, dt, samples):
    """The line run from rest one period before t = 0 (the same pose: the same stations) to
    ``samples`` steps after it: k_QD and fairlead tension at t = 0, dt, ..., whose two-step
    memory has long forgotten that start."""
    model = QuasiDynamicLine(line, case.environment, case.seabed,
                             time=-STEPS_PER_PERIOD * dt)
    t = (np.arange(STEPS_PER_PERIOD + samples) - STEPS_PER_PERIOD) * dt
    out = _run(model, t, *fairlead_state(case.motion, line, t))
    tension = np.linalg.norm(out["ff"], axis=1)
    return out["k"][STEPS_PER_PERIOD:], tension[STEPS_PER_PERIOD:]


@pytest.mark.parametrize("max_step", [None, 0.001])
def test_a_fairlead_moving_at_the_start_starts_with_its_history(max_step):
    """start_moving gives the line the history of the path it is on: k_QD from t = 0 on is
    that of the line long in motion, with or without sub-steps; a fairlead at rest at the
    start keeps the start at rest bit for bit; once stepped, the history is the line's own."""
    extra = [] if max_step is None else [f"lines.chain.quasi_dynamic.max_time_step={max_step}"]
    case, line, dt, state = _moving_case(extra)
    k_ref, _ = _steady_reference(case, line, dt, 11)
    model = QuasiDynamicLine.from_case(line, case.environment, case.seabed)
    assert model.start_moving(state, dt)
    assert model.time == 0.0 and np.array_equal(model.fairlead, line.fairlead)
    t = np.arange(11) * dt
    out = _run(model, t, *state(t))
    error = np.abs(out["k"] - k_ref).max()
    print(f"moving start (max_time_step {max_step}): k_QD(0) = {out['k'][0]:.6f}, "
          f"against the steady run {error:.1e}")
    assert abs(k_ref[0] - 1.0) > 0.1  # the motion loads the line at t = 0 already
    assert error <= MOVING_START_TOL
    with pytest.raises(ValueError, match="before the first step"):
        model.start_moving(state, dt)
    # at rest at the start (a velocity of zero): nothing changes
    still = QuasiDynamicLine.from_case(line, case.environment, case.seabed)
    fresh = still.state_arrays()
    assert not still.start_moving(lambda t: (state(t)[0], np.zeros((np.size(t), 3))), dt)
    for key, value in still.state_arrays().items():
        np.testing.assert_array_equal(value, fresh[key])


def test_a_forced_run_starts_a_moving_fairlead_in_motion():
    """run_forced_motion builds the quasi-dynamic line on the motion it follows: its tension
    from t = 0 is the steady one, with no step at the start; with the case's ramp (at rest at
    t = 0) the line is built at rest as before, bit for bit."""
    case, line, dt, _ = _moving_case()
    _, tension_ref = _steady_reference(case, line, dt, 11)
    tension = run_forced_motion(case).dataset["fairlead_tension"].values[0]
    error = np.abs(tension - tension_ref).max() / tension_ref.min()
    print(f"forced run started in motion: tension against the steady run {error:.1e}")
    assert error <= MOVING_START_TOL
    ramped = load_case(CASE_B)
    (model,) = build_line_models(ramped)
    fresh = QuasiDynamicLine.from_case(ramped.lines[0], ramped.environment, ramped.seabed)
    for key, value in model.state_arrays().items():
        np.testing.assert_array_equal(value, fresh.state_arrays()[key])
