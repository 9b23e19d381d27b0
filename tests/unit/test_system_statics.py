"""Statics of mooring systems (floatmoor.mooring.system_statics): the equilibrium of free
points joined by catenary sections, its stiffness at the body and its time series."""

from __future__ import annotations

import time

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.case.schema import Point
from floatmoor.errors import SolverError
from floatmoor.mooring import _system_statics_kernels as k
from floatmoor.mooring.catenary import solve_catenary
from floatmoor.mooring.system_statics import (
    SystemStatics, body_point_stiffness, build_static_system, coupled_stiffness, solve_statics,
)
from tests.conftest import LINDAHL_CASE
from tests.oracles import statics_numpy
from tests.unit.statics_systems import (
    CHAIN, ENVIRONMENT, ROPE, SEABED, chain_rope_chain, make_line, three_lines,
)

#: Kernel against the NumPy reference: both converge the force residual to ~1e-9 of the
#: tensions, which leaves the positions within ~1e-8 m of each other on these ~1 km systems.
POSITION_ATOL = 1e-7
#: Stiffness against central differences of the equilibrium (steps 5 cm, 2e-4 rad; solved to
#: a relative residual of 1e-10): the truncation error is ~(h/L)^2 ~ 1e-7 and the
#: equilibrium's noise ~1e-10 T / h ~ 1e-3 N/m, both far below 1e-5 of the stiffness.
FD_RTOL = 1e-5


def _system(maker, **kw):
    points, lines = maker(**kw)
    return build_static_system(points, lines, ENVIRONMENT, SEABED)


# ------------------------------------------------------------------------ one section
def test_single_section_line_is_exactly_todays_catenary():
    case = load_case(LINDAHL_CASE, ['lines.chain.model="quasi-static"'])
    system = build_static_system(case.points, case.lines, case.environment, case.seabed)
    line = case.lines[0]
    solution = solve_statics(system)
    w = line.line_type.weight_in_water(case.environment)
    cb = case.seabed.friction_coefficient if line.quasi_static.seabed_friction else 0.0
    ref = solve_catenary(line.anchor, line.fairlead, line.length,
                         line.line_type.axial_stiffness, w, cb, case.environment.seabed_z,
                         tol=line.quasi_static.tolerance,
                         max_iter=line.quasi_static.max_iterations)
    assert solution.iterations == 0  # no free point
    assert np.array_equal(solution.end_force[0], ref.fairlead_force)
    assert np.array_equal(solution.start_force[0], ref.anchor_force)
    assert solution.laid_length[0] == ref.laid_length
    assert np.array_equal(solution.section_stiffness[0, 3], ref.stiffness)


@pytest.mark.parametrize("kind", ["suspended", "touchdown", "touchdown with friction"])
def test_section_stiffness_is_the_derivative_of_its_end_forces(kind):
    pa = np.array([0.0, 0.0, -200.0]) if kind != "suspended" else np.array([0.0, 0.0, -150.0])
    pb = np.array([520.0, 210.0, -20.0])
    cb = 0.6 if kind == "touchdown with friction" else 0.0
    args = (600.0, 4.93e8, 980.0, cb, -200.0, np.nan, np.nan, 1e-13, 100)

    def forces(a, b):
        out = np.empty(k.N_SECTION_OUT)
        assert k.section_solve(a, b, *args, out) == 0
        return out

    out = forces(pa, pb)
    assert out[k.S_LB] > 0.0 if kind != "suspended" else out[k.S_LB] == 0.0
    h = 1e-4
    for which, p in (("A", 0), ("B", 1)):
        for c in range(3):
            dp = np.zeros(3)
            dp[c] = h
            ends_p = [pa, pb]
            ends_m = [pa, pb]
            ends_p[p] = ends_p[p] + dp
            ends_m[p] = ends_m[p] - dp
            if which == "A" and kind != "suspended" and c == 2:
                continue  # lifting the anchor off the seabed changes the regime (one-sided)
            fp, fm = forces(*ends_p), forces(*ends_m)
            for name, f in (("A", k.S_FA), ("B", k.S_FB)):
                fd = -(fp[f:f + 3] - fm[f:f + 3]) / (2 * h)
                blk = {"AA": k.S_KAA, "AB": k.S_KAB, "BA": k.S_KBA, "BB": k.S_KBB}[name + which]
                col = out[blk:blk + 9].reshape(3, 3)[:, c]
                np.testing.assert_allclose(col, fd, rtol=1e-5, atol=1e-6 * np.abs(out[:9]).max(),
                                           err_msg=f"K_{name}{which}, column {c}")


