"""The implicit (generalised-alpha) step of a DG mooring system: the bordered Jacobian against
central differences of the system's force, one step against the NumPy oracle
(:mod:`tests.oracles.dg_system_implicit_numpy`: dense Newton on a finite-difference
Jacobian), and a system of one section against the single line's implicit steps."""

from __future__ import annotations

from dataclasses import replace
from types import SimpleNamespace

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.case.schema import DynamicSettings
from floatmoor.mooring.dg import _implicit_kernels as ik
from floatmoor.mooring.dg import _system_implicit_kernels as si
from floatmoor.mooring.dg import _system_kernels as sk
from floatmoor.mooring.dg.line import CableProperties, DynamicLine
from floatmoor.mooring.dg.system import DynamicSystem, SystemSection
from floatmoor.mooring.dg.system_parts import point_contact
from tests.conftest import CASES
from tests.oracles import dg_numpy as oracle
from tests.oracles import dg_system_implicit_numpy as system_oracle
from tests.mooring.dg.test_mooring_dg_kernels import oracle_params


pytestmark = pytest.mark.oracle

#: Central differences with h = 1e-6 of the state's scale: truncation and roundoff both
#: ~1e-9 of the largest entry (as tests/mooring/dg/test_dg_implicit_kernels.py's JACOBIAN_RTOL).
JACOBIAN_RTOL = 1e-6
#: Kernel step (bordered analytic Jacobian, banded LU and Schur complement) against the oracle
#: step (dense finite-difference Jacobian): both iterate Newton to a 1e-14 m correction (as
#: tests/mooring/dg/test_dg_implicit_kernels.py's STEP_RTOL).
STEP_RTOL = 1e-9
SEABED = -60.0


def point(name: str, kind: str, position, **kw) -> SimpleNamespace:
    """A point as the schema's ``Point``."""
    d = {**dict(mass=0.0, volume=0.0, drag_area=0.0, added_mass_coefficient=0.0), **kw}
    return SimpleNamespace(name=name, kind=kind, position=tuple(position), **d)


def _props(L: float, current, **kw) -> CableProperties:
    d = dict(length=L, mass_per_length=20.0, axial_stiffness=4e6, diameter=0.05,
             material_density=5000.0, normal_drag_coefficient=1.2,
             tangential_drag_coefficient=0.3, added_mass_coefficient=1.0,
             tangential_added_mass_coefficient=0.2, current_velocity=current,
             seabed_z=SEABED, friction_coefficient=0.5, internal_damping=2e4)
    d.update(kw)
    return CableProperties(**d)


def _settings(K: int, p: int) -> DynamicSettings:
    return DynamicSettings(elements=K, order=p, cfl=0.8, max_time_step=None,
                           slack_filter=False, seabed_contact="implicit",
                           time_integration="implicit")


#: anchor a - clump c (on the seabed, contact of its own) - buoy b (drag) - massless joint j
#: (one-element section b-j: both its ends free) - body fairlead f, and j - second anchor a2
POINTS = [("a", "fixed", (0.0, 0.0, SEABED), {}),
          ("c", "free", (20.0, 0.0, SEABED - 0.01), dict(mass=500.0, volume=0.05)),
          ("b", "free", (45.0, 1.0, -35.0), dict(mass=300.0, volume=0.8, drag_area=1.5,
                                                  added_mass_coefficient=0.8)),
          ("j", "free", (60.0, -1.0, -25.0), {}),
          ("f", "body", (75.0, 0.0, -8.0), {}),
          ("a2", "fixed", (70.0, 30.0, SEABED), {})]
SECTIONS = [("a", "c", 21.0, 2, 3, {}), ("c", "b", 32.0, 3, 3, {}),
            ("b", "j", 16.0, 1, 2, dict(mass_per_length=5.0, axial_stiffness=1e6)),
            ("j", "f", 24.0, 2, 4, dict(internal_damping=0.0)),
            ("j", "a2", 50.0, 2, 2, {})]


def _system(current) -> DynamicSystem:
    pts = [point(n, kd, pos, **kw) for n, kd, pos, kw in POINTS]
    secs = [SystemSection("l", i, _props(L, current, **kw), _settings(K, p), s, e)
            for i, (s, e, L, K, p, kw) in enumerate(SECTIONS)]
    return DynamicSystem(pts, secs)


