"""The dynamic lines of a coupled run advanced once per body step and evaluated together
(floatmoor.mooring.dg.batch; docs/theory/floater.md#coupling-scheme): explicit lines give the
same forces, to the last bit, as the two advances per step and the line-by-line stage forces
before it; an implicit line steps over the body step as one interval, its middle state
interpolated in time close to the one its steps reach there."""

from __future__ import annotations

import re

import numpy as np
import pytest
from numpy.typing import NDArray

from floatmoor.case.coupling import CoupledCase
from floatmoor.case.load import load_case
from floatmoor.errors import SolverError
from floatmoor.mooring.dg import _implicit_kernels as _ik
from floatmoor.mooring.dg import _kernels as _k
from floatmoor.mooring.dg._batch_kernels import dg_end_forces_batch, hermite_middle
from floatmoor.mooring.dg.batch import DynamicLineBatch
from floatmoor.mooring.dg.line import DynamicLine
from floatmoor.mooring.dg.reference import reference_element
from floatmoor.simulation.assembly import assemble
from floatmoor.simulation.coupled import ONE_INTERVAL_LIMIT, MooredBody
from floatmoor.simulation.coupled_run import settings_from_case
from tests.conftest import CASES
from tests.oracles import dg_numpy as oracle


pytestmark = pytest.mark.oracle

BUOY_CASE = CASES / "cylinder_buoy" / "buoy_regular_T1.20.toml"
#: The buoy with cheap chains (as tests/simulation/test_coupling_step.py), each line another way:
#: explicit, implicit, and "auto" on 5 elements (a second discretisation; its 1.2 s window
#: ends inside a body step, where the advance falls back to two solve_path calls).
OVERRIDES = ["simulation.duration=1.5", "waves.ramp_duration=0.5",
             'waves={kind = "regular", height = 0.02, period = 1.2}',
             "line_types.chain.axial_stiffness=2.0e4",
             "lines.*.dynamic.elements=4", "lines.*.dynamic.order=3",
             'lines.line1.dynamic.time_integration="explicit"',
             'lines.line2.dynamic.time_integration="implicit"',
             'lines.line3.dynamic.time_integration="auto"', "lines.line3.dynamic.elements=5"]
#: The lines all explicit (two discretisations): the batch must give the two advances' bits.
EXPLICIT = OVERRIDES[:4] + ["lines.*.dynamic.elements=4", "lines.*.dynamic.order=3",
                            'lines.*.dynamic.time_integration="explicit"',
                            "lines.line3.dynamic.elements=5", "simulation.duration=0.6"]
#: The oracle's end forces against the kernel's: round-off of sums over a few nodes
#: (relative to the tension).
ORACLE_RTOL = 1e-12
#: The interpolated middle state's fairlead force against the one the line's steps reach at
#: the middle (the same step size on the same fairlead curve), relative to the largest
#: fairlead force of the run: measured 4.3 % at worst on these soft chains on their 10 ms body
#: step (rms 0.32 %) with steps doubling after 2 good ones, 7.5 % after 4 (GOOD_STEPS) with the
#: slack-taut event check (other steps around the snaps); 1.3 x margin. The end state is off by
#: up to 390 %.
MIDDLE_RTOL = 0.10


class TwoCallScheme(MooredBody):
    """The scheme before the batch: every memory line advanced by its own ``solve_path`` to
    t + dt / 2 before stage 1 and to t + dt before stage 3, each stage's forces from each
    line's ``end_forces_moving``."""

    def _advance_dynamic(self, *args: object) -> None:
        pass

    def _advance_memory_lines(self, time: float, x: NDArray, v: NDArray) -> None:
        pos, vel = self._points(x, v)
        for i, model in enumerate(self.models):
            if model is not None:
                ff, af, lb, st = np.zeros((1, 3)), np.zeros((1, 3)), np.zeros(1), np.zeros(1)
                model.solve_path(np.array([time]), pos[i:i + 1], vel[i:i + 1], ff, af, lb, st)
                self.laid_length[i] = lb[0]

    def line_forces(self, x: NDArray, v: NDArray | None = None) -> tuple[NDArray, NDArray]:
        _, vel = self._points(x, np.zeros(6) if v is None else v)
        out = [m.end_forces() if v is None else m.end_forces_moving(vel[i])
               for i, m in enumerate(self.models)]
        return np.array([f for f, _ in out]), np.array([a for _, a in out])

    def _points(self, x: NDArray, v: NDArray) -> tuple[NDArray, NDArray]:
        from floatmoor.body.kinematics import points_state

        return points_state(x, v, self.arms, self.centre)


