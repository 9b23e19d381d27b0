"""The numba DG cable kernels and the reference-element operators against the NumPy oracle.

Two implementations of one method (docs/development.md#4-kinds-of-tests and
docs/development.md#54-kernel-oracle-tolerance): :mod:`tests.oracles.dg_numpy` writes the
semi-discretisation of docs/theory/cable.md and docs/theory/dynamic_line.md vectorised in NumPy,
with reference-element operators built from the barycentric Lagrange basis instead of the Legendre
Vandermonde matrix. The states are random: taut and slack, in air and in water, above, on and below
the seabed, moving faster and slower than the friction slip speed, with current, drag, added mass,
internal damping (including its clipping at zero tension) and explicit seabed contact.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.polynomial import legendre as npl

from floatmoor.case.schema import DynamicSettings
from floatmoor.mooring.dg import _kernels as k
from floatmoor.mooring.dg.line import CableProperties
from floatmoor.mooring.dg.reference import lgl_nodes, reference_element
from tests.oracles import dg_numpy as oracle


pytestmark = pytest.mark.oracle

#: docs/development.md#54-kernel-oracle-tolerance: every numba kernel matches its NumPy oracle to
#: 1e-12 relative. The error is measured relative to the largest value of the compared field (the
#: accelerations, tensions and fluxes of a random state are all of one magnitude by construction).
#: Observed <= 7e-16 with identical operators.
ORACLE_RTOL = 1e-12
#: The reference element's operators (Vandermonde route) against the oracle's (barycentric
#: Lagrange route): both exact in exact arithmetic, so roundoff times the operator norm
#: (D ~ p^2 for p <= 8). Observed <= 7e-15.
OPERATOR_RTOL = 1e-12
#: Nodes and quadrature weights: the two root finders agree to a few ulps. Observed 1.1e-15.
NODES_ATOL = 1e-14
#: D applied to a polynomial of degree <= p, exactness up to roundoff amplified by ||D||
#: (~p^2, about 40 at p = 8) and by cancellation in the derivative. Observed <= 7e-15.
EXACTNESS_RTOL = 1e-12
#: Cubic Hermite interpolation reproduces a cubic exactly: roundoff of a few terms.
HERMITE_RTOL = 1e-13

ORDERS = range(1, 9)


# -- reference element ------------------------------------------------------------------------
@pytest.mark.parametrize("p", ORDERS)
def test_lgl_nodes_and_weights_match_oracle(p: int) -> None:
    x, w = lgl_nodes(p)
    xo, wo = oracle.lgl_nodes(p)
    assert np.max(np.abs(x - xo)) <= NODES_ATOL
    assert np.max(np.abs(w - wo)) <= NODES_ATOL
    assert abs(np.sum(w) - 2.0) <= NODES_ATOL
    # LGL quadrature is exact to degree 2p - 1
    for n in range(2 * p):
        exact = (1.0 - (-1.0) ** (n + 1)) / (n + 1)
        assert abs(np.sum(w * x**n) - exact) <= NODES_ATOL * (n + 1)


@pytest.mark.parametrize("p", ORDERS)
def test_operators_match_oracle(p: int) -> None:
    ref = reference_element(p)
    ops = oracle.operators(p)
    for name, a, b in [("D", ref.differentiation, ops.D), ("M", ref.mass, ops.M),
                       ("LIFT", ref.lift, ops.LIFT)]:
        err = np.max(np.abs(a - b)) / np.max(np.abs(b))
        print(f"p={p} {name}: {err:.1e}")
        assert err <= OPERATOR_RTOL, name
    assert ref.differentiation.flags.c_contiguous and ref.lift.flags.c_contiguous


@pytest.mark.parametrize("p", ORDERS)
def test_differentiation_exact_on_polynomials(p: int, rng: np.random.Generator) -> None:
    D = reference_element(p).differentiation
    x = reference_element(p).nodes
    for n in range(p + 1):
        c = np.zeros(n + 1)
        c[n] = 1.0  # the Legendre polynomial P_n and a random polynomial of degree n
        for coeffs in (c, rng.normal(size=n + 1)):
            exact = npl.legval(x, npl.legder(coeffs)) if n > 0 else np.zeros_like(x)
            got = D @ npl.legval(x, coeffs)
            scale = max(1.0, np.max(np.abs(exact)))
            assert np.max(np.abs(got - exact)) <= EXACTNESS_RTOL * scale


@pytest.mark.parametrize("p", ORDERS)
def test_mass_matrix_is_exact_and_agrees_with_lgl_quadrature(p: int) -> None:
    """M = int l_i l_j exactly (Gauss-Legendre with p + 3 points in the oracle); for products
    of degree <= 2p - 1 it agrees with the diagonal LGL quadrature, and its row sums are the
    LGL weights."""
    ref = reference_element(p)
    x, w, M = ref.nodes, ref.weights, ref.mass
    assert np.max(np.abs(M - M.T)) <= OPERATOR_RTOL
    assert np.max(np.abs(M.sum(axis=1) - w)) <= OPERATOR_RTOL
    for a in range(p + 1):
        for b in range(p + 1):
            fa, fb = x**a, x**b
            exact = (1.0 - (-1.0) ** (a + b + 1)) / (a + b + 1)
            assert abs(fa @ M @ fb - exact) <= OPERATOR_RTOL
            if a + b <= 2 * p - 1:
                assert abs(np.sum(w * fa * fb) - exact) <= OPERATOR_RTOL
    # degree 2p: LGL quadrature is no longer exact (so M is not lumped), the exact M still is
    fp = x**p
    exact = 2.0 / (2 * p + 1)
    assert abs(fp @ M @ fp - exact) <= OPERATOR_RTOL
    assert abs(np.sum(w * fp * fp) - exact) > 1e-6


@pytest.mark.parametrize("p", range(2, 9))
def test_filter_keeps_low_modes_and_removes_the_highest(p: int, rng: np.random.Generator) -> None:
    ref = reference_element(p)
    x, F = ref.nodes, ref.filter
    for n in range(p // 2 + 1):
        u = np.polynomial.polynomial.polyval(x, rng.normal(size=n + 1))
        assert np.max(np.abs(F @ u - u)) <= OPERATOR_RTOL * max(1.0, np.max(np.abs(u)))
    top = np.zeros(p + 1)
    top[p] = 1.0
    u = npl.legval(x, top)
    # sigma_p = exp(-36): the highest Legendre mode is removed to machine precision
    assert np.max(np.abs(F @ u)) <= 1e-14 * np.max(np.abs(u))
    # filtering never amplifies a mode (sigma <= 1), in the discrete L2 (mass) norm
    for _ in range(5):
        u = rng.normal(size=p + 1)
        assert (F @ u) @ ref.mass @ (F @ u) <= u @ ref.mass @ u * (1.0 + 1e-14)


# -- Hermite interpolation --------------------------------------------------------------------
def test_hermite_exact_on_cubics(rng: np.random.Generator) -> None:
    for _ in range(20):
        t0 = rng.uniform(-2.0, 2.0)
        t1 = t0 + rng.uniform(1e-3, 2.0)
        coef = rng.normal(size=(4, 3))  # a cubic per component
        pos_f = lambda t: coef[0] + coef[1] * t + coef[2] * t**2 + coef[3] * t**3  # noqa: E731
        vel_f = lambda t: coef[1] + 2 * coef[2] * t + 3 * coef[3] * t**2  # noqa: E731
        for t in [t0, t1, *rng.uniform(t0, t1, size=5)]:
            pos, vel = np.zeros(3), np.zeros(3)
            k.hermite(t0, t1, pos_f(t0), vel_f(t0), pos_f(t1), vel_f(t1), t, pos, vel)
            scale = np.max(np.abs(coef)) * (1.0 + abs(t0) + abs(t1)) ** 3
            assert np.max(np.abs(pos - pos_f(t))) <= HERMITE_RTOL * scale
            assert np.max(np.abs(vel - vel_f(t))) <= HERMITE_RTOL * scale
            po, vo = oracle.hermite(t0, t1, pos_f(t0), vel_f(t0), pos_f(t1), vel_f(t1), t)
            assert np.max(np.abs(pos - po)) <= 1e-10 * scale


def test_hermite_zero_length_interval_returns_the_end() -> None:
    p0, v0, p1, v1 = np.zeros(3), np.ones(3), np.full(3, 2.0), np.full(3, 3.0)
    pos, vel = np.zeros(3), np.zeros(3)
    k.hermite(1.0, 1.0, p0, v0, p1, v1, 1.0, pos, vel)
    assert np.array_equal(pos, p1) and np.array_equal(vel, v1)


# -- right-hand side ----------------------------------------------------------------------------
#: (label, state kind, property overrides, contact)
CASES = [
    ("taut-vacuum", "taut", dict(water_density=0.0, gravity=0.0), "implicit"),
    ("taut-vacuum-gravity", "taut", dict(water_density=0.0), "implicit"),
    ("slack-vacuum", "slack", dict(water_density=0.0), "implicit"),
    ("taut-water-drag", "taut",
     dict(normal_drag_coefficient=1.2, tangential_drag_coefficient=0.3), "implicit"),
    ("slack-water-everything", "slack",
     dict(normal_drag_coefficient=2.5, tangential_drag_coefficient=0.5,
          added_mass_coefficient=3.8, tangential_added_mass_coefficient=0.4,
          current_velocity=(0.4, -0.2, 0.05)), "implicit"),
    ("surface-piercing", "surface",
     dict(normal_drag_coefficient=1.0, tangential_drag_coefficient=0.2,
          added_mass_coefficient=1.0, tangential_added_mass_coefficient=0.5,
          current_velocity=(0.3, 0.1, 0.0)), "implicit"),
    ("internal-damping", "taut",
     dict(internal_damping=40.0, normal_drag_coefficient=1.0, added_mass_coefficient=1.0),
     "implicit"),
    ("internal-damping-clipped", "near-slack", dict(internal_damping=400.0), "implicit"),
    ("seabed-implicit", "seabed",
     dict(friction_coefficient=0.6, seabed_stiffness=1e3, seabed_damping_ratio=0.7,
          normal_drag_coefficient=2.0, tangential_drag_coefficient=0.4), "implicit"),
    ("seabed-explicit", "seabed",
     dict(friction_coefficient=0.6, seabed_stiffness=1e3, seabed_damping_ratio=0.7,
          normal_drag_coefficient=2.0, tangential_drag_coefficient=0.4,
          added_mass_coefficient=2.0, current_velocity=(0.2, 0.0, 0.0)), "explicit"),
]


def make_state(kind: str, K: int, p: int, L: float, rng: np.random.Generator):
    """Random node positions and velocities of a line from the origin (in the x-z plane, with
    y perturbations), with its anchor, fairlead and fairlead velocity."""
    Np = p + 1
    # fraction of the arc length at the LGL nodes (interface nodes duplicated)
    xi = (np.arange(K)[:, None] + 0.5 * (oracle.lgl_nodes(p)[0] + 1.0)) / K
    if kind == "taut":  # 5 % stretch, well away from the water line and the seabed
        anchor, fair = np.array([0.0, 0.0, -30.0]), np.array([0.8, 0.0, 0.6]) * 1.05 * L
        fair = fair + anchor
        noise = 0.002 * L / K / p**2  # nodal noise of slope ~1e-3 << strain
    elif kind == "near-slack":  # strain ~ 0: internal damping decides the sign of T
        anchor, fair = np.array([0.0, 0.0, -30.0]), np.array([0.8, 0.0, 0.6]) * 1.002 * L
        fair = fair + anchor
        noise = 0.002 * L / K
    elif kind == "slack":  # span 70 % of L: compression at many nodes
        anchor, fair = np.array([0.0, 0.0, -30.0]), np.array([0.7, 0.0, 0.0]) * L
        fair = fair + anchor
        noise = 0.05 * L / K
    elif kind == "surface":  # crosses z = 0 and has nodes exactly at z = 0
        anchor, fair = np.array([0.0, 0.0, -0.5 * L]), np.array([0.6 * L, 0.0, 0.5 * L])
        noise = 0.02 * L / K
    elif kind == "seabed":  # lying on a seabed at z = -10 with penetrations up to 5 cm
        anchor, fair = np.array([0.0, 0.0, -10.0]), np.array([0.98 * L, 0.0, -9.0])
        noise = 0.02 * L / K
    else:
        raise ValueError(kind)
    r = anchor + xi[..., None] * (fair - anchor) + rng.normal(scale=noise, size=(K, Np, 3))
    # a smooth transverse bow, so that the tangent turns along the line
    r[..., 1] += 0.02 * L * rng.normal() * np.sin(np.pi * xi)
    if kind == "surface":
        r[1, 0, 2] = 0.0
        r[0, -1, 2] = 0.0
    if kind == "seabed":
        r[..., 2] = -10.0 + rng.uniform(-0.05, 0.05, size=(K, Np))
        r[0, 0, 2] = -10.0
    v = rng.normal(scale=0.5, size=(K, Np, 3))
    if kind == "seabed":  # horizontal speeds both below and above the 0.01 m/s slip speed
        v[..., :2] *= 10.0 ** rng.uniform(-3.5, 0.0, size=(K, Np, 1))
        v[0, 1, :2] = 0.0
    fvel = rng.normal(scale=0.5, size=3)
    return r, v, anchor, fair, fvel


def make_properties(overrides: dict) -> CableProperties:
    base = dict(length=20.0, mass_per_length=1.5, axial_stiffness=300.0, diameter=0.05,
                material_density=2500.0, water_density=1000.0, gravity=9.81)
    base.update(overrides)
    return CableProperties(**base)


def oracle_params(pr: CableProperties, K: int, contact: str) -> dict:
    """The oracle's parameters from docs/theory/cable.md, computed here (not by ``packed``)."""
    A_c = pr.mass_per_length / pr.material_density
    k_b = pr.seabed_stiffness * pr.diameter  # per length: contact width = diameter
    return dict(h=pr.length / K, m=pr.mass_per_length, EA=pr.axial_stiffness, d=pr.diameter,
                A_c=A_c, rho_w=pr.water_density, g=pr.gravity,
                cdn=pr.normal_drag_coefficient, cdt=pr.tangential_drag_coefficient,
                m_an=pr.added_mass_coefficient * pr.water_density * A_c,
                m_at=pr.tangential_added_mass_coefficient * pr.water_density * A_c,
                c_int=pr.internal_damping,
                w_sub=abs(pr.mass_per_length * pr.gravity * (1 - pr.water_density
                                                             / pr.material_density)),
                z_b=pr.seabed_z if math.isfinite(pr.seabed_z) else -1e300, k_b=k_b,
                c_b=2.0 * pr.seabed_damping_ratio * math.sqrt(pr.mass_per_length * k_b),
                mu=pr.friction_coefficient, v_c=pr.slip_speed, current=pr.current_velocity,
                explicit_contact=contact == "explicit")