# ------------------------------------------------------------------------ equilibrium
@pytest.mark.parametrize("maker", [chain_rope_chain, three_lines])
def test_equilibrium_matches_numpy_reference(maker):
    system = _system(maker)
    solution = solve_statics(system)
    assert solution.residual <= 1e-9
    free = system.free_index
    # free points balance their sections' forces, their weight and their buoyancy
    net = solution.point_force[free] + system.external_force[free]
    assert np.abs(net).max() <= 1e-8 * np.abs(solution.end_force).max()
    assert np.abs(solution.positions - statics_numpy.solve(system)).max() <= POSITION_ATOL
    # the clump hangs off the seabed, the first chain rests partly on it
    assert solution.laid_length[0] > 0.0
    assert np.all(solution.positions[free, 2] > system.seabed_z + 1.0)


def test_far_off_initial_guess_reaches_the_same_equilibrium():
    points, lines = three_lines()
    reference = solve_statics(build_static_system(points, lines, ENVIRONMENT, SEABED))
    moved = [Point(p.name, p.kind, (0.5 * p.position[0], 0.5 * p.position[1], -120.0),
                   p.mass, p.volume) if p.kind == "free" else p for p in points]
    solution = solve_statics(build_static_system(moved, lines, ENVIRONMENT, SEABED))
    assert np.abs(solution.positions - reference.positions).max() <= POSITION_ATOL


# ------------------------------------------------------------------------ stiffness
def _equilibrium_forces(system, statics, body):
    solution = statics.solve(body)
    return solution, solution.point_force[system.body_index]


def test_body_point_stiffness_matches_finite_differences_of_the_equilibrium():
    system = _system(three_lines)
    statics = SystemStatics(system, force_rtol=1e-10)
    base = system.positions[system.body_index]
    solution = statics.solve(base)
    K = body_point_stiffness(system, solution)
    h = 5e-2
    fd = np.zeros_like(K)
    for j in range(K.shape[1]):
        dp = np.zeros(K.shape[1])
        dp[j] = h
        fp = _equilibrium_forces(system, statics, base + dp.reshape(-1, 3))[1].ravel()
        fm = _equilibrium_forces(system, statics, base - dp.reshape(-1, 3))[1].ravel()
        fd[:, j] = -(fp - fm) / (2 * h)
    np.testing.assert_allclose(K, fd, rtol=FD_RTOL, atol=FD_RTOL * np.abs(K).max())
    # condensing matters: the fairleads' own section stiffness alone is far from it
    own = np.zeros_like(K)
    for j, p in enumerate(system.body_index):
        for s, (a, b) in enumerate(zip(system.section_start, system.section_end)):
            if b == p:
                own[3 * j:3 * j + 3, 3 * j:3 * j + 3] += solution.section_stiffness[s, 3]
            if a == p:
                own[3 * j:3 * j + 3, 3 * j:3 * j + 3] += solution.section_stiffness[s, 0]
    assert np.abs(own - K).max() > 0.1 * np.abs(K).max()


def _rotation(theta):
    angle = np.linalg.norm(theta)
    if angle == 0.0:
        return np.eye(3)
    n = theta / angle
    N = np.array([[0.0, -n[2], n[1]], [n[2], 0.0, -n[0]], [-n[1], n[0], 0.0]])
    return np.eye(3) + np.sin(angle) * N + (1.0 - np.cos(angle)) * N @ N


def test_coupled_6x6_stiffness_matches_finite_differences_of_the_equilibrium():
    system = _system(three_lines)
    statics = SystemStatics(system, force_rtol=1e-10)
    ref = np.array([0.0, 0.0, -5.0])
    rel = system.positions[system.body_index] - ref
    solution = statics.solve(rel + ref)
    K6 = coupled_stiffness(system, solution, ref)

    def load(q):
        R = _rotation(q[3:])
        centre = ref + q[:3]
        points = centre + rel @ R.T
        forces = _equilibrium_forces(system, statics, points)[1]
        return np.concatenate([forces.sum(axis=0),
                               np.cross(points - centre, forces).sum(axis=0)])

    fd = np.zeros((6, 6))
    for j, h in enumerate([5e-2] * 3 + [2e-4] * 3):
        dq = np.zeros(6)
        dq[j] = h
        fd[:, j] = -(load(dq) - load(-dq)) / (2 * h)
    scale = np.abs(K6).max(axis=1, keepdims=True)  # rows mix N/m, N, N m/rad
    assert np.all(np.abs(K6 - fd) <= FD_RTOL * scale), (K6 - fd) / scale


# ------------------------------------------------------------------------ time series
def _circle_path(system, n, radius=4.0, period=40.0, dt=0.5):
    t = np.arange(n) * dt
    offset = np.stack([radius * np.sin(2 * np.pi * t / period), np.zeros(n),
                       0.5 * radius * np.cos(2 * np.pi * t / period)], axis=1)
    return t, system.positions[system.body_index][None, :, :] + offset[:, None, :]