def _system(scheme: type[MooredBody], overrides: list[str] = OVERRIDES):
    case = load_case(BUOY_CASE, overrides)
    settings = settings_from_case(case)
    system = assemble(case, settings)
    system.moored.__class__ = scheme
    steps = int(round(case.simulation.duration / CoupledCase.of(case).time_step))
    system.loads.prepare(system.moored.body.time, steps)
    return system, steps


def _observed(moored: MooredBody, stages: list[NDArray]) -> None:
    """Record every stage's 6-DOF mooring force and its fairlead and anchor forces (those of
    ``line_forces`` at the stage's state: a run whose lines are all dynamic takes the stage's
    force without it) into ``stages``."""
    original = moored.mooring_force

    def observed(x: NDArray, v: NDArray) -> NDArray:
        f = original(x, v)
        ff, af = moored.line_forces(x, v)
        stages.append(np.concatenate((f[None, :3], f[None, 3:], ff, af)))
        return f

    moored.mooring_force = observed  # type: ignore[method-assign]


def test_explicit_lines_give_the_forces_of_two_advances() -> None:
    batched, steps = _system(MooredBody, EXPLICIT)
    reference, _ = _system(TwoCallScheme, EXPLICIT)
    a, b = batched.moored, reference.moored
    assert [type(m) for m in a.models] == [DynamicLine] * 3
    assert all(m.implicit is None for m in a.models)
    stages_a: list[NDArray] = []
    stages_b: list[NDArray] = []
    _observed(a, stages_a)
    _observed(b, stages_b)
    for _ in range(steps):
        a.step()
        b.step()
    assert len(stages_a) == len(stages_b) == 4 * steps
    # the same bits: every stage's forces, the body, the lines' states and laid lengths
    assert np.array_equal(np.array(stages_a), np.array(stages_b))
    assert np.array_equal(a.body.x, b.body.x) and np.array_equal(a.body.v, b.body.v)
    for ma, mb in zip(a.models, b.models):
        assert np.array_equal(ma.r, mb.r) and np.array_equal(ma.v, mb.v)
        assert ma.time == mb.time and np.array_equal(ma.fairlead, mb.fairlead)
    assert np.array_equal(a.laid_length, b.laid_length)
    assert np.abs(np.array(stages_a)).max() > 0.1  # (the lines pull)


def _fairlead_force(batch: DynamicLineBatch, j: int, r: NDArray, v: NDArray,
                    fairlead: NDArray) -> NDArray:
    g, row = batch._where[j]
    el = g.element
    ff, af, laid = np.zeros((1, 3)), np.zeros((1, 3)), np.zeros(1)
    dg_end_forces_batch(r[None], v[None], g.anchors[row:row + 1], fairlead[None],
                        np.zeros((1, 3)), g.prm[row:row + 1], el.differentiation, el.lift,
                        el.weights, ff, af, laid)
    return ff[0]