def read_only(anchor: np.ndarray) -> np.ndarray:
    """A read-only copy of ``anchor``, as the model passes it (floatmoor/mooring/dg/line.py):
    a writable one would compile the kernels it reaches a second time on an empty numba
    cache."""
    fixed = anchor.copy()
    fixed.flags.writeable = False
    return fixed


def kernel_rhs(r, v, anchor, fpos, fvel, prm, D, LIFT):
    K, Np = r.shape[:2]
    q, qt, N = (np.zeros((K, Np, 3)) for _ in range(3))
    Nstar, faces, slack, dv = np.zeros((K + 1, 3)), np.zeros((K + 1, 3)), np.zeros(K), np.zeros(
        (K, Np, 3))
    # the anchor read-only and fa=None, as the line's kernels pass them to their helpers
    k.dg_rhs(r, v, read_only(anchor), fpos, fvel, prm, D, LIFT, q, qt, N, Nstar, faces, slack,
             dv, None)
    return dv, q, N, Nstar, slack


def relerr(a: np.ndarray, b: np.ndarray) -> float:
    scale = np.max(np.abs(b))
    return float(np.max(np.abs(a - b)) / scale) if scale > 0 else float(np.max(np.abs(a)))


@pytest.mark.parametrize("label,kind,overrides,contact", CASES, ids=[c[0] for c in CASES])
@pytest.mark.parametrize("p", [1, 2, 3, 5, 8])
def test_rhs_matches_oracle(label, kind, overrides, contact, p, rng) -> None:
    K = 4
    pr = make_properties(dict(overrides, seabed_z=-10.0) if kind == "seabed" else overrides)
    # the right-hand side holds the Kelvin-Voigt term only when it is explicit
    settings = DynamicSettings(elements=K, order=p, cfl=0.5, max_time_step=None,
                               slack_filter=True, seabed_contact=contact,
                               internal_damping="explicit")
    prm = pr.packed(settings, pr.length / K)
    ref = reference_element(p)
    par = oracle_params(pr, K, contact)
    worst = 0.0
    for _ in range(3):
        r, v, anchor, fpos, fvel = make_state(kind, K, p, pr.length, rng)
        dv, q, N, Nstar, slack = kernel_rhs(r, v, anchor, fpos, fvel, prm, ref.differentiation,
                                            ref.lift)
        ao, fo = oracle.rhs(r, v, anchor, fpos, fvel, D=ref.differentiation, LIFT=ref.lift,
                            **par)
        errs = {"dv": relerr(dv, ao), "q": relerr(q, fo.q), "N": relerr(N, fo.N),
                "N*": relerr(Nstar, fo.Nstar)}
        worst = max(worst, *errs.values())
        for name, e in errs.items():
            assert e <= ORACLE_RTOL, (name, e)
        assert np.array_equal(slack, fo.slack)
        # with the oracle's own (barycentric) operators: checks the operators as well
        ao2, _ = oracle.rhs(r, v, anchor, fpos, fvel, D=oracle.operators(p).D,
                            LIFT=oracle.operators(p).LIFT, **par)
        assert relerr(dv, ao2) <= OPERATOR_RTOL
    print(f"{label} p={p}: max relative error {worst:.1e}")


