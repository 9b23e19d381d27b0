"""The stick-spring seabed friction (docs/theory/cable.md#seabed-friction): its kernels against
the NumPy oracle (tests/oracles/friction_numpy.py), its tangent against central differences,
and the DG right-hand side with it against the oracle's force."""

from __future__ import annotations

import numpy as np
import pytest

from floatmoor.case.schema import DynamicSettings
from floatmoor.mooring.dg import _friction_kernels as fk
from floatmoor.mooring.dg import _kernels as k
from floatmoor.mooring.dg.reference import reference_element
from tests.oracles import dg_numpy as oracle
from tests.oracles import friction_numpy as friction_oracle
from tests.mooring.dg.test_mooring_dg_kernels import (make_properties, make_state, oracle_params,
                                                    read_only)


pytestmark = pytest.mark.oracle

#: Same formulas in a different order: a few ulps of the largest force.
ORACLE_RTOL = 1e-12
#: Central differences of a piecewise-smooth force away from its kinks, h = 1e-7 of the
#: displacement: truncation h^2 f''' and roundoff eps |f| / h both ~1e-9 relative.
TANGENT_RTOL = 1e-6

KS, MU_KB, ZB = 2.0e4, 0.6 * 1.0e3, -10.0


def _nodes(rng: np.random.Generator, n: int = 40) -> tuple[np.ndarray, np.ndarray]:
    """Node positions below and above the seabed and anchors half or twice the sliding
    displacement away (stick, slip), never at the switch."""
    r = rng.normal(size=(n, 3))
    r[:, 2] = ZB + rng.uniform(-0.05, 0.01, size=n)
    cap = MU_KB * np.maximum(ZB - r[:, 2], 0.0)
    angle = rng.uniform(0.0, 2.0 * np.pi, size=n)
    factor = np.where(rng.uniform(size=n) < 0.5, 0.5, 2.0)
    dl = factor * cap / KS + 1e-12
    anchors = r[:, :2] + dl[:, None] * np.c_[np.cos(angle), np.sin(angle)]
    return r, anchors


def test_kernels_match_oracle(rng) -> None:
    r, anchors = _nodes(rng)
    bed = r[:, 2] < ZB
    d = anchors - r[:, :2]
    cap = MU_KB * (ZB - r[:, 2])
    f_ref = friction_oracle.force(d[bed], cap[bed], KS)
    t_ref = friction_oracle.tangent(d[bed], cap[bed], KS, MU_KB)
    f = np.array([fk.stick_force(dx, dy, c, KS) for (dx, dy), c in zip(d[bed], cap[bed])])
    t = np.array([fk.stick_tangent(dx, dy, c, KS, MU_KB) for (dx, dy), c in zip(d[bed],
                                                                                cap[bed])])
    t = t[:, [0, 1, 4, 2, 3, 5]].reshape(-1, 2, 3)  # (xx, xy, yx, yy, xz, yz) as rows
    assert np.max(np.abs(f - f_ref)) <= ORACLE_RTOL * np.max(np.abs(f_ref))
    assert np.max(np.abs(t - t_ref)) <= ORACLE_RTOL * np.max(np.abs(t_ref))
    fa = anchors.reshape(4, 10, 2).copy()
    fk.return_map(r.reshape(4, 10, 3), fa, KS, MU_KB, ZB)
    ref = friction_oracle.return_map(r, anchors, KS, MU_KB, ZB).reshape(4, 10, 2)
    assert np.max(np.abs(fa - ref)) <= ORACLE_RTOL * np.max(np.abs(ref))
    # after the mapping no node is outside the friction cone, and a sliding node is on it
    after = friction_oracle.force(fa.reshape(-1, 2)[bed] - r[bed, :2], cap[bed], KS)
    assert np.all(np.linalg.norm(after, axis=-1) <= cap[bed] * (1 + 1e-12))


def test_tangent_matches_central_differences(rng) -> None:
    r, anchors = _nodes(rng)
    for (x, y, z), (ax, ay) in zip(r, anchors):
        if z >= ZB:
            continue
        ana = np.array(fk.stick_tangent(ax - x, ay - y, MU_KB * (ZB - z), KS, MU_KB))
        ana = ana[[0, 1, 4, 2, 3, 5]].reshape(2, 3)

        def f(p):
            return np.array(fk.stick_force(ax - p[0], ay - p[1], MU_KB * (ZB - p[2]), KS))

        h = 1e-7 * max(np.hypot(ax - x, ay - y), ZB - z)
        num = np.zeros((2, 3))
        for j in range(3):
            e = np.zeros(3)
            e[j] = h
            num[:, j] = -(f(np.array([x, y, z]) + e) - f(np.array([x, y, z]) - e)) / (2 * h)
        assert np.max(np.abs(ana - num)) <= TANGENT_RTOL * np.max(np.abs(ana)), (ana, num)