def test_implicit_middle_state_is_interpolated(monkeypatch: pytest.MonkeyPatch) -> None:
    """Each implicit advance (line 2, and line 3 while "auto" steps implicitly) is one kernel
    call over [t, t + dt]; the middle state it keeps is close to the state the same steps
    reach at t + dt / 2 (the line run again from t to there on the same fairlead curve), and
    far from the end state."""
    one_interval = DynamicLineBatch._advance_implicit
    errors: list[tuple[float, float, float]] = []
    kernel_calls: list[int] = []

    def checked(self, j, line, g, row, t_end, pos_end, vel_end) -> None:
        integ = line.implicit
        r0, v0, t0 = line.r.copy(), line.v.copy(), line.time
        p0, u0, saved = line.fairlead.copy(), line.fairlead_velocity.copy(), integ.state_arrays()
        run_kernel = line.run_kernel
        calls = []
        monkeypatch.setattr(line, "run_kernel", lambda *a: calls.append(a) or run_kernel(*a))
        one_interval(self, j, line, g, row, t_end, pos_end, vel_end)
        monkeypatch.setattr(line, "run_kernel", run_kernel)
        kernel_calls.append(len(calls))
        assert calls[0][0] is True and list(calls[0][1]) == [t0, t_end]
        after = line.r.copy(), line.v.copy(), integ.state_arrays()
        h = t_end - t0
        p_mid = 0.5 * (p0 + pos_end) + h / 8.0 * (u0 - vel_end)  # the fairlead curve's middle
        u_mid = 1.5 * (pos_end - p0) / h - 0.25 * (u0 + vel_end)
        line.r[...], line.v[...] = r0, v0
        integ.set_state_arrays(saved)
        integ.cs[_ik.CS_LEVEL] += 1  # the same step size on half the interval
        out = [np.zeros((2, 3)), np.zeros((2, 3)), np.zeros(2), np.zeros(2)]
        assert run_kernel(True, np.array([t0, t0 + h / 2]), np.array([p0, p_mid]),
                          np.array([u0, u_mid]), *out)[0] == _k.DG_OK
        exact = _fairlead_force(self, j, line.r, line.v, p_mid)
        interpolated = _fairlead_force(self, j, g.r_mid[row], g.v_mid[row], p_mid)
        end = _fairlead_force(self, j, after[0], after[1], p_mid)
        errors.append((float(np.linalg.norm(interpolated - exact)),
                       float(np.linalg.norm(end - exact)), float(np.linalg.norm(exact))))
        line.r[...], line.v[...] = after[0], after[1]
        integ.set_state_arrays(after[2])

    monkeypatch.setattr(DynamicLineBatch, "_advance_implicit", checked)
    system, steps = _system(MooredBody)
    system.moored._batch.batch_kernel = False  # (one call per line, checked above)
    for _ in range(steps):
        system.moored.step()
    e = np.array(errors)
    assert len(e) >= steps and set(kernel_calls) == {1}
    scale = e[:, 2].max()
    assert e[:, 0].max() < MIDDLE_RTOL * scale
    assert e[:, 1].max() > 10.0 * MIDDLE_RTOL * scale  # (the end state would fail)


@pytest.mark.parametrize("extra, batched", [
    ([], 1),  # an explicit line beside an implicit one of its discretisation
    (['lines.line1.dynamic.time_integration="implicit"'], 2),
    # one discretisation, all implicit: after the first step, the whole-batch path
    (['lines.*.dynamic.time_integration="implicit"', "lines.line3.dynamic.elements=4"], 3),
    # the same, "auto": the whole-batch path between its decisions
    (['lines.*.dynamic.time_integration="auto"', "lines.line3.dynamic.elements=4"], 3),
    (['seabed.friction_model="stick_spring"'], 0)])  # (its anchors: one call per line)
def test_batch_kernel_gives_the_bits_of_one_call_per_line(extra: list[str],
                                                          batched: int) -> None:
    """The implicit lines of one discretisation advanced in one kernel call
    (``_batch_kernels.dg_advance_implicit_batch``) take the steps of one kernel call per line
    (:meth:`DynamicLineBatch._advance_implicit`, itself checked above): every stage's forces,
    the body, the lines' states, laid lengths and integrator states to the last bit."""
    a, steps = _system(MooredBody, OVERRIDES + extra)
    b, _ = _system(MooredBody, OVERRIDES + extra)
    b.moored._batch.batch_kernel = False
    batch = a.moored._batch
    counts: list[int] = []
    wholes: list[float] = []
    run = batch._run_batch_kernel
    batch._run_batch_kernel = (  # type: ignore[method-assign]
        lambda g: counts.append(int(g.active.sum())) or run(g))
    advance_all = batch._advance_all
    batch._advance_all = (  # type: ignore[method-assign]
        lambda t_end, *a: wholes.append(t_end) or advance_all(t_end, *a))
    # (the counters of the settle: a line settled before, its shape reused, counted none)
    start = [[m.implicit.cs.copy() for m in s.moored.models if m.implicit is not None]
             for s in (a, b)]
    stages_a: list[NDArray] = []
    stages_b: list[NDArray] = []
    _observed(a.moored, stages_a)
    _observed(b.moored, stages_b)
    for _ in range(steps):
        a.moored.step()
        b.moored.step()
    assert (max(counts) if counts else 0) == batched
    assert len(stages_a) == len(stages_b) == 4 * steps
    if "auto" in str(extra):
        assert 0 < len(wholes) < steps - 2
    else:
        assert len(wholes) == (steps - 1 if batched == 3 else 0)
    assert np.array_equal(np.array(stages_a), np.array(stages_b))
    assert np.array_equal(a.moored.body.x, b.moored.body.x)
    for ma, mb in zip(a.moored.models, b.moored.models):
        assert np.array_equal(ma.r, mb.r) and np.array_equal(ma.v, mb.v)
        assert ma.time == mb.time and np.array_equal(ma.fairlead, mb.fairlead)
        if ma.implicit is not None:
            sa, sb = ma.implicit.state_arrays(), mb.implicit.state_arrays()
            sa["implicit_cs"] = sa["implicit_cs"] - start[0].pop(0)
            sb["implicit_cs"] = sb["implicit_cs"] - start[1].pop(0)
            assert all(np.array_equal(sa[k], sb[k]) for k in sa)
    assert np.array_equal(a.moored.laid_length, b.moored.laid_length)