@pytest.mark.parametrize("p", [2, 5])
def test_rhs_settling_damping_matches_oracle(p, rng) -> None:
    """The relaxation damping of DynamicLine.settle (P_RELAX): -gamma v on top of everything
    else, in the kernel as in the oracle."""
    K, gamma = 4, 37.0
    pr = make_properties(dict(normal_drag_coefficient=2.0, added_mass_coefficient=1.0,
                              seabed_z=-10.0, seabed_stiffness=1e3, friction_coefficient=0.4))
    settings = DynamicSettings(elements=K, order=p, cfl=0.5, max_time_step=None,
                               slack_filter=True, seabed_contact="explicit")
    prm = pr.packed(settings, pr.length / K)
    ref = reference_element(p)
    r, v, anchor, fpos, fvel = make_state("seabed", K, p, pr.length, rng)
    plain = kernel_rhs(r, v, anchor, fpos, fvel, prm, ref.differentiation, ref.lift)[0]
    prm[k.P_RELAX] = gamma
    damped = kernel_rhs(r, v, anchor, fpos, fvel, prm, ref.differentiation, ref.lift)[0]
    ao, _ = oracle.rhs(r, v, anchor, fpos, fvel, D=ref.differentiation, LIFT=ref.lift,
                       relax=gamma, **oracle_params(pr, K, "explicit"))
    assert relerr(damped, ao) <= ORACLE_RTOL
    assert relerr(damped - plain, -gamma * v) <= ORACLE_RTOL


