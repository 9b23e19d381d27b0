"""The DG system kernels: a one-section system is the dynamic line bit for bit, the system's
right-hand side (sections and free points) matches the NumPy oracle, checkpoints restore the
state exactly and instabilities name the section."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.case.schema import DynamicSettings
from floatmoor.errors import SolverError
from floatmoor.mooring.dg import _system_kernels as sk
from floatmoor.mooring.dg.line import CableProperties, DynamicLine
from floatmoor.mooring.dg.system import DynamicSystem, SystemSection
from tests.conftest import CASES
from tests.oracles import dg_numpy as oracle


pytestmark = pytest.mark.oracle

#: docs/development.md#54-kernel-oracle-tolerance: kernels match their NumPy oracle to 1e-12
#: relative (to the field's largest value); observed <= 1e-15.
ORACLE_RTOL = 1e-12


def point(name: str, kind: str, position, **kw) -> SimpleNamespace:
    """A point as the schema's ``Point``."""
    d = {**dict(mass=0.0, volume=0.0, drag_area=0.0, added_mass_coefficient=0.0), **kw}
    return SimpleNamespace(name=name, kind=kind, position=tuple(position), **d)


def settings(K: int, p: int, **kw) -> DynamicSettings:
    d = dict(elements=K, order=p, cfl=0.8, max_time_step=None, slack_filter=True,
             seabed_contact="implicit")
    d.update(kw)
    return DynamicSettings(**d)


@pytest.mark.parametrize("damping", ["implicit", pytest.param("explicit", marks=pytest.mark.slow)])
def test_one_section_system_is_the_dynamic_line_bit_for_bit(damping: str) -> None:
    case = load_case(CASES / "lindahl" / "lindahl_r0.20_T1.25.toml",
                     ["lines.chain.dynamic.elements=12", "lines.chain.dynamic.order=5",
                      'lines.chain.dynamic.time_integration="explicit"',
                      f'lines.chain.dynamic.internal_damping="{damping}"',
                      "line_types.chain.internal_damping_ratio=0.05"])
    ln = case.lines[0]
    line = DynamicLine.from_case(ln, case.environment, case.seabed)
    sec = SystemSection("chain", 0, CableProperties.from_case(ln, case.environment, case.seabed),
                        ln.dynamic, "a", "f")
    system = DynamicSystem([point("a", "fixed", ln.anchor), point("f", "body", ln.fairlead)],
                           [sec], initial_positions=line.r.reshape(-1, 3))
    assert system.time_step == line.time_step
    t = np.linspace(0.0, 0.5, 51)
    w = 2 * np.pi / 1.25
    path = np.asarray(ln.fairlead) + 0.2 * np.outer(np.sin(w * t), [1.0, 0.0, 0.3])
    vel = 0.2 * w * np.outer(np.cos(w * t), [1.0, 0.0, 0.3])
    n = t.size
    ff, af, lb = np.zeros((n, 3)), np.zeros((n, 3)), np.zeros(n)
    line.solve_path(t, path, vel, ff, af, lb, np.zeros(n))
    sf, ef, lb2, pp = np.zeros((n, 1, 3)), np.zeros((n, 1, 3)), np.zeros((n, 1)), np.zeros((n, 2, 3))
    system.solve_path(t, path[:, None], vel[:, None], sf, ef, lb2, pp, np.zeros(n))
    for a, b in ((ff, ef[:, 0]), (af, sf[:, 0]), (lb, lb2[:, 0]), (line.r.reshape(-1, 3), system.r),
                 (line.v.reshape(-1, 3), system.v), (path, pp[:, 1])):
        assert a.tobytes() == b.tobytes()
    assert np.array_equal(system.advance(0.6, path[-1], vel[-1])[0],
                          line.advance(0.6, path[-1], vel[-1]))


def _water_props(L: float, **kw) -> CableProperties:
    d = dict(length=L, mass_per_length=20.0, axial_stiffness=4e6, diameter=0.05,
             material_density=5000.0, normal_drag_coefficient=1.2,
             tangential_drag_coefficient=0.3, added_mass_coefficient=1.0,
             tangential_added_mass_coefficient=0.2, current_velocity=(0.3, 0.1, 0.0))
    d.update(kw)
    return CableProperties(**d)


