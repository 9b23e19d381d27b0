"""The implicit DG step's kernels: banded algebra against SciPy, the Newton Jacobian against
central differences of the force, and one generalised-alpha step against the NumPy oracle
(:mod:`tests.oracles.dg_implicit_numpy`: dense Newton on a finite-difference Jacobian of the
NumPy right-hand side)."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg

from floatmoor.case.schema import DynamicSettings
from floatmoor.mooring.dg import _implicit_kernels as ik
from floatmoor.mooring.dg import _kernels as k
from floatmoor.mooring.dg._banded_kernels import band_factor, band_solve
from floatmoor.mooring.dg.implicit import implicit_parameters
from floatmoor.mooring.dg.reference import reference_element
from tests.oracles import dg_implicit_numpy as implicit_oracle
from tests.mooring.dg.test_mooring_dg_kernels import CASES, make_properties, make_state, oracle_params


pytestmark = pytest.mark.oracle

#: Banded LU without pivoting on a diagonally dominant matrix against LAPACK's banded solver
#: (with pivoting): roundoff times the condition number (< 10 by construction).
BAND_RTOL = 1e-12
#: Central differences with step h: truncation ~ h^2 f''' and roundoff ~ eps |F| / h. With
#: h = 1e-6 of the state's scale both are ~1e-9 of the largest entry; observed <= 3e-9.
JACOBIAN_RTOL = 1e-6
#: Kernel step (analytic Jacobian, banded) against the oracle step (finite-difference dense
#: Jacobian): both iterate Newton to a 1e-14 m correction, so they agree to that over the
#: state's scale, plus the oracle's finite-difference noise in its last correction.
STEP_RTOL = 1e-9


def test_band_solve_matches_scipy(rng: np.random.Generator) -> None:
    n, kl, ku = 40, 5, 8
    dense = np.zeros((n, n))
    for i in range(n):
        for j in range(max(0, i - kl), min(n, i + ku + 1)):
            dense[i, j] = rng.normal()
        dense[i, i] = 3.0 * (kl + ku) + rng.uniform()
    band = np.zeros((n, kl + ku + 1))
    for i in range(n):
        for j in range(max(0, i - kl), min(n, i + ku + 1)):
            band[i, kl + j - i] = dense[i, j]
    b = rng.normal(size=n)
    assert band_factor(band, n, kl, ku) == -1
    x = b.copy()
    band_solve(band, n, kl, ku, x)
    ab = np.zeros((kl + ku + 1, n))
    for i in range(n):
        for j in range(max(0, i - kl), min(n, i + ku + 1)):
            ab[ku + i - j, j] = dense[i, j]
    ref = scipy.linalg.solve_banded((kl, ku), ab, b)
    assert np.max(np.abs(x - ref)) <= BAND_RTOL * np.max(np.abs(ref))


def test_band_factor_reports_a_zero_pivot() -> None:
    band = np.zeros((3, 3))
    band[:, 1] = [1.0, 0.0, 1.0]
    assert band_factor(band, 3, 1, 1) == 1


def _implicit_prm(pr, K: int, p: int) -> np.ndarray:
    settings = DynamicSettings(elements=K, order=p, cfl=0.5, max_time_step=None,
                               slack_filter=False, seabed_contact="implicit",
                               internal_damping="implicit", time_integration="implicit")
    return implicit_parameters(pr.packed(settings, pr.length / K))


def _read_only(anchor: np.ndarray) -> np.ndarray:
    """A read-only copy of ``anchor``, as the model passes it (floatmoor/mooring/dg/line.py):
    a writable one would compile the kernels a second time on an empty numba cache."""
    fixed = anchor.copy()
    fixed.flags.writeable = False
    return fixed


def _force(r, v, anchor, fpos, fvel, prm, D, LIFT, fa=None):
    """F = M_eff A, the force per length the Jacobian differentiates (``fa``: the
    stick-spring friction's anchors)."""
    K, Np = r.shape[:2]
    q, qt, N, a, out = (np.zeros((K, Np, 3)) for _ in range(5))
    Nstar, faces, slack = np.zeros((K + 1, 3)), np.zeros((K + 1, 3)), np.zeros(K)
    ik.dg_acceleration(r, v, _read_only(anchor), fpos, fvel, prm, D, LIFT, q, qt, N, Nstar,
                       faces, slack, a, fa)
    ik._mass_times(r, q, prm, a, out)
    return out, q, qt


def _dense(band: np.ndarray, Np: int) -> np.ndarray:
    n, kl, ku = band.shape[0], 3 * Np + 2, 6 * Np - 1
    J = np.zeros((n, n))
    for i in range(n):
        for j in range(max(0, i - kl), min(n, i + ku + 1)):
            J[i, j] = band[i, kl + j - i]
    return J


#: The cases whose force has no kink within a finite-difference step of the state: the
#: surface-piercing line switches buoyancy, drag and added mass at z = 0 (nodes exactly there)
_SMOOTH = [c for c in CASES if c[1] != "surface"]


@pytest.mark.parametrize("label,kind,overrides,contact", _SMOOTH, ids=[c[0] for c in _SMOOTH])
@pytest.mark.parametrize("p", [1, 3, 5])
def test_jacobian_matches_central_differences(label, kind, overrides, contact, p, rng) -> None:
    """J = a M - kc dF/dr - cc dF/dv. dF/dv is exact for any state; dF/dr at rest (v = 0, the
    fairlead still, no current), where the terms the Jacobian leaves out (the turn of the drag
    and of the damping tension with the tangent) vanish."""
    K = 3
    pr = make_properties(dict(overrides, seabed_z=-10.0) if kind == "seabed" else overrides)
    still = make_properties(dict(dict(overrides, seabed_z=-10.0) if kind == "seabed"
                                 else overrides, current_velocity=(0.0, 0.0, 0.0)))
    ref = reference_element(p)
    D, LIFT = ref.differentiation, ref.lift
    r, v, anchor, fpos, fvel = make_state(kind, K, p, pr.length, rng)
    if kind == "seabed":
        r[0, 0, 2] -= 1e-3  # off the contact kink at z = z_b
    Np = p + 1
    n = 3 * K * Np
    E, Dg = np.zeros((K, Np, 3, 3)), np.zeros((K, Np, 3, 3))
    band = np.zeros((n, 9 * Np + 2))
    for which, (vv, fv) in (("v", (v, fvel)), ("r", (np.zeros_like(v), np.zeros(3)))):
        kc, cc = (0.0, 1.0) if which == "v" else (1.0, 0.0)
        prm = _implicit_prm(pr if which == "v" else still, K, p)
        _, q, qt = _force(r, vv, anchor, fpos, fv, prm, D, LIFT)
        ik.dg_jacobian(r, vv, q, qt, prm, D, LIFT, 0.0, kc, cc, E, Dg, band, None)
        J = _dense(band, Np)
        num = np.zeros((n, n))
        x0 = (vv if which == "v" else r).reshape(-1)
        h = 1e-6 * max(1.0, float(np.max(np.abs(x0))))
        for j in range(n):
            e = np.zeros(n)
            e[j] = h
            e = e.reshape(r.shape)
            if which == "v":
                fp = _force(r, vv + e, anchor, fpos, fv, prm, D, LIFT)[0]
                fm = _force(r, vv - e, anchor, fpos, fv, prm, D, LIFT)[0]
            else:
                fp = _force(r + e, vv, anchor, fpos, fv, prm, D, LIFT)[0]
                fm = _force(r - e, vv, anchor, fpos, fv, prm, D, LIFT)[0]
            num[:, j] = -(fp - fm).reshape(-1) / (2.0 * h)
        err = np.max(np.abs(J - num)) / np.max(np.abs(num))
        print(f"{label} p={p} d/d{which}: {err:.1e}")
        assert err <= JACOBIAN_RTOL, (which, err)


@pytest.mark.parametrize("p", [1, 3])
def test_jacobian_with_stick_spring_matches_central_differences(p, rng) -> None:
    """The stick-spring friction's exact tangent in J (dF/dr at rest, as above): nodes on the
    seabed with anchors half (stick) or twice (slip) the sliding displacement away."""
    K = 3
    pr = make_properties(dict(friction_coefficient=0.6, seabed_stiffness=1e3 / 0.05,
                              seabed_damping_ratio=0.7, seabed_z=-10.0,
                              friction_model="stick_spring"))
    ref = reference_element(p)
    D, LIFT = ref.differentiation, ref.lift
    r, _, anchor, fpos, _ = make_state("seabed", K, p, pr.length, rng)
    r[0, 0, 2] -= 1e-3  # off the contact kink at z = z_b
    prm = _implicit_prm(pr, K, p)
    assert prm[k.P_KS] > 0.0
    cap = prm[k.P_MU] * prm[k.P_KB] * np.maximum(-10.0 - r[..., 2], 0.0)
    angle = rng.uniform(0.0, 2.0 * np.pi, size=r.shape[:2])
    factor = np.where(rng.uniform(size=r.shape[:2]) < 0.5, 0.5, 2.0)
    fa = r[..., :2] + (factor * cap / prm[k.P_KS])[..., None] * np.stack(
        [np.cos(angle), np.sin(angle)], axis=-1)
    Np = p + 1
    n = 3 * K * Np
    E, Dg = np.zeros((K, Np, 3, 3)), np.zeros((K, Np, 3, 3))
    band = np.zeros((n, 9 * Np + 2))
    v, fvel = np.zeros_like(r), np.zeros(3)
    _, q, qt = _force(r, v, anchor, fpos, fvel, prm, D, LIFT, fa)
    ik.dg_jacobian(r, v, q, qt, prm, D, LIFT, 0.0, 1.0, 0.0, E, Dg, band, fa)
    J = _dense(band, Np)
    num = np.zeros((n, n))
    # the slip nodes' caps are ~1e-2 of the stick forces' scale: h well inside every kink
    h = 1e-9
    for j in range(n):
        e = np.zeros(n)
        e[j] = h
        e = e.reshape(r.shape)
        fp = _force(r + e, v, anchor, fpos, fvel, prm, D, LIFT, fa)[0]
        fm = _force(r - e, v, anchor, fpos, fvel, prm, D, LIFT, fa)[0]
        num[:, j] = -(fp - fm).reshape(-1) / (2.0 * h)
    err = np.max(np.abs(J - num)) / np.max(np.abs(num))
    print(f"stick spring p={p}: {err:.1e}")
    assert err <= JACOBIAN_RTOL, err
    # without the anchors' tangent the same matrix is off by the stick stiffness
    ik.dg_jacobian(r, v, q, qt, prm, D, LIFT, 0.0, 1.0, 0.0, E, Dg, band, None)
    assert np.max(np.abs(_dense(band, Np) - num)) / np.max(np.abs(num)) > 100 * JACOBIAN_RTOL


_STEP_CASES = [c for c in CASES if c[0] in ("taut-water-drag", "seabed-explicit",
                                            "internal-damping", "taut-vacuum-gravity")]


@pytest.mark.parametrize("label,kind,overrides,contact", _STEP_CASES,
                         ids=[c[0] for c in _STEP_CASES])
def test_step_matches_oracle(label, kind, overrides, contact, rng) -> None:
    K, p, dt = 3, 3, 2e-3
    pr = make_properties(dict(overrides, seabed_z=-10.0) if kind == "seabed" else overrides)
    prm = _implicit_prm(pr, K, p)
    ref = reference_element(p)
    r, v, anchor, fpos, fvel = make_state(kind, K, p, pr.length, rng)
    if kind == "seabed":  # on the seabed, 0 to 1 mm into it, 1 % stretched (make_state's
        # random bumps strain this coarse line by over 100 %, beyond MAX_STRAIN)
        xi = (np.arange(K)[:, None] + 0.5 * (ref.nodes[None, :] + 1.0)) / K
        fpos = anchor + np.array([1.01 * pr.length, 0.0, 0.0])
        r = anchor + xi[..., None] * (fpos - anchor)
        r[..., 2] -= rng.uniform(0.0, 1e-3, size=xi.shape)
    v *= 0.1
    fpos1 = fpos + dt * fvel
    time = np.array([0.0, dt])
    path, velocity = np.array([fpos, fpos1]), np.array([fvel, fvel])

    def boundary(t: float):
        return (fpos, fvel) if t == 0.0 else (fpos1, fvel)

    par = oracle_params(pr, K, "explicit")
    par.update(D=ref.differentiation, LIFT=ref.lift, anchor=anchor)
    acc = np.zeros_like(r)
    ro, vo, ao = implicit_oracle.step(r, v, acc, boundary, 0.0, dt, 0.5, par)

    Np = p + 1
    n = 3 * K * Np
    ip = np.zeros(ik.IP_N)
    ip[ik.IP_ALPHA_M], ip[ik.IP_ALPHA_F], ip[ik.IP_BETA], ip[ik.IP_GAMMA] = (
        ik.generalised_alpha(0.5))
    ip[ik.IP_NEWTON_TOL] = 1e-14
    ip[ik.IP_FORCE_TOL] = np.inf
    ip[ik.IP_MAX_ITER] = 30
    ip[ik.IP_DT_MAX] = dt
    ip[ik.IP_LEVEL_MAX] = 0
    ip[ik.IP_FLAG_REFACTOR] = 1.0
    cs = np.zeros(ik.CS_N)
    cs[ik.CS_ACC_VALID] = 1.0
    rk, vk, An = r.copy(), v.copy(), np.zeros_like(r)
    w = [np.zeros((K, Np, 3)) for _ in range(11)]
    q, qt, N, r0, v0, a0, An0, A1, R, MR, acck = w
    # the anchor read-only and no friction anchors (fa=None), as the model passes them
    # (floatmoor/mooring/dg/implicit.py): the kernels' one compiled signature, not a second
    # one on an empty numba cache
    fixed = _read_only(anchor)
    # the state's own acceleration A, as the oracle starts from
    ik.dg_acceleration(rk, vk, fixed, fpos, fvel, prm, ref.differentiation, ref.lift, q, qt, N,
                       np.zeros((K + 1, 3)), np.zeros((K + 1, 3)), np.zeros(K), An, None)
    ff, af = np.zeros((2, 3)), np.zeros((2, 3))
    status, _ = ik.dg_run_path_implicit(
        rk, vk, acck, An, time, path, velocity, fixed, prm, ref.differentiation, ref.lift,
        ref.filter, ref.weights, ip, cs, ff, af, np.zeros(2), np.zeros(2), 0,
        np.zeros((1, 1, 3)), np.zeros((1, 1)), q, qt, N, np.zeros((K + 1, 3)),
        np.zeros((K + 1, 3)), np.zeros(K), np.zeros(3), np.zeros(3), np.zeros(Np + 6),
        np.zeros(2, dtype=np.int64), r0, v0, a0, An0, A1, R, MR, np.zeros((K, Np, 3, 3)),
        np.zeros((K, Np, 3, 3)), np.zeros((n, 9 * Np + 2)), np.zeros(n), np.zeros((K, Np)),
        True, None)
    assert status == k.DG_OK
    for name, a, b, scale in (("r", rk, ro, np.max(np.abs(ro - r))),
                              ("v", vk, vo, np.max(np.abs(vo))), ("acc", acck, ao,
                                                                   np.max(np.abs(ao)))):
        err = np.max(np.abs(a - b)) / scale
        print(f"{label} {name}: {err:.1e}")
        assert err <= STEP_RTOL, (name, err)


def test_band_factor_with_rows_ending_short_of_the_band(rng: np.random.Generator) -> None:
    """Rows that end before the band's edge (a DG Jacobian's profile: :func:`band_factor`
    stops each pivot row's update at its last nonzero) solve as LAPACK's banded solver."""
    n, kl, ku = 36, 5, 11
    dense = np.zeros((n, n))
    for i in range(n):
        last = min(n - 1, i + ku - (i % 6))  # every sixth row reaches the edge, the rest short
        for j in range(max(0, i - kl), last + 1):
            dense[i, j] = rng.normal()
        dense[i, i] = 3.0 * (kl + ku) + rng.uniform()
    band = np.zeros((n, kl + ku + 1))
    ab = np.zeros((kl + ku + 1, n))
    for i in range(n):
        for j in range(max(0, i - kl), min(n, i + ku + 1)):
            band[i, kl + j - i] = dense[i, j]
            ab[ku + i - j, j] = dense[i, j]
    b = rng.normal(size=n)
    assert band_factor(band, n, kl, ku) == -1
    x = b.copy()
    band_solve(band, n, kl, ku, x)
    ref = scipy.linalg.solve_banded((kl, ku), ab, b)
    assert np.max(np.abs(x - ref)) <= BAND_RTOL * np.max(np.abs(ref))


#: The end state's acceleration A carried to the next step is taken from the step's equation:
#: it satisfies it to roundoff (1e-16 of the largest term here; a bound 1e4 above that). The
#: cable's own A(r1, v1), which the kernel no longer evaluates once more a step, is off it by
#: what Newton left: after one correction of this step (``NEWTON_TOL`` lets it stop there)
#: 8e-9 of the largest term.
EQUATION_RTOL = 1e-12
#: Newton's tolerance of that step [m]: its first correction is below it.
NEWTON_TOL = 1e-4


def test_step_carries_the_acceleration_of_its_equation(rng: np.random.Generator) -> None:
    K, p, dt = 3, 3, 2e-3
    pr = make_properties({})
    prm = _implicit_prm(pr, K, p)
    ref = reference_element(p)
    r, v, anchor, fpos, fvel = make_state("taut", K, p, pr.length, rng)
    anchor = _read_only(anchor)  # and fa=None below: the model's signature
    v *= 0.1
    time = np.array([0.0, dt])
    path, velocity = np.array([fpos, fpos + dt * fvel]), np.array([fvel, fvel])
    Np = p + 1
    n = 3 * K * Np
    am, af, beta, gamma = ik.generalised_alpha(0.5)
    ip = np.zeros(ik.IP_N)
    ip[ik.IP_ALPHA_M], ip[ik.IP_ALPHA_F], ip[ik.IP_BETA], ip[ik.IP_GAMMA] = am, af, beta, gamma
    ip[ik.IP_NEWTON_TOL] = NEWTON_TOL
    ip[ik.IP_FORCE_TOL] = np.inf
    ip[ik.IP_MAX_ITER] = 30
    ip[ik.IP_DT_MAX] = dt
    ip[ik.IP_LEVEL_MAX] = 0
    cs = np.zeros(ik.CS_N)
    w = [np.zeros((K, Np, 3)) for _ in range(11)]
    q, qt, N, r0, v0, a0, An0, A1, R, MR, acc = w
    An = np.zeros((K, Np, 3))
    cs[ik.CS_ACC_VALID] = 1.0  # the step starts from a zero acceleration variable
    fields = (q, qt, N, np.zeros((K + 1, 3)), np.zeros((K + 1, 3)), np.zeros(K))
    ik.dg_acceleration(r, v, anchor, fpos, fvel, prm, ref.differentiation, ref.lift, *fields,
                       An, None)
    start = An.copy()
    status, _ = ik.dg_run_path_implicit(
        r, v, acc, An, time, path, velocity, anchor, prm, ref.differentiation, ref.lift,
        ref.filter, ref.weights, ip, cs, np.zeros((2, 3)), np.zeros((2, 3)), np.zeros(2),
        np.zeros(2), 0, np.zeros((1, 1, 3)), np.zeros((1, 1)), *fields, np.zeros(3),
        path[1].copy(), np.zeros(Np + 6), np.zeros(2, dtype=np.int64), r0, v0, a0, An0, A1, R,
        MR, np.zeros((K, Np, 3, 3)), np.zeros((K, Np, 3, 3)), np.zeros((n, 9 * Np + 2)),
        np.zeros(n), np.zeros((K, Np)), True, None)
    assert status == k.DG_OK and cs[ik.CS_STEPS] == 1.0 and cs[ik.CS_ITERATIONS] == 1.0
    terms = ((1.0 - am) * acc, (1.0 - af) * An, af * start)
    residual = terms[0] - terms[1] - terms[2]
    scale = max(np.max(np.abs(t)) for t in terms)
    assert np.max(np.abs(residual)) <= EQUATION_RTOL * scale
    # and it is the end state's own acceleration to within Newton's last correction
    exact = np.zeros_like(An)
    ik.dg_acceleration(r, v, anchor, path[1], fvel, prm, ref.differentiation, ref.lift, *fields,
                       exact, None)
    assert np.max(np.abs(An - exact)) <= 1e-2 * np.max(np.abs(exact))


@pytest.mark.parametrize("p", [1, 3, 5])
def test_newton_solve_on_the_dg_profile_is_the_band_solve(p, rng) -> None:
    """The Newton matrix's solve limited to the DG profile (row (k, i) from node (k, 0) - 1 to
    (k + 2, 0) - 1: the matrix has nothing outside it) gives the whole band's solve bit for
    bit."""
    K = 4
    pr = make_properties({})
    ref = reference_element(p)
    D, LIFT = ref.differentiation, ref.lift
    r, v, anchor, fpos, fvel = make_state("taut", K, p, pr.length, rng)
    prm = _implicit_prm(pr, K, p)
    Np = p + 1
    n, kl, ku = 3 * K * Np, 3 * Np + 2, 6 * Np - 1
    _, q, qt = _force(r, v, anchor, fpos, fvel, prm, D, LIFT)
    band = np.zeros((n, 9 * Np + 2))
    ik.dg_jacobian(r, v, q, qt, prm, D, LIFT, 1.0, 1e-4, 1e-2, np.zeros((K, Np, 3, 3)),
                   np.zeros((K, Np, 3, 3)), band, None)
    dense = _dense(band, Np)
    assert band_factor(band, n, kl, ku) == -1
    b = rng.normal(size=n)
    whole, profile = b.copy(), b.copy()
    band_solve(band, n, kl, ku, whole)
    ik._dg_band_solve(band, n, kl, ku, Np, profile)
    assert whole.tobytes() == profile.tobytes()
    # (a product left out that is not zero would change the bits: the factors outside the
    # profile are exact zeros, the matrix's are)
    lower, upper = np.tril(dense, -1), np.triu(dense, 1)
    for row in range(n):
        first, last = 3 * ((row // (3 * Np)) * Np - 1), 3 * ((row // (3 * Np) + 2) * Np) - 1
        assert not lower[row, :max(first, 0)].any() and not upper[row, last + 1:].any()