def test_coulomb_friction_around_the_slip_speed_matches_oracle(rng) -> None:
    """The kernel takes the friction at or above the slip speed v_c without sin() (sin(pi / 2)
    is 1.0 in floating point): horizontal speeds just below, at and just above v_c, and far
    on either side, against the oracle's sin(pi/2 |v_h| / max(v_c, |v_h|))."""
    p, K = 3, 4
    pr = make_properties(dict(friction_coefficient=0.6, seabed_z=-10.0, seabed_stiffness=1e3,
                              normal_drag_coefficient=2.0))
    settings = DynamicSettings(elements=K, order=p, cfl=0.5, max_time_step=None,
                               slack_filter=True, seabed_contact="implicit")
    prm = pr.packed(settings, pr.length / K)
    ref = reference_element(p)
    r, v, anchor, fpos, fvel = make_state("seabed", K, p, pr.length, rng)
    r[..., 2] = -10.02  # every node on the seabed
    vc = prm[k.P_VC]
    factors = np.array([0.0, 0.3, 1.0 - 1e-12, 1.0, 1.0 + 1e-12, 1.0 + 1e-6, 7.0, 1e3])
    speeds = vc * np.resize(factors, K * (p + 1)).reshape(K, p + 1)
    angle = rng.uniform(0.0, 2.0 * np.pi, size=(K, p + 1))
    v[..., 0], v[..., 1] = speeds * np.cos(angle), speeds * np.sin(angle)
    dv = kernel_rhs(r, v, anchor, fpos, fvel, prm, ref.differentiation, ref.lift)[0]
    ao, _ = oracle.rhs(r, v, anchor, fpos, fvel, D=ref.differentiation, LIFT=ref.lift,
                       **oracle_params(pr, K, "implicit"))
    assert relerr(dv, ao) <= ORACLE_RTOL
    # the friction alone (the difference to the line without it) at each node
    prm0 = prm.copy()
    prm0[k.P_MU] = 0.0
    dv0 = kernel_rhs(r, v, anchor, fpos, fvel, prm0, ref.differentiation, ref.lift)[0]
    ao0, _ = oracle.rhs(r, v, anchor, fpos, fvel, D=ref.differentiation, LIFT=ref.lift,
                        **dict(oracle_params(pr, K, "implicit"), mu=0.0))
    assert relerr(dv - dv0, ao - ao0) <= ORACLE_RTOL