def test_system_rhs_matches_the_numpy_oracle(rng: np.random.Generator) -> None:
    """Fixed anchor - section 0 (p = 3) - massive buoy with drag - section 1 (p = 2) - massless
    joint - section 2 (p = 4) - body fairlead, in a random state: node accelerations and the
    free points' substep velocities u* (module docstring of _system_kernels) against the
    oracle's per-section right-hand side with the junction written out here."""
    props = [_water_props(30.0), _water_props(40.0, mass_per_length=5.0, axial_stiffness=1e6),
             _water_props(20.0)]
    orders = [3, 2, 4]
    pts = [point("a", "fixed", (0.0, 0.0, -50.0)),
           point("b", "free", (25.0, 1.0, -35.0), mass=300.0, volume=0.8, drag_area=1.5,
                 added_mass_coefficient=0.8),
           point("j", "free", (60.0, -1.0, -20.0)),
           point("f", "body", (75.0, 0.0, -5.0))]
    secs = [SystemSection("l", i, props[i], settings(3, orders[i], internal_damping="implicit"),
                          s, e) for i, (s, e) in enumerate((("a", "b"), ("b", "j"), ("j", "f")))]
    system = DynamicSystem(pts, secs)
    r = system.r + rng.normal(scale=0.05, size=system.r.shape)
    v = rng.normal(scale=0.3, size=system.r.shape)
    x = system.x.copy()
    u = rng.normal(scale=0.3, size=x.shape)
    fvel = rng.normal(scale=0.3, size=3)
    w = system._w
    w.ppos[:] = x
    w.pvel[:] = 0.0
    w.pvel[3] = fvel
    dt = 2e-3
    a, ue = np.zeros_like(r), np.zeros_like(x)
    sk.dgs_rhs(r, v, x, u, dt, system.sec, system.prm, system.ops, system.kind, system.pprm,
               system.env, w.ppos, w.pvel, w.G, w.Zs, w.q, w.qt, w.N, w.Nstar, w.faces,
               w.slack, a, ue)
    # oracle: fields with the state velocities, then the junction velocities, then the rhs
    ops = [oracle.operators(p) for p in orders]
    ends = [(0, 1), (1, 2), (2, 3)]
    node_r = [r[system.section_slice(i)].reshape(3, orders[i] + 1, 3) for i in range(3)]
    node_v = [v[system.section_slice(i)].reshape(3, orders[i] + 1, 3) for i in range(3)]
    vel = [np.zeros(3), u[1], u[2], fvel]
    G, Zs = np.zeros((4, 3)), np.zeros(4)
    par = []
    for i, pr in enumerate(props):
        A_c = pr.mass_per_length / pr.material_density
        par.append(dict(h=pr.length / 3, m=pr.mass_per_length, EA=pr.axial_stiffness,
                        d=pr.diameter, A_c=A_c, rho_w=1000.0, g=9.81,
                        cdn=pr.normal_drag_coefficient, cdt=pr.tangential_drag_coefficient,
                        m_an=1000.0 * A_c, m_at=0.2 * 1000.0 * A_c, current=(0.3, 0.1, 0.0)))
        s, e = ends[i]
        fl = oracle.tension_field(node_r[i], node_v[i], x[s], x[e], vel[e], D=ops[i].D,
                                  LIFT=ops[i].LIFT, h=par[i]["h"], m=par[i]["m"],
                                  EA=par[i]["EA"], m_at=par[i]["m_at"], avel=vel[s])
        Z = (pr.mass_per_length + par[i]["m_at"]) * np.sqrt(pr.axial_stiffness
                                                             / pr.mass_per_length)
        G[s] += fl.N[0, 0] + Z * node_v[i][0, 0]
        Zs[s] += Z
        G[e] += -fl.N[-1, -1] + Z * node_v[i][-1, -1]
        Zs[e] += Z
    ustar = np.zeros((4, 3))
    # buoy: (M + Ca rho V) u* = ... with the drag linearised about u (physics in the kernel doc)
    M, V, CdA, Ca = 300.0, 0.8, 1.5, 0.8
    meff = M + Ca * 1000.0 * V
    cd = 0.5 * 1000.0 * CdA * np.linalg.norm(np.array([0.3, 0.1, 0.0]) - u[1])
    force = G[1] + cd * np.array([0.3, 0.1, 0.0]) + np.array([0.0, 0.0, (1000.0 * V - M) * 9.81])
    ustar[1] = (meff * u[1] + dt * force) / (meff + dt * (Zs[1] + cd))
    ustar[2] = G[2] / Zs[2]  # massless joint: the end fluxes balance
    flux_vel = [np.zeros(3), ustar[1], ustar[2], fvel]
    assert np.abs(ue[1:3] - ustar[1:3]).max() <= ORACLE_RTOL * np.abs(ustar[1:3]).max()
    for i in range(3):
        s, e = ends[i]
        ao, _ = oracle.rhs(node_r[i], node_v[i], x[s], x[e], vel[e], D=ops[i].D,
                           LIFT=ops[i].LIFT, avel=vel[s], flux_velocities=(flux_vel[s],
                                                                            flux_vel[e]),
                           **par[i])
        ak = a[system.section_slice(i)].reshape(ao.shape)
        assert np.abs(ak - ao).max() <= ORACLE_RTOL * np.abs(ao).max(), i