@pytest.mark.parametrize("z", [0.08, 2.0])
def test_one_interval_only_below_the_dashpot_limit(tmp_path, z: float) -> None:
    """The model problem of tests/simulation/test_coupling_stability.py, its line implicit: at
    Z dt / M = 0.08 it steps over the body step as one interval, at 2 (where the interpolated
    middle state would be unstable) over the two samples, and both damp a kick."""
    from floatmoor.body.cummins import CumminsBody
    from tests.simulation import test_coupling_stability as stab

    path = tmp_path / "case.toml"
    path.write_text(stab.CASE.replace("order = 4", 'order = 4\ntime_integration = "implicit"'))
    case = load_case(path)
    lt = case.lines[0].line_type
    dt = z * stab.BODY_MASS / np.sqrt(lt.axial_stiffness * lt.mass_per_length)
    big = 1e9
    body = CumminsBody(np.diag([stab.BODY_MASS] + [big] * 5), np.zeros((6, 6)),
                       np.diag([0.0] + [big] * 5), np.zeros(6), None, dt)
    moored = MooredBody(body, case.lines, case.environment, case.seabed,
                        np.array(case.lines[0].fairlead))
    moored.start(np.zeros(6))
    assert moored.models[0].implicit is not None
    assert moored.dashpot_number() == pytest.approx(z, rel=0.01)  # (the sag tilts e)
    assert list(moored._batch.one_interval) == [z <= ONE_INTERVAL_LIMIT]
    body.static_force = -np.concatenate((moored.line_forces(np.zeros(6))[0][0], np.zeros(3)))
    body.v[0] = stab.KICK
    speeds = []
    for _ in range(40):
        moored.step()
        speeds.append(body.v[0])
    assert np.abs(speeds[30:]).max() <= stab.DECAYED * stab.KICK


def test_hermite_middle_matches_the_polynomials() -> None:
    """The kernel's middle values are those of the cubic (and quintic) Hermite curves: exact
    on polynomials of their degree."""
    rng = np.random.default_rng(5)
    c = rng.normal(size=(6, 2, 3, 3))
    h = 0.3

    def at(s: float, deg: int, d: int) -> NDArray:
        return sum(np.prod(range(k - d + 1, k + 1)) * c[k] * s ** (k - d) / h ** d
                   for k in range(d, deg + 1))

    for deg, quintic in ((3, False), (5, True)):
        r_mid, v_mid = np.zeros((2, 3, 3)), np.zeros((2, 3, 3))
        hermite_middle(at(0, deg, 0), at(0, deg, 1), at(0, deg, 2), at(1, deg, 0),
                       at(1, deg, 1), at(1, deg, 2), h, quintic, r_mid, v_mid)
        assert np.allclose(r_mid, at(0.5, deg, 0), rtol=1e-12, atol=1e-12)
        assert np.allclose(v_mid, at(0.5, deg, 1), rtol=1e-12, atol=1e-12)


def test_restored_states_are_the_batch_states() -> None:
    """A state restored in place (a resumed checkpoint) is what the next stages evaluate."""
    system, _ = _system(MooredBody)
    moored = system.moored
    saved = moored.state_arrays()
    moored.step()
    moored.set_state_arrays(saved)
    ff, _ = moored.line_forces(moored.body.x, moored.body.v)
    fresh, _ = _system(MooredBody)
    ff0, _ = fresh.moored.line_forces(fresh.moored.body.x, fresh.moored.body.v)
    assert np.array_equal(ff, ff0)