def test_rhs_cases_exercise_their_branches(rng) -> None:
    """The random states do reach the branches they are meant for."""
    p, K = 3, 4
    for kind, check in [
        ("slack", lambda r, fo: fo.slack.sum() >= 1),
        ("taut", lambda r, fo: fo.slack.sum() == 0),
        ("surface", lambda r, fo: (r[..., 2] < 0).any() and (r[..., 2] >= 0).any()),
        ("seabed", lambda r, fo: (r[..., 2] < -10.0).any() and (r[..., 2] > -10.0).any()),
    ]:
        r, v, anchor, fpos, fvel = make_state(kind, K, p, 20.0, rng)
        ref = reference_element(p)
        pr = make_properties({})
        par = oracle_params(pr, K, "implicit")
        _, fo = oracle.rhs(r, v, anchor, fpos, fvel, D=ref.differentiation, LIFT=ref.lift, **par)
        assert check(r, fo), kind
    # internal damping large enough to clip some tensions to zero at positive strain
    pr = make_properties(dict(internal_damping=400.0))
    par = oracle_params(pr, K, "implicit")
    ref = reference_element(p)
    clipped = 0
    for _ in range(3):
        r, v, anchor, fpos, fvel = make_state("near-slack", K, p, 20.0, rng)
        fo = oracle.tension_field(r, v, anchor, fpos, fvel, D=ref.differentiation,
                                  LIFT=ref.lift, h=par["h"], m=par["m"], EA=par["EA"],
                                  c_int=par["c_int"])
        eps = np.linalg.norm(fo.q, axis=-1) - 1.0
        clipped += int(np.sum((eps > 0) & (np.linalg.norm(fo.N, axis=-1) == 0.0)))
    assert clipped > 0