def test_rhs_with_stick_spring_matches_oracle(rng) -> None:
    """dg_rhs with the anchors: the oracle's right-hand side without friction plus the
    oracle's stick-spring force through the inverse mass."""
    K, p = 4, 3
    over = dict(friction_coefficient=0.6, seabed_stiffness=1e3 / 0.05, seabed_damping_ratio=0.7,
                normal_drag_coefficient=2.0, seabed_z=-10.0, friction_model="stick_spring")
    pr = make_properties(over)
    settings = DynamicSettings(elements=K, order=p, cfl=0.5, max_time_step=None,
                               slack_filter=True, seabed_contact="implicit",
                               internal_damping="explicit")
    prm = pr.packed(settings, pr.length / K)
    assert prm[k.P_KS] == pr.seabed_stiffness * pr.diameter
    ref = reference_element(p)
    r, v, anchor, fpos, fvel = make_state("seabed", K, p, pr.length, rng)
    cap = prm[k.P_MU] * prm[k.P_KB] * np.maximum(-10.0 - r[..., 2], 0.0)
    angle = rng.uniform(0.0, 2.0 * np.pi, size=r.shape[:2])
    factor = np.where(rng.uniform(size=r.shape[:2]) < 0.5, 0.5, 2.0)
    fa = r[..., :2] + (factor * cap / prm[k.P_KS])[..., None] * np.stack(
        [np.cos(angle), np.sin(angle)], axis=-1)
    q, qt, N = (np.zeros((K, p + 1, 3)) for _ in range(3))
    dv = np.zeros((K, p + 1, 3))
    k.dg_rhs(r, v, read_only(anchor), fpos, fvel, prm, ref.differentiation, ref.lift, q, qt,
             N, np.zeros((K + 1, 3)), np.zeros((K + 1, 3)), np.zeros(K), dv, fa)
    par = oracle_params(pr, K, "implicit")
    par.update(mu=0.0)
    a_ref, fl = oracle.rhs(r, v, anchor, fpos, fvel, D=ref.differentiation, LIFT=ref.lift,
                           **par)
    f = np.zeros_like(r)
    bed = r[..., 2] < -10.0
    f[bed, :2] = friction_oracle.force(fa[bed] - r[bed, :2], cap[bed], prm[k.P_KS])
    ql = np.linalg.norm(fl.q, axis=-1)
    t = fl.q / ql[..., None]
    mn = pr.mass_per_length + np.where(r[..., 2] < 0.0, par["m_an"], 0.0)
    mt = pr.mass_per_length + np.where(r[..., 2] < 0.0, par["m_at"], 0.0)
    ft = np.sum(f * t, axis=-1)
    a_ref = a_ref + (f - ft[..., None] * t) / mn[..., None] + (ft / mt)[..., None] * t
    assert np.any(bed) and np.any(~bed)
    assert np.max(np.abs(dv - a_ref)) <= 1e-10 * np.max(np.abs(a_ref))


def test_system_lines_refuse_stick_spring() -> None:
    """The DG system (sections, free points) has the Coulomb law only: a case asking it for
    the stick spring is refused at the key, before any run."""
    import pytest

    from floatmoor.case.load import load_case
    from floatmoor.errors import CaseError
    from tests.conftest import CASES

    with pytest.raises(CaseError, match=r"seabed\.friction_model.*stick_spring"):
        load_case(CASES / "systems" / "three_line_clump_buoy.toml",
                  ['lines.*.model="dynamic"', 'seabed.friction_model="stick_spring"'])
    load_case(CASES / "systems" / "three_line_clump_buoy.toml",
              ['lines.*.model="dynamic"', 'seabed.friction_model="coulomb"'])


def _dragged_line(integration: str):
    """A chain lying on the seabed, its fairlead (on the seabed too) dragged sideways."""
    from floatmoor.mooring.dg.line import CableProperties, DynamicLine

    props = CableProperties(length=10.0, mass_per_length=1.5, axial_stiffness=1e5,
                            diameter=0.03, material_density=5000.0, seabed_z=-10.0,
                            seabed_stiffness=3e6, seabed_damping_ratio=1.0,
                            friction_coefficient=0.5, normal_drag_coefficient=1.0,
                            friction_model="stick_spring")
    settings = DynamicSettings(elements=4, order=3, cfl=0.8, max_time_step=0.005,
                               slack_filter=True, seabed_contact="implicit",
                               time_integration=integration)
    line = DynamicLine(props, settings, np.array([0.0, 0.0, -10.0]),
                       np.array([9.9, 0.0, -9.9]))
    line.settle()
    t = np.linspace(0.0, 0.4, 41)
    path = np.c_[9.9 + 0 * t, 0.5 * np.sin(np.pi * t / 0.4) ** 2, -9.9 + 0 * t]
    vel = np.gradient(path, t, axis=0)
    return line, t, path, vel


def test_anchors_are_state_and_resume_bit_identical() -> None:
    """The friction anchors move where the chain slides, travel in state_arrays, and a run
    restored from them continues bit-identically (implicit steps)."""
    line, t, path, vel = _dragged_line("implicit")
    start = line.friction_anchors.copy()
    n = t.size
    half = n // 2

    def run(dg, a, b):
        m = b - a
        ff = np.zeros((m, 3))
        dg.solve_path(t[a:b], path[a:b], vel[a:b], ff, np.zeros((m, 3)), np.zeros(m),
                      np.zeros(m))
        return ff

    run(line, 0, half + 1)
    saved = {k: np.array(v, copy=True) for k, v in line.state_arrays().items()}
    assert "friction_anchors" in saved
    moved = np.abs(saved["friction_anchors"] - start).max()
    assert moved > 1e-3  # the chain slid, dragging its anchors
    first = run(line, half, n)
    other, *_ = _dragged_line("implicit")
    other.set_state_arrays(saved)
    np.testing.assert_array_equal(other.friction_anchors, saved["friction_anchors"])
    second = run(other, half, n)
    np.testing.assert_array_equal(first, second)