def _forces(system: DynamicSystem, r, v, x, u, ppos, pvel) -> np.ndarray:
    """The kernel's force: M_eff A of every node, then every free point's force."""
    w, imp = system._w, system.implicit
    A, Fp, MA = np.zeros_like(r), np.zeros_like(x), np.zeros_like(r)
    pp, pv = ppos.copy(), pvel.copy()
    si.dgi_forces(r, v, x, u, system.sec, imp.prm, system.ops, system.kind, system.pprm,
                  system.env, pp, pv, w.q, w.qt, w.N, w.Nstar, w.faces, w.slack, A, Fp,
                  np.zeros((3, 3)))
    for s in range(len(system.sections)):
        sl = system.section_slice(s)
        K, Np = system.sec[s, sk.S_K], system.sec[s, sk.S_NP]
        ik._mass_times(r[sl].reshape(K, Np, 3), w.q[sl].reshape(K, Np, 3), imp.prm[s],
                       A[sl].reshape(K, Np, 3), MA[sl].reshape(K, Np, 3))
    free = np.flatnonzero(system.kind == sk.FREE)
    return np.concatenate([MA.reshape(-1), Fp[free].reshape(-1)])


def _dense_jacobian(system: DynamicSystem, r, v, x, u, ppos, pvel, kc, cc) -> np.ndarray:
    """The kernel's bordered matrix (acoef 0) as one dense matrix, nodes then free points."""
    imp, w = system.implicit, system._w
    _forces(system, r, v, x, u, ppos, pvel)  # (q, qt of the state)
    nodes = system.n_nodes
    E, Dg = np.zeros((nodes, 3, 3)), np.zeros((nodes, 3, 3))
    B, C = np.zeros(18 * nodes), np.zeros(18 * nodes)
    nf = imp.Spp.shape[0]
    Spp = np.zeros((nf, nf))
    si.dgi_jacobian(r, v, x, u, system.sec, imp.prm, system.ops, system.kind, system.pprm,
                    system.env, imp.fslot, w.q, w.qt, 0.0, kc, cc, E, Dg, imp.bands, imp.boff,
                    B, C, Spp, np.zeros((3, 3)), np.zeros(3))
    n = 3 * nodes
    J = np.zeros((n + nf, n + nf))
    J[n:, n:] = Spp
    for s in range(len(system.sections)):
        K, Np = int(system.sec[s, sk.S_K]), int(system.sec[s, sk.S_NP])
        m, o = 3 * K * Np, 3 * int(system.sec[s, sk.S_NODE])
        band = imp.bands[imp.boff[s]:imp.boff[s + 1]].reshape(m, 9 * Np + 2)
        kl, ku = 3 * Np + 2, 6 * Np - 1
        for i in range(m):
            for j in range(max(0, i - kl), min(m, i + ku + 1)):
                J[o + i, o + j] = band[i, kl + j - i]
        Bs = B[6 * o:6 * (o + m)].reshape(m, 6)
        Cs = C[6 * o:6 * (o + m)].reshape(m, 6)
        for end, col in ((0, sk.S_START), (1, sk.S_END)):
            p = system.sec[s, col]
            if system.kind[p] != sk.FREE:
                assert not Bs[:, 3 * end:3 * end + 3].any()
                continue
            f = n + 3 * imp.fslot[p]
            J[o:o + m, f:f + 3] += Bs[:, 3 * end:3 * end + 3]
            J[f:f + 3, o:o + m] += Cs[:, 3 * end:3 * end + 3].T
    return J


def _random_state(system: DynamicSystem, rng, moving: bool):
    r = system.r + rng.normal(scale=0.03, size=system.r.shape)
    x = system.x.copy()
    free = system.kind == sk.FREE
    x[free] += rng.normal(scale=0.03, size=(int(free.sum()), 3))
    x[1, 2] = SEABED - 0.01  # the clump in contact, off its kink
    scale = 0.3 if moving else 0.0
    v = rng.normal(scale=scale, size=r.shape)
    u = np.where(free[:, None], rng.normal(scale=scale, size=x.shape), 0.0)
    ppos, pvel = x.copy(), np.zeros_like(x)
    pvel[4] = rng.normal(scale=scale, size=3)  # the body point moves
    return r, v, x, u, ppos, pvel


