"""The dynamic lines of a coupled run advanced once per body step and evaluated together
(floatmoor.mooring.dg.batch; docs/theory/floater.md#coupling-scheme): the same forces, to
the last bit, as the two advances per step and the line-by-line stage forces before it."""

from __future__ import annotations

import numpy as np
import pytest
from numpy.typing import NDArray

from floatmoor.case.load import load_case
from floatmoor.errors import SolverError
from floatmoor.mooring.dg import _kernels as _k
from floatmoor.mooring.dg._batch_kernels import dg_end_forces_batch
from floatmoor.mooring.dg.line import DynamicLine
from floatmoor.simulation.assembly import assemble
from floatmoor.simulation.coupled import MooredBody
from floatmoor.simulation.coupled_run import settings_from_case
from tests.conftest import CASES
from tests.oracles import dg_numpy as oracle

BUOY_CASE = CASES / "cylinder_buoy" / "buoy_regular_T1.20.toml"
#: The buoy with cheap chains (as tests/body/test_coupling_step.py), each line another way:
#: explicit, implicit, and "auto" on 5 elements (a second discretisation; its 1.2 s window
#: ends inside a body step, where the advance falls back to two solve_path calls).
OVERRIDES = ["simulation.duration=1.5", "waves.ramp_duration=0.5",
             'waves={kind = "regular", height = 0.02, period = 1.2}',
             "line_types.chain.axial_stiffness=2.0e4",
             "lines.*.dynamic.elements=4", "lines.*.dynamic.order=3",
             'lines.line1.dynamic.time_integration="explicit"',
             'lines.line2.dynamic.time_integration="implicit"',
             'lines.line3.dynamic.time_integration="auto"', "lines.line3.dynamic.elements=5"]
#: The oracle's end forces against the kernel's: round-off of sums over a few nodes
#: (relative to the tension).
ORACLE_RTOL = 1e-12


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


def _system(scheme: type[MooredBody]):
    case = load_case(BUOY_CASE, OVERRIDES)
    settings = settings_from_case(case)
    system = assemble(case, settings)
    system.moored.__class__ = scheme
    steps = int(round(case.simulation.duration / settings.time_step))
    system.loads.prepare(system.moored.body.time, steps)
    return system, steps


def _observed(moored: MooredBody, stages: list[NDArray]) -> None:
    """Record every stage's fairlead and anchor forces into ``stages``."""
    original = moored.line_forces

    def observed(x: NDArray, v: NDArray | None = None) -> tuple[NDArray, NDArray]:
        ff, af = original(x, v)
        stages.append(np.concatenate((ff, af)))
        return ff, af

    moored.line_forces = observed  # type: ignore[method-assign]


def test_one_advance_per_step_gives_the_forces_of_two() -> None:
    batched, steps = _system(MooredBody)
    reference, _ = _system(TwoCallScheme)
    a, b = batched.moored, reference.moored
    models = a.models
    assert [type(m) for m in models] == [DynamicLine] * 3
    assert models[0].implicit is None and models[2].auto is not None
    stages_a: list[NDArray] = []
    stages_b: list[NDArray] = []
    _observed(a, stages_a)
    _observed(b, stages_b)
    fell_back = 0
    for _ in range(steps):
        auto = models[2].auto
        if auto.counters is not None and models[2].plain_steps_until(a.body.time
                                                                    + a.body.dt) is None:
            fell_back += 1
        a.step()
        b.step()
    assert fell_back >= 1  # the "auto" line's window ended inside a step at least once
    assert len(stages_a) == len(stages_b) == 4 * steps
    # the same bits: every stage's forces, the body, the lines' states and laid lengths
    assert np.array_equal(np.array(stages_a), np.array(stages_b))
    assert np.array_equal(a.body.x, b.body.x) and np.array_equal(a.body.v, b.body.v)
    for ma, mb in zip(a.models, b.models):
        assert np.array_equal(ma.r, mb.r) and np.array_equal(ma.v, mb.v)
        assert ma.time == mb.time and np.array_equal(ma.fairlead, mb.fairlead)
    assert np.array_equal(a.laid_length, b.laid_length)
    assert np.abs(np.array(stages_a)).max() > 0.1  # (the lines pull)


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
    (the line, the quantity, the arc length and the time), explicit (0) or implicit (1)."""
    messages = []
    for scheme in (MooredBody, TwoCallScheme):
        system, _ = _system(scheme)
        system.moored.models[line].v[1, 2, 0] = np.nan
        with pytest.raises(SolverError) as err:
            system.moored.step()
        messages.append(str(err.value))
    assert messages[0] == messages[1]
    assert f"line 'line{line + 1}' (dynamic)" in messages[0]


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
    work = [np.zeros((K, p + 1, 3)) for _ in range(3)] + [np.zeros((K + 1, 3)),
                                                          np.zeros((K + 1, 3)), np.zeros(K)]
    ff, af, laid = np.zeros((m, 3)), np.zeros((m, 3)), np.zeros(m)
    dg_end_forces_batch(r, v, anchors, ends, fvel, prm, ops.D, ops.LIFT, ops.weights, *work,
                        ff, af, laid)
    for line in range(m):
        f = oracle.tension_field(r[line], v[line], anchors[line], ends[line], fvel[line],
                                 D=ops.D, LIFT=ops.LIFT, h=h, m=mass, EA=EA, c_int=c_int)
        scale = np.abs(f.Nstar).max()
        assert np.allclose(ff[line], -f.Nstar[-1], rtol=0.0, atol=ORACLE_RTOL * scale)
        assert np.allclose(af[line], f.Nstar[0], rtol=0.0, atol=ORACLE_RTOL * scale)
    assert np.all(laid == 0.0)