@pytest.mark.parametrize("p", [2, 5])
def test_tension_field_matches_oracle(p: int, rng: np.random.Generator) -> None:
    """dg_tension_field alone (the end-force recorder uses it), with tangential added mass in
    the face impedance."""
    K = 5
    pr = make_properties(dict(tangential_added_mass_coefficient=0.7, internal_damping=20.0))
    settings = DynamicSettings(elements=K, order=p, cfl=0.5, max_time_step=None,
                               slack_filter=True, seabed_contact="implicit")
    prm = pr.packed(settings, pr.length / K)
    ref = reference_element(p)
    par = oracle_params(pr, K, "implicit")
    r, v, anchor, fpos, fvel = make_state("surface", K, p, pr.length, rng)
    q, qt, N = (np.zeros((K, p + 1, 3)) for _ in range(3))
    Nstar, faces, slack = np.zeros((K + 1, 3)), np.zeros((K + 1, 3)), np.zeros(K)
    k.dg_tension_field(r, v, read_only(anchor), fpos, fvel, prm, ref.differentiation, ref.lift,
                       q, qt, N, Nstar, faces, slack)  # (the line's read-only anchor)
    fo = oracle.tension_field(r, v, anchor, fpos, fvel, D=ref.differentiation, LIFT=ref.lift,
                              h=par["h"], m=par["m"], EA=par["EA"], c_int=par["c_int"],
                              m_at=par["m_at"])
    for name, a, b in [("q", q, fo.q), ("N", N, fo.N), ("N*", Nstar, fo.Nstar)]:
        assert relerr(a, b) <= ORACLE_RTOL, name
    assert np.array_equal(slack, fo.slack)