@pytest.mark.parametrize("which", ["v", "r"])
def test_bordered_jacobian_matches_central_differences(which: str, rng) -> None:
    """J = -kc dF/dr - cc dF/dv over the nodes and free points, the border (end positions'
    lift into the end elements' gradients, the end faces' penalty, the points' end fluxes)
    and the points' blocks (drag, contact, friction) included. dF/dv exact in any state;
    dF/dr at rest without current, where the terms the section Jacobian leaves out (the
    turn of drag and damping tension with the tangent) vanish (as the single line's test)."""
    moving = which == "v"
    system = _system((0.3, 0.1, 0.0) if moving else (0.0, 0.0, 0.0))
    r, v, x, u, ppos, pvel = _random_state(system, rng, moving)
    kc, cc = (0.0, 1.0) if moving else (1.0, 0.0)
    J = _dense_jacobian(system, r, v, x, u, ppos, pvel, kc, cc)
    free = np.flatnonzero(system.kind == sk.FREE)
    base = np.concatenate([(v if moving else r).reshape(-1), (u if moving else x)[free]
                           .reshape(-1)])
    h = 1e-6 * max(1.0, float(np.max(np.abs(base))))
    num = np.zeros_like(J)
    nn = r.size
    for j in range(base.size):
        cols = []
        for sign in (1.0, -1.0):
            z = base.copy()
            z[j] += sign * h
            rr, vv, xx, uu = r, v, x.copy(), u.copy()
            if moving:
                vv = z[:nn].reshape(r.shape)
                uu[free] = z[nn:].reshape(-1, 3)
            else:
                rr = z[:nn].reshape(r.shape)
                xx[free] = z[nn:].reshape(-1, 3)
            cols.append(_forces(system, rr, vv, xx, uu, ppos, pvel))
        num[:, j] = -(cols[0] - cols[1]) / (2.0 * h)
    err = np.max(np.abs(J - num)) / np.max(np.abs(num))
    border = np.max(np.abs(J[:nn, nn:] - num[:nn, nn:])) / np.max(np.abs(num[:nn, nn:]))
    points = np.max(np.abs(J[nn:] - num[nn:])) / np.max(np.abs(num[nn:]))
    assert max(err, border, points) <= JACOBIAN_RTOL, (err, border, points)


def test_step_matches_the_numpy_oracle(rng) -> None:
    """One step of the whole system (kernel: bordered Newton, banded LU and Schur
    complement) against the oracle's dense finite-difference Newton on the same residual."""
    system = _system((0.3, 0.1, 0.0))
    r, v, x, u, ppos, pvel = _random_state(system, rng, True)
    v *= 0.1
    u *= 0.1
    dt = 2e-3
    fvel = pvel[4].copy()
    system.r[:], system.v[:], system.x[:], system.u[:] = r, v, x, u
    imp = system.implicit
    imp.ip[ik.IP_NEWTON_TOL] = 1e-14
    imp.ip[ik.IP_FORCE_TOL] = np.inf
    imp.ip[ik.IP_MAX_ITER] = 30
    imp.ip[ik.IP_DT_MAX] = dt
    imp.ip[ik.IP_LEVEL_MAX] = 0
    bpos = np.array([x[4], x[4] + dt * fvel])[:, None]
    bvel = np.array([fvel, fvel])[:, None]
    si.dgi_start(system.r, system.v, system.x, system.u, bpos[0], bvel[0], system.sec,
                 imp.prm, system.ops, system.kind, system.body, system.pprm, system.env,
                 imp.st, imp._pw, (system._w.q, system._w.qt, system._w.N, system._w.Nstar,
                                   system._w.faces), system._w.slack, np.zeros((3, 3)))
    imp.cs[ik.CS_ACC_VALID] = 1.0
    acc0, pacc0 = imp.st[0].copy(), imp.st[2].copy()
    S, P = len(system.sections), len(system.points)
    system.solve_path(np.array([0.0, dt]), bpos, bvel, np.zeros((2, S, 3)),
                      np.zeros((2, S, 3)), np.zeros((2, S)), np.zeros((2, P, 3)), np.zeros(2))
    # the oracle
    sections, sl = [], []
    for s, (a, b, L, K, p, kw) in enumerate(SECTIONS):
        pr = system.sections[s].properties
        ops = oracle.operators(p)
        par = oracle_params(pr, K, "explicit")
        par.update(D=ops.D, LIFT=ops.LIFT)
        sections.append(system_oracle.Section(system.point_index[a], system.point_index[b],
                                              par))
        sl.append(system.section_slice(s))
    pr0 = system.sections[0].properties
    points = []
    for pt in system.points:
        kb, cb, fr = point_contact(pt, pr0)
        points.append(system_oracle.Point(pt.kind, pt.mass, pt.volume, pt.drag_area,
                                          pt.added_mass_coefficient, kb, cb, fr))
    env = dict(rho_w=pr0.water_density, g=pr0.gravity, current=pr0.current_velocity,
               z_b=SEABED, v_c=pr0.slip_speed)

    def ends(t: float):
        xe, ue = x.copy(), np.zeros_like(x)
        xe[4], ue[4] = x[4] + t * fvel, fvel
        return xe, ue

    shape = [r[q].reshape(SECTIONS[s][3], SECTIONS[s][4] + 1, 3) for s, q in enumerate(sl)]
    ro, vo, ao, xo, uo, pao = system_oracle.step(
        sections, points, [r[q].reshape(sh.shape) for q, sh in zip(sl, shape)],
        [v[q].reshape(sh.shape) for q, sh in zip(sl, shape)], x, u,
        [acc0[q].reshape(sh.shape) for q, sh in zip(sl, shape)], pacc0, ends, env, 0.0, dt,
        0.5)
    ro, vo, ao = (np.concatenate([a.reshape(-1, 3) for a in z]) for z in (ro, vo, ao))
    free = system.kind == sk.FREE
    for name, a, b, scale in (("r", system.r, ro, np.max(np.abs(ro - r))),
                              ("v", system.v, vo, np.max(np.abs(vo))),
                              ("acc", imp.st[0], ao, np.max(np.abs(ao))),
                              ("x", system.x[free], xo[free], np.max(np.abs(xo - x))),
                              ("u", system.u[free], uo[free], np.max(np.abs(uo))),
                              ("pacc", imp.st[2][free], pao[free], np.max(np.abs(pao)))):
        err = np.max(np.abs(a - b)) / scale
        assert err <= STEP_RTOL, (name, err)


