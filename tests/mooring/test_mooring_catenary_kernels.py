"""The numba catenary kernels against the plain NumPy/SciPy oracle (tests/oracles).

Two implementations of one method (docs/development.md#4-kinds-of-tests): the kernels
reformulate the closed forms against cancellation and solve by Newton; the oracle evaluates
them literally and solves by nested bracketing, with a complex-step Jacobian.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from floatmoor.mooring import _catenary_kernels as k
from floatmoor.mooring import _catenary_profile as p
from tests.oracles import catenary_numpy as oracle


pytestmark = pytest.mark.oracle

#: Both codes solve the same equations, the kernel to TOL and the oracle to machine precision
#: (checked with 50-digit mpmath while writing this test: oracle residuals <= 1e-15 L). The
#: conditioning of the nearly taut lines sampled here turns 1e-15 L into ~1e-12 of the tension
#: (observed 1.8e-12); 1e-10 relative to the fairlead tension, the oracle bar of
#: docs/development.md#54-kernel-oracle-tolerance for a kernel that reformulates the equations,
#: leaves a 50x margin.
TENSION_RTOL = 1e-10
#: Laid length, relative to L: same origin as TENSION_RTOL.
LAID_LENGTH_RTOL = 1e-10
#: Stiffness: kernel's hand-derived partials vs the complex-step Jacobian (exact to roundoff),
#: both inverted; the inversion of a taut line's Jacobian amplifies roundoff by its condition
#: number (~1e4). Observed 2e-12.
STIFFNESS_RTOL = 1e-10
#: Profile positions relative to L and tensions relative to the fairlead tension.
PROFILE_RTOL = 1e-10
#: The 3-D kernel only rotates the 2-D solution into the line's plane: roundoff only.
PLANE_MAPPING_RTOL = 1e-13

#: Kernel tolerance for the comparison: tighter than the default (1e-12 L), whose residual a
#: nearly taut line amplifies to ~1e-10 in the tensions; roundoff is a few 1e-16 L.
TOL = 1e-14
MAX_ITER = 100


def random_lines(seed: int, n: int) -> list[oracle.Line]:
    """Seeded random lines across the profile types (L 10 to 2000 m, W L / EA 1e-5 to 1e-2)."""
    rng = np.random.default_rng(seed)
    lines = []
    for i in range(n):
        L = 10 ** rng.uniform(1.0, 3.3)
        W = 10 ** rng.uniform(1.0, 3.7)
        EA = W * L / 10 ** rng.uniform(-5.0, -2.0)
        kind = i % 5
        if kind == 0:  # free of the seabed, fairlead above or below the anchor
            seabed, CB = False, 0.0
            ratio, angle = rng.uniform(0.3, 0.99), rng.uniform(-1.4, 1.4)
        elif kind == 1:  # touchdown, frictionless
            seabed, CB = True, 0.0
            ratio, angle = rng.uniform(0.6, 0.98), rng.uniform(0.05, 1.2)
        elif kind == 2:  # touchdown with friction (both anchor-tension regimes occur)
            seabed, CB = True, rng.uniform(0.05, 1.5)
            ratio, angle = rng.uniform(0.6, 0.98), rng.uniform(0.05, 1.2)
        elif kind == 3:  # nearly taut or taut, with or without seabed (anchor uplift)
            seabed, CB = bool(rng.integers(2)), 0.0
            ratio, angle = rng.uniform(0.995, 1.003), rng.uniform(0.1, 1.4)
        else:  # slack on the seabed, or just off it
            seabed, CB = True, rng.uniform(0.0, 1.0)
            ratio, angle = rng.uniform(0.3, 0.9), rng.uniform(0.3, 1.5)
        lines.append(oracle.Line(ratio * L * math.cos(angle), ratio * L * math.sin(angle), L, EA,
                                 W, CB, seabed))
    return lines


def kernel_solve(line: oracle.Line) -> tuple[int, np.ndarray]:
    out = np.empty(k.N_OUT_2D)
    status = k.catenary_solve(line.XF, line.ZF, line.L, line.EA, line.W, line.CB,
                              int(line.seabed), math.nan, math.nan, TOL, MAX_ITER, out)
    return status, out


@pytest.fixture(scope="module")
def solved() -> list[tuple[oracle.Line, np.ndarray, oracle.Solution]]:
    cases = []
    for line in random_lines(20261122, 150):
        status, out = kernel_solve(line)
        assert status == k.CAT_OK, line
        cases.append((line, out, oracle.solve(line)))
    return cases


def test_output_layouts_are_consistent():
    two_d = [k.I_HF, k.I_VF, k.I_HA, k.I_VA, k.I_LB, k.I_K11, k.I_K12, k.I_K21, k.I_K22,
             k.I_ITER, k.I_RESID, k.I_PROFILE]
    assert sorted(two_d) == list(range(k.N_OUT_2D))
    three_d = ([k.I3_FAIRLEAD_FORCE + j for j in range(3)]
               + [k.I3_ANCHOR_FORCE + j for j in range(3)]
               + [k.I3_HF, k.I3_VF, k.I3_HA, k.I3_VA, k.I3_LB, k.I3_ITER, k.I3_RESID]
               + [k.I3_STIFFNESS + j for j in range(9)] + [k.I3_PROFILE, k.I3_SWAPPED])
    assert sorted(three_d) == list(range(k.N_OUT_3D))
    codes = [k.CAT_OK, k.CAT_NOT_CONVERGED, k.CAT_INVALID_INPUT, k.CAT_BELOW_SEABED,
             k.CAT_SAG_BELOW_SEABED]
    assert len(set(codes)) == len(codes) and k.CAT_OK == 0


def test_tensions_match_oracle(solved):
    worst = 0.0
    profiles = set()
    for line, out, ref in solved:
        T = math.hypot(ref.HF, ref.VF)
        ours = out[[k.I_HF, k.I_VF, k.I_HA, k.I_VA]]
        theirs = np.array([ref.HF, ref.VF, ref.HA, ref.VA])
        err = np.max(np.abs(ours - theirs)) / T
        worst = max(worst, err)
        assert err <= TENSION_RTOL, (line, ours, theirs)
        assert abs(out[k.I_LB] - ref.LB) <= LAID_LENGTH_RTOL * line.L, line
        assert out[k.I_RESID] <= TOL
        profiles.add(int(out[k.I_PROFILE]))
    # the sample covers every profile type the oracle solves
    assert {k.PROFILE_SUSPENDED, k.PROFILE_TAUT, k.PROFILE_TOUCHDOWN,
            k.PROFILE_SLACK} <= profiles
    print(f"\n{len(solved)} lines: worst tension difference {worst:.2e} of the fairlead tension "
          f"(tolerance {TENSION_RTOL:.0e})")


def test_stiffness_matches_complex_step_oracle(solved):
    worst = 0.0
    n = 0
    for line, out, ref in solved:
        if ref.HF == 0.0:  # slack: no Jacobian (the oracle's equations are singular)
            continue
        K_ref = oracle.stiffness(line, ref)
        K = out[k.I_K11:k.I_K22 + 1].reshape(2, 2)
        err = np.max(np.abs(K - K_ref)) / np.max(np.abs(K_ref))
        worst = max(worst, err)
        n += 1
        assert err <= STIFFNESS_RTOL, (line, K, K_ref)
    print(f"\n{n} lines: worst stiffness difference {worst:.2e} of max|K| "
          f"(tolerance {STIFFNESS_RTOL:.0e})")


def test_profile_matches_oracle(solved):
    worst_x = worst_t = 0.0
    for line, out, ref in solved[::3]:
        if ref.HF == 0.0:
            continue
        s = np.linspace(0.0, line.L, 13)
        s[1] = 1e-9 * line.L  # just off the anchor
        x, z, T = np.empty(13), np.empty(13), np.empty(13)
        p.catenary_profile(line.XF, line.ZF, line.L, line.EA, line.W, line.CB, int(line.seabed),
                           out[k.I_HF], out[k.I_VF], s, x, z, T)
        xr, zr, Tr = oracle.profile(line, ref, s)
        Tf = math.hypot(ref.HF, ref.VF)
        ex = max(np.max(np.abs(x - xr)), np.max(np.abs(z - zr))) / line.L
        et = np.max(np.abs(T - Tr)) / Tf
        worst_x, worst_t = max(worst_x, ex), max(worst_t, et)
        assert ex <= PROFILE_RTOL and et <= PROFILE_RTOL, line
        # the profile ends at the fairlead with the fairlead tension
        assert abs(x[-1] - line.XF) + abs(z[-1] - line.ZF) <= 1e-11 * line.L
        assert T[-1] == pytest.approx(math.hypot(out[k.I_HF], out[k.I_VF]), rel=1e-14)
    print(f"\nworst profile differences: position {worst_x:.2e} L, tension {worst_t:.2e} T "
          f"(tolerance {PROFILE_RTOL:.0e})")


def test_3d_kernel_is_the_2d_solution_in_the_line_plane(solved):
    rng = np.random.default_rng(7)
    worst = 0.0
    for line, _, _ in solved[::2]:
        heading = rng.uniform(0.0, 2.0 * math.pi)
        anchor = rng.uniform(-500.0, 500.0, 3)
        fairlead = anchor + np.array([line.XF * math.cos(heading), line.XF * math.sin(heading),
                                      line.ZF])
        seabed_z = anchor[2] if line.seabed else -math.inf
        out3 = np.empty(k.N_OUT_3D)
        status = k.catenary_solve_3d(anchor, fairlead, line.L, line.EA, line.W, line.CB,
                                     seabed_z, math.nan, math.nan, TOL, MAX_ITER, out3)
        if line.ZF < 0.0:  # the fairlead is the lower end: the kernel swaps the roles
            assert status == k.CAT_OK and out3[k.I3_SWAPPED] == 1.0
            continue
        assert status == k.CAT_OK and out3[k.I3_SWAPPED] == 0.0
        # the 2-D problem the positions define (rounded positions: XF, ZF differ from `line`)
        span = fairlead - anchor
        XF = float(np.hypot(span[0], span[1]))
        u = np.array([span[0] / XF, span[1] / XF, 0.0])
        out = np.empty(k.N_OUT_2D)
        assert k.catenary_solve(XF, float(span[2]), line.L, line.EA, line.W, line.CB,
                                int(line.seabed), math.nan, math.nan, TOL, MAX_ITER,
                                out) == k.CAT_OK
        H, V, HA, VA = out[k.I_HF], out[k.I_VF], out[k.I_HA], out[k.I_VA]
        T = math.hypot(H, V)
        expect_f = np.array([-H * u[0], -H * u[1], -V])
        expect_a = np.array([HA * u[0], HA * u[1], VA])
        ff = out3[k.I3_FAIRLEAD_FORCE:k.I3_FAIRLEAD_FORCE + 3]
        fa = out3[k.I3_ANCHOR_FORCE:k.I3_ANCHOR_FORCE + 3]
        err = max(np.max(np.abs(ff - expect_f)), np.max(np.abs(fa - expect_a))) / T
        worst = max(worst, err)
        assert err <= PLANE_MAPPING_RTOL, line
        # in-plane stiffness block: u^T K u = dHF/dXF, K_zz = dVF/dZF, transverse = HF / XF
        K = out3[k.I3_STIFFNESS:k.I3_STIFFNESS + 9].reshape(3, 3)
        n = np.array([-u[1], u[0], 0.0])
        K2 = out[k.I_K11:k.I_K22 + 1]
        scale = np.max(np.abs(K))
        assert abs(u @ K @ u - K2[0]) <= PLANE_MAPPING_RTOL * scale
        assert abs(u @ K[:, 2] - K2[1]) <= PLANE_MAPPING_RTOL * scale
        assert abs(K[2, :] @ u - K2[2]) <= PLANE_MAPPING_RTOL * scale
        assert abs(K[2, 2] - K2[3]) <= PLANE_MAPPING_RTOL * scale
        assert abs(n @ K @ n - H / XF) <= PLANE_MAPPING_RTOL * scale
        assert abs(n @ K @ u) + abs(n @ K[:, 2]) <= PLANE_MAPPING_RTOL * scale
        # the profile in 3-D is the 2-D profile placed in the plane
        s = np.linspace(0.0, line.L, 7)
        pos, T3 = np.empty((7, 3)), np.empty(7)
        x, z, T2 = np.empty(7), np.empty(7), np.empty(7)
        p.catenary_profile_3d(anchor, fairlead, line.L, line.EA, line.W, line.CB, seabed_z,
                              out3[k.I3_HF], out3[k.I3_VF], s, pos, T3)
        p.catenary_profile(XF, float(span[2]), line.L, line.EA, line.W, line.CB,
                           int(line.seabed), H, V, s, x, z, T2)
        expect = anchor + x[:, None] * u + z[:, None] * np.array([0.0, 0.0, 1.0])
        assert np.max(np.abs(pos - expect)) <= 1e-13 * (line.L + np.max(np.abs(anchor)))
        np.testing.assert_allclose(T3, T2, rtol=PLANE_MAPPING_RTOL)
    print(f"\nworst 3-D vs 2-D force difference {worst:.2e} T (tolerance {PLANE_MAPPING_RTOL:.0e})")


def test_kernels_allocate_nothing_and_reuse_out():
    """Repeated calls with one ``out`` give identical results (no state, no aliasing)."""
    line = random_lines(3, 2)[1]
    first = kernel_solve(line)[1]
    out = np.full(k.N_OUT_2D, 123.0)
    for _ in range(3):
        k.catenary_solve(line.XF, line.ZF, line.L, line.EA, line.W, line.CB, int(line.seabed),
                         math.nan, math.nan, TOL, MAX_ITER, out)
    np.testing.assert_array_equal(out, first)


def test_bracketing_fallback_finds_the_same_solution(solved):
    """With one Newton iteration allowed, cold starts fall back to the bracketing solver
    (then a Newton polish); the answer must be the same line."""
    worst = 0.0
    fallbacks = 0
    for line, out, _ in solved[::4]:
        if out[k.I_PROFILE] == k.PROFILE_SLACK:
            continue
        fb = np.empty(k.N_OUT_2D)
        status = k.catenary_solve(line.XF, line.ZF, line.L, line.EA, line.W, line.CB,
                                  int(line.seabed), math.nan, math.nan, TOL, 1, fb)
        assert status == k.CAT_OK, line
        fallbacks += fb[k.I_ITER] > 1
        T = math.hypot(out[k.I_HF], out[k.I_VF])
        err = np.max(np.abs(fb[:k.I_LB] - out[:k.I_LB])) / T
        worst = max(worst, err)
        assert err <= TENSION_RTOL, line
    assert fallbacks >= 10
    print(f"\nbracketing fallback on {fallbacks} lines: worst difference {worst:.2e} T")


@pytest.mark.parametrize("h0, v0", [(1e-20, 1e20), (1e20, -1e20), (1.0, 1.0), (math.inf, 0.0),
                                    (-5.0, 3.0)])
def test_absurd_warm_starts_still_converge(solved, h0, v0):
    for line, out, _ in solved[::10]:
        scale = line.W * line.L
        guess = np.empty(k.N_OUT_2D)
        status = k.catenary_solve(line.XF, line.ZF, line.L, line.EA, line.W, line.CB,
                                  int(line.seabed), h0 * scale, v0 * scale, TOL, 100, guess)
        assert status == k.CAT_OK, line
        T = math.hypot(out[k.I_HF], out[k.I_VF])
        assert np.max(np.abs(guess[:k.I_LB] - out[:k.I_LB])) <= TENSION_RTOL * T