@pytest.mark.parametrize("p", [1, 3, 6])
def test_uniformly_stretched_line_is_at_rest(p: int) -> None:
    """Consistency: a straight line at uniform strain, at rest, in vacuum without gravity, has
    zero acceleration (the DG derivative of a linear field is exact, the fluxes balance)."""
    K = 6
    pr = make_properties(dict(water_density=0.0, gravity=0.0))
    settings = DynamicSettings(elements=K, order=p, cfl=0.5, max_time_step=None,
                               slack_filter=True, seabed_contact="implicit")
    prm = pr.packed(settings, pr.length / K)
    ref = reference_element(p)
    anchor, fair = np.array([1.0, -2.0, -3.0]), np.array([17.0, 5.0, 12.0])  # 23.7 m apart
    s = (np.arange(K)[:, None] + 0.5 * (ref.nodes + 1.0)) / K
    r = anchor + s[..., None] * (fair - anchor)
    dv, q, N, Nstar, slack = kernel_rhs(r, np.zeros_like(r), anchor, fair, np.zeros(3), prm,
                                        ref.differentiation, ref.lift)
    T = pr.axial_stiffness * (np.linalg.norm(fair - anchor) / pr.length - 1.0)
    assert np.max(np.abs(np.linalg.norm(N, axis=-1) - T)) <= 1e-12 * T
    assert np.max(np.abs(dv)) <= 1e-11 * T * K / pr.length / pr.mass_per_length * p**2
    assert not slack.any()


# -- implicit internal damping ----------------------------------------------------------------
#: The kernel solves the banded system of the damping tensions (n unknowns), the oracle the
#: dense system of the velocities (3n): the same backward-Euler step, conditioned by
#: 1 + dt |operator| (dt chosen up to 10x the explicit damping limit). Observed <= 3e-14.
IMPLICIT_DAMPING_RTOL = 1e-11

DAMPING_KINDS = ["taut", "near-slack", "slack", "surface", "seabed"]


def kernel_damping_step(r, v, anchor, fpos, fvel, prm, ref, dt):
    """One backward-Euler damping step of the kernels, factors rebuilt."""
    K, Np = r.shape[:2]
    w = [np.zeros((K, Np, 3)), np.zeros((K, Np, 2)), np.zeros((K, Np)), np.zeros((K, Np)),
         np.zeros((K, Np, Np + 1, 3)), np.zeros((K * Np, 3 * Np)), np.zeros(K * Np),
         np.zeros(4)]
    tng, minv, cn, flags, Y, band, e, info = w
    q, qt, N = (np.zeros((K, Np, 3)) for _ in range(3))
    faces = np.zeros((K + 1, 3))
    v1 = v.copy()
    taut = k._damping_system(r, anchor, fpos, prm, ref.differentiation, ref.lift, dt, q, faces,
                             tng, minv, cn, flags, Y, band, info)
    if taut:
        k._damping_solve(v1, fvel, prm, ref.differentiation, ref.lift, dt, qt, N, faces, tng,
                         minv, cn, band, e)
    return v1, taut


#: The two tests below call the private damping kernels from Python, which compiles their
#: Python-callable twins (~2.5 s on an empty numba cache, for these tests alone): they run in
#: the slow set. The default run checks the same kernels (``_damping_system`` and the solve
#: of ``_damping_solve_ends``) against the dense oracle through the system's damping step,
#: tests/mooring/dg/test_dg_system.py::test_damping_step_with_free_points_matches_the_numpy_oracle
#: (docs/development.md#numba-compile-time).
_TWIN_COMPILING = pytest.mark.slow