def test_one_section_system_is_the_implicit_line_bit_for_bit() -> None:
    """A system of one section, anchor to body fairlead, stepping implicitly with the line's
    step parameters, gives the single line's implicit run bit for bit (records, steps taken,
    state)."""
    case = load_case(CASES / "lindahl" / "lindahl_r0.20_T1.25.toml",
                     ["lines.chain.dynamic.elements=6", "lines.chain.dynamic.order=3",
                      'lines.chain.dynamic.time_integration="implicit"',
                      "line_types.chain.internal_damping_ratio=0.05"])
    ln = case.lines[0]
    line = DynamicLine.from_case(ln, case.environment, case.seabed)
    sec = SystemSection("chain", 0, CableProperties.from_case(ln, case.environment,
                                                              case.seabed), ln.dynamic, "a", "f")
    system = DynamicSystem([point("a", "fixed", ln.anchor), point("f", "body", ln.fairlead)],
                           [sec], initial_positions=line.r.reshape(-1, 3))
    assert system.integration == "implicit"
    assert line.implicit.ip[ik.IP_FLAG_EVENTS] == system.implicit.ip[ik.IP_FLAG_EVENTS] == 1.0
    # the system's step has one tolerance and a strict Newton throughout: the line's near a
    # snap, which it keeps when its snap window never closes
    line.implicit.ip[ik.IP_SNAP_WINDOW] = np.inf
    system.implicit.ip[:] = line.implicit.ip  # (its force scale: the line's unsettled start)
    t = np.linspace(0.0, 2.0, 201)
    w = 2 * np.pi / 1.25
    path = np.asarray(ln.fairlead) + 0.2 * np.outer(np.sin(w * t), [1.0, 0.0, 0.3])
    vel = 0.2 * w * np.outer(np.cos(w * t), [1.0, 0.0, 0.3])
    n = t.size
    ff, af, lb, st = np.zeros((n, 3)), np.zeros((n, 3)), np.zeros(n), np.zeros(n)
    line.solve_path(t, path, vel, ff, af, lb, st)
    sf, ef, lb2 = np.zeros((n, 1, 3)), np.zeros((n, 1, 3)), np.zeros((n, 1))
    pp, st2 = np.zeros((n, 2, 3)), np.zeros(n)
    system.solve_path(t, path[:, None], vel[:, None], sf, ef, lb2, pp, st2)
    assert st.sum() > n  # (the step control acted: more than one step per sample)
    for a, b in ((ff, ef[:, 0]), (af, sf[:, 0]), (lb, lb2[:, 0]), (st, st2),
                 (line.r.reshape(-1, 3), system.r), (line.v.reshape(-1, 3), system.v)):
        assert a.tobytes() == b.tobytes()