@pytest.mark.parametrize("line", [0, 1])
def test_a_failing_line_fails_as_before(line: int) -> None:
    """A line whose state is not finite stops the step with the error the two advances gave
    (the line, the quantity, the arc length and the time): an explicit line (0) at the middle
    sample, as before; an implicit line (1), now one interval, at the step's end."""
    messages = []
    for scheme in (MooredBody, TwoCallScheme):
        system, _ = _system(scheme)
        system.moored.models[line].v[1, 2, 0] = np.nan
        with pytest.raises(SolverError) as err:
            system.moored.step()
        messages.append(str(err.value))
    assert f"line 'line{line + 1}' (dynamic)" in messages[0]
    if line == 0:
        assert messages[0] == messages[1]
    else:
        assert messages[0] == messages[1].replace("t = 0.005 s", "t = 0.01 s")
        assert "t = 0.01 s" in messages[0]


def test_a_failing_line_in_the_whole_batch_step() -> None:
    """Every line implicit and of one discretisation: a line whose state is not finite stops
    the step taken in one call for all with the error of one call per line (the line, the
    quantity, the arc length and the time)."""
    extra = ['lines.*.dynamic.time_integration="implicit"', "lines.line3.dynamic.elements=4"]
    messages = []
    for batch_kernel in (True, False):
        system, _ = _system(MooredBody, OVERRIDES + extra)
        moored = system.moored
        moored._batch.batch_kernel = batch_kernel
        for _ in range(2):
            moored.step()
        assert (moored._batch._plain_until == np.inf) == batch_kernel
        moored.models[1].v[1, 2, 0] = np.nan
        with pytest.raises(SolverError) as err:
            moored.step()
        # (without the rejected steps' count: a line settled before counted none in its settle)
        messages.append(re.sub(r"\d+ rejected", "", str(err.value)))
        assert moored._batch._plain_until == -np.inf  # (each line looked at again)
    assert messages[0] == messages[1] and "line 'line2' (dynamic)" in messages[0]


@pytest.mark.parametrize("c_int", [0.0, 50.0])
def test_batch_end_forces_match_the_oracle(c_int: float) -> None:
    rng = np.random.default_rng(3)
    K, p, m = 3, 3, 4
    ops = oracle.operators(p)
    h, EA, mass = 2.0, 1.0e5, 1.5
    anchors = rng.normal(size=(m, 3))
    ends = anchors + np.array([5.0, 0.5, 2.0])
    s = (np.arange(K)[:, None] + 0.5 * (ops.nodes[None, :] + 1.0)).reshape(-1) / K
    r = np.array([a + 1.02 * np.outer(s, e - a) for a, e in zip(anchors, ends)])
    r = r.reshape(m, K, p + 1, 3) + 1e-3 * rng.normal(size=(m, K, p + 1, 3))
    v = rng.normal(size=r.shape)
    fvel = rng.normal(size=(m, 3))
    prm = np.zeros((m, _k.N_PRM))
    prm[:, _k.P_M], prm[:, _k.P_EA], prm[:, _k.P_CINT], prm[:, _k.P_H] = mass, EA, c_int, h
    prm[:, _k.P_C] = np.sqrt(EA / mass)
    prm[:, _k.P_ZB] = -1e9  # (no node on the seabed)
    ff, af, laid = np.zeros((m, 3)), np.zeros((m, 3)), np.zeros(m)
    anchors.flags.writeable = False  # as the batch holds them: the kernel's one signature
    dg_end_forces_batch(r, v, anchors, ends, fvel, prm, ops.D, ops.LIFT, ops.weights, ff, af,
                        laid)
    for line in range(m):
        f = oracle.tension_field(r[line], v[line], anchors[line], ends[line], fvel[line],
                                 D=ops.D, LIFT=ops.LIFT, h=h, m=mass, EA=EA, c_int=c_int)
        scale = np.abs(f.Nstar).max()
        assert np.allclose(ff[line], -f.Nstar[-1], rtol=0.0, atol=ORACLE_RTOL * scale)
        assert np.allclose(af[line], f.Nstar[0], rtol=0.0, atol=ORACLE_RTOL * scale)
    assert np.all(laid == 0.0)