@_TWIN_COMPILING
@pytest.mark.parametrize("kind", DAMPING_KINDS)
@pytest.mark.parametrize("p", [1, 2, 3, 5, 8])
def test_implicit_damping_step_matches_oracle(kind, p, rng) -> None:
    """The factored banded system of the damping tensions gives the backward-Euler step of
    the damping force that the oracle solves densely for the velocities: in water with normal
    and tangential added mass (the mass inversion along the frozen tangents), across the
    water line, on the seabed, taut, near slack and slack."""
    K = 4
    over = dict(internal_damping=60.0, added_mass_coefficient=1.5,
                tangential_added_mass_coefficient=0.3)
    if kind == "seabed":
        over["seabed_z"] = -10.0
    pr = make_properties(over)
    settings = DynamicSettings(elements=K, order=p, cfl=0.5, max_time_step=None,
                               slack_filter=True, seabed_contact="implicit")
    prm = pr.packed(settings, pr.length / K)
    assert prm[k.P_IMPLICIT_DAMPING] == 1.0  # the default
    ref = reference_element(p)
    par = oracle_params(pr, K, "implicit")
    keys = ("h", "m", "c_int", "m_an", "m_at")
    worst = 0.0
    for dt in (1e-4, 1e-2):
        r, v, anchor, fpos, fvel = make_state(kind, K, p, pr.length, rng)
        v1, taut = kernel_damping_step(r, v, anchor, fpos, fvel, prm, ref, dt)
        want = oracle.implicit_damping_step(v, r, anchor, fpos, fvel, dt, D=ref.differentiation,
                                            LIFT=ref.lift, **{x: par[x] for x in keys})
        if not taut:
            assert np.array_equal(v1, v)
        worst = max(worst, relerr(v1 - v, want - v) if np.any(want != v) else 0.0)
        assert relerr(v1, want) <= IMPLICIT_DAMPING_RTOL
    print(f"{kind} p={p}: velocity change error {worst:.1e}")
    assert worst <= 1e-9


@_TWIN_COMPILING
def test_implicit_damping_dissipates(rng) -> None:
    """With the fairlead at rest the backward-Euler damping step only removes kinetic energy,
    however large dt, also when its factors are reused for other velocities. The energy norm
    is the exact DG mass matrix (the derivative pair is summation-by-parts in it) with a
    uniform line mass (no added mass, which makes the mass depend on the node's tangent)."""
    K, p = 5, 4
    pr = make_properties(dict(internal_damping=500.0))
    settings = DynamicSettings(elements=K, order=p, cfl=0.5, max_time_step=None,
                               slack_filter=True, seabed_contact="implicit")
    prm = pr.packed(settings, pr.length / K)
    ref = reference_element(p)
    Np = p + 1
    tng, minv, cn, flags, Y, band, e, info = (
        np.zeros((K, Np, 3)), np.zeros((K, Np, 2)), np.zeros((K, Np)), np.zeros((K, Np)),
        np.zeros((K, Np, Np + 1, 3)), np.zeros((K * Np, 3 * Np)), np.zeros(K * Np), np.zeros(4))
    q, qt, N = (np.zeros((K, Np, 3)) for _ in range(3))
    faces = np.zeros((K + 1, 3))

    def energy(x):
        return float(np.einsum("kic,ij,kjc->", x, ref.mass, x))

    for dt in (1e-3, 1.0, 1e3):
        r, _, anchor, fpos, _ = make_state("taut", K, p, pr.length, rng)
        info[0] = 0.0
        assert k._damping_system(r, anchor, fpos, prm, ref.differentiation, ref.lift, dt, q,
                                 faces, tng, minv, cn, flags, Y, band, info)
        drops = []
        for _ in range(3):  # the same factors for new velocities
            v = rng.normal(size=(K, Np, 3))
            before = energy(v)
            k._damping_solve(v, np.zeros(3), prm, ref.differentiation, ref.lift, dt, qt, N,
                             faces, tng, minv, cn, band, e)
            drops.append(1.0 - energy(v) / before)
        print(f"dt = {dt:g}: kinetic energy removed {drops}")
        assert min(drops) >= -1e-13
        assert max(drops) > 0.0