def test_an_implicit_system_refuses_no_long_run_and_settles_explicitly() -> None:
    """The implicit steps' count follows the accuracy (no explicit-step budget); settling
    takes the explicit steps and leaves the implicit state to be recomputed."""
    system = _system((0.0, 0.0, 0.0))
    assert system.integration == "implicit"
    system.refuse_long_work(1e9, "the run")
    system.implicit.cs[ik.CS_ACC_VALID] = 1.0
    system.settle(max_time=0.01)
    assert system.implicit.cs[ik.CS_ACC_VALID] == 0.0
    assert system.time_step == min(ln.time_step for ln in system.lines)
    assert all(ln.settings.time_integration == "explicit" for ln in system.lines)


def test_explicit_sections_keep_the_explicit_system() -> None:
    pts = [point(n, kd, pos, **kw) for n, kd, pos, kw in POINTS]
    secs = [SystemSection("l", i, _props(L, (0.0, 0.0, 0.0), **kw),
                          replace(_settings(K, p), time_integration="explicit"), s, e)
            for i, (s, e, L, K, p, kw) in enumerate(SECTIONS)]
    system = DynamicSystem(pts, secs)
    assert system.integration == "explicit" and system.implicit is None
    assert system.time_step == min(ln.time_step for ln in system.lines) < 0.01


def _auto_system() -> DynamicSystem:
    pts = [point(n, kd, pos, **kw) for n, kd, pos, kw in POINTS]
    secs = [SystemSection("l", i, _props(L, (0.0, 0.0, 0.0), **kw),
                          replace(_settings(K, p), time_integration="auto"), s, e)
            for i, (s, e, L, K, p, kw) in enumerate(SECTIONS)]
    return DynamicSystem(pts, secs)


def _run(system: DynamicSystem, t: np.ndarray) -> np.ndarray:
    n, S, P = t.size, len(system.sections), len(system.points)
    path = np.array(system.body_positions)[None] + 0.3 * np.sin(t)[:, None, None]
    vel = 0.3 * np.cos(t)[:, None, None] * np.ones((1, 1, 3))
    ef = np.zeros((n, S, 3))
    system.solve_path(t, path, vel, np.zeros((n, S, 3)), ef, np.zeros((n, S)),
                      np.zeros((n, P, 3)), np.zeros(n))
    return ef


def test_implicit_state_arrays_restore_the_run_bit_for_bit() -> None:
    system = _system((0.0, 0.0, 0.0))
    _run(system, np.linspace(0.0, 0.3, 4))
    saved = system.state_arrays()
    assert "implicit_schur" in saved
    first = _run(system, np.linspace(0.3, 0.6, 4))
    system.set_state_arrays(saved)
    again = _run(system, np.linspace(0.3, 0.6, 4))
    assert first.tobytes() == again.tobytes()


def test_auto_system_starts_implicit_and_goes_explicit_when_that_is_cheaper() -> None:
    """``"auto"``: implicit steps (counted) while the explicit ones would cost more; with an
    explicit step made long enough to be the cheaper (the bookkeeping's step), the system goes
    explicit at the end of a window and takes no more implicit steps."""
    system = _auto_system()
    assert system.integration == "auto" and system._stepping_implicit()
    system.auto.explicit_step = 1e-7  # explicit far dearer: its first window, a probe, passes
    _run(system, np.linspace(0.0, 0.5, 6))
    steps = system.implicit.cs[ik.CS_STEPS]
    assert steps > 0 and not system.auto.switched
    system.auto.explicit_step = 10.0  # (the switch's arithmetic only; the run keeps its step)
    _run(system, np.linspace(0.5, 3.5, 31))
    assert system.auto.switched and not system._stepping_implicit()
    switched_at = system.auto.switched_at
    assert 0.5 < switched_at <= 3.5
    steps = system.implicit.cs[ik.CS_STEPS]
    _run(system, np.linspace(3.5, 3.6, 3))
    assert system.implicit.cs[ik.CS_STEPS] == steps
    saved = system.state_arrays()
    again = _auto_system()
    again.set_state_arrays(saved)
    assert again.auto.switched and again.auto.switched_at == switched_at