def _small_system() -> DynamicSystem:
    props = _water_props(30.0, internal_damping=2e4)
    pts = [point("a", "fixed", (0.0, 0.0, -40.0)), point("j", "free", (25.0, 0.0, -25.0),
                                                          mass=50.0, volume=0.01),
           point("f", "body", (50.0, 0.0, -5.0))]
    return DynamicSystem(pts, [SystemSection("moor", 0, props, settings(3, 3), "a", "j"),
                               SystemSection("moor", 1, props, settings(3, 3), "j", "f")])


def _run(system: DynamicSystem, t: np.ndarray) -> np.ndarray:
    n = t.size
    path = np.array(system.body_positions)[None] + 0.3 * np.sin(t)[:, None, None]
    vel = 0.3 * np.cos(t)[:, None, None] * np.ones((1, 1, 3))
    ef = np.zeros((n, 2, 3))
    system.solve_path(t, path, vel, np.zeros((n, 2, 3)), ef, np.zeros((n, 2)),
                      np.zeros((n, 3, 3)), np.zeros(n))
    return ef


def test_state_arrays_restore_the_run_bit_for_bit() -> None:
    system = _small_system()
    _run(system, np.linspace(0.0, 0.3, 4))
    saved = system.state_arrays()
    first = _run(system, np.linspace(0.3, 0.6, 4))
    system.set_state_arrays(saved)
    again = _run(system, np.linspace(0.3, 0.6, 4))
    assert first.tobytes() == again.tobytes()


def test_instability_names_the_section_time_and_quantity() -> None:
    system = _small_system()
    system.time_step *= 20.0  # far beyond the stability limit
    with pytest.raises(SolverError, match=r"line 'moor' section \d .*t = .* s"):
        _run(system, np.linspace(0.0, 5.0, 51))
    assert system.failed_index > 0


