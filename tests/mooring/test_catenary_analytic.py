"""Quasi-static elastic catenary against analytic solutions (verification cases 5.1.1,
5.1.2 and 5.1.10 of ``docs/development.md``).

References: Irvine (1981) and Jonkman (2007) for the elastic catenary with seabed contact and
friction; the inelastic catenary in its cosh form for an independent closed form; the
hanging bar under self-weight for the stretch.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from floatmoor.errors import SolverError
from floatmoor.mooring import _catenary_kernels as k
from floatmoor.mooring import _catenary_profile as p
from floatmoor.mooring.catenary import (
    STATUS_MESSAGES, catenary_profile, describe_failure, solve_catenary,
)
from tests.oracles import catenary_numpy as oracle


pytestmark = [pytest.mark.verification, pytest.mark.oracle]

#: The inelastic closed form (EA -> inf) against the solver with EA = 1e16 W L: the elastic terms
#: are O(T/EA) ~ 1e-15 and the solver reaches 1e-14 L; the closed-form bar of
#: docs/development.md#4-kinds-of-tests.
INELASTIC_RTOL = 1e-10
#: docs/development.md#case-511-elastic-catenary: the solution substituted back into the equations
#: holds to 1e-9 L.
EQUATIONS_ATOL_REL = 1e-9
#: docs/development.md#case-512-hanging-bar: stretch w L^2 / (2 EA), quasi-static bar 1e-8.
HANGING_RTOL = 1e-8
#: docs/development.md#case-511-elastic-catenary: analytic stiffness against central finite
#: differences, rtol 1e-5 (relative to the largest entry of the matrix). Steps of 1e-7 L on solves
#: converged to 1e-14 L: truncation ~ (1e-7)^2, noise ~ 1e-14 / 1e-7 = 1e-7.
STIFFNESS_FD_RTOL = 1e-5
FD_STEP_REL = 1e-7
FD_TOL = 1e-14
#: docs/development.md#case-5110-invariances: swapped ends, rotation and translation change
#: nothing, 1e-10 (QS).
INVARIANCE_RTOL = 1e-10
#: Warm start from the solution at a fairlead position 1e-3 L away: Newton converges
#: quadratically, 1e-3 -> 1e-6 -> 1e-12 -> below 1e-14, so 4 iterations must do.
WARM_START_MAX_ITER = 4

TOL = 1e-12
NAN = math.nan


def solve2d(XF, ZF, L, EA, W, CB=0.0, seabed=0, h0=NAN, v0=NAN, tol=TOL, max_iter=100):
    out = np.empty(k.N_OUT_2D)
    status = k.catenary_solve(float(XF), float(ZF), float(L), float(EA), float(W), float(CB),
                              int(seabed), h0, v0, tol, max_iter, out)
    return status, out


def solve3d(anchor, fairlead, L, EA, W, CB=0.0, seabed_z=-math.inf, h0=NAN, v0=NAN, tol=TOL):
    out = np.empty(k.N_OUT_3D)
    status = k.catenary_solve_3d(np.asarray(anchor, dtype=float), np.asarray(fairlead, dtype=float),
                                 float(L), float(EA), float(W), float(CB), float(seabed_z), h0, v0,
                                 tol, 100, out)
    return status, out


def forces(out):
    return (out[k.I3_FAIRLEAD_FORCE:k.I3_FAIRLEAD_FORCE + 3].copy(),
            out[k.I3_ANCHOR_FORCE:k.I3_ANCHOR_FORCE + 3].copy())


def stiffness3(out):
    return out[k.I3_STIFFNESS:k.I3_STIFFNESS + 9].reshape(3, 3).copy()


# ----------------------------------------------------------------------------- closed forms
@pytest.mark.parametrize("a_over_xf, x0_over_xf, XF", [
    (0.3, 0.5, 80.0),    # symmetric sag, vertex mid-span (VA < 0 < VF)
    (0.5, 0.2, 150.0),   # vertex near the anchor
    (1.5, -0.4, 60.0),   # vertex outside the span: both ends pull up and out (VA > 0)
    (0.5, 1.3, 30.0),    # vertex beyond the fairlead: fairlead below the anchor (VF < 0)
    (5.0, 0.5, 200.0),   # shallow sag
])
def test_inelastic_suspended_catenary(a_over_xf, x0_over_xf, XF):
    """z = a (cosh((x - x0)/a) - cosh(x0/a)), a = H/W: end point, length and forces."""
    W = 700.0
    a, x0 = a_over_xf * XF, x0_over_xf * XF
    L = a * (math.sinh((XF - x0) / a) + math.sinh(x0 / a))
    ZF = a * (math.cosh((XF - x0) / a) - math.cosh(x0 / a))
    H = W * a
    VF = H * math.sinh((XF - x0) / a)
    VA = -H * math.sinh(x0 / a)
    EA = 1e16 * W * L
    status, out = solve2d(XF, ZF, L, EA, W, tol=1e-14)
    assert status == k.CAT_OK
    T = math.hypot(H, VF)
    err = max(abs(out[k.I_HF] - H), abs(out[k.I_VF] - VF), abs(out[k.I_HA] - H),
              abs(out[k.I_VA] - VA)) / T
    print(f"\ninelastic suspended a/XF={a_over_xf}: max force error {err:.2e} T "
          f"(tolerance {INELASTIC_RTOL:.0e})")
    assert err <= INELASTIC_RTOL


@pytest.mark.parametrize("CB", [0.0, 0.2, 5.0])
def test_inelastic_touchdown_catenary(CB):
    """Resting length LB, then z = a (cosh((x - LB)/a) - 1) up to the fairlead."""
    W, a, LB, XS = 1200.0, 40.0, 150.0, 90.0  # XS: horizontal span of the suspended part
    Ls = a * math.sinh(XS / a)
    L, XF, ZF = LB + Ls, LB + XS, a * (math.cosh(XS / a) - 1.0)
    H, VF = W * a, W * Ls
    status, out = solve2d(XF, ZF, L, 1e16 * W * L, W, CB, seabed=1, tol=1e-14)
    assert status == k.CAT_OK and out[k.I_PROFILE] == k.PROFILE_TOUCHDOWN
    err = max(abs(out[k.I_HF] - H), abs(out[k.I_VF] - VF)) / math.hypot(H, VF)
    assert err <= INELASTIC_RTOL
    assert out[k.I_LB] == pytest.approx(LB, rel=INELASTIC_RTOL)
    # friction reduces the anchor tension by CB W LB, floored at zero (docs/theory/quasi_static.md)
    assert out[k.I_HA] == pytest.approx(max(H - CB * W * LB, 0.0), rel=INELASTIC_RTOL,
                                        abs=INELASTIC_RTOL * H)
    assert out[k.I_VA] == 0.0
    print(f"\ninelastic touchdown CB={CB}: force error {err:.2e} T")


def test_vertical_hanging_line_stretches_by_w_l2_over_2ea():
    """A line hanging between two points on a vertical, with its lower end force free."""
    L, W, EA = 120.0, 800.0, 2.0e7
    stretch = W * L**2 / (2 * EA)
    for seabed in (0, 1):
        status, out = solve2d(0.0, L + stretch, L, EA, W, seabed=seabed)
        assert status == k.CAT_OK and out[k.I_PROFILE] == k.PROFILE_VERTICAL
        assert out[k.I_VF] == pytest.approx(W * L, rel=HANGING_RTOL)
        assert abs(out[k.I_VA]) <= HANGING_RTOL * W * L
        assert out[k.I_HF] == 0.0 and out[k.I_LB] == 0.0
    # tip load P: VA = P, VF = P + W L, stretch W L^2/(2 EA) + P L / EA
    P = 3.0e4
    status, out = solve2d(0.0, L + stretch + P * L / EA, L, EA, W)
    assert status == k.CAT_OK
    assert out[k.I_VA] == pytest.approx(P, rel=HANGING_RTOL)
    assert out[k.I_VF] == pytest.approx(P + W * L, rel=HANGING_RTOL)
    # profile: T(s) = P + W s, z(s) = s + (P s + W s^2 / 2) / EA
    s = np.linspace(0.0, L, 9)
    x, z, T = np.empty(9), np.empty(9), np.empty(9)
    p.catenary_profile(0.0, L + stretch + P * L / EA, L, EA, W, 0.0, 0, out[k.I_HF], out[k.I_VF],
                       s, x, z, T)
    np.testing.assert_allclose(T, P + W * s, rtol=HANGING_RTOL)
    np.testing.assert_allclose(z, s + (P * s + W * s**2 / 2) / EA, rtol=HANGING_RTOL, atol=1e-12)
    assert np.all(x == 0.0)
    print(f"\nhanging line: VF = {out[k.I_VF]:.10g} N vs P + W L = {P + W * L:.10g} N")


# ----------------------------------------------------------------------------- equations
def _random_case(rng, kind):
    L = 10 ** rng.uniform(1.0, 3.3)
    W = 10 ** rng.uniform(1.0, 3.7)
    EA = W * L * 10 ** rng.uniform(2.0, 5.0)
    CB, seabed = 0.0, 0
    if kind == "suspended":
        ratio, angle = rng.uniform(0.2, 0.99), rng.uniform(-1.5, 1.5)
    elif kind == "taut":
        seabed = int(rng.integers(2))
        ratio, angle = rng.uniform(1.0, 1.02), rng.uniform(0.05, 1.5)
    elif kind == "touchdown":
        seabed, CB = 1, float(rng.choice([0.0, rng.uniform(0.05, 2.0)]))
        ratio, angle = rng.uniform(0.5, 0.999), rng.uniform(0.02, 1.4)
    elif kind == "slack":
        seabed, CB = 1, rng.uniform(0.0, 1.0)
        ratio, angle = rng.uniform(0.1, 0.6), rng.uniform(0.3, 1.5)
    elif kind == "on_seabed":
        seabed, CB = 1, float(rng.choice([0.0, rng.uniform(0.05, 2.0)]))
        ratio, angle = rng.uniform(0.5, 1.01), 0.0
    else:  # vertical
        seabed = int(rng.integers(2))
        ratio, angle = rng.uniform(-1.2, 1.2), math.pi / 2
    XF = 0.0 if kind == "vertical" else ratio * L * math.cos(angle)
    ZF = 0.0 if kind == "on_seabed" else ratio * L * math.sin(angle)
    if seabed and ZF < 0:
        ZF = -ZF
    return oracle.Line(XF, ZF, L, EA, W, CB, bool(seabed))


def _equation_error(line, out):
    """|X - XF| + |Z - ZF| of the solution in the equations of docs/theory/quasi_static.md or
    their H = 0 limits."""
    H, VF, L, W, EA = out[k.I_HF], out[k.I_VF], line.L, line.W, line.EA
    if H > 0.0:
        rX, rZ = oracle.residual(line, H, VF)
        return abs(rX) + abs(rZ)
    if line.seabed and VF < W * L:
        # H = 0: a vertical hanging part of length Ls = VF/W, the rest lying slack (XF <= LB)
        Ls = VF / W
        assert line.XF <= L - Ls + 1e-15 * L
        assert out[k.I_LB] == pytest.approx(L - Ls, rel=1e-15, abs=1e-15 * L)
        return abs(Ls + W * Ls**2 / (2 * EA) - line.ZF)
    # vertical line: Z = (|VF| - |VA|)/W + (VA + VF) L / (2 EA), the H -> 0 limit
    VA = VF - W * L
    assert line.XF == 0.0
    return abs((abs(VF) - abs(VA)) / W + (VA + VF) * L / (2 * EA) - line.ZF)


def test_equations_hold_on_random_lines_of_every_profile_type():
    rng = np.random.default_rng(51)
    kinds = ["suspended", "taut", "touchdown", "slack", "on_seabed", "vertical"]
    worst = dict.fromkeys(kinds, 0.0)
    seen = set()
    for i in range(480):
        kind = kinds[i % len(kinds)]
        line = _random_case(rng, kind)
        status, out = solve2d(line.XF, line.ZF, line.L, line.EA, line.W, line.CB,
                              int(line.seabed))
        assert status == k.CAT_OK, line
        err = _equation_error(line, out) / line.L
        worst[kind] = max(worst[kind], err)
        assert err <= EQUATIONS_ATOL_REL, (line, out)
        seen.add(int(out[k.I_PROFILE]))
        # statics: vertical equilibrium of the suspended part, horizontal of the line
        H, VF, HA, VA, LB = out[[k.I_HF, k.I_VF, k.I_HA, k.I_VA, k.I_LB]]
        assert VF - VA == pytest.approx(line.W * (line.L - LB), rel=1e-12, abs=1e-9 * line.W)
        if LB == 0.0:
            assert HA == H
        else:
            assert VA == 0.0
            assert HA == pytest.approx(max(H - line.CB * line.W * LB, 0.0), rel=1e-12,
                                       abs=1e-12 * max(H, 1.0))
    assert seen == {k.PROFILE_SUSPENDED, k.PROFILE_TAUT, k.PROFILE_TOUCHDOWN,
                    k.PROFILE_ON_SEABED, k.PROFILE_SLACK, k.PROFILE_VERTICAL}
    print("\nworst equation residual / L by kind: "
          + ", ".join(f"{kind} {err:.1e}" for kind, err in worst.items())
          + f" (tolerance {EQUATIONS_ATOL_REL:.0e})")


# ----------------------------------------------------------------------------- stiffness
STIFFNESS_CASES = {
    # name: (XF, ZF, L, EA, W, CB, seabed)
    "suspended sagging below the anchor": (60.0, 10.0, 100.0, 1e7, 500.0, 0.0, 0),
    "fairlead below the anchor": (70.0, -40.0, 100.0, 1e7, 500.0, 0.0, 0),
    "taut": (80.0, 60.5, 100.0, 1e8, 500.0, 0.0, 0),
    "touchdown": (700.0, 150.0, 800.0, 5e8, 1000.0, 0.0, 1),
    "touchdown, friction, anchor loaded": (700.0, 150.0, 800.0, 5e8, 1000.0, 0.1, 1),
    "touchdown, friction, anchor unloaded": (700.0, 150.0, 800.0, 5e8, 1000.0, 2.0, 1),
    "anchor uplift": (700.0, 400.0, 800.0, 5e8, 1000.0, 0.3, 1),
    "nearly vertical taut": (1e-3, 100.5, 100.0, 1e7, 500.0, 0.0, 0),
    "nearly vertical folded": (1e-2, 50.0, 100.0, 1e7, 500.0, 0.0, 0),
}


@pytest.mark.parametrize("name", list(STIFFNESS_CASES))
def test_2d_stiffness_matches_central_differences(name):
    XF, ZF, L, EA, W, CB, seabed = STIFFNESS_CASES[name]
    status, out = solve2d(XF, ZF, L, EA, W, CB, seabed, tol=FD_TOL)
    assert status == k.CAT_OK
    h0, v0 = out[k.I_HF], out[k.I_VF]
    h = FD_STEP_REL * L
    K_fd = np.empty((2, 2))
    for j, (dx, dz) in enumerate(((h, 0.0), (0.0, h))):
        _, op = solve2d(XF + dx, ZF + dz, L, EA, W, CB, seabed, h0, v0, tol=FD_TOL)
        _, om = solve2d(XF - dx, ZF - dz, L, EA, W, CB, seabed, h0, v0, tol=FD_TOL)
        K_fd[0, j] = (op[k.I_HF] - om[k.I_HF]) / (2 * h)
        K_fd[1, j] = (op[k.I_VF] - om[k.I_VF]) / (2 * h)
    K = out[k.I_K11:k.I_K22 + 1].reshape(2, 2)
    err = np.max(np.abs(K - K_fd)) / np.max(np.abs(K_fd))
    print(f"\n2x2 stiffness, {name}: {err:.1e} of max|K| (tolerance {STIFFNESS_FD_RTOL:.0e})")
    assert err <= STIFFNESS_FD_RTOL


STIFFNESS_3D_CASES = {
    # name: (anchor, fairlead, L, EA, W, CB, seabed_z)
    "touchdown, friction": ([-600.0, -300.0, -200.0], [0.0, 0.0, -12.0], 800.0, 5e8, 1000.0,
                            0.4, -200.0),
    "free, oblique": ([3.0, -4.0, -30.0], [50.0, 40.0, 5.0], 100.0, 1e7, 300.0, 0.0, -math.inf),
    "fairlead is the lower end, resting": ([0.0, 0.0, -12.0], [-600.0, 300.0, -200.0], 800.0,
                                           5e8, 1000.0, 0.0, -200.0),
    "fairlead is the lower end, resting, friction": ([0.0, 0.0, -12.0], [-600.0, 300.0, -200.0],
                                                     800.0, 5e8, 1000.0, 0.05, -200.0),
    "fairlead is the lower end, free": ([0.0, 0.0, 10.0], [60.0, -20.0, -40.0], 100.0, 1e7,
                                        300.0, 0.0, -math.inf),
    "nearly vertical taut": ([0.0, 0.0, -100.0], [1e-3, 2e-3, 0.6], 100.0, 1e7, 500.0, 0.0,
                             -math.inf),
    "exactly vertical taut": ([5.0, 5.0, -100.0], [5.0, 5.0, 0.6], 100.0, 1e7, 500.0, 0.0,
                              -math.inf),
}


@pytest.mark.parametrize("name", list(STIFFNESS_3D_CASES))
def test_3d_stiffness_matches_central_differences(name):
    anchor, fairlead, L, EA, W, CB, seabed_z = STIFFNESS_3D_CASES[name]
    fairlead = np.asarray(fairlead)
    status, out = solve3d(anchor, fairlead, L, EA, W, CB, seabed_z, tol=FD_TOL)
    assert status == k.CAT_OK
    h0, v0 = out[k.I3_HF], out[k.I3_VF]
    h = FD_STEP_REL * L
    K_fd = np.empty((3, 3))
    for j in range(3):
        step = np.zeros(3)
        step[j] = h
        sp, op = solve3d(anchor, fairlead + step, L, EA, W, CB, seabed_z, h0, v0, tol=FD_TOL)
        sm, om = solve3d(anchor, fairlead - step, L, EA, W, CB, seabed_z, h0, v0, tol=FD_TOL)
        assert sp == sm == k.CAT_OK
        K_fd[:, j] = -(forces(op)[0] - forces(om)[0]) / (2 * h)
    K = stiffness3(out)
    err = np.max(np.abs(K - K_fd)) / np.max(np.abs(K_fd))
    print(f"\n3x3 stiffness, {name}: {err:.1e} of max|K| (tolerance {STIFFNESS_FD_RTOL:.0e})")
    assert err <= STIFFNESS_FD_RTOL


# ----------------------------------------------------------------------------- invariance
INVARIANCE_CASES = {
    "touchdown": ([-600.0, -300.0, -200.0], [0.0, 0.0, -12.0], 800.0, 5e8, 1000.0, 0.4, -200.0),
    "slack on the seabed": ([-300.0, 0.0, -200.0], [0.0, 0.0, -12.0], 800.0, 5e8, 1000.0, 0.4,
                            -200.0),
    "anchor uplift": ([-600.0, -300.0, -200.0], [0.0, 0.0, 150.0], 800.0, 5e8, 1000.0, 0.0,
                      -200.0),
    "free, sagging": ([3.0, -4.0, -30.0], [50.0, 40.0, 5.0], 100.0, 1e7, 300.0, 0.0, -math.inf),
    "free, ends level": ([0.0, 0.0, -30.0], [80.0, 0.0, -30.0], 100.0, 1e7, 300.0, 0.0, -100.0),
    "vertical folded": ([0.0, 0.0, -30.0], [0.0, 0.0, 20.0], 100.0, 1e7, 300.0, 0.0, -math.inf),
}


@pytest.mark.parametrize("name", list(INVARIANCE_CASES))
def test_swapped_ends_give_the_same_line(name):
    anchor, fairlead, L, EA, W, CB, seabed_z = INVARIANCE_CASES[name]
    s1, o1 = solve3d(anchor, fairlead, L, EA, W, CB, seabed_z)
    s2, o2 = solve3d(fairlead, anchor, L, EA, W, CB, seabed_z)
    assert s1 == s2 == k.CAT_OK
    f1, a1 = forces(o1)
    f2, a2 = forces(o2)
    T = max(np.linalg.norm(f1), np.linalg.norm(a1), W * L)
    err = max(np.max(np.abs(f1 - a2)), np.max(np.abs(a1 - f2))) / T
    print(f"\nswapped ends, {name}: {err:.1e} T (tolerance {INVARIANCE_RTOL:.0e})")
    assert err <= INVARIANCE_RTOL
    # upper/lower-end quantities do not depend on the names of the ends
    if anchor[2] != fairlead[2]:
        np.testing.assert_allclose(o1[k.I3_HF:k.I3_LB + 1], o2[k.I3_HF:k.I3_LB + 1],
                                   rtol=INVARIANCE_RTOL, atol=INVARIANCE_RTOL * T)
    else:  # level ends: symmetric line, HF = HA and VF = -VA
        assert o1[k.I3_HA] == pytest.approx(o1[k.I3_HF], rel=INVARIANCE_RTOL)
        assert o1[k.I3_VA] == pytest.approx(-o1[k.I3_VF], rel=INVARIANCE_RTOL)


@pytest.mark.parametrize("name", list(INVARIANCE_CASES))
def test_rotation_about_z_and_translation_change_nothing(name):
    anchor, fairlead, L, EA, W, CB, seabed_z = INVARIANCE_CASES[name]
    anchor, fairlead = np.asarray(anchor), np.asarray(fairlead)
    s1, o1 = solve3d(anchor, fairlead, L, EA, W, CB, seabed_z)
    assert s1 == k.CAT_OK
    f1, a1 = forces(o1)
    K1 = stiffness3(o1)
    T = max(np.linalg.norm(f1), np.linalg.norm(a1), W * L)
    worst = 0.0
    moves = ((0.7, [10.0, -20.0, 0.0]), (2.9, [-1e3, 4e2, 0.0]), (-1.3, [0.5, 0.0, 0.0]))
    for angle, shift in moves:
        c, s = math.cos(angle), math.sin(angle)
        R = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
        shift = np.asarray(shift)
        s2, o2 = solve3d(R @ anchor + shift, R @ fairlead + shift, L, EA, W, CB, seabed_z)
        assert s2 == k.CAT_OK
        f2, a2 = forces(o2)
        err = max(np.max(np.abs(f2 - R @ f1)), np.max(np.abs(a2 - R @ a1))) / T
        errk = np.max(np.abs(stiffness3(o2) - R @ K1 @ R.T)) / np.max(np.abs(K1))
        worst = max(worst, err, errk)
        assert err <= INVARIANCE_RTOL and errk <= INVARIANCE_RTOL
    # a vertical translation moves the seabed along
    dz = 37.0
    s3, o3 = solve3d(anchor + [0.0, 0.0, dz], fairlead + [0.0, 0.0, dz], L, EA, W, CB,
                     seabed_z + dz)
    assert s3 == k.CAT_OK
    f3, a3 = forces(o3)
    err = max(np.max(np.abs(f3 - f1)), np.max(np.abs(a3 - a1))) / T
    worst = max(worst, err)
    assert err <= INVARIANCE_RTOL
    print(f"\nrotation/translation, {name}: {worst:.1e} (tolerance {INVARIANCE_RTOL:.0e})")


# ----------------------------------------------------------------------------- edge cases
L0, EA0, W0 = 100.0, 1e7, 500.0
C0 = 1.0 + W0 * L0 / (2 * EA0)  # ZF / L of the fixed-fixed vertical line with VA = 0
LS0 = 40.0  # a hanging length, and the fairlead height it needs:
ZS0 = LS0 + W0 * LS0**2 / (2 * EA0)

EDGE_CASES = {
    # name: (XF, ZF, CB, seabed, expected profile, expected {quantity: value})
    "nearly taut, free": (60.0, 80.0 * (1 - 1e-12), 0.0, 0, k.PROFILE_SUSPENDED, {}),
    "just taut, free": (60.0 * (1 + 1e-9), 80.0 * (1 + 1e-9), 0.0, 0, k.PROFILE_TAUT, {}),
    "nearly taut on a seabed": (80.0, 60.0 * (1 - 1e-9), 0.3, 1, None, {}),
    "stretched 1 %": (80.8, 60.6, 0.0, 1, k.PROFILE_TAUT, {}),
    "nearly vertical, folded": (1e-9 * L0, 0.5 * L0, 0.0, 0, k.PROFILE_SUSPENDED, {}),
    "nearly vertical, taut": (1e-12 * L0, 1.001 * L0, 0.0, 0, k.PROFILE_TAUT, {}),
    "nearly vertical, fairlead below": (1e-9 * L0, -0.7 * L0, 0.0, 0, k.PROFILE_SUSPENDED, {}),
    "vertical, folded": (0.0, 0.5 * L0, 0.0, 0, k.PROFILE_VERTICAL,
                         {k.I_VF: W0 * (L0 - (L0 - 0.5 * L0 / C0) / 2)}),
    "vertical, fixed-fixed, VA = 0": (0.0, L0 * C0, 0.0, 0, k.PROFILE_VERTICAL,
                                      {k.I_VF: W0 * L0, k.I_VA: 0.0}),
    "vertical, taut": (0.0, 1.01 * L0, 0.0, 0, k.PROFILE_VERTICAL,
                       {k.I_VA: EA0 * 0.01 - W0 * L0 / 2}),
    "vertical, hanging down taut": (0.0, -1.01 * L0, 0.0, 0, k.PROFILE_VERTICAL,
                                    {k.I_VF: -EA0 * 0.01 + W0 * L0 / 2}),
    "vertical onto the seabed": (0.0, ZS0, 0.0, 1, k.PROFILE_SLACK,
                                 {k.I_VF: W0 * LS0, k.I_LB: L0 - LS0, k.I_HF: 0.0}),
    "slack on the seabed": (30.0, ZS0, 0.5, 1, k.PROFILE_SLACK, {k.I_VF: W0 * LS0, k.I_HF: 0.0}),
    "slack boundary": (L0 - LS0, ZS0, 0.5, 1, k.PROFILE_SLACK, {k.I_VF: W0 * LS0}),
    "just past the slack boundary": ((L0 - LS0) * (1 + 1e-9), ZS0, 0.5, 1, k.PROFILE_TOUCHDOWN,
                                     {k.I_VF: W0 * LS0}),
    "almost all on the seabed": (0.99 * L0, 1e-6 * L0, 0.0, 1, None, {}),
    "almost all on the seabed, tight": (1.0001 * L0, 1e-6 * L0, 0.2, 1, k.PROFILE_TOUCHDOWN, {}),
    "all on the seabed, slack": (0.9 * L0, 0.0, 0.5, 1, k.PROFILE_ON_SEABED,
                                 {k.I_HF: 0.0, k.I_VF: 0.0, k.I_LB: L0}),
    "all on the seabed, taut": (1.001 * L0, 0.0, 0.0, 1, k.PROFILE_ON_SEABED,
                                {k.I_HF: EA0 * 0.001, k.I_HA: EA0 * 0.001, k.I_LB: L0}),
    "all on the seabed, taut, friction, anchor loaded": (
        1.001 * L0, 0.0, 0.1, 1, k.PROFILE_ON_SEABED,
        {k.I_HF: EA0 * 0.001 + 0.05 * W0 * L0, k.I_HA: EA0 * 0.001 - 0.05 * W0 * L0}),
    "all on the seabed, taut, friction, anchor unloaded": (
        1.00001 * L0, 0.0, 0.5, 1, k.PROFILE_ON_SEABED,
        {k.I_HF: math.sqrt(2 * EA0 * 0.5 * W0 * 1e-5 * L0), k.I_HA: 0.0}),
}


@pytest.mark.parametrize("name", list(EDGE_CASES))
def test_edge_cases_converge_and_satisfy_the_equations(name):
    XF, ZF, CB, seabed, profile, expected = EDGE_CASES[name]
    line = oracle.Line(XF, ZF, L0, EA0, W0, CB, bool(seabed))
    status, out = solve2d(XF, ZF, L0, EA0, W0, CB, seabed)
    assert status == k.CAT_OK
    assert np.all(np.isfinite(out))
    if profile is not None:
        assert out[k.I_PROFILE] == profile
    if out[k.I_PROFILE] == k.PROFILE_ON_SEABED:
        # X = L + seabed stretch (the touchdown equation with VF = 0, LB = L)
        H = out[k.I_HF]
        if H > 0.0:
            assert out[k.I_VF] == 0.0
            rX, rZ = oracle.residual(line, H, 0.0)
            err = abs(rX) / L0
        else:
            err = 0.0 if XF <= L0 else math.inf
    else:
        err = _equation_error(line, out) / L0
    assert err <= EQUATIONS_ATOL_REL
    scale = max(math.hypot(out[k.I_HF], out[k.I_VF]), W0 * L0)
    for index, value in expected.items():
        assert out[index] == pytest.approx(value, rel=1e-9, abs=1e-9 * scale), index
    print(f"\n{name}: equations {err:.1e} L, {int(out[k.I_ITER])} iterations")


def test_solution_is_continuous_across_profile_changes():
    """Slack -> touchdown (H leaves 0) and touchdown -> suspended (VF crosses W L)."""
    base = solve2d(L0 - LS0, ZS0, L0, EA0, W0, 0.5, 1)[1]
    near = solve2d((L0 - LS0) * (1 + 1e-10), ZS0, L0, EA0, W0, 0.5, 1)[1]
    assert near[k.I_PROFILE] == k.PROFILE_TOUCHDOWN and base[k.I_PROFILE] == k.PROFILE_SLACK
    assert abs(near[k.I_HF] - base[k.I_HF]) <= 1e-6 * W0 * L0
    assert abs(near[k.I_VF] - base[k.I_VF]) <= 1e-6 * W0 * L0
    # the vertex exactly at the anchor (VA = 0): the touchdown and suspended formulas agree
    H = 3.0 * W0 * L0
    a = math.asinh(W0 * L0 / H)
    XF = H / W0 * a + H * L0 / EA0
    ZF = H / W0 * (math.sqrt(1 + (W0 * L0 / H) ** 2) - 1) + W0 * L0**2 / (2 * EA0)
    for dx in (-1e-9, 0.0, 1e-9):
        status, out = solve2d(XF + dx * L0, ZF, L0, EA0, W0, 0.0, 1)
        assert status == k.CAT_OK
        assert out[k.I_HF] == pytest.approx(H, rel=1e-5)
        assert out[k.I_VF] == pytest.approx(W0 * L0, rel=1e-5)
        assert out[k.I_LB] <= 1e-5 * L0


# ----------------------------------------------------------------------------- failures
@pytest.mark.parametrize("args, status, words", [
    ((NAN, 10.0, 100.0, 1e7, 500.0, 0.0, 0), k.CAT_INVALID_INPUT, ["XF = nan"]),
    ((50.0, 10.0, math.inf, 1e7, 500.0, 0.0, 0), k.CAT_INVALID_INPUT, ["L = inf"]),
    ((-1.0, 10.0, 100.0, 1e7, 500.0, 0.0, 0), k.CAT_INVALID_INPUT, ["XF = -1", "negative"]),
    ((50.0, 10.0, 0.0, 1e7, 500.0, 0.0, 0), k.CAT_INVALID_INPUT, ["L = 0 m", "not positive"]),
    ((50.0, 10.0, 100.0, -1e7, 500.0, 0.0, 0), k.CAT_INVALID_INPUT, ["EA = -1e+07 N"]),
    ((50.0, 10.0, 100.0, 1e7, -5.0, 0.0, 0), k.CAT_INVALID_INPUT, ["W = -5 N/m", "buoyant"]),
    ((50.0, 10.0, 100.0, 1e7, 0.0, 0.0, 0), k.CAT_INVALID_INPUT, ["W = 0 N/m"]),
    ((50.0, 10.0, 100.0, 1e7, 500.0, -0.1, 1), k.CAT_INVALID_INPUT, ["friction coefficient"]),
    ((50.0, -10.0, 100.0, 1e7, 500.0, 0.0, 1), k.CAT_BELOW_SEABED, ["10 m below the anchor"]),
])
def test_invalid_input_is_reported_with_the_reason(args, status, words):
    got, out = solve2d(*args)
    assert got == status
    assert np.all(np.isnan(out[[k.I_HF, k.I_VF, k.I_HA, k.I_VA, k.I_K11]]))
    message = describe_failure(got, *args[:5])
    for word in words:
        assert word in message, message
    print(f"\n{message}")


def test_bad_tolerance_and_iteration_limit_are_invalid():
    assert solve2d(50.0, 10.0, 100.0, 1e7, 500.0, tol=0.0)[0] == k.CAT_INVALID_INPUT
    assert solve2d(50.0, 10.0, 100.0, 1e7, 500.0, max_iter=0)[0] == k.CAT_INVALID_INPUT


def test_unreachable_tolerance_reports_not_converged():
    status, out = solve2d(50.0, 10.0, 100.0, 1e7, 500.0, tol=1e-300)
    assert status == k.CAT_NOT_CONVERGED
    assert np.isnan(out[k.I_HF]) and out[k.I_RESID] > 1e-300
    message = describe_failure(status, 50.0, 10.0, 100.0, 1e7, 500.0)
    assert "did not converge" in message and "chord/L = 0.509902" in message


def test_3d_seabed_contact_tolerance_and_penetration():
    L, EA, W, seabed_z = 800.0, 5e8, 1000.0, -200.0
    fairlead = [0.0, 0.0, -12.0]
    # an anchor within SEABED_CONTACT_TOL * L of the seabed rests on it
    for dz in (-0.5, 0.5):
        anchor = [-700.0, 0.0, seabed_z + dz * k.SEABED_CONTACT_TOL * L]
        status, out = solve3d(anchor, fairlead, L, EA, W, 0.0, seabed_z)
        assert status == k.CAT_OK and out[k.I3_PROFILE] == k.PROFILE_TOUCHDOWN
    # below it: refused
    status, _ = solve3d([-700.0, 0.0, seabed_z - 2 * k.SEABED_CONTACT_TOL * L], fairlead, L, EA,
                        W, 0.0, seabed_z)
    assert status == k.CAT_BELOW_SEABED
    status, _ = solve3d([-700.0, 0.0, seabed_z], [0.0, 0.0, seabed_z - 1.0], L, EA, W, 0.0,
                        seabed_z)
    assert status == k.CAT_BELOW_SEABED
    # both ends off the seabed, the sag reaches below it: flagged, the solution still written
    status, out = solve3d([-300.0, 0.0, -150.0], [0.0, 0.0, -12.0], L, EA, W, 0.0, seabed_z)
    assert status == k.CAT_SAG_BELOW_SEABED and np.isfinite(out[k.I3_HF])
    with pytest.raises(SolverError, match="sags below"):
        solve_catenary([-300.0, 0.0, -150.0], [0.0, 0.0, -12.0], L, EA, W, seabed_z=seabed_z)
    with pytest.raises(SolverError, match="below the anchor"):
        solve_catenary([-700.0, 0.0, seabed_z], [0.0, 0.0, seabed_z - 1.0], L, EA, W,
                       seabed_z=seabed_z)


def test_every_status_has_a_message():
    statuses = {v for name, v in vars(k).items() if name.startswith("CAT_")}
    assert statuses == set(STATUS_MESSAGES)
    assert len(set(STATUS_MESSAGES.values())) == len(STATUS_MESSAGES)
    for status in statuses:
        message = describe_failure(status, 1.0, 2.0, 3.0, 4.0, 5.0)
        assert not message.startswith("unknown") and "XF" in message
    assert describe_failure(99, 1.0, 2.0, 3.0, 4.0, 5.0).startswith("unknown catenary status 99")


# ----------------------------------------------------------------------------- warm start
WARM_CASES = {
    "chain with touchdown": ([-800.0, 0.0, -200.0], [0.0, 0.0, -10.0], 850.0, 7.5e8, 1100.0,
                             0.0),
    "chain with touchdown and friction": ([-800.0, 0.0, -200.0], [0.0, 0.0, -10.0], 850.0,
                                          7.5e8, 1100.0, 0.6),
    "Lindahl-like chain": ([-32.0, 0.0, -3.0], [0.0, 0.0, 0.2], 33.0, 1.6e6, 12.0, 0.3),
    "anchor uplift": ([-500.0, 0.0, -200.0], [0.0, 0.0, -10.0], 560.0, 7.5e8, 1100.0, 0.0),
    "synthetic, nearly taut": ([-600.0, 0.0, -200.0], [0.0, 0.0, -10.0], 628.5, 2e8, 60.0, 0.0),
    "shared line, free": ([-500.0, 0.0, -50.0], [0.0, 0.0, -50.0], 560.0, 7.5e8, 1100.0, 0.0),
}


@pytest.mark.parametrize("name", list(WARM_CASES))
def test_warm_start_converges_in_few_iterations(name):
    anchor, fairlead, L, EA, W, CB = WARM_CASES[name]
    seabed_z = anchor[2] if name != "shared line, free" else -200.0
    status, base = solve3d(anchor, fairlead, L, EA, W, CB, seabed_z)
    assert status == k.CAT_OK
    worst = 0
    for angle in np.linspace(0.0, 2 * math.pi, 12, endpoint=False):
        for elevation in (-0.6, 0.0, 0.6):
            step = 1e-3 * L * np.array([math.cos(angle) * math.cos(elevation),
                                        math.sin(angle) * math.cos(elevation),
                                        math.sin(elevation)])
            status, out = solve3d(anchor, np.asarray(fairlead) + step, L, EA, W, CB, seabed_z,
                                  base[k.I3_HF], base[k.I3_VF])
            assert status == k.CAT_OK
            worst = max(worst, int(out[k.I3_ITER]))
    print(f"\nwarm start, {name}: at most {worst} iterations after a 1e-3 L step "
          f"(limit {WARM_START_MAX_ITER})")
    assert worst <= WARM_START_MAX_ITER


# ----------------------------------------------------------------------------- Python API
def test_python_api_solution_and_profile():
    anchor, fairlead = np.array([-600.0, -300.0, -200.0]), np.array([0.0, 0.0, -12.0])
    L, EA, W, CB = 800.0, 5e8, 1000.0, 0.4
    sol = solve_catenary(anchor, fairlead, L, EA, W, CB, seabed_z=-200.0)
    assert sol.profile_type == "touchdown" and 0.0 < sol.laid_length < L
    assert sol.fairlead_tension == pytest.approx(np.linalg.norm(sol.fairlead_force))
    assert sol.fairlead_tension == pytest.approx(math.hypot(sol.horizontal_tension,
                                                            sol.fairlead_vertical_tension))
    # friction: the anchor carries less than the fairlead's horizontal tension
    assert sol.anchor_horizontal_tension == pytest.approx(
        max(sol.horizontal_tension - CB * W * sol.laid_length, 0.0), rel=1e-12)
    assert sol.anchor_vertical_tension == 0.0
    # the line pulls the fairlead towards the anchor and down
    towards = (anchor - fairlead)[:2] / np.linalg.norm((anchor - fairlead)[:2])
    assert sol.fairlead_force[:2] @ towards == pytest.approx(sol.horizontal_tension)
    assert sol.fairlead_force[2] < 0.0
    # the stiffness is symmetric without friction on the suspended part only; positive here
    assert np.all(np.linalg.eigvals(sol.stiffness).real > 0.0)
    warm = solve_catenary(anchor, fairlead + 0.1, L, EA, W, CB, seabed_z=-200.0,
                          initial_guess=sol)
    assert warm.iterations <= WARM_START_MAX_ITER
    pos, T = catenary_profile(anchor, fairlead, L, EA, W, CB, seabed_z=-200.0, n_points=41,
                              solution=sol)
    np.testing.assert_allclose(pos[0], anchor, atol=1e-9)
    np.testing.assert_allclose(pos[-1], fairlead, atol=1e-9)
    assert T[-1] == pytest.approx(sol.fairlead_tension, rel=1e-12)
    assert T[0] == pytest.approx(sol.anchor_tension, rel=1e-12, abs=1e-9)
    resting = np.linspace(0.0, L, 41) < sol.laid_length
    assert np.all(pos[resting, 2] == -200.0)
    assert np.all(np.diff(T) >= -1e-9)  # tension grows from the anchor up
    with pytest.raises(ValueError, match="shape"):
        solve_catenary(anchor[:2], fairlead, L, EA, W)
    with pytest.raises(SolverError, match="not positive"):
        solve_catenary(anchor, fairlead, L, EA, -W)


def test_python_api_with_the_fairlead_as_the_lower_end():
    """Forces and named tensions refer to the points as passed, whichever end is lower."""
    upper, lower = np.array([0.0, 0.0, -12.0]), np.array([-600.0, -300.0, -200.0])
    a = solve_catenary(lower, upper, 800.0, 5e8, 1000.0, 0.4, seabed_z=-200.0)
    b = solve_catenary(upper, lower, 800.0, 5e8, 1000.0, 0.4, seabed_z=-200.0)
    np.testing.assert_allclose(b.fairlead_force, a.anchor_force, rtol=1e-12, atol=1e-6)
    assert b.horizontal_tension == pytest.approx(a.anchor_horizontal_tension, rel=1e-12)
    assert b.fairlead_vertical_tension == pytest.approx(-a.anchor_vertical_tension, abs=1e-6)
    assert b.anchor_vertical_tension == pytest.approx(-a.fairlead_vertical_tension, rel=1e-12)
    pa, Ta = catenary_profile(lower, upper, 800.0, 5e8, 1000.0, 0.4, seabed_z=-200.0)
    pb, Tb = catenary_profile(upper, lower, 800.0, 5e8, 1000.0, 0.4, seabed_z=-200.0)
    np.testing.assert_allclose(pb, pa[::-1], atol=1e-9)
    np.testing.assert_allclose(Tb, Ta[::-1], rtol=1e-12)