def test_batched_mooring_force_composes_its_kernels() -> None:
    """The stage kernel of a run whose lines are all dynamic is the three kernels it composes,
    called one after the other, to the last bit (each has its own NumPy oracle)."""
    from floatmoor.body._kinematics_kernels import generalised_force_into, points_state_into
    from floatmoor.simulation._coupling_kernels import batched_mooring_force

    system, steps = _system(MooredBody, EXPLICIT[:-1] + ["lines.line3.dynamic.elements=4"])
    moored = system.moored
    assert moored._all_batched
    for _ in range(3):
        moored.step()
    rng = np.random.default_rng(11)
    x, v = 0.01 * rng.normal(size=6), 0.1 * rng.normal(size=6)
    for mid in (False, True):
        moored._at_mid = mid
        force = moored.mooring_force(x, v)
        args = moored._batch.end_force_arguments(mid)
        pos, vel = np.zeros((3, 3)), np.zeros((3, 3))
        ff, af, out = np.zeros((3, 3)), np.zeros((3, 3)), np.zeros(6)
        points_state_into(x, v, moored.arms, moored.centre, pos, vel)
        r, rv, anchors, fpos, prm, D, LIFT, weights, laid = args
        dg_end_forces_batch(r, rv, anchors, fpos, vel, prm, D, LIFT, weights, ff, af, laid)
        generalised_force_into(x, ff, moored.arms, out)
        assert np.array_equal(force, out)
        # and the general path (line by line through line_forces) gives the same bits
        moored._all_batched = False
        assert np.array_equal(moored.mooring_force(x, v), out)
        moored._all_batched = True
    assert np.abs(out).max() > 0.1


@pytest.mark.parametrize("K", [1, 2, 4])
@pytest.mark.parametrize("c_int", [0.0, 50.0])
def test_batch_end_forces_are_the_tension_fields_bits(K: int, c_int: float) -> None:
    """The end forces from the end nodes alone are the fluxes of the whole tension field
    (``dg_tension_field``), to the last bit: taut and slack ends, in and out of the water,
    one element and several, with and without the internal damping."""
    rng = np.random.default_rng(7 + K)
    p, m = 3, 6
    ops = reference_element(p)
    h, EA, mass = 2.0, 1.0e5, 1.5
    anchors = rng.normal(size=(m, 3))
    stretch = np.array([1.02, 0.97, 1.02, 0.97, 1.001, 1.05])  # (slack where < 1)
    ends = anchors + np.array([1.0, 0.1, 0.4]) * h * K
    s = (np.arange(K)[:, None] + 0.5 * (ops.nodes[None, :] + 1.0)).reshape(-1) / K
    r = np.array([a + f * np.outer(s, e - a) for a, e, f in zip(anchors, ends, stretch)])
    r = r.reshape(m, K, p + 1, 3) + 1e-3 * rng.normal(size=(m, K, p + 1, 3))
    r[::2, ..., 2] -= 3.0 * h * K  # (submerged: the added mass in the impedance)
    v = rng.normal(size=r.shape)
    fvel = rng.normal(size=(m, 3))
    prm = np.zeros((m, _k.N_PRM))
    prm[:, _k.P_M], prm[:, _k.P_EA], prm[:, _k.P_CINT], prm[:, _k.P_H] = mass, EA, c_int, h
    prm[:, _k.P_C], prm[:, _k.P_MAT] = np.sqrt(EA / mass), 0.3
    prm[:, _k.P_ZB], prm[:, _k.P_D] = np.median(r[..., 2]), 0.01  # (half the nodes laid)
    ff, af, laid = np.zeros((m, 3)), np.zeros((m, 3)), np.zeros(m)
    anchors.flags.writeable = False
    dg_end_forces_batch(r, v, anchors, ends, fvel, prm, ops.differentiation, ops.lift,
                        ops.weights, ff, af, laid)
    for line in range(m):
        q, qt, N = (np.zeros((K, p + 1, 3)) for _ in range(3))
        Nstar, faces, slack = np.zeros((K + 1, 3)), np.zeros((K + 1, 3)), np.zeros(K)
        _k.dg_tension_field(r[line], v[line], anchors[line], ends[line], fvel[line], prm[line],
                            ops.differentiation, ops.lift, q, qt, N, Nstar, faces, slack)
        assert np.array_equal(ff[line], -Nstar[K]) and np.array_equal(af[line], Nstar[0])
        on_bed = r[line, ..., 2] <= prm[line, _k.P_ZB] + 0.1 * prm[line, _k.P_D]
        assert laid[line] == pytest.approx(0.5 * h * (on_bed * ops.weights).sum(), rel=1e-12)
    assert 0.0 < laid.sum() < m * K * h