def test_damping_step_with_free_points_matches_the_numpy_oracle(rng: np.random.Generator
                                                                 ) -> None:
    """The backward-Euler Kelvin-Voigt step with the free points' velocities among the
    unknowns (``_damping_phase``: frozen factors, cached responses, one dense solve per group)
    against the oracle's dense solve of the whole affine step: fixed anchor - damped section
    (K = 3, p = 3) - massive buoy - damped one-element section (p = 2, both ends free) -
    massless joint - undamped section (p = 4) - body fairlead, and a damped section (p = 3)
    from the joint to a second anchor; a random state, some nodes slack."""
    cint = 3e5
    props = [_water_props(30.0, internal_damping=cint),
             _water_props(20.0, mass_per_length=5.0, axial_stiffness=1e6,
                          internal_damping=cint / 3),
             _water_props(25.0), _water_props(30.0, internal_damping=cint)]
    orders, elems = [3, 2, 4, 3], [3, 1, 2, 2]
    pts = [point("a", "fixed", (0.0, 0.0, -50.0)),
           point("b", "free", (25.0, 1.0, -35.0), mass=300.0, volume=0.8, drag_area=1.5,
                 added_mass_coefficient=0.8),
           point("j", "free", (45.0, -1.0, -25.0)),
           point("f", "body", (70.0, 0.0, -5.0)),
           point("c", "fixed", (60.0, -20.0, -50.0))]
    ends = [(0, 1), (1, 2), (2, 3), (2, 4)]
    names = "abjfc"
    secs = [SystemSection("l", i, props[i], settings(elems[i], orders[i], slack_filter=False,
                                                     internal_damping="implicit"),
                          names[s], names[e]) for i, (s, e) in enumerate(ends)]
    system = DynamicSystem(pts, secs)
    r = system.r + rng.normal(scale=0.02, size=system.r.shape)
    v = rng.normal(scale=0.3, size=system.r.shape)
    x = system.x.copy()
    u = rng.normal(scale=0.3, size=x.shape)
    u[[0, 4]] = 0.0
    fvel = rng.normal(scale=0.3, size=3)
    w = system._w
    w.ppos[3], w.pvel[3] = x[3], fvel
    dt = 2e-3
    r1, v1, u1 = r.copy(), v.copy(), u.copy()
    sk.dgs_damping_step(r1, v1, x, u1, dt, system.sec, system.prm, system.ops, system.kind,
                        system.pprm, system.env, w.ppos, w.pvel, w.q, w.qt, w.N, w.faces,
                        w.slack, w.tmp, *w.damping, w.coupling)
    assert np.array_equal(r1, r)  # no node below the seabed
    vel = u.copy()
    vel[3] = fvel
    meff = np.array([0.0, 300.0 + 0.8 * 1000.0 * 0.8, 0.0, 0.0, 0.0])
    oracle_secs = []
    for i, pr in enumerate(props):
        A_c = pr.mass_per_length / pr.material_density
        op = oracle.operators(orders[i])
        sl = system.section_slice(i)
        shape = (elems[i], orders[i] + 1, 3)
        oracle_secs.append(dict(r=r[sl].reshape(shape), v=v[sl].reshape(shape),
                                start=ends[i][0], end=ends[i][1], D=op.D, LIFT=op.LIFT,
                                h=pr.length / elems[i], m=pr.mass_per_length,
                                EA=pr.axial_stiffness, c_int=pr.internal_damping,
                                m_an=1000.0 * A_c, m_at=0.2 * 1000.0 * A_c))
    vo, uo = oracle.system_damping_step(oracle_secs, x, vel, system.kind == sk.FREE, meff, dt)
    # the step's changes, relative to the largest
    dvo = np.concatenate([vs.reshape(-1, 3) for vs in vo]) - v
    assert np.abs(dvo).max() > 1e-3  # the damping acts
    # observed 1.3e-14 (nodes) and 5.7e-15 (points) of the largest change
    assert np.abs((v1 - v) - dvo).max() <= ORACLE_RTOL * np.abs(dvo).max()
    duo = uo[1:3] - u[1:3]
    assert np.abs(duo).max() > 1e-3
    assert np.abs((u1[1:3] - u[1:3]) - duo).max() <= ORACLE_RTOL * np.abs(duo).max()
    # the step again with the factors and responses kept (no rebuild): the same
    r2, v2, u2 = r.copy(), v.copy(), u.copy()
    count = w.damping[7][:, 3].copy()
    sk.dgs_damping_step(r2, v2, x, u2, dt, system.sec, system.prm, system.ops, system.kind,
                        system.pprm, system.env, w.ppos, w.pvel, w.q, w.qt, w.N, w.faces,
                        w.slack, w.tmp, *w.damping, w.coupling)
    assert np.array_equal(w.damping[7][:, 3], count)
    assert np.array_equal(v2, v1) and np.array_equal(u2, u1)