def _series(system, t, path):
    n, ns, npnt = len(t), len(system.section_names), len(system.point_names)
    out = dict(positions=np.empty((n, npnt, 3)), start_force=np.empty((n, ns, 3)),
               end_force=np.empty((n, ns, 3)), laid_length=np.empty((n, ns)),
               iterations=np.empty(n), residual=np.empty(n))
    SystemStatics(system).solve_path(t, path, **out)
    return out


def test_warm_started_series_matches_independent_solves():
    system = _system(three_lines)
    t, path = _circle_path(system, 40)
    out = _series(system, t, path)
    for i in (0, 7, 23, 39):
        cold = solve_statics(system, path[i])  # from the system's initial guesses
        assert np.abs(out["positions"][i] - cold.positions).max() <= POSITION_ATOL
        np.testing.assert_allclose(out["end_force"][i], cold.end_force, rtol=1e-7,
                                   atol=1e-7 * np.abs(cold.end_force).max())
        np.testing.assert_allclose(out["start_force"][i], cold.start_force, rtol=1e-7,
                                   atol=1e-7 * np.abs(cold.start_force).max())
        np.testing.assert_allclose(out["laid_length"][i], cold.laid_length, atol=1e-6)
    assert np.all(out["residual"] <= 1e-9)
    assert out["iterations"][1:].max() <= 6  # warm starts


def test_series_kernel_matches_numpy_reference_and_is_fast():
    system = _system(three_lines)
    t, path = _circle_path(system, 400)
    _series(system, t[:2], path[:2])  # compile / load the kernels
    start = time.perf_counter()
    out = _series(system, t, path)
    per_sample = (time.perf_counter() - start) / len(t)
    for i in (0, 133, 399):
        ref = statics_numpy.solve(system, path[i])
        assert np.abs(out["positions"][i] - ref).max() <= POSITION_ATOL
    print(f"\nthree-line system statics: {per_sample * 1e3:.3f} ms per sample "
          f"({int(np.mean(out['iterations']) * 100) / 100} Newton iterations on average)")
    assert per_sample < 0.05  # generous: ~0.1 ms measured on one core


# ------------------------------------------------------------------------ failures
def test_unsupported_free_points_are_refused_naming_the_point():
    points, lines = chain_rope_chain()
    points = points + [Point("lost1", "free", (100.0, 0.0, -50.0), mass=100.0),
                       Point("lost2", "free", (150.0, 0.0, -50.0))]
    lines = lines + [make_line("stray", [(CHAIN, 60.0, "lost1", "lost2")], points)]
    with pytest.raises(SolverError, match=r"free point 'lost1' has no support.*'lost1', "
                                          r"'lost2'.*net force"):
        build_static_system(points, lines, ENVIRONMENT, SEABED)


def test_free_point_without_section_is_refused():
    points, lines = chain_rope_chain()
    points = points + [Point("alone", "free", (100.0, 0.0, -50.0), mass=100.0)]
    with pytest.raises(SolverError, match="free point 'alone' has no section"):
        build_static_system(points, lines, ENVIRONMENT, SEABED)


def test_buoy_without_equilibrium_below_the_surface_fails_with_its_residual():
    # a 5 m^3 buoy on 230 m of rope from an anchor 200 m deep: it would float above the surface
    points = [Point("anchor", "fixed", (0.0, 0.0, -200.0)),
              Point("buoy", "free", (30.0, 0.0, -60.0), mass=1000.0, volume=5.0)]
    lines = [make_line("riser", [(ROPE, 230.0, "anchor", "buoy")], points)]
    system = build_static_system(points, lines, ENVIRONMENT, SEABED)
    with pytest.raises(SolverError) as info:
        solve_statics(system)
    message = str(info.value)
    assert "free point 'buoy' has no equilibrium below the surface" in message
    lift = float(message.split("a net upward force of ")[1].split(" N")[0])
    # held at the surface it pulls up by its net buoyancy less the weight of the 200 m of
    # rope hanging from it (the other 30 m rest on the seabed; the stretch is ~2e-4)
    g, rho = ENVIRONMENT.gravity, ENVIRONMENT.water_density
    expected = rho * g * 5.0 - 1000.0 * g - ROPE.weight_in_water(ENVIRONMENT) * 200.0
    assert lift == pytest.approx(expected, rel=1e-3)


def test_clump_pressed_onto_the_seabed_fails_naming_it():
    system = _system(chain_rope_chain, anchor_x=-900.0)
    with pytest.raises(SolverError, match="free point 'clump' is pressed onto the seabed"):
        solve_statics(system)


def test_failure_along_a_path_names_the_time():
    system = _system(chain_rope_chain)
    t = np.array([0.0, 1.0, 2.0])
    body = system.positions[system.body_index]
    path = np.stack([body, body + [-60.0, 0.0, 0.0], body + [-120.0, 0.0, 0.0]])
    with pytest.raises(SolverError, match=r"at t = [12] s: free point 'clump' is pressed"):
        _series(system, t, path)
